// Scene of `kimp study` (issue 5): FEM wall-height cases -> fitted k (PHYSICS.md §4) -> the
// isolated building of PHYSICS.md §2-3 pounding on moat walls with each height's k.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pipeline/fit.h"
#include "pipeline/ground_motion_scene.h"
#include "pipeline/lumped_scene.h"
#include "pipeline/scene_io.h"
#include "pipeline/with_fem/fem_scene.h"

namespace kimp::pipeline
{
  /** The FEM scene of the study: PHYSICS.md §4 defaults with H = 1.00, 1.25, 1.50, 2.00 m. */
  FemScene default_study_fem_scene();

  /** The fits of every height (PHYSICS.md §4 "Fit"). */
  struct StudyFitScene
  {
    double cor       = 0.7;                   ///< COR of both fitted laws, (0, 1]
    double width     = thesis_building_width; ///< building side W, m: k_total = k_per_m·W
    bool   raw_force = false; ///< fit the raw instead of the smoothed FEM contact force
    /// Contact window from the force alone (the FEM indentation of a chattering rigid slab turns
    /// negative while the force is still on, which would cut the window at the first bounce).
    bool   force_only_contact  = true;
    double separation_fraction = 1.0; ///< FitOptions::separation_fraction (> 0)
  };

  template <class Io>
  void visit(Io &io, StudyFitScene &s)
  {
    io.quantity("cor", s.cor, "", "COR of the fitted Kelvin-Voigt and Jankowski laws, (0, 1]");
    io.quantity("width",
                s.width,
                "m",
                "building side width W: k_total = k_per_metre x W (> 0; 27.78 m gives the "
                "thesis' Table 2.2 from Table 2.1)");
    io.flag("raw_force", s.raw_force, "fit the raw FEM contact force instead of the smoothed one");
    io.flag("force_only_contact",
            s.force_only_contact,
            "contact window from the force alone (true) or from the FEM indentation (false)");
    io.quantity("separation_fraction",
                s.separation_fraction,
                "",
                "a contact ends at a force-free run longer than this fraction of its duration so "
                "far (> 0; larger merges the bounces of one impact)");
  }

  /** Moat walls of the study: on both sides, gap from the building's own no-wall response. */
  struct StudyWallsScene
  {
    double                mass          = 500e3; ///< m_wall, kg (> 0)
    double                gap_reduction = 0.10;  ///< gap = (1 − r)·peak isolation displacement
    std::optional<double> gap; ///< fixed gap of both walls, m (overrides gap_reduction)
  };

  template <class Io>
  void visit(Io &io, StudyWallsScene &s)
  {
    io.quantity("mass", s.mass, "t", "wall mass for m_eff in the impact laws (> 0)");
    io.quantity("gap_reduction",
                s.gap_reduction,
                "%",
                "gap = (1 - gap_reduction) x the no-wall peak isolation displacement of each "
                "record (in [0, 1))");
    io.quantity("gap", s.gap, "cm", "fixed gap of both walls (null: from gap_reduction; > 0)");
  }

  /**
   * The study scene. Load with read_scene<StudyScene>(file) (validated); an empty document is
   * the default study.
   */
  struct StudyScene
  {
    FemScene                       fem = default_study_fem_scene();
    StudyFitScene                  fit;
    BuildingScene                  building;
    IsolatorScene                  isolator;
    StudyWallsScene                walls;
    IntegrationScene               integration;
    std::vector<GroundMotionScene> records{GroundMotionScene{}};
    /// Add the PEER records of peer_record_names() when the records directory holds them.
    bool        peer_records = true;
    std::string records_dir  = "";   ///< "" = KIMP_RECORDS_DIR / ../shared/data/records
    bool        charts       = true; ///< run scripts/study_charts.py
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
            "directory of the PEER records (\"\" = KIMP_RECORDS_DIR or ../shared/data/records)");
    io.flag("charts", s.charts, "draw the charts with scripts/study_charts.py (python3)");
  }

  /** Every range and cross-field rule; key paths as in the file ("walls.gap_reduction"). */
  void validate(const StudyScene &scene, ValidationContext &ctx);

  /** The lumped scene of the study's building without walls, shaken by `record`. */
  LumpedScene study_lumped_scene(const StudyScene &scene, const GroundMotionScene &record);

  /** Records the study runs: scene.records, plus the PEER records found (if peer_records). */
  std::vector<GroundMotionScene> study_records(const StudyScene &scene);
} // namespace kimp::pipeline
