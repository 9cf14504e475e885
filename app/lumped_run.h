// `kimp lumped SCENE.yaml -o DIR`: runs every case of a lumped scene (docs/physics.md §2) and
// writes DIR/lumped.h5 (docs/architecture.md "Results files"), DIR/summary.json and DIR/peaks.csv.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/lumped_scene.h"
#include "io/summary.h"
#include "lumped/excitation/ground_motion.h"
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
    double                          wall_time = 0.0;   ///< s
    double                          pga       = 0.0;   ///< of the motion used, m/s²

    bool ok() const { return status == "ok"; }
  };

  /**
   * Run one resolved case (apply_case() already done) under `motion` (before the case's extra
   * ground_motion_scale, which is applied here through scene.ground_motion.scale relative to
   * `base_scale`). Numerical and model errors are caught and recorded in `status`.
   * @param[in] motion     the scene's ground motion after its own scaling and trimming
   * @param[in] base_scale the scene's ground_motion.scale already contained in `motion`
   */
  LumpedCaseResult run_lumped_case(const std::string          &name,
                                   const LumpedScene          &scene,
                                   const lumped::GroundMotion &motion,
                                   double                      base_scale = 1.0);

  /**
   * Run every case of `scene` and write lumped.h5, summary.json and peaks.csv into `output`.
   * @return the results, in case order.
   */
  std::vector<LumpedCaseResult>
  run_lumped(const io::LoadedScene<LumpedScene>         &scene,
             const io::OutputDir                        &output,
             const std::optional<std::filesystem::path> &records_dir_override = {});

  /// Register `kimp lumped` (with --records-dir); it exits non-zero when a case failed.
} // namespace kimp::app
