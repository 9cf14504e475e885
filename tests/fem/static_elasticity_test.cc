// Static tip stiffness of the moat wall with backfill ("same with soil"): the bonded
// soil adds a parallel support, so the stiffness rises monotonically with the soil modulus and
// stays above the bare-cantilever value (which matches Timoshenko, see impact_test.cc).
#include <gtest/gtest.h>
#include <iostream>

#include "tests/fem/impact_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  TEST(WallWithBackfill, TipStiffnessRisesMonotonicallyWithSoilModulus)
  {
    // docs/physics.md §4 wall (H = 1.25 m, t = 0.25 m) and backfill (2.0 m wide, flush with the
    // top).
    constexpr double   height = 1.25, thickness = 0.25, width = 2.0;
    constexpr unsigned n_thickness = 8;
    const double       k_bare =
      backfilled_wall_tip_stiffness({height, thickness, concrete, 0, 0, soil, n_thickness});
    // Without soil the wall is the bare cantilever.
    EXPECT_DOUBLE_EQ(k_bare, cantilever_tip_stiffness(height, thickness, concrete, n_thickness));
    double k_previous = k_bare;
    if (rank() == 0)
      std::cout << "wall tip stiffness, soil E = 0 (bare): " << k_bare << " N/m per m\n";
    for (const double e_soil : {20e6, 50e6, 100e6, 200e6})
    {
      Material backfill       = soil;
      backfill.youngs_modulus = e_soil;
      const double k          = backfilled_wall_tip_stiffness(
        {height, thickness, concrete, width, height, backfill, n_thickness});
      if (rank() == 0)
        std::cout << "wall tip stiffness, soil E = " << e_soil / 1e6 << " MPa: " << k
                  << " N/m per m (x" << k / k_bare << " bare)\n";
      EXPECT_GT(k, k_previous) << "soil E = " << e_soil << " Pa";
      k_previous = k;
    }
  }

  TEST(WallWithBackfill, SoftSoilTendsToTheBareWall)
  {
    // The soil's contribution is linear in its modulus for a soft soil: E -> 0 recovers the bare
    // wall continuously (1 kPa soil changes the stiffness by < 0.1 %).
    constexpr double tolerance = 1e-3;
    const double     k_bare    = cantilever_tip_stiffness(1.25, 0.25, concrete, 8);
    Material         backfill  = soil;
    backfill.youngs_modulus    = 1e3;
    const double k = backfilled_wall_tip_stiffness({1.25, 0.25, concrete, 2.0, 1.25, backfill, 8});
    EXPECT_NEAR(k / k_bare, 1.0, tolerance) << "k = " << k << ", bare " << k_bare;
    EXPECT_GT(k, k_bare);
  }
} // namespace
