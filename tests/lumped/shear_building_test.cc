// Shear buildings and the non-classical damping of docs/physics.md §2-3 (thesis Table 4.2,
// eq. 3.1-3.3).
#include <cmath>
#include <gtest/gtest.h>

#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/structure/shear_building.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double period_rel_tol = 0.005; // docs/physics.md §5: T1 = 0.398 s to the digits given
    constexpr double c_iso_rel_tol  = 1e-4;  // 1.0496 MN·s/m to the digits given
    constexpr double rayleigh_abs_tol = 1e-12;
  } // namespace

  TEST(ShearBuilding, FixedBaseFourStoreyFundamentalPeriod)
  {
    const ShearBuilding   b = reference_fixed_base_building(4);
    const BuildingDamping d = building_damping(b);
    EXPECT_NEAR(d.modes.period(0), 0.398, period_rel_tol * 0.398) << "T1: " << d.modes.period(0);
  }

  TEST(ShearBuilding, RayleighRatiosExactAtFirstAndLastMode)
  {
    for (const bool isolated : {false, true})
      for (unsigned int n = 2; n <= 6; ++n)
      {
        const ShearBuilding b =
          isolated ? reference_isolated_building(n) : reference_fixed_base_building(n);
        const BuildingDamping d     = building_damping(b);
        const auto            ratio = [&](const Eigen::Index j)
        {
          const double w = d.modes.omega(j);
          return d.rayleigh.a / (2 * w) + d.rayleigh.b * w / 2;
        };
        const double target = isolated ? 0.02 : 0.05;
        EXPECT_NEAR(ratio(0), target, rayleigh_abs_tol) << "n: " << n << " isolated " << isolated;
        EXPECT_NEAR(ratio(d.modes.omega.size() - 1), target, rayleigh_abs_tol) << "n: " << n;
        // Intermediate modes get less than the target (Rayleigh curve below the chord).
        for (Eigen::Index j = 1; j + 1 < d.modes.omega.size(); ++j)
          EXPECT_LT(ratio(j), target) << "mode " << j;
      }
  }

  TEST(ShearBuilding, IsolationExcessDampingOfTable42)
  {
    const ShearBuilding   b = reference_isolated_building(4);
    const BuildingDamping d = building_damping(b);
    EXPECT_NEAR(b.total_mass(), 1530e3, 1e-9);
    EXPECT_NEAR(d.c_iso, 1.0496e6, c_iso_rel_tol * 1.0496e6) << "c_iso: " << d.c_iso;
    // C[0,0] = a·m0 + b·(K1 + k_storey) + c_iso; the rest is pure Rayleigh.
    const double expected = d.rayleigh.a * 320e3 + d.rayleigh.b * (200e6 + 600e6) + d.c_iso;
    EXPECT_NEAR(d.matrix.diag[0], expected, 1e-9 * expected);
    EXPECT_NEAR(d.matrix.upper[0], -d.rayleigh.b * 600e6, 1e-6);
  }

  TEST(ShearBuilding, StiffnessMatrixOfIsolatedBuilding)
  {
    const ShearBuilding     b = reference_isolated_building(3);
    const TridiagonalMatrix k = stiffness_matrix(b, true);
    ASSERT_EQ(k.size(), 4u);
    EXPECT_EQ(k.diag[0], 200e6 + 600e6);
    EXPECT_EQ(k.diag[1], 1200e6);
    EXPECT_EQ(k.diag[3], 600e6);
    EXPECT_EQ(k.upper[2], -600e6);
    const Eigen::MatrixXd dense = k.to_dense();
    EXPECT_EQ((dense - dense.transpose()).norm(), 0.0);
    EXPECT_EQ(stiffness_matrix(b, false).diag[0], 600e6);
  }

  TEST(ShearBuilding, RejectsInvalidInput)
  {
    ShearBuilding b         = reference_fixed_base_building(3);
    b.storey_stiffnesses[1] = -3.0;
    try
    {
      validate(b);
      FAIL() << "negative storey stiffness accepted";
    }
    catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("storey_stiffnesses[1] = -3"), std::string::npos)
        << e.what();
    }
    b = reference_isolated_building(3);
    b.storey_stiffnesses.push_back(1e8);
    EXPECT_THROW(validate(b), std::invalid_argument);
    b                         = reference_isolated_building(3);
    b.isolation_damping_ratio = 0.01;
    EXPECT_THROW(validate(b), std::invalid_argument);
    EXPECT_THROW(reference_fixed_base_building(0), std::invalid_argument);
  }
} // namespace kimp::lumped
