// `kimp lumped SCENE.yaml -o DIR`: runs every case of a lumped scene (docs/physics.md §2) and
// writes DIR/lumped.h5 (docs/architecture.md "Results files"), DIR/summary.json and DIR/peaks.csv.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/lumped/lumped_scene.h"
#include "io/summary.h"
#include "lumped/excitation/ground_motion.h"
#include "lumped/integrators/adaptive_step.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/free_run_prefix.h"
#include "lumped/integrators/response.h"
#include "lumped/structure/modal.h"

namespace kimp::app
{
  /// Modal data of one building block of the model.
  struct BuildingModes
  {
    std::string         name;
    std::vector<double> periods;          ///< s, ascending mode number
    double              rayleigh_a = 0.0; ///< 1/s
    double              rayleigh_b = 0.0; ///< s
    double              c_iso      = 0.0; ///< N·s/m
  };

  /// Result of one case; `status` is "ok" or "failed: <reason>" (then response is empty).
  /// A yielding wall's part of a case: its limits, from the model (docs/physics.md §2
  /// "Yielding moat wall"); the run's values are in the response's contact `contact`.
  struct YieldingWallLimits
  {
    std::string wall;                       ///< "left_wall", "right_wall"
    std::size_t contact              = 0;   ///< index of its "<wall>_backfill" contact
    double      capacity             = 0.0; ///< N (bilinear: the cap; hyperbolic: F_ult)
    double      failure_displacement = 0.0; ///< m
  };

  struct LumpedCaseResult
  {
    std::string                     name;
    std::string                     status = "ok";
    lumped::Response                response;
    std::optional<lumped::Response> companion; ///< without contacts, if requested
    std::vector<BuildingModes>      buildings;
    std::vector<std::string>        contact_names;
    std::vector<int>                storey_upper_dofs; ///< global DOF above each storey
    std::vector<std::string>        dof_labels;        ///< "building floor 1", ... per global DOF
    std::vector<std::string>        storey_labels;     ///< "building storey 1", ... per storey
    std::string                     isolator;          ///< isolator name ("" without isolator)
    double                          dt_critical = 0.0; ///< s (cdm), 0 for newmark
    std::string                     governing;         ///< bound governing dt_critical
    double                          wall_time       = 0.0; ///< s
    double                          pga             = 0.0; ///< of the motion used, m/s²
    double                          estimated_steps = 0.0; ///< before the run (0: unknown)
    /// How Δt was chosen: "fixed" (integration.dt a time), "stable" (cdm, safety·Δt_cr),
    /// "variable" (cdm `dt: auto`, lumped::AdaptiveCentralDifference) or "record" (newmark auto).
    std::string dt_policy;
    /// The variable-step run's steps and estimated errors (dt_policy "variable").
    std::optional<lumped::AdaptiveStepReport> adaptive;
    /// The yielding walls of the model, left first.
    std::vector<YieldingWallLimits> yielding_walls;

    bool ok() const { return status == "ok"; }
  };

  /// A yielding wall at the end of a run (a planar wall, or a wall face in plan), SI: what
  /// lumped.h5, summary.json and the Python module give of it.
  struct YieldingWallRecord
  {
    double                peak_force            = 0.0; ///< peak contact force on the wall, N
    double                capacity              = 0.0; ///< of the wall-and-backfill part, N
    double                peak_resistance       = 0.0; ///< N
    double                peak_displacement     = 0.0; ///< m
    double                residual_displacement = 0.0; ///< the permanent set, m
    double                failure_displacement  = 0.0; ///< m
    std::optional<double> failure_time;                ///< s (unset: not failed)
    double                plastic_work  = 0.0;         ///< J
    double                radiated_work = 0.0;         ///< J
  };

  /// The record of a case's yielding wall `w`: its part's values from the part's contact result
  /// `part` (response.contacts[w.contact]).
  YieldingWallRecord yielding_wall_record(const YieldingWallLimits    &w,
                                          const lumped::ContactResult &part);

