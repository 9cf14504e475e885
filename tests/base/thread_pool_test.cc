// base::for_each_index (base/thread_pool.h): every index exactly once on several threads, the
// caller's `beside` work before its share, a stop that leaves the rest untaken, and the first
// exception rethrown after the join.
#include <atomic>
#include <chrono>
#include <gtest/gtest.h>
#include <stdexcept>
#include <thread>
#include <vector>

#include "base/thread_pool.h"

namespace
{
  using kimp::base::for_each_index;

  TEST(ThreadPool, EveryIndexRunsExactlyOnceAndBesideRunsOnTheCaller)
  {
    constexpr std::size_t         n = 1000;
    std::vector<std::atomic<int>> hits(n);
    bool                          beside_ran = false;
    for_each_index(
      n,
      4,
      [&](std::size_t i)
      {
        ++hits[i];
        return true;
      },
      [&] { beside_ran = true; });
    EXPECT_TRUE(beside_ran);
    for (std::size_t i = 0; i < n; ++i)
      EXPECT_EQ(hits[i], 1) << i;
    // No items: beside still runs, work never.
    beside_ran = false;
    for_each_index(
      0,
      3,
      [](std::size_t) -> bool { throw std::logic_error("no item"); },
      [&] { beside_ran = true; });
    EXPECT_TRUE(beside_ran);
  }

  TEST(ThreadPool, AFalseOrAnExceptionStopsTheCounterAndTheExceptionIsRethrown)
  {
    // Items of 20 us each, so that the stop's own few microseconds let at most a few more run.
    constexpr std::size_t n    = 2000;
    const auto            item = [] { std::this_thread::sleep_for(std::chrono::microseconds(20)); };
    std::atomic<std::size_t> ran{0};
    for_each_index(n,
                   2,
                   [&](std::size_t i)
                   {
                     ++ran;
                     item();
                     return i != 10;
                   });
    // Index 10 stops the counter: the other threads finish the items they hold (out of 2000).
    EXPECT_LT(ran.load(), 50u);
    ran = 0;
    EXPECT_THROW(for_each_index(n,
                                3,
                                [&](std::size_t i)
                                {
                                  ++ran;
                                  item();
                                  if (i == 5)
                                    throw std::runtime_error("item 5");
                                  return true;
                                }),
                 std::runtime_error);
    EXPECT_LT(ran.load(), 50u);
    EXPECT_THROW(for_each_index(
                   n,
                   2,
                   [](std::size_t) { return true; },
                   [] { throw std::runtime_error("beside"); }),
                 std::runtime_error);
  }
} // namespace
