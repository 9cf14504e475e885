// `kimp study [SCENE.yaml] -o DIR` (docs/architecture.md "Data flow of the main job"):
// per wall height FEM -> fitted k (laws 2 and 4) -> k table -> building pounding runs -> files.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/study/pushover_fit.h"
#include "app/study/study_extras.h"
#include "app/study/study_flexible_wall.h"
#include "app/study/study_ladder.h"
#include "app/study/study_laws.h"
#include "app/study/study_scene.h"
#include "app/study/yielding_wall_element.h"
#include "fit/fitter.h"
#include "io/fem_results.h"
#include "io/summary.h"

namespace kimp::app
{
  /** Thesis Table 2.1 (ADINA) at one wall height, kN/mm/m and kN/mm^1.5/m. */
  struct ThesisStiffness
  {
    double wall_height;  ///< m
    double kelvin_voigt; ///< kN/mm per metre
    double jankowski;    ///< kN/mm^1.5 per metre
  };

  /**
   * data/reference/thesis_table_2_1.csv: $KIMP_DATA_DIR/data/reference/,
   * $KIMP_DATA_DIR/reference/, then the source tree kimp was built from.
   */
  std::filesystem::path thesis_table_2_1_file();

  /**
   * Table 2.1 from a CSV file whose first columns are wall_height_m,
   * kelvin_voigt_kN_per_mm_per_m, jankowski_kN_per_mm1.5_per_m (one row per wall height).
   * @throws std::runtime_error naming the file (and line) when it is missing or malformed.
   */
  std::vector<ThesisStiffness> read_thesis_table_2_1(const std::filesystem::path &file);

  /** The rows of Table 2.1 (docs/physics.md §4), read once from thesis_table_2_1_file(). */
  const std::vector<ThesisStiffness> &thesis_table_2_1();

  /** One row of the k table: the fits of one wall height. */
  struct StudyHeight
  {
    double      wall_height = 0.0; ///< m
    std::string name;              ///< "H1.25"
    io::FemCase fem_case;
    bool        fem_from_cache = false;
    double      fem_seconds    = 0.0; ///< s
    double      fit_seconds    = 0.0; ///< s
    /// The fit of each study law, in the order of study_laws() (with the linear counterpart).
    std::vector<StudyLawFit> laws          = unfitted_study_laws();
    bool                     auto_fidelity = false; ///< fidelity: auto (ladder below)
    LadderResult             ladder;                ///< levels climbed (fidelity: auto)
    std::string              fidelity_reason;       ///< why this level (for the log and report)
    /// The k(H, v) axis (app/study/study_velocity.h): impact velocity of the FEM case, m/s, and
    /// whether it is the reference velocity (fem.slab.velocity, where the ladder ran).
    double impact_velocity    = 0.0;
    bool   reference_velocity = true;
    /// Material model of the FEM case: false = linear elastic (also when fidelity: auto chose
    /// linear for an inelastic scene), true = the scene's inelastic soil/concrete models.
    bool        inelastic = false;
    std::string material_reason; ///< why this material model (fidelity: auto), for the report

    /// The entry of the study law named `law` ("kelvin_voigt").
    const StudyLawFit &law(std::string_view name) const { return law_fit(laws, name); }
  };

  /** One building run: a record, a wall height (0: no walls) and a law. */
  struct StudyBuildingRun
  {
    std::string record;
    double      wall_height = 0.0;            ///< m; 0 for the run without walls
    std::string law;                          ///< "none" without walls
    double      k_total                = 0.0; ///< N/m^n of each wall (k_per_m·W)
    double      exponent               = 1.0;
    double      gap                    = 0.0; ///< m, both walls
    double      pga                    = 0.0; ///< m/s²
    double      base_displacement      = 0.0; ///< peak |u_0|, m
    double      top_displacement       = 0.0; ///< m
    double      base_acceleration      = 0.0; ///< peak absolute, m/s²
    double      top_acceleration       = 0.0; ///< m/s²
    double      max_floor_acceleration = 0.0; ///< over the superstructure floors, m/s²
    double      max_interstorey_drift  = 0.0; ///< m
    double      peak_impact_force      = 0.0; ///< N, over both walls
    /// The wall's static collapse load estimate × W, N (app/study/wall_capacity.h; 0: none).
    double      wall_capacity          = 0.0;
    std::size_t n_impacts              = 0;
    double      permanent_indentation  = 0.0; ///< m, larger wall
    double      amplification_base_acc = 1.0; ///< peak / peak without walls
    double      amplification_top_acc  = 1.0;
    double      amplification_drift    = 1.0;
    double      wall_seconds           = 0.0; ///< s
    std::string status                 = "ok";
    bool        flexible_wall          = false; ///< walls: the height's SDOF (else rigid)
    double      peak_wall_displacement = 0.0;   ///< m, flexible walls: larger of the two
    double      energy_error = 0.0; ///< flexible and yielding walls: max relative residual
    /// A yielding wall (law "yielding_wall": an inelastic study's walls, or a linear study's
    /// estimate element beside its laws): the larger wall's values.
    bool        yielding_wall = false;
    std::string wall_source;                        ///< its element's source: pushover or estimate
    double      wall_capacity_per_metre    = 0.0;   ///< its element's capacity, N/m
    double      wall_peak_resistance       = 0.0;   ///< peak R of the wall-and-backfill part, N
    double      wall_residual_displacement = 0.0;   ///< permanent set at the end, m
    bool        wall_failed                = false; ///< pushed past its failure limit
    double      wall_failure_time          = 0.0;   ///< s (wall_failed only)
    double      wall_plastic_work          = 0.0;   ///< J, both walls
    double      wall_radiated_work         = 0.0;   ///< J, both walls
    double      energy_input               = 0.0;   ///< W_in of the run, J
  };

