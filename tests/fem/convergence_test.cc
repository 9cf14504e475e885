// Mesh convergence of the docs/physics.md §4 scene (H = 1.25 m, elastic slab): peak force and
// contact duration change < 2 % between the two finest contact sizes. Slow (label `slow`).
#include <gtest/gtest.h>
#include <iostream>

#include "tests/fem/impact_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  TEST(MeshConvergence, PeakForceAndDurationConvergeAtH125)
  {
    constexpr double          tolerance = 0.02;
    std::vector<ImpactResult> results;
    for (const double h : {0.05, 0.025, 0.0125})
    {
      auto p = scene_parameters(h, false, "scene_h" + std::to_string(h) + ".msh", 0.1);
      results.push_back(run_impact(p, MPI_COMM_WORLD, nullptr));
      if (rank() == 0)
        std::cout << "h = " << h << " m: " << summary_line(results.back()) << '\n';
    }
    const auto &fine = results[2].summary, &medium = results[1].summary;
    EXPECT_NEAR(fine.peak_force / medium.peak_force, 1.0, tolerance);
    EXPECT_NEAR(fine.contact_duration / medium.contact_duration, 1.0, tolerance);
    EXPECT_NEAR(fine.impulse / medium.impulse, 1.0, tolerance);
    EXPECT_NEAR(fine.apparent_cor / medium.apparent_cor, 1.0, tolerance);
  }
} // namespace
