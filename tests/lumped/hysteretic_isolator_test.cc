// Friction pendulum and Bouc-Wen isolators (docs/physics.md §2, "Isolators") against closed forms:
// the pendulum period 2π√(R/g), the loop areas 4μW(D − u_y) and of the n = 1 Bouc-Wen loop, the
// bilinear limit of Bouc-Wen for large n; the trial/commit contract, exact tangents, and both
// central difference kernels on a building with each isolator (energy balance).
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <memory>
#include <vector>

#include "lumped/excitation/ground_motion.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/bouc_wen_isolator.h"
#include "lumped/isolators/friction_pendulum_isolator.h"
#include "lumped/structure/pounding_model.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::lumped
{
  namespace
  {
    using kimp::testing::zero_motion;

    constexpr double pi = 3.14159265358979323846;

    /// Imposed u(t) = D·sin(2πt/T) for `cycles` cycles in `steps_per_cycle` steps each,
    /// committing every step; returns ∮F du by the trapezoid rule over the last cycle.
    double last_cycle_work(Isolator    &iso,
                           const double D,
                           const double T,
                           const int    cycles,
                           const int    steps_per_cycle)
    {
      const double dt   = T / steps_per_cycle;
      double       u    = 0.0;
      double       f    = 0.0;
      double       work = 0.0;
      for (int cycle = 0; cycle < cycles; ++cycle)
      {
        work = 0.0;
        for (int i = 1; i <= steps_per_cycle; ++i)
        {
          const double t  = (cycle * steps_per_cycle + i) * dt;
          const double un = D * std::sin(2.0 * pi * t / T);
          const double vn = D * 2.0 * pi / T * std::cos(2.0 * pi * t / T);
          const double fn = iso.set_trial(un, vn).force;
          iso.commit();
          work += 0.5 * (f + fn) * (un - u);
          u = un;
          f = fn;
        }
      }
      return work;
    }

    /// Central-difference derivative check of both tangents at the trial state (u, v).
    void expect_exact_tangents(Isolator          &iso,
                               const double       u,
                               const double       v,
                               const double       scale,
                               const std::string &what)
    {
      constexpr double rel = 1e-5; // step 1e-9 m (1e-7 m/s): truncation + round-off
      const auto       r   = iso.set_trial(u, v);
      const double     hu  = 1e-9;
      const double     ku =
        (iso.set_trial(u + hu, v).force - iso.set_trial(u - hu, v).force) / (2.0 * hu);
      const double hv = 1e-7;
      const double cv =
        (iso.set_trial(u, v + hv).force - iso.set_trial(u, v - hv).force) / (2.0 * hv);
      EXPECT_NEAR(r.stiffness, ku, rel * scale) << what;
      EXPECT_NEAR(r.damping, cv, rel * scale) << what;
    }

    /// The contract of docs/architecture.md "Force laws" after a load history.
    void expect_contract(Isolator &iso, const std::string &what)
    {
      for (const double u : {0.02, 0.05, 0.01, -0.04, -0.01})
      {
        iso.set_trial(u, 0.3);
        iso.commit();
      }
      const double e0 = iso.dissipated_energy();
      const double s0 = iso.stored_energy();
      const double f0 = iso.committed_force();
      const auto   a  = iso.set_trial(0.03, 0.2);
      const auto   b  = iso.set_trial(0.03, 0.2);
      EXPECT_EQ(a.force, b.force) << what;
      EXPECT_EQ(a.stiffness, b.stiffness) << what;
      EXPECT_EQ(a.damping, b.damping) << what;
      EXPECT_EQ(iso.dissipated_energy(), e0) << what << ": a trial changed committed state";
      iso.revert_to_last_commit();
      EXPECT_EQ(iso.stored_energy(), s0) << what;
      EXPECT_EQ(iso.committed_force(), f0) << what;
      const auto copy = iso.clone();
      EXPECT_EQ(copy->set_trial(0.07, 0.1).force, iso.set_trial(0.07, 0.1).force) << what;
      copy->commit();
      EXPECT_EQ(iso.dissipated_energy(), e0) << what << ": the clone shares state";
      const double f1 = iso.set_trial(0.031, 0.2).force;
      iso.commit();
      EXPECT_EQ(iso.committed_force(), f1) << what;
      // Dissipation never decreases.
      double previous = iso.dissipated_energy();
      for (int i = 0; i < 200; ++i)
      {
        iso.set_trial(0.08 * std::sin(0.37 * i) * std::cos(0.05 * i), 0.5 * std::cos(0.2 * i));
        iso.commit();
        EXPECT_GE(iso.dissipated_energy(), previous) << what << " step " << i;
        previous = iso.dissipated_energy();
      }
      iso.revert_to_start();
      EXPECT_EQ(iso.dissipated_energy(), 0.0) << what;
      EXPECT_EQ(iso.stored_energy(), 0.0) << what;
      EXPECT_EQ(iso.set_trial(0.0, 0.0).force, 0.0) << what;
    }

    PoundingModel sdof_isolated(const double m, std::shared_ptr<const Isolator> iso)
    {
      TridiagonalMatrix k(1), c(1);
      return PoundingModel({m}, k, c, std::move(iso), {}, {});
    }
  } // namespace

  TEST(FrictionPendulum, FrictionlessFreeVibrationHasPendulumPeriod)
  {
    // m = W/g on a frictionless spherical surface: u = u0·cos(2πt/T), T = 2π√(R/g).
    const double m = 1000e3, R = 2.0, u0 = 0.1;
    const double W = m * standard_gravity;
    const double T = 2.0 * pi * std::sqrt(R / standard_gravity);
    for (const CdmKernel kernel : {CdmKernel::automatic, CdmKernel::reference})
    {
      CentralDifferenceOptions opt;
      opt.dt                   = 1e-3; // T/2837: period error (ωΔt)²/24 ≈ 2e-7
      opt.output_interval      = 1e-3;
      opt.initial_displacement = {u0};
      opt.kernel               = kernel;
      const auto iso           = std::make_shared<FrictionPendulumIsolator>(
        FrictionPendulumParameters{W, R, 0.0, 0.0, 0.0, 1e9});
      const auto  r = CentralDifference(sdof_isolated(m, iso), opt).run(zero_motion(0.01, 10.0));
      const auto &h = r.history;
      // Upward zero crossings of u, linearly interpolated.
      std::vector<double> crossings;
      for (std::size_t i = 1; i < h.time.size(); ++i)
        if (h.displacement[i - 1] < 0.0 && h.displacement[i] >= 0.0)
          crossings.push_back(h.time[i - 1] + (h.time[i] - h.time[i - 1]) * h.displacement[i - 1] /
                                                (h.displacement[i - 1] - h.displacement[i]));
      ASSERT_GE(crossings.size(), 2u);
      const double     period     = (crossings.back() - crossings.front()) / (crossings.size() - 1);
      constexpr double period_tol = 1e-6; // relative; measured −2.0e-7 (CDM period error)
      EXPECT_NEAR(period, T, period_tol * T) << "kernel " << static_cast<int>(kernel);
      EXPECT_NEAR(r.peak_displacement[0], u0, 1e-4 * u0);
      EXPECT_EQ(r.energy.hysteretic, 0.0);
    }
  }

  TEST(FrictionPendulum, ClosedCycleDissipatesRigidPlasticLoopArea)
  {
    // Constant μ: the loop is the elastic-plastic one, area 4μW(D − u_y), u_y = μW/k_init, which
    // tends to the rigid-plastic 4μW·D. The pendulum spring W/R is conservative.
    const double             W = 15e6, R = 2.236, mu = 0.06, k_init = 1e10, D = 0.2;
    FrictionPendulumIsolator iso({W, R, mu, mu, 20.0, k_init});
    const double             uy     = mu * W / k_init;
    const double             exact  = 4.0 * mu * W * (D - uy);
    const double             before = iso.dissipated_energy();
    const double             loop   = last_cycle_work(iso, D, 2.0, 3, 20000);
    // The trapezoid of the two steps that cross a stick-slip corner errs by ≤ k_init·h²/8 each,
    // h ≤ 2πD/20000.
    const double h = 2.0 * pi * D / 20000;
    EXPECT_NEAR(loop, exact, 4.0 * k_init * h * h / 8.0);
    EXPECT_NEAR(loop, 4.0 * mu * W * D, 1e-3 * exact); // rigid-plastic: u_y/D = 4.5e-4
    EXPECT_GT(iso.dissipated_energy(), before);
  }

  TEST(FrictionPendulum, VelocityDependentFriction)
  {
    const double             W = 10e6;
    FrictionPendulumIsolator iso({W, 2.0, 0.03, 0.09, 25.0, 1e9});
    EXPECT_DOUBLE_EQ(iso.friction_coefficient(0.0), 0.03);
    EXPECT_NEAR(iso.friction_coefficient(1.0), 0.09 - 0.06 * std::exp(-25.0), 1e-15);
    EXPECT_DOUBLE_EQ(iso.friction_coefficient(-0.04), iso.friction_coefficient(0.04));
    EXPECT_DOUBLE_EQ(iso.pendulum_stiffness(), W / 2.0);
    // Sliding at v: F = W/R·u + μ(v)·W.
    iso.set_trial(0.1, 0.5);
    iso.commit();
    const auto r = iso.set_trial(0.11, 0.5);
    EXPECT_NEAR(r.force, W / 2.0 * 0.11 + iso.friction_coefficient(0.5) * W, 1e-9 * W);
    expect_exact_tangents(iso, 0.12, 0.5, W, "sliding");
    expect_exact_tangents(iso, 0.12, -0.3, W, "sliding, negative rate");
    // Reversal: sticking (elastic) branch.
    expect_exact_tangents(iso, 0.1099, -0.1, 1e9, "sticking");
  }

  TEST(FrictionPendulum, StickSlipStateOfTheCommittedUpdate)
  {
    // μ·W/k_init = 0.04·15e6/1e9 = 0.6 mm of elastic travel from rest (μ_slow at v = 0).
    FrictionPendulumIsolator iso({15e6, 2.236, 0.04, 0.04, 20.0, 1e9});
    EXPECT_TRUE(iso.stick_slip());
    EXPECT_TRUE(iso.sticking()); // virgin state: elastic
    iso.set_trial(0.5e-3, 0.01);
    iso.commit();
    EXPECT_TRUE(iso.sticking()) << "0.5 mm < 0.6 mm: still elastic";
    iso.set_trial(1.0e-3, 0.01);
    EXPECT_TRUE(iso.sticking()) << "a trial does not change the committed state";
    iso.commit();
    EXPECT_FALSE(iso.sticking()) << "1 mm > 0.6 mm: sliding";
    // Reversal: back on the elastic branch (2·μ·W/k_init = 1.2 mm before sliding again).
    iso.set_trial(0.9e-3, -0.01);
    iso.commit();
    EXPECT_TRUE(iso.sticking());
    iso.revert_to_start();
    EXPECT_TRUE(iso.sticking());
    // Laws without stick-slip keep the defaults.
    const BilinearIsolator b(25e6, 2.5e6, 1e5);
    EXPECT_FALSE(b.stick_slip());
    EXPECT_FALSE(b.sticking());
  }

  TEST(FrictionPendulum, Contract)
  {
    FrictionPendulumIsolator iso({15e6, 2.236, 0.04, 0.08, 20.0, 1e9}, 1e4);
    expect_contract(iso, "friction_pendulum");
    EXPECT_EQ(iso.viscous_coefficient(), 1e4);
    EXPECT_EQ(iso.initial_stiffness(), 1e9 + 15e6 / 2.236);
    EXPECT_EQ(iso.name(), "friction_pendulum");
  }

  TEST(FrictionPendulum, RejectsInvalidParameters)
  {
    try
    {
      FrictionPendulumIsolator iso({15e6, 2.0, 0.08, 0.04, 20.0, 1e9});
      FAIL() << "mu_fast < mu_slow accepted";
    }
    catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("isolator.mu_fast = 0.04"), std::string::npos)
        << e.what();
    }
    EXPECT_THROW(FrictionPendulumIsolator({0.0, 2.0, 0.04, 0.08, 20.0, 1e9}),
                 std::invalid_argument);
    EXPECT_THROW(FrictionPendulumIsolator({1e6, 0.0, 0.04, 0.08, 20.0, 1e9}),
                 std::invalid_argument);
    EXPECT_THROW(FrictionPendulumIsolator({1e6, 2.0, -0.1, 0.08, 20.0, 1e9}),
                 std::invalid_argument);
    EXPECT_THROW(FrictionPendulumIsolator({1e6, 2.0, 0.04, 0.08, -1.0, 1e9}),
                 std::invalid_argument);
    EXPECT_THROW(FrictionPendulumIsolator({1e6, 2.0, 0.04, 0.08, 20.0, 0.0}),
                 std::invalid_argument);
  }

  TEST(BoucWen, LargeExponentGivesTheBilinearLoop)
  {
    // Thesis isolator K1 = 200 MN/m, K2 = 25 MN/m, Q = 1500 kN: the bilinear loop area is
    // 4Q(D − u_y); Bouc-Wen with β = γ = 0.5, A = 1 tends to it as n grows (the rounding of the
    // yield corner shrinks like u_y/n).
    const double K1 = 200e6, K2 = 25e6, Q = 1.5e6, D = 0.15;
    const double alpha = K2 / K1, Fy = Q / (1.0 - alpha), uy = Q / (K1 - K2);
    const double bilinear       = 4.0 * Q * (D - uy);
    double       previous_error = INFINITY;
    for (const double n : {2.0, 10.0, 50.0, 200.0})
    {
      BoucWenIsolator iso({K1, alpha, Fy, 1.0, 0.5, 0.5, n});
      const double    loop  = last_cycle_work(iso, D, 2.0, 3, 20000);
      const double    error = std::abs(loop - bilinear) / bilinear;
      EXPECT_LT(error, previous_error) << "n = " << n;
      previous_error = error;
      // Same strength: the peak force tends to K2·D + Q.
      EXPECT_LT(iso.set_trial(D, 0.0).force, K2 * D + Q * (1.0 + 1e-12)) << "n = " << n;
    }
    constexpr double n200_tol = 1e-5; // measured 1.6e-6 at n = 200 (5.9e-3 at n = 2)
    EXPECT_LT(previous_error, n200_tol);
  }

  TEST(BoucWen, ExponentOneLoopAreaClosedForm)
  {
    // n = 1, β = γ = 0.5, A = 1: unloading dz/du = 1/u_y (z·du < 0), loading
    // dz/du = (1 − |z|)/u_y. Steady loop of amplitude D with tip z_m = 1 − exp(−(2D −
    // z_m·u_y)/u_y): ∮F du = 2Q·(L − u_y·z_m − u_y·z_m²/2), L = 2D − z_m·u_y (the K2 spring is
    // conservative).
    const double K1 = 200e6, alpha = 0.125, Fy = 1.7e6, D = 0.05;
    const double Q = (1.0 - alpha) * Fy, uy = Fy / K1;
    double       zm = 1.0;
    for (int i = 0; i < 200; ++i)
      zm = 1.0 - std::exp(-(2.0 * D - zm * uy) / uy);
    const double     L     = 2.0 * D - zm * uy;
    const double     exact = 2.0 * Q * (L - uy * zm - 0.5 * uy * zm * zm);
    BoucWenIsolator  iso({K1, alpha, Fy, 1.0, 0.5, 0.5, 1.0});
    const double     loop     = last_cycle_work(iso, D, 2.0, 4, 40000);
    constexpr double loop_tol = 1e-4; // backward Euler in z, O(Δu): measured −3.6e-5
    EXPECT_NEAR(loop, exact, loop_tol * exact);
    // Over a closed cycle the stored energy returns: the dissipation equals the loop area.
    const double before = iso.dissipated_energy();
    const double again  = last_cycle_work(iso, D, 2.0, 1, 40000);
    EXPECT_NEAR(iso.dissipated_energy() - before, again, loop_tol * exact);
  }

  TEST(BoucWen, InitialStiffnessTangentsAndContract)
  {
    const double    K1 = 200e6, alpha = 0.125, Fy = 1.7e6;
    BoucWenIsolator iso({K1, alpha, Fy, 1.0, 0.6, 0.4, 2.0});
    EXPECT_DOUBLE_EQ(iso.initial_stiffness(), K1);
    EXPECT_NEAR(iso.set_trial(1e-7, 0.0).force, K1 * 1e-7, 1e-6 * K1 * 1e-7);
    iso.revert_to_last_commit();
    for (const double u : {0.004, 0.02, 0.05})
    {
      iso.set_trial(u, 0.0);
      iso.commit();
    }
    expect_exact_tangents(iso, 0.052, 0.0, K1, "loading");
    expect_exact_tangents(iso, 0.045, 0.0, K1, "unloading");
    expect_exact_tangents(iso, -0.02, 0.0, K1, "reversed");
    expect_contract(iso, "bouc_wen");
    EXPECT_EQ(iso.name(), "bouc_wen");
  }

  TEST(BoucWen, RejectsInvalidParameters)
  {
    EXPECT_THROW(BoucWenIsolator({0.0, 0.1, 1e6}), std::invalid_argument);
    EXPECT_THROW(BoucWenIsolator({1e8, 1.0, 1e6}), std::invalid_argument);
    EXPECT_THROW(BoucWenIsolator({1e8, 0.1, 0.0}), std::invalid_argument);
    EXPECT_THROW(BoucWenIsolator({1e8, 0.1, 1e6, 1.0, 0.2, 0.8}), std::invalid_argument);
    EXPECT_THROW(BoucWenIsolator({1e8, 0.1, 1e6, 1.0, 0.5, 0.5, 0.5}), std::invalid_argument);
  }

  TEST(HystereticIsolators, BothKernelsAgreeAndEnergyBalances)
  {
    // The thesis building on each new isolator under a near-fault pulse: the fused kernel
    // (virtual isolator calls) and the reference kernel give the same response, and
    // E_0 + W_in = E_kin + E_strain + E_viscous + E_hyst closes.
    const GroundMotion  motion = kimp::testing::near_fault_motion(10.0);
    const ShearBuilding base   = reference_isolated_building(4);
    const double        W      = standard_gravity * base.total_mass();
    const std::vector<std::shared_ptr<const Isolator>> isolators = {
      std::make_shared<FrictionPendulumIsolator>(
        FrictionPendulumParameters{W, 2.236, 0.04, 0.08, 20.0, 1e9}),
      std::make_shared<BoucWenIsolator>(
        BoucWenParameters{200e6, 0.125, 0.1 * W / 0.875, 1.0, 0.5, 0.5, 2.0})};
    for (const auto &iso : isolators)
    {
      PoundingScene scene;
      scene.building          = base;
      scene.building.isolator = iso;
      const PoundingModel      model(scene);
      CentralDifferenceOptions opt;
      opt.dt               = 5e-4;
      const Response fused = CentralDifference(model, opt).run(motion);
      opt.kernel           = CdmKernel::reference;
      const Response ref   = CentralDifference(model, opt).run(motion);
      for (std::size_t i = 0; i < fused.peak_displacement.size(); ++i)
        EXPECT_NEAR(fused.peak_displacement[i],
                    ref.peak_displacement[i],
                    1e-9 * ref.peak_displacement[i])
          << iso->name() << " DOF " << i;
      EXPECT_LT(fused.energy.max_relative_error, 0.01) << iso->name();
      EXPECT_GT(fused.energy.hysteretic, 0.1 * fused.energy.input) << iso->name();
      NewmarkOptions nopt;
      nopt.dt                = 2e-3;
      const Response newmark = NewmarkIntegrator(model, nopt).run(motion);
      EXPECT_LT(newmark.energy.relative_error, 0.01) << iso->name();
      EXPECT_NEAR(newmark.peak_displacement[0],
                  fused.peak_displacement[0],
                  0.02 * fused.peak_displacement[0])
        << iso->name();
    }
  }
} // namespace kimp::lumped
