// The lumped engine as a sweep CaseRunner: each case's scene text is read as a
// LumpedScene, run with run_lumped_case() and reduced to one row of scalar metrics.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "app/lumped/lumped_run.h"
#include "app/lumped/plan_run.h"
#include "app/sweep/sweep_engine.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::app
{
  /**
   * Metrics of one lumped case (units in brackets): dt [s], n_steps, per DOF of the model
   * peak_displacement_dof<i> [m] and peak_abs_acceleration_dof<i> [m/s^2], per storey
   * peak_drift_storey<s> [m], max_interstorey_drift [m], n_impacts, per contact
   * <contact>.n_impacts, <contact>.max_impact_velocity [m/s], <contact>.peak_force [N] and
   * <contact>.indentation [m], energy_error (max relative energy residual), <building>.T1 [s]
   * (fundamental period of each building block); with a companion run
   * (integration.companion) also free_peak_displacement_dof<i> [m] and the amplification factors
   * amp_abs_acceleration_dof<i>, amp_drift_storey<s>. `prefix` is put before every name.
   */
  void
  append_lumped_metrics(const LumpedCaseResult &result, const std::string &prefix, CaseRow &row);

  /**
   * Metrics of one run in plan (units in brackets): dt [s], n_steps, the peaks of the
   * directionality chart with the names of `kimp lumped`'s summary.json
   * (base_corner_displacement [m], corner_impact_force [N], friction_force [N],
   * top_acceleration [m/s^2], corner_drift [m], rotation [rad], isolator_force [N]), n_impacts,
   * per level l and direction d (x, y, theta) peak_displacement_level<l>_<d> [m or rad] and
   * peak_abs_acceleration_level<l>_<d> [m/s^2 or rad/s^2], per level
   * peak_corner_displacement_level<l> [m] and peak_horizontal_acceleration_level<l> [m/s^2], per
   * storey peak_drift_x_storey<s>, peak_drift_y_storey<s> and peak_corner_drift_storey<s> [m],
   * per wall face peak_wall_force_face<j> [N], friction_work [J] and energy_error. `prefix` is
   * put before every name.
   */
  void append_plan_metrics(const PlanRun &run, const std::string &prefix, CaseRow &row);

  /**
   * Metrics of the assembled model: per building block <block>.first_dof, <block>.n_dofs and
   * <block>.n_storeys (so that charts can pick the main building's floors), per contact c
   * <c>.clearance [m], the clear gap g_c before contact, and, with a companion run,
   * <c>.srss_gap [m] = sqrt(d_L² + d_R²), the gap the SRSS rule asks for this contact, where d_L,
   * d_R are the peak displacements without contact of the two facing DOFs (0 for a wall moving
   * with the ground). `prefix` is put before every name.
   */
  void append_model_metrics(const lumped::PoundingModel &model,
                            const LumpedCaseResult      &result,
                            const std::string           &prefix,
                            CaseRow                     &row);

  /**
   * A thread-safe cache of contact-free runs (lumped::FreeRunPrefix) keyed by
   * FreeRunPrefix::key(), keeping the `capacity` most recently used ones: the first case of a
   * model computes its free run, the others (other gaps, contact laws, walls) wait for it and
   * share it. A free run that fails (e.g. diverges) is cached as nullptr: its cases run from
   * t = 0 as without the cache.
   */
  class FreeRunCache
  {
  public:
    explicit FreeRunCache(std::size_t capacity = 12);
    ~FreeRunCache();
    FreeRunCache(const FreeRunCache &)            = delete;
    FreeRunCache &operator=(const FreeRunCache &) = delete;

    /// The free run of `free` (Δt = `dt`, s) under `motion`, computed at most once while cached.
    std::shared_ptr<const lumped::FreeRunPrefix>
    get(const lumped::CentralDifference &free, double dt, const lumped::GroundMotion &motion);

    /// Free runs computed so far and cases served from the cache.
    std::size_t computed() const;
    std::size_t served() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };

  /**
   * CaseRunner for LumpedScene texts (with an optional `plan` section: such a scene is one run
   * of the plan engine, append_plan_metrics()). A scene with several `cases` gives one row whose
   * metric names start with "<case name>."; the row fails with the first failing case's status.
   * Cases share recorded ground motions (loaded once per record, scaling and trimming) and,
   * when `share_free_runs` is set, contact-free runs through a FreeRunCache: each central
   * difference case without histories starts at its first possible contact and takes its
   * companion run from the cache (bitwise the same results as running every case alone).
   * A case of the scene with its own record (`cases[i].record`) runs with that record.
   * @param[in] records_dir_override directory of the PEER records (else the scene's default)
   * @param[in] scene_directory directory of the base scene file: relative paths of the case
   *            scenes (impact.k_table, record files) are relative to it
   */
  CaseRunner make_lumped_case_runner(std::optional<std::filesystem::path> records_dir_override = {},
                                     bool                                 share_free_runs = true,
                                     std::filesystem::path                scene_directory = {});
} // namespace kimp::app
