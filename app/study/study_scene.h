// Scene of `kimp study`: FEM wall-height cases -> fitted k (docs/physics.md §4) -> the
// isolated building of docs/physics.md §2-3 pounding on moat walls with each height's k.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/fem/fem_scene.h"
#include "app/laws/fit_run.h"
#include "app/lumped/building_keys.h"
#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_scene.h"
#include "fit/fit_config.h"
#include "io/scene_io.h"

namespace kimp::app
{
  /** The FEM scene of the study: docs/physics.md §4 defaults with H = 1.00, 1.25, 1.50, 2.00 m. */
  FemScene default_study_fem_scene();

  /** How the study chooses the FEM discretisation of each height. */
  enum class Fidelity
  {
    fixed,       ///< the scene's mesh and penalty (reproducible, no error estimate)
    auto_ladder, ///< climb fidelity_h_contact, then fidelity_penalty_factors (study_ladder.h)
  };

  /** The study's FEM section: the FemScene keys plus the fidelity ladder. */
  struct StudyFemScene : FemScene
  {
    StudyFemScene()
      : FemScene(default_study_fem_scene())
    {
    }

    Fidelity            fidelity                 = Fidelity::auto_ladder;
    double              fidelity_tolerance       = 0.01; ///< relative change of k, > 0
    std::vector<double> fidelity_h_contact       = {0.05, 0.025, 0.0125}; ///< m, decreasing
    std::vector<double> fidelity_penalty_factors = {1.0};                 ///< increasing
    /// auto: also run the reported level with the other far side (rollers <-> absorbing) and
    /// report the spread of the engineer's quantities (one more run of the finest level).
    bool fidelity_far_side_spread = false;
    /// Impact velocities of the k(H, v) table, m/s (> 0, increasing); slab.velocity, the
    /// reference velocity of the fidelity ladder and the building runs, is always added.
    std::vector<double> velocities = {0.5, 1.0, 2.0};
  };

  /// A list of contact element sizes, one FEM mesh level each (shown in cm,
  /// contact_element_range()); `doc` says how the levels are run.
  template <class Io>
  void visit_contact_element_sizes(Io                  &io,
                                   std::string_view     key,
                                   std::vector<double> &sizes,
                                   std::string_view     doc)
  {
    io.quantity_list(key, sizes, "cm", doc, contact_element_range());
  }

  template <class Io>
  void visit(Io &io, StudyFemScene &s)
  {
    visit(io, static_cast<FemScene &>(s));
    io.choice("fidelity",
              s.fidelity,
              {{"auto", Fidelity::auto_ladder}, {"fixed", Fidelity::fixed}},
              "auto: per height climb fidelity_h_contact (then fidelity_penalty_factors) until "
              "k_KV and k_Jankowski change by less than fidelity_tolerance, and report the "
              "change as the numerical error of k; fixed: mesh.h_contact and "
              "contact.penalty_factor as given, error not estimated");
    io.quantity("fidelity_tolerance",
                s.fidelity_tolerance,
                "%",
                "auto: largest relative change of k between consecutive levels",
                io::Range::positive());
    visit_contact_element_sizes(io,
                                "fidelity_h_contact",
                                s.fidelity_h_contact,
                                "auto: contact element sizes, coarse to fine (each level costs "
                                "about 4x the previous one; 1.25 cm takes about 10 s per height)");
    io.quantity_list("fidelity_penalty_factors",
                     s.fidelity_penalty_factors,
                     "",
                     "auto: penalty factors tried at the mesh reached, increasing (the first "
                     "one is used for the mesh ladder)",
                     io::Range::positive());
    io.flag("fidelity_far_side_spread",
            s.fidelity_far_side_spread,
            "auto: also run the reported level with the other far side (boundary.far rollers "
            "<-> absorbing) and report the spread of the engineer's quantities between the two "
            "(one more run of the finest level per height)");
    io.quantity_list("velocities",
                     s.velocities,
                     "m/s",
                     "impact velocities of the k(H, v) table, increasing: one FEM case per "
                     "height and velocity, at the FEM level (and material model) the fidelity "
                     "ladder chose at slab.velocity, which is always part of the table and is the "
                     "reference velocity of the building runs ([]: slab.velocity only)",
                     io::Range::positive());
  }

  /// The key wall_height of an extra study run at one wall height; `doc` names the study.
  template <class Io>
  void visit_study_wall_height(Io &io, double &wall_height, std::string_view doc)
  {
    io.quantity("wall_height", wall_height, "m", doc, moat_wall_height_range());
  }

  /** FEM accuracy-vs-cost and lumped time-step studies at one wall height. */
  struct StudyAccuracyScene
  {
    double              wall_height     = 1.25;                  ///< m
    std::vector<double> h_contact       = {0.05, 0.025, 0.0125}; ///< m, explicit levels
    std::vector<double> penalty_factors = {1.0, 10.0};           ///< at the middle mesh level
    bool implicit = true; ///< also implicit Newmark on every mesh level but the finest
    std::vector<double> lumped_dt = {2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5}; ///< s
    double              lumped_reference_dt = 2.5e-6; ///< s, CDM reference
  };

