// `kimp lumped` of a scene with a `plan` section (docs/physics.md §7 "Pounding in plan"): one run
// of the plan engine, written as DIR/lumped.h5, DIR/summary.json and DIR/peaks.csv.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/lumped/lumped_run.h"
#include "app/lumped/plan_scene.h"
#include "io/output_dir.h"
#include "lumped/plan/plan_central_difference.h"

namespace kimp::app
{
  /// One plan run in memory.
  struct PlanRun
  {
    lumped::plan::PlanGroundMotion motion;
    lumped::plan::PlanResponse     response;
    std::vector<std::string>       contact_names;
    std::size_t                    n_corners = 0; ///< of level 0's outline
    /// The geometry drawn by the results page's plan view (SI, at rest): level 0's outline and
    /// the point its DoFs refer to (its centre of mass), the moat wall (empty without a moat)
    /// and each contact's material point on the slab.
    lumped::plan::Polygon            slab_outline;
    lumped::plan::Point              slab_reference = lumped::plan::Point::Zero();
    lumped::plan::Polygon            wall;
    std::vector<lumped::plan::Point> contact_positions;
    /// The superstructure's damping model, ζ (every mode with modal damping, per direction with
    /// Rayleigh) and ζ_iso of the isolation level (lumped::plan::PlanBuilding).
    lumped::plan::PlanDampingModel damping       = lumped::plan::PlanDampingModel::rayleigh;
    double                         damping_ratio = 0.0;
    double                         isolation_damping_ratio = 0.0;
    double                         dt_critical             = 0.0;
    double                         wall_time               = 0.0; ///< s
  };

  /// The yielding wall faces of a run (summary.json `yielding_walls`): per face, as the planar
  /// walls, its peak contact force `peak_force` and the wall-and-backfill part's `capacity`,
  /// `peak_resistance` (N) and their ratio, `peak_displacement`, `residual_displacement`,
  /// `failure_displacement` (m; null: no limit), `plastic_work`, `radiated_work` (J), `failed`,
  /// `failure_time` (s, null while standing), with its `face` and `final_displacement` (m).
  nlohmann::json yielding_walls_json(const lumped::plan::PlanResponse &response);

  /// "rayleigh" or "modal" (the scene's `plan.damping`).
  const char *damping_name(lumped::plan::PlanDampingModel model);

  /// The damping model of a run (summary.json `damping`): `model` (damping_name()),
  /// `damping_ratio` and `isolation_damping_ratio`.
  nlohmann::json plan_damping_json(const PlanRun &run);

  /// The energy terms of a run by their names in lumped::plan::PlanEnergy (summary.json `energy`,
  /// the group /lumped/default/energy of lumped.h5), J; the relative errors without unit.
  nlohmann::json plan_energy_json(const lumped::plan::PlanEnergy &energy);

  /// The headline peaks of a plan run (summary.json of `kimp lumped`, the sweep's metrics).
  struct PlanPeaks
  {
    double corner_force   = 0.0; ///< largest contact normal force, N
    double friction_force = 0.0; ///< largest contact friction force, N
    double rotation       = 0.0; ///< largest peak rotation of any level, rad
    double corner_drift   = 0.0; ///< largest peak corner drift, m
  };
  PlanPeaks plan_peaks(const lumped::plan::PlanResponse &response);

  /**
   * Run a scene with a plan section: its motion (load_plan_motion()), its model and options, the
   * step budget (integration.max_steps) checked before the run.
   * @throws io::SceneError for a record, std::runtime_error for a run above the budget, what the
   *         engine throws (TimeStepError, DivergenceError, std::invalid_argument).
   */
  PlanRun run_plan(const PlanLumpedScene                      &scene,
                   const std::string                          &file_name,
                   const std::string                          &scene_text,
                   const std::optional<std::filesystem::path> &records_dir_override = {});

  /**
   * The cost of a plan scene's run under `motion`, known before it runs: its engine's step, the
   * steps over integration.duration (or the motion's), 3 DoFs per level and the cost per
   * DoF-step of lumped_run.h (the plan engine's measured cost is within it).
   * @throws std::invalid_argument what the engine refuses.
   */
  RunEstimate estimate_plan_case(const PlanLumpedScene                &scene,
                                 const lumped::plan::PlanGroundMotion &motion);

  /// run_plan(), then lumped.h5 (/lumped/default, "plan" = 1), summary.json and peaks.csv in
  /// `output`.
  PlanRun run_plan_lumped(const io::LoadedScene<PlanLumpedScene>     &loaded,
                          const io::OutputDir                        &output,
                          const std::optional<std::filesystem::path> &records_dir_override = {});
} // namespace kimp::app
