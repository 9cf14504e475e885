// Central difference method (thesis eq. 3.9-3.13) on single-DOF systems against closed forms:
// free and harmonically forced vibration, second-order convergence (MFEM test_ode2 style), the
// stability guard (refusal with both numbers, dt = auto) and divergence detection; the fused
// dense kernel against the block-tridiagonal reference kernel.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/integration_errors.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/lumped_scenes.h"
#include "tests/support/response_compare.h"

namespace kimp::lumped
{
  namespace
  {
    using kimp::testing::expect_identical;
    using kimp::testing::max_relative_difference;
    using kimp::testing::moat_wall;
    using kimp::testing::zero_motion;

    constexpr double free_vibration_tol = 2e-4; // max |u − u_exact| / u0, Δt = T/1000
    constexpr double forced_tol         = 2e-3; // relative to the peak response
    constexpr double min_rate           = 1.9;  // order 2 − 0.1 (docs/architecture.md "Tests")

    PoundingModel
    sdof(const double m, const double k, const double c, std::vector<ContactPair> contacts = {})
    {
      TridiagonalMatrix kk(1), cc(1);
      kk.diag[0] = k;
      cc.diag[0] = c;
      return PoundingModel({m}, kk, cc, nullptr, std::move(contacts), {{-1, 0, "sdof"}});
    }

    ContactPair wall_contact(const ForceLawSpec &spec, const double gap, const double m_eff)
    {
      ContactPair c;
      c.name           = "wall";
      c.left_dof       = 0;
      c.right_dof      = -1;
      c.gap            = gap;
      c.effective_mass = m_eff;
      ForceLawSpec s   = spec;
      s.effective_mass = m_eff;
      c.law            = make_force_law(s);
      return c;
    }

    /// The thesis building between modified Kelvin-Voigt walls (permanent indentation, so the
    /// laws carry history between impacts) under a short synthetic record.
    PoundingModel walled_building(const double gap)
    {
      return PoundingModel(kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, gap));
    }

    /// The same run with the fused kernel (which must be chosen) and the reference kernel.
    double fused_against_reference(const PoundingModel     &model,
                                   CentralDifferenceOptions opt,
                                   const GroundMotion      &g,
                                   const std::string       &what)
    {
      const Response fused = kimp::testing::stepped_run(model, opt, g, true, what);
      opt.kernel           = CdmKernel::reference;
      const double d =
        max_relative_difference(fused,
                                kimp::testing::stepped_run(model, opt, g, false, what),
                                what);
      std::cout << "  fused vs reference, " << what << ": " << d << " (impacts "
                << fused.n_impacts() << ")\n";
      return d;
    }

    /// Options of `kernel` at time step `dt`, the rest at the defaults.
    CentralDifferenceOptions kernel_options(CdmKernel kernel, double dt)
    {
      CentralDifferenceOptions opt;
      opt.dt     = dt;
      opt.kernel = kernel;
      return opt;
    }

    /// The fused kernel (chosen automatically on these models) and the reference kernel.
    const std::pair<CdmKernel, const char *> both_kernels[] = {{CdmKernel::automatic, "fused"},
                                                               {CdmKernel::reference, "reference"}};