  /// A number of a YieldingWallRecord: its name in summary.json and the Python module (the
  /// datasets of lumped.h5 have the same names), its SI unit and its member.
  struct YieldingWallQuantity
  {
    const char *name;
    const char *unit;
    double YieldingWallRecord::*value;
  };

  /// Every number of the record in its order, but the optional failure_time.
  inline constexpr YieldingWallQuantity yielding_wall_quantities[] = {
    {"peak_force", "N", &YieldingWallRecord::peak_force},
    {"capacity", "N", &YieldingWallRecord::capacity},
    {"peak_resistance", "N", &YieldingWallRecord::peak_resistance},
    {"peak_displacement", "m", &YieldingWallRecord::peak_displacement},
    {"residual_displacement", "m", &YieldingWallRecord::residual_displacement},
    {"failure_displacement", "m", &YieldingWallRecord::failure_displacement},
    {"plastic_work", "J", &YieldingWallRecord::plastic_work},
    {"radiated_work", "J", &YieldingWallRecord::radiated_work}};

  /// A term of a case's energy balance: its name in lumped.h5 `energy` and in the Python module,
  /// its SI unit and its member; a `walls` term is in lumped.h5 only for a case with yielding
  /// walls.
  struct EnergyTerm
  {
    const char *name;
    const char *unit;
    double lumped::EnergyBalance::*value;
    bool                           walls = false;
  };

  /// Every term of lumped::EnergyBalance, in its order.
  const std::vector<EnergyTerm> &energy_terms();

  /// Seconds per DoF and time step assumed by the cost estimate: about twice the cost measured
  /// on the shipped scenes (8-17 ns for the central difference method); Newmark iterates.
  inline constexpr double cdm_seconds_per_dof_step     = 2e-8;
  inline constexpr double newmark_seconds_per_dof_step = 2e-7;
  /// Seconds per DoF and recorded history row (integration.output_interval), measured.
  inline constexpr double history_seconds_per_dof_row = 3e-7;
  /// Memory a case's histories may take, bytes: each row holds about 3 DoFs + 8 values (8 bytes
  /// each) and exists three times at the end (recorder, in-memory HDF5 file, its image).
  inline constexpr double history_memory_budget = 2e9;

  /// Cost of one case, known before it runs.
  struct RunEstimate
  {
    double      dt           = 0.0; ///< time step, s
    double      duration     = 0.0; ///< analysis length, s
    double      n_steps      = 0.0; ///< duration/dt, as a double (it may exceed every integer type)
    std::size_t n_dofs       = 0;
    double      history_rows = 0.0; ///< samples recorded every integration.output_interval
    double      seconds      = 0.0; ///< estimated wall time, s

    /// "2.4e+06 steps of 1e-05 s over 24 s x 5 DoFs = 1.2e+07 DoF-steps, 2.4e+03 history rows,
    /// ~0.24 s".
    std::string text() const;
  };

  /**
   * The estimate of `scene`'s run under `motion` (after the case's scaling): the step the
   * integrator would choose, the duration (integration.duration or the record's length) and
   * the model's DoFs.
   * @throws what the model or the integrator throw for an invalid case.
   */
  RunEstimate estimate_lumped_case(const LumpedScene &scene, const lumped::GroundMotion &motion);

  /**
   * @throws std::runtime_error "case NAME: <estimate> exceeds the step budget
   *   integration.max_steps = N ..." when estimate.n_steps > integration.max_steps, and
   *   "case NAME: R history rows ... need ~M GB ..." when the histories would need more than
   *   history_memory_budget.
   */
  void check_run_budget(const std::string      &name,
                        const RunEstimate      &estimate,
                        const IntegrationScene &integration);

  /**
   * Why `response` is physically implausible ("" if it is not): a peak |displacement| above
   * integration.plausible_displacement or a peak |absolute acceleration| above
   * integration.plausible_acceleration, with the value, the DoF and the limit.
   */
  std::string implausibility(const lumped::Response &response, const IntegrationScene &integration);

