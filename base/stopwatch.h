// Elapsed wall time on the steady clock, the one way kimp times its runs and steps.
#pragma once

#include <chrono>

namespace kimp::base
{
  using SteadyClock = std::chrono::steady_clock;

  /// Seconds elapsed since `start` on the steady clock.
  inline double seconds_since(SteadyClock::time_point start)
  {
    return std::chrono::duration<double>(SteadyClock::now() - start).count();
  }
} // namespace kimp::base
