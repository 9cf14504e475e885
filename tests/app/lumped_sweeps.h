// A lumped sweep run to its table, and the base scenes of such sweeps, for the app tests of sweeps.
#pragma once

#include <filesystem>
#include <string>

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

  /**
   * A lumped base scene of the sweep tests: an isolated building of `n_storeys`, walls at
   * `wall_gap` on both sides, the YAML lines `neighbours` (may be empty), `duration` of the
   * synthetic motion with its pulse at 2 s, integrated by the CDM at `dt` without stored
   * histories and with the companion run.
   */
  inline std::string pulse_sweep_scene(int                n_storeys,
                                       const std::string &wall_gap,
                                       const std::string &neighbours,
                                       const std::string &duration,
                                       const std::string &dt)
  {
    return "building: {kind: isolated, n_storeys: " + std::to_string(n_storeys) +
           "}\nwalls: {left: {gap: " + wall_gap + "}, right: {gap: " + wall_gap + "}}\n" +
           neighbours + "ground_motion:\n  record: synthetic\n  synthetic: {duration: " + duration +
           ", pulse_time: 2 s}\nintegration: {method: cdm, dt: " + dt +
           ", output_interval: 0 s, companion: true}\n";
  }
} // namespace kimp::testing
