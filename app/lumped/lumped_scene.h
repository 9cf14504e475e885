// Scene of `kimp lumped`: the shear building of docs/physics.md §2-3 (thesis Table 4.2 defaults),
// its isolator, moat walls, impact law, neighbours, ground motion, integration and a list of cases,
// read through the Io verbs of scene_io.h and turned into a lumped::PoundingScene.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/laws/cor_key.h"
#include "app/laws/impact_scene.h"
#include "app/laws/yielding_wall_scene.h"
#include "app/lumped/building_keys.h"
#include "app/lumped/ground_motion_scene.h"
#include "app/step_budget.h"
#include "io/scene_io.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/isolators/bouc_wen_isolator.h"
#include "lumped/isolators/friction_pendulum_isolator.h"
#include "lumped/structure/pounding_model.h"
#include "lumped/structure/shear_building.h"

namespace kimp::app
{
  enum class BuildingKind
  {
    isolated,
    fixed_base
  };

  enum class IsolatorKind
  {
    linear,
    bilinear,
    friction_pendulum,
    bouc_wen
  };

  enum class IntegrationMethod
  {
    cdm,
    newmark
  };

  /// The storeys of a shear building (thesis Table 4.2), the same keys for the main building and
  /// its neighbours: floor j sits on storey j, the top floor has its own mass.
  struct StoreysScene
  {
    unsigned int n_storeys        = 4;
    double       floor_mass       = 320e3;
    double       top_mass         = 250e3;
    double       storey_stiffness = 600e6;

    /// Masses of floors 1..n_storeys (the last one top_mass), kg.
    std::vector<double> floor_masses() const;
  };

  template <class Io>
  void visit(Io &io, StoreysScene &s)
  {
    io.integer("n_storeys", s.n_storeys, "storeys above the isolation level or the ground", 1, 100);
    visit_mass(io, "floor_mass", s.floor_mass, "mass of every floor below the top");
    visit_mass(io, "top_mass", s.top_mass, "mass of the top floor");
    visit_stiffness(io, "storey_stiffness", s.storey_stiffness, "shear stiffness of each storey");
  }

  /// The main building (thesis Table 4.2): its storeys, isolation level and damping ratios.
  struct BuildingScene : StoreysScene
  {
    BuildingKind kind                     = BuildingKind::isolated;
    double       isolation_mass           = 320e3;
    double       damping_ratio            = 0.02; ///< ζ_sstr of an isolated building
    double       fixed_base_damping_ratio = 0.05; ///< ζ of a fixed-base building
  };

  template <class Io>
  void visit(Io &io, BuildingScene &s)
  {
    io.choice("kind",
              s.kind,
              {{"isolated", BuildingKind::isolated}, {"fixed_base", BuildingKind::fixed_base}},
              "isolated (isolation level = DOF 0) or fixed_base (floors on the ground)");
    visit(io, static_cast<StoreysScene &>(s));
    visit_mass(io, "isolation_mass", s.isolation_mass, "mass of the isolation level (base mat)");
    visit_damping_ratio(
      io,
      "damping_ratio",
      s.damping_ratio,
      "superstructure damping of an isolated building (Rayleigh, first and last mode)");
    visit_damping_ratio(io,
                        "fixed_base_damping_ratio",
                        s.fixed_base_damping_ratio,
                        "damping of a fixed-base building (Rayleigh, first and last mode)");
  }

  /// The friction coefficients of a friction pendulum (mu_slow, mu_fast): 0 <= mu < 1.
  inline io::Range friction_pendulum_mu_range()
  {
    return io::Range::at_least(0.0).and_less(1.0);
  }

