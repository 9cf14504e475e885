// Isolator laws: closed-cycle hysteretic energy 4·Q·(D − D_y) (thesis §3.1), exact tangent,
// trial/commit contract (docs/architecture.md "Tests"), parameter checks.
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <vector>

#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/linear_isolator.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double energy_rel_tol  = 1e-12;
    constexpr double tangent_rel_tol = 1e-6;

    /// Drive the isolator along `path` in steps of at most `max_step`, committing each; returns
    /// ∫F du by the trapezoid rule.
    double drive(Isolator &iso, double &u, const std::vector<double> &path, const double max_step)
    {
      double work = 0.0;
      double f    = iso.set_trial(u, 0.0).force;
      iso.revert_to_last_commit();
      for (const double target : path)
      {
        const int    n  = static_cast<int>(std::ceil(std::abs(target - u) / max_step));
        const double u0 = u;
        for (int i = 1; i <= n; ++i)
        {
          const double un = u0 + (target - u0) * i / n;
          const double fn = iso.set_trial(un, 0.0).force;
          iso.commit();
          work += 0.5 * (f + fn) * (un - u);
          u = un;
          f = fn;
        }
      }
      return work;
    }
  } // namespace

  TEST(BilinearIsolator, ClosedCycleDissipatesLoopArea)
  {
    // Thesis Table 4.2 isolator: K1 200 MN/m, K2 25 MN/m, Q = 1500.9 kN -> D_y = 8.58 mm.
    const double K1 = 200e6, K2 = 25e6, Q = 1500.93e3;
    for (const double D : {0.02, 0.1674, 0.3})
    {
      BilinearIsolator iso(K1, K2, Q);
      const double     dy = Q / (K1 - K2);
      double           u  = 0.0;
      drive(iso, u, {D}, 1e-3);
      const double before = iso.dissipated_energy();
      const double loop   = drive(iso, u, {-D, D}, 1e-3);
      const double cycle  = iso.dissipated_energy() - before;
      const double exact  = 4.0 * Q * (D - dy);
      EXPECT_NEAR(cycle, exact, energy_rel_tol * exact) << "D: " << D;
      // The loop area (∫F du around the cycle, trapezoid rule with step h) is the same energy;
      // the two steps that cross a yield corner err by at most (K1 − K2)·h²/8 each.
      const double h = 1e-3;
      EXPECT_NEAR(loop, exact, 2.0 * (K1 - K2) * h * h / 8.0) << "D: " << D;
      EXPECT_NEAR(iso.yield_force(), Q / (1.0 - K2 / K1), 1e-9 * Q);
    }
  }

  TEST(BilinearIsolator, ReferenceYieldValues)
  {
    const double     q = 0.1 * 9.81 * 1530e3;
    BilinearIsolator iso(200e6, 25e6, q);
    EXPECT_NEAR(q, 1500.9e3, 0.05e3);
    EXPECT_NEAR(iso.yield_force(), 1715.3e3, 0.05e3);
    EXPECT_NEAR(iso.yield_displacement(), 8.58e-3, 0.005e-3);
  }

  TEST(BilinearIsolator, StoredPlusDissipatedEqualsWork)
  {
    BilinearIsolator                       iso(200e6, 25e6, 1.5e6);
    std::mt19937                           rng(42);
    std::uniform_real_distribution<double> dist(-0.2, 0.2);
    double                                 u = 0.0;
    std::vector<double>                    path;
    for (int i = 0; i < 30; ++i)
      path.push_back(dist(rng));
    const double work = drive(iso, u, path, 1e-4);
    // Exact for piecewise-linear F(u) when every step is short: the trapezoid of a step that
    // crosses yield has an O(Δu²) error, hence the tolerance.
    EXPECT_NEAR(iso.stored_energy() + iso.dissipated_energy(), work, 1e-5 * work);
  }

  TEST(BilinearIsolator, TangentIsExactDerivative)
  {
    BilinearIsolator iso(200e6, 25e6, 1.5e6);
    double           u = 0.0;
    drive(iso, u, {0.05, 0.01}, 1e-3);
    // Elastic unloading branch at u = 0.01 and post-yield branch after reloading beyond.
    for (const double trial : {0.012, 0.03, -0.004, 0.2})
    {
      const double h  = 1e-7;
      const auto   r  = iso.set_trial(trial, 0.0);
      const double fp = iso.set_trial(trial + h, 0.0).force;
      const double fm = iso.set_trial(trial - h, 0.0).force;
      EXPECT_NEAR(r.stiffness, (fp - fm) / (2 * h), tangent_rel_tol * 200e6) << "u: " << trial;
    }
  }

  TEST(BilinearIsolator, TrialIsIdempotentAndRevertIsExact)
  {
    BilinearIsolator iso(200e6, 25e6, 1.5e6);
    double           u = 0.0;
    drive(iso, u, {0.1, -0.03}, 1e-3);
    const double e0 = iso.dissipated_energy();
    const auto   a  = iso.set_trial(0.25, 0.0);
    const auto   b  = iso.set_trial(0.25, 0.0);
    EXPECT_EQ(a.force, b.force);
    EXPECT_EQ(a.stiffness, b.stiffness);
    iso.revert_to_last_commit();
    EXPECT_EQ(iso.dissipated_energy(), e0);
    auto copy = iso.clone();
    EXPECT_EQ(copy->set_trial(0.07, 0.0).force, iso.set_trial(0.07, 0.0).force);
    iso.revert_to_start();
    EXPECT_EQ(iso.dissipated_energy(), 0.0);
    EXPECT_EQ(iso.set_trial(1e-3, 0.0).force, 200e6 * 1e-3);
  }

  TEST(BilinearIsolator, RejectsInvalidParameters)
  {
    try
    {
      BilinearIsolator iso(200e6, -3.0, 1e6);
      FAIL() << "negative K2 accepted";
    }
    catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("isolator.K2 = -3"), std::string::npos) << e.what();
    }
    EXPECT_THROW(BilinearIsolator(200e6, 250e6, 1e6), std::invalid_argument);
    EXPECT_THROW(BilinearIsolator(0.0, 0.0, 1e6), std::invalid_argument);
    EXPECT_THROW(BilinearIsolator(200e6, 25e6, 0.0), std::invalid_argument);
    EXPECT_THROW(LinearIsolator(-1.0), std::invalid_argument);
    EXPECT_THROW(LinearIsolator(1e6, -1.0), std::invalid_argument);
  }

  TEST(LinearIsolator, ElasticAndConservative)
  {
    LinearIsolator iso(2e7, 1e5);
    const auto     r = iso.set_trial(0.1, 3.0);
    EXPECT_EQ(r.force, 2e6);
    EXPECT_EQ(r.stiffness, 2e7);
    iso.commit();
    EXPECT_DOUBLE_EQ(iso.stored_energy(), 0.5 * 2e7 * 0.01);
    EXPECT_EQ(iso.dissipated_energy(), 0.0);
    EXPECT_EQ(iso.viscous_coefficient(), 1e5);
  }
} // namespace kimp::lumped
