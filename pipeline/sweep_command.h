// `kimp sweep SWEEP.yaml -o DIR`: distributed (MPI ranks x threads), resumable parameter sweeps
// over any scene key (issue 6); see sweep_plan.h for the sweep file and sweep_engine.h for results.
#pragma once

#include <CLI/CLI.hpp>

namespace kimp::pipeline
{
  /// Register `kimp sweep` (options --threads, --retry-failed, --records-dir).
  void register_sweep_command(CLI::App &app);
} // namespace kimp::pipeline