    /// Runs of the undamped SDOF (ω = 2π, u_0 = 1 cm) over one period T = 1 s with
    /// Δt = T/20 ... T/320 by `Integrator` with its `Options`: three samples (t = 0, T/2, T),
    /// and the error of u(T) falls at order > min_rate. `check(r, dt)` sees each run first (a
    /// fatal failure in it ends the test).
    template <class Integrator, class Options, class Check>
    void expect_second_order_over_one_period(const Check &check)
    {
      const double m = 1e3, w = 2 * M_PI, u0 = 0.01;
      double       previous = 0.0;
      for (int level = 0; level < 5; ++level)
      {
        const double dt = 1.0 / (20 << level);
        Options      opt;
        opt.dt                   = dt;
        opt.duration             = 1.0;
        opt.output_interval      = 0.5;
        opt.initial_displacement = {u0};
        const Response r = Integrator(sdof(m, m * w * w, 0.0), opt).run(zero_motion(dt, 1.0));
        ASSERT_EQ(r.history.time.size(), 3u);
        ASSERT_NO_FATAL_FAILURE(check(r, dt));
        const double err = std::abs(r.history.displacement[2] - u0);
        if (level > 0)
        {
          const double rate = std::log2(previous / err);
          EXPECT_GT(rate, min_rate) << "dt: " << dt << " error " << err << " previous " << previous;
        }
        previous = err;
      }
    }
  } // namespace

  TEST(CentralDifference, DampedFreeVibrationMatchesClosedForm)
  {
    const double             m = 1e3, w = 2 * M_PI, zeta = 0.05, u0 = 0.01;
    const double             wd = w * std::sqrt(1 - zeta * zeta);
    CentralDifferenceOptions opt;
    opt.dt                   = 1e-3;
    opt.output_interval      = 1e-3;
    opt.initial_displacement = {u0};
    const Response r =
      CentralDifference(sdof(m, m * w * w, 2 * zeta * w * m), opt).run(zero_motion(0.01, 3.0));
    double max_err = 0.0;
    for (std::size_t s = 0; s < r.history.time.size(); ++s)
    {
      const double t = r.history.time[s];
      const double exact =
        std::exp(-zeta * w * t) * (u0 * std::cos(wd * t) + zeta * w * u0 / wd * std::sin(wd * t));
      max_err = std::max(max_err, std::abs(r.history.displacement[s] - exact));
    }
    EXPECT_LT(max_err / u0, free_vibration_tol) << "max error " << max_err;
    EXPECT_LT(r.energy.relative_error, 1e-3);
  }

  TEST(CentralDifference, HarmonicGroundMotionMatchesClosedForm)
  {
    // u'' + 2ζωu' + ω²u = −A·sin(Ωt) from rest: steady state plus the free transient.
    const double m = 2e5, w = 2 * M_PI / 0.5, zeta = 0.05, A = 3.0, W = 2 * M_PI / 0.8;
    const double wd = w * std::sqrt(1 - zeta * zeta);
    const double p = w * w - W * W, q = 2 * zeta * w * W;
    const double c1 = -A * p / (p * p + q * q), c2 = A * q / (p * p + q * q);
    const double d1 = -c2, d2 = (zeta * w * d1 - c1 * W) / wd;
    GroundMotion g;
    g.dt = 2e-4;
    for (int i = 0; i < 30000; ++i)
      g.acceleration.push_back(A * std::sin(W * i * g.dt));
    CentralDifferenceOptions opt;
    opt.dt                 = 2e-4;
    opt.output_interval    = 2e-3;
    const Response r       = CentralDifference(sdof(m, m * w * w, 2 * zeta * w * m), opt).run(g);
    double         max_err = 0.0, peak = 0.0;
    for (std::size_t s = 0; s < r.history.time.size(); ++s)
    {
      const double t = r.history.time[s];
      const double exact =
        c1 * std::sin(W * t) + c2 * std::cos(W * t) +
        std::exp(-zeta * w * t) * (d1 * std::cos(wd * t) + d2 * std::sin(wd * t));
      max_err = std::max(max_err, std::abs(r.history.displacement[s] - exact));
      peak    = std::max(peak, std::abs(exact));
    }
    EXPECT_LT(max_err / peak, forced_tol) << "max error " << max_err << " peak " << peak;
    EXPECT_NEAR(r.peak_displacement[0], peak, forced_tol * peak);
  }

  TEST(CentralDifference, SecondOrderConvergence)
  {
    // Undamped SDOF, one period T = 1 s; error of u(T) for Δt = T/20 ... T/320.
    expect_second_order_over_one_period<CentralDifference, CentralDifferenceOptions>(
      [](const Response &r, double) { ASSERT_NEAR(r.history.time[2], 1.0, 1e-12); });
  }

  TEST(CentralDifference, TimeStepAboveStabilityLimitIsRefused)
  {
    ForceLawSpec spec;
    spec.law                   = "linear";
    spec.stiffness             = 2.5e9; // 2500 kN/mm
    const double         m     = 3.2e5;
    PoundingModel        model = sdof(m, 2e8, 0.0, {wall_contact(spec, 0.1, m * 5e5 / (m + 5e5))});
    const StabilityLimit s     = stability_limit(model, 0.05);
    const double         w_imp = std::sqrt(2.5e9 / (m * 5e5 / (m + 5e5)));
    EXPECT_NEAR(s.omega_impact, w_imp, 1e-9 * w_imp);
    EXPECT_NEAR(s.dt_critical, 2.0 / std::max(w_imp, s.omega_closed), 1e-15);

    CentralDifferenceOptions opt;
    opt.dt = 1.01 * s.dt_critical;
    try
    {
      CentralDifference(model, opt).run(zero_motion(0.01, 1.0));
      FAIL() << "dt above the limit accepted";
    }
    catch (const TimeStepError &e)
    {
      std::ostringstream dt_text, cr_text;
      dt_text << opt.dt;
      cr_text << s.dt_critical;
      const std::string what = e.what();
      EXPECT_NE(what.find(dt_text.str()), std::string::npos) << what;
      EXPECT_NE(what.find(cr_text.str()), std::string::npos) << what;
      EXPECT_NE(what.find("wall"), std::string::npos) << what;
    }
  }

  TEST(CentralDifference, AutoTimeStepIsStableAndDividesRecordStep)
  {
    ForceLawSpec spec;
    spec.law       = "linear";
    spec.stiffness = 2.5e9;
    const double m = 3.2e5, v = 1.0;
    for (const double safety : {0.5, 0.01})
    {
      CentralDifferenceOptions opt;
      opt.initial_velocity = {v};
      opt.safety           = safety;
      const CentralDifference cdm(sdof(m, 0.0, 0.0, {wall_contact(spec, 0.01, m)}), opt);
      const Response          r     = cdm.run(zero_motion(0.01, 0.5));
      const double            ratio = 0.01 / r.dt;
      EXPECT_NEAR(ratio, std::round(ratio), 1e-9);
      EXPECT_LE(r.dt, safety * cdm.stability().dt_critical);
      // Elastic impact on a rigid wall: the mass comes back with its speed. At the default
      // safety (about 3 steps per contact) the run is stable but the onset of contact inside a
      // step costs accuracy; at safety 0.01 the rebound speed and peak force k·v·√(m/k) are
      // within 1 %.
      const double tol = safety == 0.5 ? 0.25 : 0.01;
      ASSERT_EQ(r.contacts[0].impacts.size(), 1u) << "safety " << safety;
      const auto  &u    = r.history.displacement;
      const double vout = (u[u.size() - 1] - u[u.size() - 11]) / (10 * r.history.interval);
      EXPECT_NEAR(vout, -v, tol * v) << "rebound velocity, safety " << safety;
      const double f_exact = v * std::sqrt(2.5e9 * m);
      EXPECT_NEAR(r.contacts[0].peak_force, f_exact, tol * f_exact) << "safety " << safety;
      EXPECT_LT(r.energy.relative_error, 2 * tol) << "safety " << safety;
    }
  }

  TEST(CentralDifference, DivergenceIsReportedWithTimeAndDof)
  {
    // A stiff Hertz contact whose tangent is estimated at a far too small penetration: the guard
    // accepts Δt, the impact then blows up, and the run must stop with an error, not return.
    ForceLawSpec spec;
    spec.law                   = "jankowski";
    spec.stiffness             = 2.37e10;
    spec.cor                   = 0.7;
    const double             m = 1e3;
    CentralDifferenceOptions opt;
    opt.dt                       = 5e-3;
    opt.expected_max_penetration = 1e-12;
    opt.initial_velocity         = {1.0};
    const CentralDifference cdm(sdof(m, 0.0, 0.0, {wall_contact(spec, 0.002, m)}), opt);
    try
    {
      cdm.run(zero_motion(0.01, 2.0));
      FAIL() << "divergent run returned";
    }
    catch (const DivergenceError &e)
    {
      EXPECT_EQ(e.dof, 0);
      EXPECT_GT(e.time, 0.0);
      EXPECT_NE(std::string(e.what()).find("t = "), std::string::npos) << e.what();
    }
  }

  TEST(Newmark, SecondOrderAndEnergyConservingOnLinearSdof)
  {
    // Average acceleration conserves the energy of a linear undamped system exactly.
    expect_second_order_over_one_period<NewmarkIntegrator, NewmarkOptions>(
      [](const Response &r, double dt)
      {
        EXPECT_NEAR(r.energy.kinetic + r.energy.strain, r.energy.initial, 1e-9 * r.energy.initial)
          << "dt: " << dt;
      });
  }

  TEST(Newmark, StableAboveTheExplicitLimit)
  {
    // Building against Hertz-type walls (750 kN/mm^1.5): Newmark at 1.5 × the explicit limit
    // (which the central difference method refuses) runs, balances energy and lands close to a
    // fine explicit reference.
    const GroundMotion  g = kimp::testing::near_fault_motion(10.0);
    const PoundingModel model(
      kimp::testing::walled_scene("jankowski", 750e3 / std::pow(1e-3, 1.5), 0.12));
    const double             dt = 1.5 * stability_limit(model, 0.05).dt_critical;
    CentralDifferenceOptions cdm_opt;
    cdm_opt.dt = dt;
    EXPECT_THROW(CentralDifference(model, cdm_opt).run(g), TimeStepError);
    cdm_opt.dt         = 1e-4;
    const Response ref = CentralDifference(model, cdm_opt).run(g);
    NewmarkOptions opt;
    opt.dt           = dt;
    const Response r = NewmarkIntegrator(model, opt).run(g);
    ASSERT_GT(r.n_impacts(), 0u);
    EXPECT_LT(r.energy.max_relative_error, 0.05);
    EXPECT_NEAR(r.peak_displacement[4], ref.peak_displacement[4], 0.02 * ref.peak_displacement[4])
      << "dt: " << dt;
    EXPECT_NEAR(r.peak_displacement[0], ref.peak_displacement[0], 0.02 * ref.peak_displacement[0])
      << "dt: " << dt;
  }

  TEST(Newmark, ConvergesToTheCentralDifferenceReference)
  {
    const GroundMotion       g = kimp::testing::near_fault_motion(10.0);
    const PoundingModel      model(kimp::testing::walled_scene("kelvin_voigt", 2.5e9, 0.12));
    CentralDifferenceOptions ref_opt;
    ref_opt.dt              = 1e-5;
    ref_opt.output_interval = 0.0;
    const Response ref      = CentralDifference(model, ref_opt).run(g);
    ASSERT_GT(ref.n_impacts(), 0u);
    const auto peak_force = [](const Response &r)
    {
      double f = 0.0;
      for (const ContactResult &c : r.contacts)
        f = std::max(f, c.peak_force);
      return f;
    };
    double previous = INFINITY;
    for (const double dt : {2e-3, 5e-4, 1.25e-4})
    {
      NewmarkOptions opt;
      opt.dt                   = dt;
      opt.output_interval      = 0.0;
      const Response r         = NewmarkIntegrator(model, opt).run(g);
      const double   err_force = std::abs(peak_force(r) - peak_force(ref)) / peak_force(ref);
      const double   err_disp =
        std::abs(r.peak_displacement[4] - ref.peak_displacement[4]) / ref.peak_displacement[4];
      EXPECT_LT(err_force, previous) << "dt: " << dt;
      previous = std::max(err_force, 1e-6);
      if (dt < 2e-4)
      {
        EXPECT_LT(err_force, 0.01) << "dt: " << dt;
        EXPECT_LT(err_disp, 1e-3) << "dt: " << dt;
      }
    }
  }

  TEST(CentralDifferenceStepper, RestartAfterInitReproducesAnUninterruptedRun)
  {
    // Both kernels (the fused one carries u, Δu, peaks and sums in its own state).
    for (const auto &[kernel, name] : both_kernels)
    {
      const GroundMotion       g   = kimp::testing::near_fault_motion(10.0);
      CentralDifferenceOptions opt = kernel_options(kernel, 1e-4);
      opt.initial_displacement     = {0.01, 0.012, 0.014, 0.016, 0.018};
      const CentralDifference cdm(walled_building(0.10), opt);
      const Response          uninterrupted = cdm.run(g);
      ASSERT_GT(uninterrupted.n_impacts(), 1u) << "the restart must cross impacts to mean much";
      const double first_impact = uninterrupted.contacts[0].impacts.empty() ?
                                    uninterrupted.contacts[1].impacts[0].time :
                                    uninterrupted.contacts[0].impacts[0].time;

      CentralDifferenceStepper stepper(cdm);
      stepper.init(g);
      // Run well past the first impact, so that the laws, the isolator and the energy sums all
      // carry history, then restart.
      const long interrupted_at = std::lround(first_impact / opt.dt) + 5000;
      ASSERT_EQ(stepper.advance(interrupted_at), interrupted_at);
      ASSERT_GT(stepper.response().n_impacts(), 0u);
      stepper.init(g);
      EXPECT_EQ(stepper.step_index(), 0);
      EXPECT_EQ(stepper.time(), 0.0);
      EXPECT_EQ(stepper.displacement(), opt.initial_displacement);
      EXPECT_EQ(stepper.response().n_impacts(), 0u);
      EXPECT_EQ(stepper.advance(stepper.last_step() + 100), stepper.last_step() + 1);
      EXPECT_TRUE(stepper.finished());
      expect_identical(stepper.response(),
                       uninterrupted,
                       std::string("restart after init(), ") + name);
    }
  }

  TEST(CentralDifferenceStepper, StepContractHoldsForAnyChunking)
  {
    for (const auto &[kernel, name] : both_kernels)
    {
      // advance(k) and step() in random chunks give exactly run(); each step moves
      // u_n -> u_{n-1}, t_n = n dt exactly, and stepping past the end is refused.
      const GroundMotion       g   = kimp::testing::near_fault_motion(6.0);
      CentralDifferenceOptions opt = kernel_options(kernel, 2e-4);
      opt.output_interval          = 0.0126; // not a divisor of the block or of 512 steps
      const CentralDifference cdm(walled_building(0.06), opt);
      const Response          whole = cdm.run(g);
      ASSERT_GT(whole.n_impacts(), 0u);
      std::mt19937                       rng(20261122);
      std::uniform_int_distribution<int> chunk(0, 700);
      CentralDifferenceStepper           stepper(cdm);
      stepper.init(g);
      while (!stepper.finished())
      {
        const int k = chunk(rng);
        if (k < 50)
        {
          const std::vector<double> u_n = stepper.displacement();
          const long                n   = stepper.step_index();
          stepper.step();
          EXPECT_EQ(stepper.displacement(-1), u_n) << "step " << n;
          EXPECT_EQ(stepper.step_index(), n + 1);
          EXPECT_EQ(stepper.time(), static_cast<double>(n + 1) * stepper.dt()) << "step " << n;
        }
        else
          stepper.advance(k);
      }
      expect_identical(stepper.response(), whole, std::string("random chunks, ") + name);
      EXPECT_THROW(stepper.step(), std::logic_error);
      EXPECT_EQ(stepper.advance(10), 0);
      CentralDifferenceStepper fresh(cdm);
      EXPECT_THROW(fresh.step(), std::logic_error);
    }
  }

  TEST(CentralDifference, ContactWorkAgreesWithTheLawsEnergyBookkeeping)
  {
    // W_contact = Σ∫F dδ, the work the structure does on the contacts (trapezoid over the
    // integrator's steps), against the laws' own Σ(stored + dissipated) (trapezoid over their
    // deformation). With every contact open at the end nothing is stored, so the two differ only
    // by quadrature: a check of both bookkeepings (observed <= 3e-4 of W_in at Δt = 1e-4 s).
    constexpr double   bookkeeping_tol = 1e-3; // relative to W_in
    const GroundMotion g               = kimp::testing::near_fault_motion(12.0);
    for (const std::string law :
         {"kelvin_voigt", "modified_kelvin_voigt", "jankowski", "hertzdamp", "hysteretic"})
    {
      const double stiffness =
        law.find("kelvin") != std::string::npos ? 2.5e9 : 750e3 / std::pow(1e-3, 1.5);
      CentralDifferenceOptions opt;
      opt.dt = 1e-4;
      const Response r =
        CentralDifference(PoundingModel(kimp::testing::walled_scene(law, stiffness, 0.10)), opt)
          .run(g);
      ASSERT_GT(r.n_impacts(), 0u) << law;
      const std::vector<double> &f = r.history.contact_force;
      ASSERT_EQ(f[f.size() - 1], 0.0) << law << ": contact closed at the end";
      ASSERT_EQ(f[f.size() - 2], 0.0) << law << ": contact closed at the end";
      EXPECT_NEAR(r.energy.contact_work,
                  r.energy.impact_dissipated,
                  bookkeeping_tol * r.energy.input)
        << law << ": W_in " << r.energy.input;
      EXPECT_LT(r.energy.max_relative_error, 1e-4) << law;
    }
  }

  TEST(CentralDifference, FusedKernelAgreesWithTheReferenceKernel)
  {
    // Same physics, different algebra (increment form with dense products vs right-hand side
    // and Thomas/dense block solve): the two differ by round-off, which impacts amplify (a contact
    // that closes one step earlier in one of them). Peaks, histories and energies agree within
    // `linear_tol` without contacts and `pounding_tol` with them (observed over 12 s at 1e-4 s:
    // <= 1.3e-9 and <= 4.5e-9, mostly the reference kernel's round-off, see the next tests).
    constexpr double         linear_tol   = 1e-8;
    constexpr double         pounding_tol = 1e-7;
    const GroundMotion       g            = kimp::testing::near_fault_motion(12.0);
    const ForceLawSpec       mkv = kimp::testing::contact_law("modified_kelvin_voigt", 2.5e9);
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;

    PoundingScene bare;
    bare.building = reference_isolated_building(4);
    EXPECT_LT(fused_against_reference(PoundingModel(bare), opt, g, "no walls"), linear_tol);
    PoundingScene linear_iso;
    linear_iso.building = reference_isolated_building_linear(4, 40e6);
    EXPECT_LT(fused_against_reference(PoundingModel(linear_iso), opt, g, "linear isolator"),
              linear_tol);
    PoundingScene fixed;
    fixed.building = reference_fixed_base_building(6);
    EXPECT_LT(fused_against_reference(PoundingModel(fixed), opt, g, "fixed base, 6 storeys"),
              linear_tol);
    CentralDifferenceOptions moving = opt;
    moving.initial_displacement     = {0.01, 0.012, 0.014, 0.016, 0.018};
    moving.initial_velocity         = {0.3, 0.31, 0.32, 0.33, 0.34};
    EXPECT_LT(fused_against_reference(PoundingModel(bare), moving, g, "initial conditions"),
              linear_tol);

    EXPECT_LT(fused_against_reference(walled_building(0.10), opt, g, "walls both sides"),
              pounding_tol);
    PoundingScene basement = bare;
    basement.left_wall     = moat_wall(0.10, mkv);
    basement.right_wall    = moat_wall(0.12, mkv);
    basement.basement      = true;
    EXPECT_LT(fused_against_reference(PoundingModel(basement), opt, g, "basement walls"),
              pounding_tol);
    // The bumper example of the scenes with a smaller gap so that it pounds in 12 s.
    PoundingScene bumpers = bare;
    bumpers.left_wall     = kimp::testing::bumper_wall(0.12);
    bumpers.right_wall    = kimp::testing::bumper_wall(0.12);
    EXPECT_LT(fused_against_reference(PoundingModel(bumpers), opt, g, "bumpers"), pounding_tol);
    PoundingScene    neighbour = bare;
    AdjacentBuilding nb;
    nb.building               = reference_fixed_base_building(3);
    nb.separation             = 0.04;
    nb.law                    = force_law_factory(mkv);
    neighbour.right_neighbour = nb;
    EXPECT_LT(fused_against_reference(PoundingModel(neighbour), opt, g, "neighbour, 8 DOFs"),
              pounding_tol);

    // Beyond 8 DOFs the any-size fused kernel runs (two neighbours: 13 DOFs; anysize_kernel_test).
    neighbour.left_neighbour = nb;
    EXPECT_TRUE(kimp::testing::uses_fused_kernel(PoundingModel(neighbour), opt, g));
  }

  TEST(CentralDifference, FusedKernelIsBitwiseIndependentOfTheVectorWidth)
  {
    // SSE2, AVX2 and AVX-512F variants (those the processor has) do the same per-lane
    // operations without FMA contraction: identical bits.
    const GroundMotion       g = kimp::testing::near_fault_motion(8.0);
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;
    Response sse2;
    ASSERT_NO_FATAL_FAILURE(
      kimp::testing::expect_independent_of_vector_width(walled_building(0.06), opt, g, sse2));
    opt.vector_lanes = 3;
    EXPECT_THROW(CentralDifference(walled_building(0.06), opt), std::invalid_argument);
  }
} // namespace kimp::lumped