  /// Isolation system: linear (k), bilinear (K1, K2, Q), friction pendulum (radius, friction) or
  /// Bouc-Wen (K1, K2, Q and A, beta, gamma, n), plus ζ_iso (docs/physics.md §2, "Isolators").
  struct IsolatorScene
  {
    IsolatorKind          kind    = IsolatorKind::bilinear;
    double                K1      = 200e6;
    double                K2      = 25e6;
    double                Q_ratio = 0.1;        ///< Q / W_tot (W_tot incl. the isolation level)
    std::optional<double> Q;                    ///< characteristic strength, N (overrides Q_ratio)
    double                k             = 25e6; ///< linear isolator stiffness, N/m
    double                damping_ratio = 0.05; ///< ζ_iso
    // friction pendulum
    std::optional<double> weight;          ///< W on the bearings, N (null: g·Σm)
    double                radius  = 2.236; ///< R, m (T = 2π√(R/g) ≈ 3 s)
    double                mu_slow = 0.04;
    double                mu_fast = 0.08;
    double                rate    = 20.0; ///< a of μ(v), s/m
    double                k_init  = 1e9;  ///< sticking stiffness, N/m
    // Bouc-Wen
    double bw_A     = 1.0;
    double bw_beta  = 0.5;
    double bw_gamma = 0.5;
    double bw_n     = 2.0;
  };

  template <class Io>
  void visit(Io &io, IsolatorScene &s)
  {
    io.choice("kind",
              s.kind,
              {{"bilinear", IsolatorKind::bilinear},
               {"linear", IsolatorKind::linear},
               {"friction_pendulum", IsolatorKind::friction_pendulum},
               {"bouc_wen", IsolatorKind::bouc_wen}},
              "bilinear hysteretic (K1, K2, Q), linear (k), friction_pendulum (radius, mu_slow, "
              "mu_fast, rate, k_init) or bouc_wen (K1, K2, Q, A, beta, gamma, n)");
    visit_stiffness(io, "K1", s.K1, "bilinear, bouc_wen: initial stiffness");
    visit_stiffness(io,
                    "K2",
                    s.K2,
                    "bilinear, bouc_wen: post-yield stiffness (< K1; post-yield ratio K2/K1)",
                    io::Range::non_negative());
    io.quantity("Q_ratio",
                s.Q_ratio,
                "%",
                "bilinear, bouc_wen: characteristic strength / total weight (yield force "
                "F_y = Q/(1 - K2/K1))",
                io::Range::greater(0.0).and_less(1.0));
    io.quantity("Q",
                s.Q,
                "kN",
                "bilinear, bouc_wen: characteristic strength (overrides Q_ratio)",
                io::Range::positive());
    visit_stiffness(io, "k", s.k, "linear: stiffness");
    visit_damping_ratio(
      io,
      "damping_ratio",
      s.damping_ratio,
      "isolation damping zeta_iso (>= building.damping_ratio); c_iso = 2(zeta_iso - "
      "zeta_sstr)sqrt(m_tot k), k = initial stiffness");
    io.quantity("weight",
                s.weight,
                "kN",
                "friction_pendulum: weight W on the bearings (null = g x total mass)",
                io::Range::positive().because("or null"));
    io.quantity("radius",
                s.radius,
                "m",
                "friction_pendulum: effective radius R (pendulum period 2 pi sqrt(R/g))",
                io::Range::positive());
    io.quantity("mu_slow",
                s.mu_slow,
                "",
                "friction_pendulum: friction coefficient at low sliding velocity",
                friction_pendulum_mu_range());
    io.quantity("mu_fast",
                s.mu_fast,
                "",
                "friction_pendulum: friction coefficient at high sliding velocity (>= mu_slow)",
                friction_pendulum_mu_range());
    io.quantity("rate",
                s.rate,
                "s/m",
                "friction_pendulum: a in mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|)",
                io::Range::non_negative());
    visit_stiffness(io,
                    "k_init",
                    s.k_init,
                    "friction_pendulum: elastic stiffness before sliding (stick regularisation)");
    io.quantity("A",
                s.bw_A,
                "",
                "bouc_wen: Bouc-Wen A (1: yield force F_y)",
                io::Range::positive());
    io.quantity("beta",
                s.bw_beta,
                "",
                "bouc_wen: Bouc-Wen beta (>= |gamma|)",
                io::Range::non_negative());
    // Unbounded: gamma may be negative (softening); beta + gamma > 0 is checked in validate().
    io.quantity("gamma", s.bw_gamma, "", "bouc_wen: Bouc-Wen gamma (beta + gamma > 0)");
    io.quantity("n",
                s.bw_n,
                "",
                "bouc_wen: exponent n, sharpness of yielding (large n: bilinear)",
                io::Range::at_least(1.0));
  }