  /**
   * Run one resolved case (apply_case() already done) under `motion` (before the case's extra
   * ground_motion_scale, which is applied here through scene.ground_motion.scale relative to
   * `base_scale`). Numerical and model errors, a case above the step budget and an implausible
   * result (check_run_budget(), implausibility()) are caught and recorded in `status`.
   * @param[in] motion     the scene's ground motion after its own scaling and trimming
   * @param[in] base_scale the scene's ground_motion.scale already contained in `motion`
   */
  LumpedCaseResult run_lumped_case(const std::string          &name,
                                   const LumpedScene          &scene,
                                   const lumped::GroundMotion &motion,
                                   double                      base_scale = 1.0);

  /**
   * Supplies the shared contact-free run of a model (lumped::FreeRunPrefix) for the central
   * difference method: `free` is the case's model without contacts with Δt = `dt` set, under
   * `motion`. Returns nullptr when it has none (the case then runs from t = 0). Sweeps pass a
   * cache (app/sweep/sweep_lumped.h), so that cases differing only in gaps or contact laws share
   * one free run, which is also their companion run.
   */
  using FreeRunSource = std::function<
    std::shared_ptr<const lumped::FreeRunPrefix>(const lumped::CentralDifference &free,
                                                 double                           dt,
                                                 const lumped::GroundMotion      &motion)>;

  /// run_lumped_case() with the central difference run (and its companion) taken from
  /// `free_runs` when the case records no histories: bitwise the same results, fewer steps.
  LumpedCaseResult run_lumped_case(const std::string          &name,
                                   const LumpedScene          &scene,
                                   const lumped::GroundMotion &motion,
                                   double                      base_scale,
                                   const FreeRunSource        &free_runs);

  /// Supplies the motion of a synthetic `ground_motion` section (default: load_ground_motion());
  /// the Python module passes a cache of the last one, which gives the same bits.
  using SyntheticMotionSource =
    std::function<std::shared_ptr<const lumped::GroundMotion>(const GroundMotionScene &section)>;

  /// The cases of a lumped scene, run in memory.
  struct LumpedCasesRun
  {
    std::shared_ptr<const lumped::GroundMotion> motion;  ///< the scene's ground_motion
    std::vector<LumpedCaseResult>               results; ///< in case order
  };

  /**
   * Every case of `scene` as `kimp lumped` runs them, without writing a file (run_lumped() and
   * the Python module both run the cases through this):
   * 1. the scene's ground motion and the cases' own records (cases[i].record) are loaded first,
   *    a record that cannot be found or read being an io::SceneError at its key,
   *    "FILE_NAME:LINE: cases[i].record = 'NAME': <problem>" (load_ground_motion_at(), with the
   *    line of the key in `scene_text`);
   * 2. every case's cost is estimated and logged, and a case above the step budget refuses the
   *    whole run before anything is computed (std::runtime_error of check_run_budget());
   * 3. each case runs by run_lumped_case() (failures recorded in its status).
   * @param[in] only_case run only the case of this name (the others are neither loaded nor
   *            checked); std::invalid_argument listing the cases when there is none
   * @param[in] synthetic source of a synthetic motion (empty: load_ground_motion())
   */
  LumpedCasesRun
  run_lumped_cases(const LumpedScene                          &scene,
                   const std::string                          &file_name,
                   const std::string                          &scene_text,
                   const std::optional<std::filesystem::path> &records_dir_override = {},
                   const std::optional<std::string>           &only_case            = {},
                   const SyntheticMotionSource                &synthetic            = {});

  /**
   * run_lumped_cases() of the whole scene, then lumped.h5, summary.json and peaks.csv written
   * into `output`.
   * @return the results, in case order.
   */
  std::vector<LumpedCaseResult>
  run_lumped(const io::LoadedScene<LumpedScene>         &scene,
             const io::OutputDir                        &output,
             const std::optional<std::filesystem::path> &records_dir_override = {});

  /// Register `kimp lumped` (with --records-dir); it exits non-zero when a case failed.
} // namespace kimp::app