namespace kimp::lumped
{
  TEST(CentralDifference, IncrementFormKeepsRoundOffSmallAtTinyTimeSteps)
  {
    // Undamped SDOF from u_0 (T = 1 s): the central difference recurrence has the exact solution
    // u_n = u_0·cos(nθ), sin(θ/2) = ωΔt/2, so any difference from it is round-off. At Δt = 1e-5 s
    // (10^6 steps) the fused kernel's increment form stays within `fused_tol` of u_0 (observed
    // 1e-13), the reference kernel, which solves for u_{n+1} from 2M/Δt²·u_n − ..., loses
    // ~eps·|u|/|Δu| per step (observed 7e-7 over 20 s).
    constexpr double         fused_tol = 1e-11;
    const double             m         = 1e5;
    const double             omega     = 2.0 * M_PI;
    const double             u0        = 0.1;
    const double             dt        = 1e-5;
    CentralDifferenceOptions opt;
    opt.dt                   = dt;
    opt.initial_displacement = {u0};
    const CentralDifference  cdm(sdof(m, m * omega * omega, 0.0), opt);
    CentralDifferenceStepper stepper(cdm);
    stepper.init(zero_motion(0.01, 10.0));
    ASSERT_TRUE(stepper.uses_fused_kernel());
    stepper.advance(stepper.last_step() + 1);
    const Response    r     = stepper.response();
    const long double theta = 2.0L * std::asin(static_cast<long double>(omega * dt) / 2.0L);
    const long        every = std::lround(opt.output_interval / dt);
    double            worst = 0.0;
    for (std::size_t q = 0; q < r.history.time.size(); ++q)
    {
      const long double exact =
        u0 * std::cos(static_cast<long double>(q) * static_cast<long double>(every) * theta);
      worst =
        std::max(worst, static_cast<double>(std::abs(r.history.displacement[q] - exact)) / u0);
    }
    EXPECT_LT(worst, fused_tol) << "steps " << r.n_steps;
  }
} // namespace kimp::lumped