  /// One moat wall at the isolation level: rigid (moving with the ground) or a SDOF oscillator.
  struct WallScene
  {
    bool                  present       = true;
    double                gap           = 0.15;
    double                mass          = 500e3;
    bool                  flexible      = false;
    double                stiffness     = 1.5e9; ///< SDOF wall, N/m (thesis k_w = 1500 kN/mm)
    double                damping_ratio = 0.05;  ///< SDOF wall ζ
    std::optional<double> sdof_mass; ///< SDOF wall's mass, kg (null: mass; not in m_eff)
    /// A yielding wall: the wall-and-backfill part behind the impact law (absent: rigid or
    /// flexible wall).
    std::optional<YieldingWallScene> yielding;
  };

  template <class Io>
  void visit(Io &io, WallScene &s)
  {
    io.flag("present", s.present, "is there a wall on this side");
    visit_moat_gap(io, "gap", s.gap, "distance isolation level - wall face (before bumpers)");
    visit_mass(io,
               "mass",
               s.mass,
               "wall mass for m_eff in the impact law (and the SDOF mass of a flexible wall "
               "without sdof_mass)");
    io.flag("flexible",
            s.flexible,
            "false: rigid wall moving with the ground; true: SDOF wall (sdof_mass or mass, "
            "stiffness, damping_ratio) attached to the ground");
    visit_mass(io,
               "sdof_mass",
               s.sdof_mass,
               "flexible or yielding wall: the DOF's mass (null: mass); the impact law keeps the "
               "m_eff of mass, so its dashpot is the rigid wall's");
    visit_stiffness(io,
                    "stiffness",
                    s.stiffness,
                    "flexible wall: stiffness to the ground at the slab level");
    visit_damping_ratio(io,
                        "damping_ratio",
                        s.damping_ratio,
                        "flexible wall: damping ratio of the SDOF (c = 2 zeta sqrt(k m))");
    io.optional_section("yielding",
                        s.yielding,
                        "yielding wall: the impact law in series with a wall-and-backfill part "
                        "(pushover with permanent set, radiation dashpot) on a DOF of sdof_mass "
                        "(null: mass); excludes flexible");
  }

  struct WallsScene
  {
    WallScene left;
    WallScene right;
    bool      basement = false;
  };

  template <class Io>
  void visit(Io &io, WallsScene &s)
  {
    io.section("left", s.left, "wall on the left (-x) side");
    io.section("right", s.right, "wall on the right (+x) side");
    io.flag("basement", s.basement, "the walls also reach floor 1 (impacts at DOF 0 and 1)");
  }

  /// A fixed-base neighbour; its floor j faces floor j of the main building.
  struct NeighbourScene : StoreysScene
  {
    bool                          present       = false;
    double                        separation    = 0.15;
    double                        damping_ratio = 0.05;
    std::optional<ImpactLawScene> impact;
  };

  template <class Io>
  void visit(Io &io, NeighbourScene &s)
  {
    io.flag("present", s.present, "is there a neighbour on this side");
    io.quantity("separation",
                s.separation,
                "cm",
                "clear distance between facing floors",
                io::Range::positive());
    visit(io, static_cast<StoreysScene &>(s));
    visit_damping_ratio(io,
                        "damping_ratio",
                        s.damping_ratio,
                        "Rayleigh damping, first and last mode");
    io.optional_section("impact", s.impact, "impact law of the floor contacts (default: impact)");
  }

  struct NeighboursScene
  {
    NeighbourScene left;
    NeighbourScene right;
  };

  template <class Io>
  void visit(Io &io, NeighboursScene &s)
  {
    io.section("left", s.left, "neighbour on the left (-x) side");
    io.section("right", s.right, "neighbour on the right (+x) side");
  }

