// The unilateral Coulomb penalty interface of fem/frictional_interface.h on one and two node
// pairs: closure under pressure, no tension on opening, stick then slip at mu N, and the energy
// balance of the interface forces with the stored penalty energy and the friction dissipation.
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>

#include "fem/frictional_interface.h"

namespace
{
  using kimp::fem::FrictionalInterface;

  constexpr double k_n = 1e9, k_t = 5e8, mu = 0.45;

  /** One pair: node 0 (wall) and node 1 (soil), normal +x. */
  FrictionalInterface one_pair()
  {
    FrictionalInterface::Pair p;
    p.a = 0, p.b = 1, p.nx = 1, p.ny = 0;
    p.normal_stiffness = k_n, p.tangential_stiffness = k_t, p.friction = mu;
    return FrictionalInterface({p}, 2);
  }

  TEST(FrictionalInterface, ClosedUnderPressureOpenWithoutTension)
  {
    // Soil node pressed 1 um toward the wall: lambda = k_N p on both, equal and opposite.
    FrictionalInterface c  = one_pair();
    const auto          ev = c.evaluate({0, 0, -1e-6, 0});
    EXPECT_DOUBLE_EQ(ev.normal_force, k_n * 1e-6);
    EXPECT_DOUBLE_EQ(ev.force[2], k_n * 1e-6);
    EXPECT_DOUBLE_EQ(ev.force[0], -k_n * 1e-6);
    EXPECT_EQ(ev.n_closed, 1u);
    c.commit();
    // Pulled apart (wall moved -x): no force at all, also no friction.
    const auto open = c.evaluate({-1e-6, 3e-7, 0, 0});
    EXPECT_EQ(open.normal_force, 0);
    for (const double f : open.force)
      EXPECT_EQ(f, 0);
    EXPECT_EQ(open.n_closed, 0u);
  }

  TEST(FrictionalInterface, TangentialForceSticksThenSlipsAtMuN)
  {
    // Normal force N held by a 1 um penetration; the soil node driven along y in 200 steps to
    // 10 times the stick limit: T = k_T s while |T| < mu N, then mu N (within 1 %, here exact).
    constexpr double    tolerance = 0.01;
    FrictionalInterface c         = one_pair();
    const double        pen = 1e-6, N = k_n * pen, s_stick = mu * N / k_t;
    double              max_stick_error = 0, slip_force = 0;
    for (int i = 1; i <= 200; ++i)
    {
      const double s  = 10 * s_stick * i / 200;
      const auto   ev = c.evaluate({0, 0, -pen, s});
      c.commit();
      if (s < s_stick)
        max_stick_error = std::max(max_stick_error, std::abs(ev.tangential_force - k_t * s));
      slip_force = ev.tangential_force;
      EXPECT_LE(std::abs(ev.tangential_force), mu * ev.normal_force * (1 + 1e-14));
    }
    std::cout << "slip: T = " << slip_force << " N/m vs mu N = " << mu * N << " N/m; stick error "
              << max_stick_error << " N/m; dissipation " << c.committed()[0].dissipation
              << " J/m vs mu N (s - s_stick) = " << mu * N * (9 * s_stick) << '\n';
    EXPECT_NEAR(slip_force, mu * N, tolerance * mu * N);
    EXPECT_LT(max_stick_error, 1e-9 * mu * N);
    EXPECT_NEAR(c.committed()[0].dissipation,
                mu * N * 9 * s_stick,
                tolerance * mu * N * 9 * s_stick);
    // Reversal: elastic unloading at k_T first.
    const auto back = c.evaluate({0, 0, -pen, 10 * s_stick - 0.5 * s_stick});
    EXPECT_NEAR(back.tangential_force, mu * N - 0.5 * k_t * s_stick, 1e-9 * mu * N);
  }

