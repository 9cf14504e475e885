// Central difference method (thesis eq. 3.9-3.13) on single-DOF systems against closed forms:
// free and harmonically forced vibration, second-order convergence (MFEM test_ode2 style), the
// stability guard (refusal with both numbers, dt = auto) and divergence detection.
#include <cmath>
#include <gtest/gtest.h>
#include <sstream>
#include <vector>

#include "lumped/central_difference.h"
#include "lumped/force_law_factory.h"
#include "lumped/integration_errors.h"
#include "lumped/newmark_integrator.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double free_vibration_tol = 2e-4; // max |u − u_exact| / u0, Δt = T/1000
    constexpr double forced_tol         = 2e-3; // relative to the peak response
    constexpr double min_rate           = 1.9;  // order 2 − 0.1 (STYLE.md §6.22)

    PoundingModel
    sdof(const double m, const double k, const double c, std::vector<ContactPair> contacts = {})
    {
      TridiagonalMatrix kk(1), cc(1);
      kk.diag[0] = k;
      cc.diag[0] = c;
      return PoundingModel({m}, kk, cc, nullptr, std::move(contacts), {{-1, 0, "sdof"}});
    }

    GroundMotion zero_motion(const double dt, const double duration)
    {
      GroundMotion g;
      g.dt = dt;
      g.acceleration.assign(static_cast<std::size_t>(std::lround(duration / dt)), 0.0);
      g.name = "zero";
      return g;
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
    const double m = 1e3, w = 2 * M_PI, u0 = 0.01;
    double       previous = 0.0;
    for (int level = 0; level < 5; ++level)
    {
      const double             dt = 1.0 / (20 << level);
      CentralDifferenceOptions opt;
      opt.dt                   = dt;
      opt.duration             = 1.0;
      opt.output_interval      = 0.5;
      opt.initial_displacement = {u0};
      const Response r = CentralDifference(sdof(m, m * w * w, 0.0), opt).run(zero_motion(dt, 1.0));
      ASSERT_EQ(r.history.time.size(), 3u);
      ASSERT_NEAR(r.history.time[2], 1.0, 1e-12);
      const double err = std::abs(r.history.displacement[2] - u0);
      if (level > 0)
      {
        const double rate = std::log2(previous / err);
        EXPECT_GT(rate, min_rate) << "dt: " << dt << " error " << err << " previous " << previous;
      }
      previous = err;
    }
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
    const double m = 1e3, w = 2 * M_PI, u0 = 0.01;
    double       previous = 0.0;
    for (int level = 0; level < 5; ++level)
    {
      const double   dt = 1.0 / (20 << level);
      NewmarkOptions opt;
      opt.dt                   = dt;
      opt.duration             = 1.0;
      opt.output_interval      = 0.5;
      opt.initial_displacement = {u0};
      const Response r = NewmarkIntegrator(sdof(m, m * w * w, 0.0), opt).run(zero_motion(dt, 1.0));
      ASSERT_EQ(r.history.time.size(), 3u);
      const double err = std::abs(r.history.displacement[2] - u0);
      if (level > 0)
      {
        EXPECT_GT(std::log2(previous / err), min_rate) << "dt: " << dt;
      }
      previous = err;
      // Average acceleration conserves the energy of a linear undamped system exactly.
      EXPECT_NEAR(r.energy.kinetic + r.energy.strain, r.energy.initial, 1e-9 * r.energy.initial)
        << "dt: " << dt;
    }
  }

  TEST(Newmark, StableAboveTheExplicitLimit)
  {
    // Building against Hertz-type walls (750 kN/mm^1.5): Newmark at 1.5 × the explicit limit
    // (which the central difference method refuses) runs, balances energy and lands close to a
    // fine explicit reference.
    SyntheticMotionSpec gs;
    gs.duration          = 10.0;
    const GroundMotion g = synthetic_near_fault(gs);
    ForceLawSpec       spec;
    spec.law       = "jankowski";
    spec.stiffness = 750e3 / std::pow(1e-3, 1.5);
    spec.cor       = 0.7;
    MoatWall w;
    w.gap = 0.12;
    w.law = force_law_factory(spec);
    PoundingScene scene;
    scene.building   = reference_isolated_building(4);
    scene.left_wall  = w;
    scene.right_wall = w;
    const PoundingModel      model(scene);
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
    SyntheticMotionSpec gs;
    gs.duration          = 10.0;
    const GroundMotion g = synthetic_near_fault(gs);
    ForceLawSpec       spec;
    spec.law       = "kelvin_voigt";
    spec.stiffness = 2.5e9;
    spec.cor       = 0.7;
    MoatWall w;
    w.gap = 0.12;
    w.law = force_law_factory(spec);
    PoundingScene scene;
    scene.building   = reference_isolated_building(4);
    scene.left_wall  = w;
    scene.right_wall = w;
    const PoundingModel      model(scene);
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
} // namespace kimp::lumped
