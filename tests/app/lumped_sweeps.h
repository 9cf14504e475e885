// A lumped sweep run to its table, for the app tests of sweeps.
#pragma once

#include <filesystem>

#include "app/sweep/sweep_engine.h"
#include "app/sweep/sweep_lumped.h"

namespace kimp::testing
{
  /// The table of `plan` run by the lumped case runner (sharing contact-free runs if `shared`) on
  /// `threads` threads into `dir`, which is removed afterwards.
  inline app::SweepTable run_lumped_sweep(const app::SweepPlan        &plan,
                                          const std::filesystem::path &dir,
                                          bool                         shared,
                                          unsigned int                 threads)
  {
    app::SweepOptions options;
    options.threads = threads;
    app::run_sweep(plan, app::make_lumped_case_runner({}, shared), dir, options);
    app::SweepTable table = app::collect_sweep_table(plan, dir);
    std::filesystem::remove_all(dir);
    return table;
  }
} // namespace kimp::testing