  TEST(FrictionalInterface, WorkOfTheForcesIsStoredEnergyPlusFrictionDissipation)
  {
    // Two pairs on an inclined face driven along a closed loop that presses, slides, reverses,
    // opens and closes again: the work done on the interface, sum of -f . du by the trapezoid
    // rule, equals the stored penalty energy plus the friction dissipation within 1 % of the
    // total work (2000 steps).
    constexpr double          tolerance = 0.01;
    const double              c45       = std::sqrt(0.5);
    FrictionalInterface::Pair p0, p1;
    p0.a = 0, p0.b = 1, p0.nx = c45, p0.ny = c45;
    p1.a = 2, p1.b = 3, p1.nx = c45, p1.ny = c45;
    for (auto *p : {&p0, &p1})
      p->normal_stiffness = k_n, p->tangential_stiffness = k_t, p->friction = mu;
    FrictionalInterface c({p0, p1}, 4);
    const auto          path = [](double t)
    {
      // Soil nodes 1 and 3 move; walls 0 and 2 move a little the other way.
      const double pen   = 2e-6 * std::sin(2 * M_PI * t) + 0.5e-6,
                   slide = 8e-6 * std::sin(3 * M_PI * t);
      const double r     = std::sqrt(0.5);
      return std::vector<double>{0.1 * slide * r,
                                 -0.1 * slide * r,
                                 -pen * r - slide * r,
                                 -pen * r + slide * r,
                                 0,
                                 0,
                                 -0.7 * pen * r + 0.5 * slide * r,
                                 -0.7 * pen * r - 0.5 * slide * r};
    };
    std::vector<double> u_prev = path(0);
    auto                ev     = c.evaluate(u_prev);
    c.commit();
    std::vector<double> f_prev = ev.force;
    double              work = 0, total = 0;
    const int           n = 2000;
    for (int i = 1; i <= n; ++i)
    {
      const auto u = path(static_cast<double>(i) / n);
      ev           = c.evaluate(u);
      c.commit();
      for (std::size_t k = 0; k < u.size(); ++k)
      {
        const double dw = -0.5 * (ev.force[k] + f_prev[k]) * (u[k] - u_prev[k]);
        work += dw;
        total += std::abs(dw);
      }
      u_prev = u;
      f_prev = ev.force;
    }
    const double balance = work - ev.penalty_energy - ev.dissipation;
    std::cout << "interface energy: work " << work << " J/m, stored " << ev.penalty_energy
              << " J/m, friction " << ev.dissipation << " J/m, |balance| / sum |dW| "
              << std::abs(balance) / total << '\n';
    EXPECT_GT(ev.dissipation, 0);
    EXPECT_LT(std::abs(balance), tolerance * total);
  }

  TEST(FrictionalInterface, TangentIsTheDerivativeOfTheForceInEveryState)
  {
    // On an inclined face, open, stick and slip (either sign): the consistent tangent A equals
    // the central difference of -f_b over u_b and of f_b over u_a (relative 1e-6 of k_N); the
    // stick springs whatever the state when asked; and at p = 0 (the backfill placed against
    // the wall) the closed side's stick springs.
    const double              c45 = std::sqrt(0.5);
    FrictionalInterface::Pair p;
    p.a = 0, p.b = 1, p.nx = c45, p.ny = -c45;
    p.normal_stiffness = k_n, p.tangential_stiffness = k_t, p.friction = mu;
    FrictionalInterface c({p}, 2);
    c.evaluate({0, 0, -1e-6 * c45, 1e-6 * c45}); // closed, T = 0
    c.commit();
    const double tx = -p.ny, ty = p.nx;
    // Soil node b moved by (-pen n + s t) from the committed state.
    const auto at = [&](double pen, double s) {
      return std::vector<double>{0,
                                 0,
                                 (-1e-6 - pen) * p.nx + s * tx,
                                 (-1e-6 - pen) * p.ny + s * ty};
    };
    const std::vector<std::pair<const char *, std::vector<double>>> states{
      {"open", at(-2e-6, 0)},
      {"stick", at(0.5e-6, 1e-8)},
      {"slip +", at(0.5e-6, 5e-6)},
      {"slip -", at(0.5e-6, -5e-6)}};
    for (const auto &[name, u] : states)
    {
      const std::array<double, 4> a = c.tangent(0, u, false);
      for (unsigned int j = 0; j < 2; ++j)
      {
        const double        d  = 1e-12;
        std::vector<double> up = u, um = u;
        up[2 + j] += d, um[2 + j] -= d;
        const auto fp = c.evaluate(up).force, fm = c.evaluate(um).force;
        for (unsigned int i = 0; i < 2; ++i)
          EXPECT_NEAR(a[2 * i + j], -(fp[2 + i] - fm[2 + i]) / (2 * d), 1e-6 * k_n)
            << name << " (" << i << ", " << j << ")";
        up = u, um = u;
        up[j] += d, um[j] -= d;
        const auto ga = c.evaluate(up).force, gm = c.evaluate(um).force;
        for (unsigned int i = 0; i < 2; ++i)
          EXPECT_NEAR(-a[2 * i + j], -(ga[2 + i] - gm[2 + i]) / (2 * d), 1e-6 * k_n)
            << name << " over u_a (" << i << ", " << j << ")";
      }
    }
    const std::array<double, 4> stick = c.tangent(0, at(-2e-6, 0), true);
    EXPECT_NEAR(stick[0], k_n * p.nx * p.nx + k_t * tx * tx, 1e-9 * k_n);
    EXPECT_NEAR(stick[1], k_n * p.nx * p.ny + k_t * tx * ty, 1e-9 * k_n);
    FrictionalInterface         fresh({p}, 2);
    const std::array<double, 4> kink = fresh.tangent(0, {0, 0, 0, 0}, false);
    for (unsigned int e = 0; e < 4; ++e)
      EXPECT_DOUBLE_EQ(kink[e], stick[e]);
  }

  TEST(FrictionalInterface, BadPairsAreRefused)
  {
    FrictionalInterface::Pair p;
    p.a = 0, p.b = 1, p.nx = 1, p.ny = 1, p.normal_stiffness = 1, p.tangential_stiffness = 1;
    EXPECT_THROW(FrictionalInterface({p}, 2), std::invalid_argument);
    p.ny = 0, p.friction = -1;
    EXPECT_THROW(FrictionalInterface({p}, 2), std::invalid_argument);
  }
} // namespace
