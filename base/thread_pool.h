// Indices [0, n) run on a few threads that pull them from one atomic counter: the sweep's cases
// of a rank, the study's yielding-wall building runs. Header-only, the standard library only.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace kimp::base
{
  /**
   * Calls work(i) for every i in [0, n) on n_threads threads (at least 1, the caller's
   * among them), each pulling the next index from a shared counter, so that long and short
   * items balance. The other threads start at once; the caller first runs `beside` (if set,
   * other work that shares the cores), then pulls indices too, and returns when every thread
   * has joined. work() returns false to stop every thread taking further indices (those in
   * flight finish). An exception of `beside` or `work` stops the counter the same way and is
   * rethrown (the first one) after the join.
   */
  inline void for_each_index(std::size_t                             n,
                             std::size_t                             n_threads,
                             const std::function<bool(std::size_t)> &work,
                             const std::function<void()>            &beside = {})
  {
    std::atomic<std::size_t> next{0};
    std::exception_ptr       failure;
    std::atomic_flag         failed    = ATOMIC_FLAG_INIT;
    const auto               stop_with = [&](std::exception_ptr e)
    {
      if (!failed.test_and_set())
        failure = e;
      next = n;
    };
    const auto pull = [&]()
    {
      try
      {
        for (std::size_t i = next++; i < n; i = next++)
          if (!work(i))
            next = n;
      }
      catch (...)
      {
        stop_with(std::current_exception());
      }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < n_threads; ++t)
      pool.emplace_back(pull);
    try
    {
      if (beside)
        beside();
    }
    catch (...)
    {
      stop_with(std::current_exception());
    }
    pull();
    for (std::thread &thread : pool)
      thread.join();
    if (failure)
      std::rethrow_exception(failure);
  }
} // namespace kimp::base