  /// Time integration (lumped::CentralDifferenceOptions / NewmarkOptions).
  struct IntegrationScene
  {
    IntegrationMethod method = IntegrationMethod::cdm;
    std::string       dt     = "auto";
    double            safety = 0.5;
    /// `dt: auto` (cdm): steps per contact half-period π/ω_imp (lumped::AdaptiveStepOptions).
    double                contact_steps            = 80.0;
    double                expected_max_penetration = 0.05;
    double                output_interval          = 0.01;
    lumped::LawVelocity   law_velocity             = lumped::LawVelocity::backward;
    std::optional<double> duration;
    bool                  companion = false;
    /// Refuse a case of more steps than this before it starts (docs/physics.md, "Run budget" in
    /// "Ground-motion records").
    double max_steps = 2e8;
    /// A case whose peak |displacement| or |absolute acceleration| exceeds these is failed as
    /// implausible (a wrong unit or scale), m and m/s².
    double plausible_displacement = 10.0;
    double plausible_acceleration = 200.0 * 9.80665;
  };

  template <class Io>
  void visit(Io &io, IntegrationScene &s)
  {
    io.choice("method",
              s.method,
              {{"cdm", IntegrationMethod::cdm}, {"newmark", IntegrationMethod::newmark}},
              "cdm: central difference (explicit, dt below the contact limit); newmark: average "
              "acceleration with Newton at contacts");
    io.quantity_text("dt",
                     s.dt,
                     "s",
                     "time step: \"auto\" (cdm: variable, large steps between contacts and "
                     "contact_steps steps per contact pulse, with an error estimate; newmark: the "
                     "record's dt), \"stable\" (cdm: the fixed step safety x dt_cr dividing the "
                     "record's dt) or a time such as \"2e-5 s\"",
                     io::Range::plausible(1e-9, 1.0, "a building's time step"));
    io.quantity("safety",
                s.safety,
                "",
                "cdm auto and stable steps: fraction of dt_cr",
                io::Range::greater(0.0).and_at_most(1.0));
    io.quantity("contact_steps",
                s.contact_steps,
                "",
                "cdm dt auto: steps per contact half-period pi/omega_imp",
                io::Range::at_least(4.0));
    io.quantity("expected_max_penetration",
                s.expected_max_penetration,
                "mm",
                "cdm: penetration at which the contact tangent enters dt_cr",
                io::Range::positive());
    io.quantity("output_interval",
                s.output_interval,
                "s",
                "history sampling; 0 = no histories",
                io::Range::non_negative());
    io.choice("law_velocity",
              s.law_velocity,
              {{"backward", lumped::LawVelocity::backward},
               {"backward_second_order", lumped::LawVelocity::backward_second_order}},
              "cdm: rate given to the laws, (u_n - u_n-1)/dt (thesis) or second order");
    io.quantity("duration",
                s.duration,
                "s",
                "analysis length (null = the record's length)",
                io::Range::positive().because("or null"));
    io.flag("companion", s.companion, "also run without contacts (amplification factors)");
    visit_max_steps(io,
                    s.max_steps,
                    "step budget: a case of more time steps is refused before it starts, with the "
                    "estimate (steps x DoFs, time)");
    io.quantity("plausible_displacement",
                s.plausible_displacement,
                "m",
                "a case whose peak |displacement| exceeds this is failed as implausible",
                io::Range::positive());
    io.quantity("plausible_acceleration",
                s.plausible_acceleration,
                "g",
                "a case whose peak |absolute acceleration| exceeds this is failed as implausible",
                io::Range::positive());
  }

  /**
   * One case: overrides of the scene for one run. Empty text and null keep the scene's value.
   * A case that changes `law` also drops the scene's exponent (the new law's default applies
   * unless the case gives one).
   */
  struct CaseScene
  {
    std::string           name = "case";
    std::string           law  = "";
    std::string           k    = "";
    std::optional<double> exponent;
    std::optional<double> cor;
    std::optional<double> gap;
    std::optional<double> left_gap;
    std::optional<double> right_gap;
    std::optional<double> ground_motion_scale;
    std::optional<double> wall_height; ///< m, impact.k_table's height for this case
    std::string           record = ""; ///< ground_motion.record of this case
  };

