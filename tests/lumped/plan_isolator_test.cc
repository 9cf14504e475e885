// Bidirectional isolators in plan: each reduces to its planar law under motion along one axis
// (any axis), the circular yield surface of the bilinear and friction pendulum laws (dissipation
// per revolution of a circular orbit in closed form), the Park-Wen bound |z| <= 1 and
// non-negative dissipation, and the trial/commit contract.
#include <cmath>
#include <gtest/gtest.h>
#include <random>

#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/bouc_wen_isolator.h"
#include "lumped/isolators/friction_pendulum_isolator.h"
#include "lumped/plan/plan_isolators.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// A random displacement path with reversals, m, sampled every 1 ms.
    std::vector<double> random_path(const unsigned seed, const double amplitude)
    {
      std::mt19937                     rng(seed);
      std::uniform_real_distribution<> target(-amplitude, amplitude);
      std::vector<double>              path = {0.0};
      for (int leg = 0; leg < 12; ++leg)
      {
        const double to = target(rng), from = path.back();
        for (int k = 1; k <= 200; ++k)
          path.push_back(from + (to - from) * k / 200.0);
      }
      return path;
    }

    /// Drive the planar law along the path and the plan law along the direction at `angle`;
    /// the plan force along that direction must equal the planar force, across it vanish.
    void expect_uniaxial(Isolator &planar, PlanIsolator &plan, const double angle, double scale)
    {
      const Point  dir(std::cos(angle), std::sin(angle));
      const auto   path  = random_path(7, 0.3);
      const double dt    = 1e-3;
      double       worst = 0.0, across = 0.0;
      for (std::size_t k = 1; k < path.size(); ++k)
      {
        const double v  = (path[k] - path[k - 1]) / dt;
        const double f1 = planar.set_trial(path[k], v).force;
        planar.commit();
        const Point f2 = plan.set_trial(path[k] * dir, v * dir);
        plan.commit();
        worst  = std::max(worst, std::abs(f2.dot(dir) - f1));
        across = std::max(across, std::abs(f2.x() * dir.y() - f2.y() * dir.x()));
      }
      EXPECT_LT(worst, 1e-9 * scale) << plan.name() << " at " << angle;
      EXPECT_LT(across, 1e-9 * scale) << plan.name() << " at " << angle;
      EXPECT_NEAR(plan.dissipated_energy(),
                  planar.dissipated_energy(),
                  1e-9 * planar.dissipated_energy())
        << plan.name();
      EXPECT_NEAR(plan.stored_energy(), planar.stored_energy(), 1e-9 * scale * 0.3) << plan.name();
    }

    /// Dissipation over the second revolution of the circular orbit u = D·(cos ωt, sin ωt).
    double circular_dissipation(PlanIsolator &iso, const double radius, const int steps)
    {
      // Ramp out radially to the orbit, go round twice; measure the second revolution.
      for (int k = 1; k <= steps; ++k)
      {
        iso.set_trial(Point(radius * k / steps, 0.0), Point(1.0, 0.0));
        iso.commit();
      }
      double start = 0.0;
      for (int k = 1; k <= 2 * steps; ++k)
      {
        const double a = 2.0 * pi * k / steps;
        iso.set_trial(radius * Point(std::cos(a), std::sin(a)),
                      radius * Point(-std::sin(a), std::cos(a)));
        iso.commit();
        if (k == steps)
          start = iso.dissipated_energy();
      }
      return iso.dissipated_energy() - start;
    }
  } // namespace

  TEST(PlanIsolator, UniaxialMotionReproducesThePlanarLaws)
  {
    for (const double angle : {0.0, 0.5 * pi, 0.7})
    {
      BilinearIsolator     b1(200e6, 25e6, 1.5e6);
      PlanBilinearIsolator b2({200e6, 25e6, 1.5e6});
      expect_uniaxial(b1, b2, angle, 1.5e6);
      for (const double n : {1.0, 2.0, 3.5})
      {
        BoucWenIsolator     w1({200e6, 0.125, 1.7e6, 1.0, 0.6, 0.4, n});
        PlanBoucWenIsolator w2({200e6, 0.125, 1.7e6, 1.0, 0.6, 0.4, n});
        expect_uniaxial(w1, w2, angle, 1.7e6);
      }
      FrictionPendulumIsolator     p1({15e6, 2.2, 0.04, 0.08, 30.0, 5e8});
      PlanFrictionPendulumIsolator p2({15e6, 2.2, 0.04, 0.08, 30.0, 5e8});
      expect_uniaxial(p1, p2, angle, 15e6);
    }
  }

  TEST(PlanIsolator, CircularYieldSurfaceDissipatesItsClosedForm)
  {
    // Radial return on a circular orbit of radius D: the elastic part keeps |f_ep|/k_ep = u_y,
    // the plastic displacement runs on a circle of radius √(D² − u_y²): Q·2π·√(D² − u_y²) per
    // revolution; the force has the radial part K2·D + Q·u_y/D and the tangential Q·√(D² − u_y²)/D.
    const double         K1 = 200e6, K2 = 25e6, Q = 1.5e6, D = 0.2;
    PlanBilinearIsolator b({K1, K2, Q});
    const double         uy = Q / (K1 - K2);
    EXPECT_NEAR(circular_dissipation(b, D, 20000),
                Q * 2 * pi * std::sqrt(D * D - uy * uy),
                1e-4 * Q * 2 * pi * D);
    EXPECT_NEAR(b.committed_force().norm(),
                std::hypot(K2 * D + Q * uy / D, Q * std::sqrt(D * D - uy * uy) / D),
                1e-3 * Q);
    // Friction pendulum at constant speed |u̇| = ω·D: μ(|u̇|)·W on the same circle.
    const double                 W = 15e6, k0 = 5e8;
    PlanFrictionPendulumIsolator p({W, 2.2, 0.06, 0.06, 0.0, k0});
    const double                 us = 0.06 * W / k0;
    EXPECT_NEAR(circular_dissipation(p, D, 20000),
                0.06 * W * 2 * pi * std::sqrt(D * D - us * us),
                1e-4 * 0.06 * W * 2 * pi * D);
  }

  TEST(PlanIsolator, ParkWenStaysInsideTheUnitCircleAndDissipates)
  {
    for (const double n : {1.0, 2.0, 4.0})
    {
      PlanBoucWenIsolator              iso({200e6, 0.125, 1.7e6, 1.0, 0.5, 0.5, n});
      double                           previous = 0.0, z_max = 0.0;
      std::mt19937                     rng(3);
      std::uniform_real_distribution<> step(-0.004, 0.004);
      Point                            u = Point::Zero();
      for (int k = 0; k < 20000; ++k)
      {
        u += Point(step(rng), step(rng)) + 0.002 * Point(std::cos(k * 0.01), std::sin(k * 0.013));
        u = u.cwiseMax(-0.4).cwiseMin(0.4);
        iso.set_trial(u, Point::Zero());
        iso.commit();
        z_max = std::max(z_max, iso.committed_z().norm());
        EXPECT_GE(iso.dissipated_energy(), previous - 1e-9) << "n " << n << " step " << k;
        previous = iso.dissipated_energy();
      }
      EXPECT_LE(z_max, 1.0 + 1e-9) << "n " << n;
      EXPECT_GT(z_max, 0.9) << "n " << n;
    }
  }

  TEST(PlanIsolator, TrialsAreIdempotentAndRevertAndCloneKeepTheState)
  {
    std::vector<std::unique_ptr<PlanIsolator>> laws;
    laws.push_back(
      std::make_unique<PlanBilinearIsolator>(BilinearParameters{200e6, 25e6, 1.5e6}, 1e5));
    laws.push_back(std::make_unique<PlanBoucWenIsolator>(BoucWenParameters{200e6, 0.125, 1.7e6}));
    laws.push_back(std::make_unique<PlanFrictionPendulumIsolator>(
      FrictionPendulumParameters{15e6, 2.2, 0.04, 0.08, 30.0, 5e8}));
    for (auto &law : laws)
    {
      law->set_trial(Point(0.05, -0.03), Point(0.2, 0.1));
      law->commit();
      const Point a = law->set_trial(Point(0.09, 0.02), Point(0.3, 0.4));
      const Point b = law->set_trial(Point(0.09, 0.02), Point(0.3, 0.4));
      EXPECT_EQ(a, b) << law->name();
      law->revert_to_last_commit();
      const auto  copy = law->clone();
      const Point c    = copy->set_trial(Point(0.09, 0.02), Point(0.3, 0.4));
      EXPECT_EQ(a, c) << law->name();
      law->revert_to_start();
      EXPECT_EQ(law->committed_force(), Point::Zero()) << law->name();
      EXPECT_EQ(law->dissipated_energy(), 0.0) << law->name();
    }
  }

  TEST(PlanIsolator, BadParametersAreRefusedWithThePlanarMessages)
  {
    const auto message = [](auto make)
    {
      try
      {
        make();
      }
      catch (const std::invalid_argument &e)
      {
        return std::string(e.what());
      }
      return std::string();
    };
    EXPECT_NE(message(
                [] {
                  PlanBilinearIsolator(BilinearParameters{200e6, 250e6, 1e6});
                })
                .find("isolator.K2"),
              std::string::npos);
    EXPECT_NE(message(
                [] {
                  PlanBoucWenIsolator({200e6, 0.1, 1e6, 1.0, 0.2, 0.5});
                })
                .find("isolator.bw_beta"),
              std::string::npos);
    EXPECT_NE(message(
                [] {
                  PlanFrictionPendulumIsolator({15e6, -1.0, 0.04, 0.08, 30, 5e8});
                })
                .find("isolator.radius"),
              std::string::npos);
  }
} // namespace kimp::lumped::plan