  /** The yielding wall element of one wall height (inelastic studies). */
  struct StudyYieldingWall
  {
    double              wall_height = 0.0; ///< m
    std::string         name;              ///< "H1.25"
    std::string         status = "ok";     ///< "ok" or "failed: ..."
    YieldingWallInputs  inputs;            ///< per metre, what it was derived from
    YieldingWallElement element;           ///< per metre (× width for the wall)
    /** Where the wall-and-backfill part comes from: "pushover" (the height's static pushover,
     *  fitted by fit_pushover()) or "estimate" (yielding_wall_inputs(): the capacity estimate
     *  and the cracked cantilever), and why (the pushover's failure, or what the fit assumed). */
    std::string source = "estimate";
    std::string source_reason;
    double      estimate_capacity = 0.0; ///< the capacity estimate, N/m (for comparison)
    PushoverFit fit;                     ///< source "pushover": the fit and its target point
    std::vector<fem::PushoverPoint> pushover_curve; ///< source "pushover": the curve fitted
    double        pushover_seconds = 0.0; ///< wall time of the pushover (also when it failed), s
    unsigned long pushover_cells   = 0;   ///< cells of the pushover's mesh
    bool          ok() const { return status == "ok"; }
  };

  /** One building run of the consistent-k iteration: k used and the impact velocity found. */
  struct ConsistentKIteration
  {
    double k_total           = 0.0; ///< N/m^n of each wall, the k this run used
    double impact_velocity   = 0.0; ///< largest closing velocity at first contact, both walls, m/s
    double velocity_used     = 0.0; ///< impact_velocity clamped to the table's velocities, m/s
    double k_next            = 0.0; ///< k(H, velocity_used), N/m^n
    double change            = 0.0; ///< |k_next − k_total| / k_total
    double peak_impact_force = 0.0; ///< N
    std::size_t n_impacts    = 0;
  };

  /** The consistent-k iteration of one record, wall height and law. */
  struct ConsistentKRun
  {
    std::string                       record;
    double                            wall_height = 0.0; ///< m
    std::string                       law;
    double                            exponent    = 1.0;
    double                            gap         = 0.0; ///< m
    double                            k_reference = 0.0; ///< k at the reference velocity, N/m^n
    std::vector<ConsistentKIteration> iterations;
    bool                              converged = false;
    std::string                       status = "ok"; ///< "ok", "not converged: ...", "failed: ..."
  };

  /** What run_study() computed. */
  struct StudyResult
  {
    std::vector<StudyHeight>      heights;
    std::vector<StudyBuildingRun> building;
    StudyExtras                   extras; ///< accuracy, stability and sensitivity studies
    /// walls.flexible: each height's wall SDOF, and the building runs against it (rows as in
    /// `building`, flexible_wall = true, amplification against the same run without walls)
    std::vector<StudyWallSdof>    wall_sdofs;
    std::vector<StudyBuildingRun> flexible_building;
    /// Each height's yielding wall element: with inelastic materials `building` runs with it
    /// instead of the laws; in a linear study it is the estimate, run beside the laws.
    std::vector<StudyYieldingWall> yielding_walls;
    double                         flexible_wall_seconds = 0.0; ///< s, SDOFs and their runs
    double                         fem_seconds           = 0.0; ///< s, all heights
    double                         fit_seconds           = 0.0; ///< s
    double                         building_seconds      = 0.0; ///< s
    double                         charts_seconds        = 0.0; ///< s
    double                         wall_seconds          = 0.0; ///< s, whole study
    std::vector<std::string>       warnings; ///< e.g. requested records not found (report.md)
    /// The k(H, v) cases at the velocities other than the reference (study_velocity.h).
    std::vector<StudyHeight> velocity_cases;
    /// The consistent-k iterations of the building runs (study_velocity.h).
    std::vector<ConsistentKRun> consistent_k;
  };

  /**
   * Run the study of `scene` into `output`: DIR/fem/H<H>.{h5,key} (FEM cache), DIR/mesh/,
   * DIR/k_table.csv, DIR/building_response.csv, DIR/study.h5, DIR/summary.json, DIR/report.md
   * and (scene.charts, python3 with matplotlib and h5py) PNG and SVG charts under DIR/charts. Rank
   * 0 only. A failed fit or building run is a row with its status; a failed FEM height is an error.
   */
  StudyResult run_study(const io::LoadedScene<StudyScene> &scene, const io::OutputDir &output);


  /**
   * `kimp study` on every rank of MPI_COMM_WORLD (MPI initialised): the heights are shared by the
   * ranks (rank r computes heights r, r + N, ... into the FEM cache), then rank 0 runs
   * run_study() into `output_dir` (created by rank 0 first).
   */
  void run_study_job(const io::LoadedScene<StudyScene> &scene,
                     const std::filesystem::path       &output_dir);
} // namespace kimp::app
