// Recalibration of C_imp (thesis eqs. 2.18-2.23): energy-matched a1 per grid point, log-space
// power-law fit against the thesis' 1.55 / 0.7076 / 0.0025 / 0.9755, Brent's root finder.
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

#include "lumped/collision/cimp_calibration.h"
#include "lumped/laws/hysteretic_law.h"

namespace
{
  using namespace kimp::lumped;

  CalibrationOptions small_grid()
  {
    CalibrationOptions o;
    o.cor_grid      = {0.3, 0.5, 0.7, 0.9};
    o.velocity_grid = {0.5, 1.5, 2.5};
    o.mass_grid     = {100e3, 400e3, 1000e3};
    return o;
  }

  TEST(BrentRoot, FindsTheRootOfCosXMinusX)
  {
    constexpr double root = 0.7390851332151607; // Dottie number
    std::size_t      n    = 0;
    const auto       f    = [&n](double x)
    {
      ++n;
      return std::cos(x) - x;
    };
    const double x = brent_root(f, {0.0, 1.0, f(0.0), f(1.0)}, {1e-14, 0.0, 100});
    EXPECT_NEAR(x, root, 1e-13);
    EXPECT_LT(n, 15u) << "superlinear convergence expected";
    EXPECT_THROW(brent_root(f, {2.0, 3.0, f(2.0), f(3.0)}, {1e-12, 0.0, 100}),
                 std::invalid_argument);
  }

  TEST(CimpCalibration, CalibratedA1MatchesTheEnergyLossAndTheCor)
  {
    constexpr double         energy_tolerance = 1e-6; // relative, Brent stops at 1e-7
    constexpr double         cor_tolerance    = 1e-3; // ΔKE = loop area to ~1e-4 at Δt = 2e-5 s
    const CalibrationOptions options          = small_grid();
    const CalibrationResult  result           = calibrate_impact_coefficient(options);
    ASSERT_EQ(result.points.size(), 36u);
    for (const auto &p : result.points)
    {
      TwoBodySetup setup;
      setup.mass_1     = p.mass;
      setup.mass_2     = options.other_mass;
      setup.velocity_1 = p.impact_velocity;
      setup.time_step  = options.time_step;
      const auto r =
        simulate_two_body(HystereticLaw({options.stiffness, 1.5, p.cor, p.effective_mass, p.a1}),
                          setup);
      const double target =
        0.5 * p.effective_mass * (1.0 - p.cor * p.cor) * std::pow(p.impact_velocity, 2);
      EXPECT_NEAR(r.dissipated_energy, target, energy_tolerance * target)
        << "COR " << p.cor << " v " << p.impact_velocity << " m1 " << p.mass;
      EXPECT_NEAR(r.effective_cor, p.cor, cor_tolerance * p.cor)
        << "COR " << p.cor << " v " << p.impact_velocity << " m1 " << p.mass;
      EXPECT_LT(p.n_evaluations, 30u);
    }
  }

  TEST(CimpCalibration, FitIsScaleFreeAndCloseToTheThesis)
  {
    // Dimensional analysis: with F = k·δ^n·(1 + C·δ̇) the COR depends on C·v_imp only, so the
    // exact exponents are p3 = 1 and p2 = 0; the thesis' 0.9755 and 0.0025 are fit noise.
    // Measured on this grid at Δt = 2e-5 s: c 1.502, p1 0.738, p2 0.0002, p3 0.9999,
    // R² 0.99997.
    constexpr double        p3_tolerance = 0.01;
    constexpr double        p2_tolerance = 0.003;
    constexpr double        p1_thesis = 0.7076, p1_tolerance = 0.04;
    constexpr double        c_thesis = 1.55, c_tolerance = 0.05;
    const CalibrationResult r = calibrate_impact_coefficient(small_grid());
    std::cout << "c " << r.c << " p1 " << r.p1 << " p2 " << r.p2 << " p3 " << r.p3 << " R2 "
              << r.r_squared << " max COR error (2.23) " << r.max_cor_error_thesis << " fit "
              << r.max_cor_error_fit << "\n";
    EXPECT_NEAR(r.p3, 1.0, p3_tolerance);
    EXPECT_NEAR(r.p2, 0.0, p2_tolerance);
    EXPECT_NEAR(r.p1, p1_thesis, p1_tolerance);
    EXPECT_NEAR(r.c, c_thesis, c_tolerance * c_thesis);
    EXPECT_GT(r.r_squared, 0.999);
    // The refitted law holds the COR better than (2.23) does (measured 0.5 % vs 5.5 %).
    EXPECT_LT(r.max_cor_error_fit, 0.015);
    EXPECT_LT(r.max_cor_error_fit, r.max_cor_error_thesis);
    EXPECT_LT(r.max_cor_error_thesis, 0.06);

    // a1·v_imp is the same at every velocity for a given COR and mass (scale freedom).
    std::map<std::pair<double, double>, double> a1_v;
    for (const auto &p : r.points)
    {
      const auto key = std::make_pair(p.cor, p.mass);
      if (!a1_v.count(key))
        a1_v[key] = p.a1 * p.impact_velocity;
      EXPECT_NEAR(p.a1 * p.impact_velocity, a1_v[key], 0.005 * a1_v[key])
        << "COR " << p.cor << " m1 " << p.mass << " v " << p.impact_velocity;
    }
  }

  TEST(CimpCalibration, RejectsDegenerateGrids)
  {
    CalibrationOptions o = small_grid();
    o.mass_grid          = {300e3};
    try
    {
      calibrate_impact_coefficient(o);
      ADD_FAILURE() << "single mass accepted";
    }
    catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("mass_grid"), std::string::npos) << e.what();
    }
    o          = small_grid();
    o.cor_grid = {0.5, 1.0};
    EXPECT_THROW(calibrate_impact_coefficient(o), std::invalid_argument);
  }
} // namespace