  template <class Io>
  void visit(Io &io, StudyAccuracyScene &s)
  {
    visit_study_wall_height(io, s.wall_height, "wall height of the accuracy study");
    visit_contact_element_sizes(io,
                                "h_contact",
                                s.h_contact,
                                "FEM mesh levels (explicit, first penalty factor); the finest is "
                                "the reference");
    io.quantity_list("penalty_factors",
                     s.penalty_factors,
                     "",
                     "FEM penalty levels, run on the finest mesh level that is not the "
                     "reference (or the only one)",
                     io::Range::positive());
    io.flag("implicit",
            s.implicit,
            "also run implicit Newmark on every mesh level but the finest (slow: about 16 s "
            "at 5 cm; a failure is recorded as a data point)");
    io.quantity_list("lumped_dt",
                     s.lumped_dt,
                     "s",
                     "time steps of the building with walls (central difference and Newmark)",
                     io::Range::positive());
    io.quantity("lumped_reference_dt",
                s.lumped_reference_dt,
                "s",
                "central-difference reference step (below every lumped_dt)",
                io::Range::positive());
  }

  /** Sensitivity of k to four scene parameters at one wall height. */
  struct StudySensitivityScene
  {
    double wall_height = 1.25; ///< m
    double variation   = 0.25; ///< each parameter × (1 ∓ variation)
  };

  template <class Io>
  void visit(Io &io, StudySensitivityScene &s)
  {
    visit_study_wall_height(io, s.wall_height, "wall height of the sensitivity study");
    io.quantity("variation",
                s.variation,
                "%",
                "soil modulus, slab mass (length), impact velocity and wall thickness are each "
                "run at (1 - variation) and (1 + variation) times their value",
                io::Range::greater(0.0).and_less(1.0));
  }

  /// The fits of every height: the fitting configuration shared with `kimp fit`
  /// (fit/fit_config.h, keys declared in app/laws/fit_run.h).
  using StudyFitScene = fit::FitConfig;

  /** Mass of the flexible wall SDOF (docs/physics.md §4 "Wall SDOF"). */
  enum class WallSdofMass
  {
    participation, ///< k^2 u_s^T M u_s: the band's receptance to second order, all modes
    mode           ///< k / omega^2 of the mode with the largest share of the static deflection
  };

  /** Moat walls of the study: on both sides, gap from the building's own no-wall response. */
  struct StudyWallsScene
  {
    double                mass          = 500e3; ///< m_wall, kg (> 0)
    double                gap_reduction = 0.10;  ///< gap = (1 − r)·peak isolation displacement
    std::optional<double> gap;         ///< fixed gap of both walls, m (overrides gap_reduction)
    bool         flexible      = true; ///< also run against each height's wall SDOF from its FEM
    double       damping_ratio = 0.05; ///< ζ of the flexible wall SDOF
    WallSdofMass flexible_mass = WallSdofMass::participation;
  };

  template <class Io>
  void visit(Io &io, StudyWallsScene &s)
  {
    visit_mass(io,
               "mass",
               s.mass,
               "wall mass for m_eff in the impact laws (rigid and flexible walls)");
    io.quantity("gap_reduction",
                s.gap_reduction,
                "%",
                "gap = (1 - gap_reduction) x the no-wall peak isolation displacement of each "
                "record",
                io::Range::at_least(0.0).and_less(1.0));
    visit_moat_gap(io, "gap", s.gap, "fixed gap of both walls (null: from gap_reduction)");
    io.flag("flexible",
            s.flexible,
            "also derive each height's wall as a SDOF from its FE model (static stiffness at "
            "the slab band, mass from its modes: flexible_mass) and run the building against "
            "it beside the rigid wall with the same impact laws (their m_eff keeps mass) "
            "(wall_sdof.csv, flexible_wall.csv)");
    visit_damping_ratio(io,
                        "damping_ratio",
                        s.damping_ratio,
                        "flexible: damping ratio of the wall SDOF (c = 2 zeta sqrt(k m))");
    io.choice("flexible_mass",
              s.flexible_mass,
              {{"participation", WallSdofMass::participation}, {"mode", WallSdofMass::mode}},
              "flexible: SDOF mass; participation: k^2 u^T M u of the static deflection u under "
              "the slab (Rayleigh; every mode by its share); mode: k / omega^2 of the mode "
              "with the largest share");
  }

  /**
   * Consistent k of the building runs (docs/physics.md §4 "k against impact velocity and
   * consistent k"): run the building, read the largest impact velocity at the walls, interpolate
   * k(H, v_imp) in the k table and rerun until k changes by less than `tolerance`.
   */
  struct StudyConsistentKScene
  {
    bool         enabled        = true;
    double       tolerance      = 0.02; ///< relative change of k between runs, > 0
    unsigned int max_iterations = 10;   ///< building runs per record, height and law
  };

