// `kimp sweep SWEEP.yaml -o DIR`: distributed (MPI ranks x threads), resumable parameter sweeps
// over any scene key; see sweep_plan.h for the sweep file and sweep_engine.h for results.
#pragma once

#include <cstddef>
#include <string>

namespace kimp::app
{
  /// What `kimp sweep` was asked to do (its command-line options).
  struct SweepRunOptions
  {
    std::string  sweep;              ///< sweep file (YAML)
    std::string  output;             ///< output directory
    std::string  records_dir;        ///< PEER records directory; empty: the default search
    unsigned int threads        = 0; ///< per rank; 0: hardware threads / ranks
    bool         retry_failed   = false;
    bool         no_charts      = false;
    bool         no_shared_runs = false; ///< every case from t = 0 (no FreeRunCache)
    /// Budget of time steps over all runs (sweep_estimate.h), refused before planning: about
    /// 10^4 s of one core at 5 DoFs.
    double max_steps = 1e11;
    /// Plan and check only (`--check`): the sweep file, its cost against the budget, every value
    /// and record on the base scene; no output directory, no case run.
    bool check = false;
  };

  /**
   * Run the sweep: this rank's cases on a thread pool (finished cases journaled, so a rerun
   * resumes), then rank 0 merges DIR/sweep.h5 and DIR/sweep.csv and writes the report and charts.
   * Initialises MPI if nobody has. With options.check it returns after the checks of the plan,
   * before the output directory is made.
   * @return the number of cases of the plan.
   */
  std::size_t run_sweep_job(const SweepRunOptions &options);
} // namespace kimp::app