  template <class Io>
  void visit(Io &io, CaseScene &s)
  {
    io.text("name", s.name, "case name (HDF5 group /lumped/<name>; letters, digits, _ - .)");
    io.text("law", s.law, "impact law of the walls (\"\" = impact.law)");
    visit_impact_stiffness(io, "k", s.k, "impact stiffness with unit N/m^n (\"\" = impact.k)");
    visit_exponent(io, s.exponent, "impact exponent n (null = the law's default)");
    visit_cor(io, s.cor, "coefficient of restitution (null = impact.cor)");
    visit_moat_gap(io, "gap", s.gap, "gap of both walls (null = walls.*.gap)");
    visit_moat_gap(io, "left_gap", s.left_gap, "gap of the left wall (wins over gap)");
    visit_moat_gap(io, "right_gap", s.right_gap, "gap of the right wall (wins over gap)");
    visit_motion_scale(io,
                       "ground_motion_scale",
                       s.ground_motion_scale,
                       "extra factor on the ground motion of this case (negative flips it)");
    visit_k_source_height(
      io,
      s.wall_height,
      "wall height at which impact.k_table is interpolated (null = impact.wall_height)");
    io.text("record", s.record, "ground motion record of this case (\"\" = ground_motion.record)");
  }

  /// The whole scene of `kimp lumped` (SI members, defaults of docs/physics.md §3).
  struct LumpedScene
  {
    BuildingScene          building;
    IsolatorScene          isolator;
    WallsScene             walls;
    ImpactScene            impact;
    NeighboursScene        neighbours;
    GroundMotionScene      ground_motion;
    IntegrationScene       integration;
    std::vector<CaseScene> cases;
  };

  template <class Io>
  void visit(Io &io, LumpedScene &s)
  {
    io.section("building", s.building, "main building (thesis Table 4.2)");
    io.section("isolator", s.isolator, "isolation system (isolated buildings only)");
    io.section("walls", s.walls, "moat walls at the isolation level (isolated buildings only)");
    io.section("impact", s.impact, "impact law of the walls");
    io.section("neighbours", s.neighbours, "adjacent fixed-base buildings");
    io.section("ground_motion", s.ground_motion, "ground acceleration");
    io.section("integration", s.integration, "time integration and output");
    io.list("cases", s.cases, "runs with overrides (empty: one case named \"default\")");
  }

  /// Every range and cross-field rule (K2 < K1, gap > bumper thickness, k unit vs exponent, ...).
  void validate(const LumpedScene &scene, io::ValidationContext &ctx);

  /// impact.k_table and the records (ground_motion, cases[i].record) resolved against the scene
  /// file's `directory` (io::read_scene_text() calls it after validate()).
  void resolve_paths(LumpedScene &scene, const std::filesystem::path &directory);

  /// The main building as a lumped::ShearBuilding (isolator included when isolated).
  lumped::ShearBuilding make_building(const LumpedScene &scene);

  /// The Bouc-Wen parameters of `isolator` shared equally by n devices (planar: one; in plan:
  /// every isolator position): K1/n, α = K2/K1 and F_y = Q/n/(1 − α), Q the isolation system's
  /// characteristic strength, N.
  lumped::BoucWenParameters
  bouc_wen_parameters(const IsolatorScene &isolator, double Q, double n = 1.0);

  /// The friction pendulum parameters of `isolator` shared equally by n devices: the weight
  /// (isolator.weight, else `weight`, N)/n, R, μ_slow, μ_fast, a and k_init/n.
  lumped::FrictionPendulumParameters
  friction_pendulum_parameters(const IsolatorScene &isolator, double weight, double n = 1.0);

  /// The complete configuration: building, walls (isolated only), neighbours, laws.
  lumped::PoundingScene make_pounding_scene(const LumpedScene &scene);

  /// The case names and the scenes with each case's overrides applied (one "default" case when
  /// `cases` is empty). Applied scenes have no cases of their own.
  std::vector<std::pair<std::string, LumpedScene>> resolve_cases(const LumpedScene &scene);

  /// `scene` with the overrides of `c` applied.
  LumpedScene apply_case(const LumpedScene &scene, const CaseScene &c);

  /// Time step requested by integration.dt: nullopt for "auto" and "stable", else seconds.
  /// @throws UnitError for a text that is neither "auto", "stable" nor a time.
  std::optional<double> requested_time_step(const IntegrationScene &integration);

  /// True when the central difference method runs with variable steps (`dt: auto`, method cdm;
  /// lumped::AdaptiveCentralDifference).
  bool variable_time_step(const IntegrationScene &integration);
} // namespace kimp::app
