// Cost of a sweep known before its cases are enumerated, and its step budget (--max-steps).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "app/lumped/lumped_run.h"

namespace kimp::app
{
  /// The base scene's cost times the number of runs.
  struct SweepEstimate
  {
    std::size_t n_cases       = 0; ///< sweep cases, companions included
    std::size_t runs_per_case = 1; ///< the scene's own cases (`cases`), x 2 with a companion
    RunEstimate base;              ///< one run of the base scene
    double      total_steps = 0.0;
    double      seconds     = 0.0; ///< on one core

    /// "200000 cases x 1 run x (4.8e+05 steps of ... ~0.5 s) = 9.6e+10 steps, ~1e+05 s of one
    /// core (the base scene's estimate; cases that change dt or the duration differ)".
    std::string text() const;
  };

  /**
   * The estimate of `n_cases` sweep cases over the base scene `scene_text` (named `scene_name`,
   * paths relative to its directory), or nothing when the base scene alone cannot be run (a
   * record that only the sweep sets): then only the number of cases is known.
   */
  std::optional<SweepEstimate>
  estimate_sweep(std::size_t                                 n_cases,
                 const std::string                          &scene_text,
                 const std::string                          &scene_name,
                 const std::optional<std::filesystem::path> &records_dir);

  /**
   * @throws std::invalid_argument "<sweep file>: the estimate (<estimate>) exceeds the step budget
   * of the sweep
   *         (--max-steps = N) ..." when estimate.total_steps > max_steps.
   */
  void check_sweep_budget(const std::string   &sweep_file,
                          const SweepEstimate &estimate,
                          double               max_steps);
} // namespace kimp::app