  template <class Io>
  void visit(Io &io, StudyConsistentKScene &s)
  {
    io.flag("enabled",
            s.enabled,
            "repeat each building run (record, height, law) with the k of its own impact "
            "velocity, k(H, v_imp), from the k(H, v) table");
    io.quantity("tolerance",
                s.tolerance,
                "%",
                "stop when k changes by less than this between two runs",
                io::Range::positive());
    io.integer("max_iterations",
               s.max_iterations,
               "building runs per record, height and law before the iteration is reported as "
               "not converged",
               1,
               100);
  }

  /**
   * The study scene. Load with read_scene<StudyScene>(file) (validated); an empty document is
   * the default study.
   */
  struct StudyScene
  {
    StudyFemScene                  fem;
    StudyFitScene                  fit;
    BuildingScene                  building;
    IsolatorScene                  isolator;
    StudyWallsScene                walls;
    IntegrationScene               integration;
    std::vector<GroundMotionScene> records{GroundMotionScene{}};
    /// Add Kobe KJMA (trimmed to 48 s) and Sylmar Converter Station (study_records()) when the
    /// records directory holds them.
    bool                  peer_records   = true;
    std::string           records_dir    = "";   ///< "" = KIMP_RECORDS_DIR / ../shared/data/records
    bool                  charts         = true; ///< run scripts/study_charts.py
    bool                  accuracy_study = true; ///< FEM and lumped accuracy against cost
    StudyAccuracyScene    accuracy;
    bool                  stability_map = true;  ///< lumped Δt vs k_imp stable/unstable map
    bool                  sensitivity   = false; ///< sensitivity of k (8 more FEM runs)
    StudySensitivityScene sensitivity_study;
    StudyConsistentKScene consistent_k;
  };

  template <class Io>
  void visit(Io &io, StudyScene &s)
  {
    io.section("fem", s.fem, "the FEM slab-wall impact per wall height (see kimp fem)");
    io.section("fit", s.fit, "fit of the Kelvin-Voigt and Jankowski laws to each FEM history");
    io.section("building", s.building, "the pounding building (thesis Table 4.2)");
    io.section("isolator", s.isolator, "its isolation system");
    io.section("walls", s.walls, "moat walls on both sides at the isolation level");
    io.section("integration", s.integration, "time integration of the building runs");
    io.list("records", s.records, "ground motions of the building runs (see kimp lumped)");
    io.flag("peer_records",
            s.peer_records,
            "also run Kobe KJMA (trimmed to 48 s) and Northridge SCS142 when the records "
            "directory holds them");
    io.text("records_dir",
            s.records_dir,
            "directory of the PEER records, relative to the scene file's directory (\"\" = "
            "KIMP_RECORDS_DIR or ../shared/data/records)");
    io.flag("charts", s.charts, "draw the charts with scripts/study_charts.py (python3)");
    io.flag("accuracy_study",
            s.accuracy_study,
            "accuracy against cost: FEM mesh, penalty (and implicit) levels -> error in k; "
            "building time step -> error in peak impact force and base acceleration");
    io.section("accuracy", s.accuracy, "settings of the accuracy study");
    io.flag("stability_map",
            s.stability_map,
            "lumped central-difference stability map: time step against k_imp (two-body "
            "collisions, m_eff of the building's isolation level and the wall), with 2/omega_imp");
    io.flag("sensitivity",
            s.sensitivity,
            "sensitivity of k to soil modulus, slab mass, impact velocity and wall thickness");
    io.section("sensitivity_study", s.sensitivity_study, "settings of the sensitivity study");
    io.section("consistent_k",
               s.consistent_k,
               "building runs with the k of their own impact velocity, k(H, v_imp)");
  }

  /** Every range and cross-field rule; key paths as in the file ("walls.gap_reduction"). */
  void validate(const StudyScene &scene, io::ValidationContext &ctx);

  /// records[i] and records_dir resolved against the scene file's `directory` (called by
  /// io::read_scene_text()).
  void resolve_paths(StudyScene &scene, const std::filesystem::path &directory);

  /**
   * Load every record of scene.records once, before any computation, so that a missing or
   * misspelt one is an error at its key: "FILE:LINE: records[i].record = 'NAME': ...; did you
   * mean ...?" (load_ground_motion_at()).
   * @throws io::SceneError for the first record that cannot be loaded.
   */
  void check_study_records(const io::LoadedScene<StudyScene> &loaded);

  /** The lumped scene of the study's building without walls, shaken by `record`. */
  LumpedScene study_lumped_scene(const StudyScene &scene, const GroundMotionScene &record);

  /** Records the study runs: scene.records, plus the PEER records found (if peer_records). */
  std::vector<GroundMotionScene> study_records(const StudyScene &scene);

  /** One warning per PEER record requested by peer_records that study_records() cannot find. */
  std::vector<std::string> missing_study_records(const StudyScene &scene);
} // namespace kimp::app
