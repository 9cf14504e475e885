// Closed forms of the 3D (plan) engine: the frequencies of a one-storey eccentric system against
// its 3×3 eigenproblem, a free rigid rectangle with eccentric mass under a ground pulse against
// the rigid-body motion, and a rectangle striking a rigid wall with a corner, obliquely, with
// friction, against the impulse-based solution (restitution and Coulomb, sliding and sticking).
#include <Eigen/Eigenvalues>
#include <cmath>
#include <gtest/gtest.h>

#include "lumped/laws/kelvin_voigt_law.h"
#include "lumped/plan/plan_central_difference.h"
#include "tests/lumped/plan_scenes.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// One level of `mass` on a 20 m × 12 m outline with the eccentricity `e`, on a storey of
    /// four columns at (±8, ±5) m of k_x = 20 MN/m, k_y = 30 MN/m each (fixed base), or on a
    /// storey without stiffness (a free body) if `free`.
    PlanBuilding one_storey(const Point &e, const bool free, const double zeta = 0.0)
    {
      PlanBuilding b;
      PlanLevel    l;
      l.mass              = 1e6;
      l.outline           = rectangle(20.0, 12.0);
      l.mass_eccentricity = e;
      b.levels            = {l};
      PlanStorey s;
      for (const double x : {-8.0, 8.0})
        for (const double y : {-5.0, 5.0})
          s.elements.push_back({Point(x, y), free ? 0.0 : 20e6, free ? 0.0 : 30e6});
      b.storeys       = {s};
      b.damping_ratio = zeta;
      return b;
    }
  } // namespace

  TEST(PlanClosedForm, OneStoreyFrequenciesMatchTheThreeByThreeEigenproblem)
  {
    constexpr double tol = 1e-6;
    // One-way eccentricity e_x: x uncoupled, y and θ coupled; roots of the 2×2 determinant.
    {
      const double          ex    = 1.5;
      const PlanBuilding    b     = one_storey(Point(ex, 0.0), false);
      const ModalProperties modes = plan_modes(b);
      const double          m = 1e6, inertia = m * (20.0 * 20.0 + 12.0 * 12.0) / 12.0;
      const double          kx = 4 * 20e6, ky = 4 * 30e6;
      const double k_theta_s = 4 * (20e6 * 25.0 + 30e6 * 64.0); // about the stiffness centre
      const double k_theta   = k_theta_s + ky * ex * ex;        // about the centre of mass
      const double a = m * inertia, bq = -(m * k_theta + inertia * ky),
                   c               = ky * k_theta - ky * ky * ex * ex;
      const double        disc     = std::sqrt(bq * bq - 4 * a * c);
      std::vector<double> expected = {std::sqrt(kx / m),
                                      std::sqrt((-bq - disc) / (2 * a)),
                                      std::sqrt((-bq + disc) / (2 * a))};
      std::sort(expected.begin(), expected.end());
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(modes.omega(j),
                    expected[static_cast<std::size_t>(j)],
                    tol * expected[static_cast<std::size_t>(j)])
          << "mode " << j;
      EXPECT_NEAR(b.levels[0].inertia(), inertia, 1e-12 * inertia);
    }
    // Two-way eccentricity against the textbook matrices about the centre of mass.
    {
      const Point        e(1.5, -0.8);
      const PlanBuilding b = one_storey(e, false);
      const double       m = 1e6, inertia = m * (20.0 * 20.0 + 12.0 * 12.0) / 12.0;
      const double       kx = 4 * 20e6, ky = 4 * 30e6, k_theta_s = 4 * (20e6 * 25.0 + 30e6 * 64.0);
      Eigen::Matrix3d    k;
      k << kx, 0, kx * e.y(), 0, ky, -ky * e.x(), kx * e.y(), -ky * e.x(),
        k_theta_s + kx * e.y() * e.y() + ky * e.x() * e.x();
      const Eigen::Matrix3d mm = Eigen::Vector3d(m, m, inertia).asDiagonal();
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> solver(k, mm);
      const ModalProperties                                     modes = plan_modes(b);
      for (int j = 0; j < 3; ++j)
      {
        const double expected = std::sqrt(solver.eigenvalues()(j));
        EXPECT_NEAR(modes.omega(j), expected, tol * expected) << "mode " << j;
      }
    }
  }

  TEST(PlanClosedForm, FreeVibrationInTheTorsionalModeHasItsPeriod)
  {
    // The integrator against the eigenproblem: start in the mode with the largest rotation and
    // count the zero crossings of θ (central difference period error (ω·Δt)²/24).
    const PlanBuilding    b     = one_storey(Point(1.5, -0.8), false);
    const ModalProperties modes = plan_modes(b);
    int                   mode  = 0;
    for (int j = 1; j < 3; ++j)
      if (std::abs(modes.shapes(2, j)) > std::abs(modes.shapes(2, mode)))
        mode = j;
    const double omega = modes.omega(mode);
    PlanScene    scene;
    scene.building = b;
    PlanOptions opt;
    opt.dt              = 1e-3;
    opt.output_interval = 1e-3;
    for (int i = 0; i < 3; ++i)
      opt.initial_displacement.push_back(0.01 * modes.shapes(i, mode) / modes.shapes(2, mode));
    const double       period = 2 * pi / omega;
    const PlanResponse r =
      PlanCentralDifference(PlanModel(scene), opt)
        .run(along_angle(kimp::testing::zero_motion(1e-3, 10.2 * period), 0.0));
    std::vector<double> crossings;
    const auto         &h = r.history;
    for (std::size_t k = 1; k < h.time.size(); ++k)
    {
      const double a = h.displacement[(k - 1) * 3 + 2], c = h.displacement[k * 3 + 2];
      if ((a < 0) != (c < 0))
        crossings.push_back(h.time[k - 1] + (h.time[k] - h.time[k - 1]) * a / (a - c));
    }
    ASSERT_GE(crossings.size(), 20u);
    const double measured =
      2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    EXPECT_NEAR(measured, period, 1e-4 * period);
  }

  TEST(PlanClosedForm, FreeRigidRectangleWithEccentricMassUnderAPulse)
  {
    // A ground pulse acts through the centre of mass: the body translates with −u_g and keeps
    // its initial spin ω_0 (θ = ω_0·t), however eccentric its mass; every corner follows.
    const Point e(2.0, -1.0);
    PlanScene   scene;
    scene.building      = one_storey(e, true);
    const double omega0 = 0.01, amplitude = 3.0, tp = 0.5, angle = pi / 6;
    GroundMotion pulse;
    pulse.dt = 1e-3;
    for (int i = 0; i < 2000; ++i)
    {
      const double t = i * pulse.dt;
      pulse.acceleration.push_back(t <= tp ? amplitude * std::sin(pi * t / tp) : 0.0);
    }
    pulse.name = "half_sine";
    PlanOptions opt;
    opt.dt               = 1e-4;
    opt.output_interval  = 0.01;
    opt.initial_velocity = {0.0, 0.0, omega0};
    const PlanResponse r =
      PlanCentralDifference(PlanModel(scene), opt).run(along_angle(pulse, angle));
    const auto ground = [&](const double t)
    {
      const double w = pi / tp;
      if (t <= tp)
        return amplitude / w * t - amplitude / (w * w) * std::sin(w * t);
      return amplitude * tp * tp / pi + 2 * amplitude / w * (t - tp);
    };
    const Point c0           = scene.building.levels[0].centre_of_mass();
    double      worst_corner = 0.0, worst_theta = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < r.history.time.size(); ++k)
    {
      const double t  = r.history.time[k];
      const double ug = ground(t);
      const Point  u_cm(-ug * std::cos(angle), -ug * std::sin(angle));
      const double theta = omega0 * t;
      worst_theta = std::max(worst_theta, std::abs(r.history.displacement[k * 3 + 2] - theta));
      for (std::size_t q = 0; q < 4; ++q)
      {
        const Point p = scene.building.levels[0].outline[q] - c0;
        const Point expected(u_cm.x() - theta * p.y(), u_cm.y() + theta * p.x());
        const Point got(r.history.corner_displacement[(k * 4 + q) * 2],
                        r.history.corner_displacement[(k * 4 + q) * 2 + 1]);
        worst_corner = std::max(worst_corner, (got - expected).norm());
        scale        = std::max(scale, expected.norm());
      }
    }
    EXPECT_LT(worst_corner, 1e-4 * scale);
    EXPECT_LT(worst_theta, 1e-12);
  }

  namespace
  {
    /// Post-impact velocities q̇ of a rigid body (diagonal mass `m`) whose contact point has the
    /// normal row g_n (δ̇ = g_n·q̇ > 0 approaching) and tangent row g_t, hit with q̇_0: the
    /// impulse dynamics dq̇ = −M⁻¹(g_nᵀ dP_n + g_tᵀ dP_t) with Coulomb friction (slip:
    /// dP_t = μ·sgn(v_t)·dP_n; stick while the ratio that holds v_t = 0 is within μ), compression
    /// until v_n = 0, restitution until the normal work returned is e²·(the work of compression)
    /// (Stronge's energetic coefficient). `stuck` reports whether sticking occurred.
    Eigen::Vector3d impulse_solution(const Eigen::Vector3d    &m,
                                     const Eigen::RowVector3d &gn,
                                     const Eigen::RowVector3d &gt,
                                     Eigen::Vector3d           qd,
                                     const double              mu,
                                     const double              e,
                                     bool                     &stuck)
    {
      const Eigen::Vector3d an  = gn.transpose().cwiseQuotient(m);
      const Eigen::Vector3d at  = gt.transpose().cwiseQuotient(m);
      const double          wnn = gn.dot(an), wtn = gt.dot(an), wtt = gt.dot(at);
      const double          dp          = gn.dot(qd) / wnn / 2e6;
      double                compression = 0.0, returned = 0.0;
      bool                  restitution = false;
      stuck                             = false;
      for (long it = 0; it < 100000000; ++it)
      {
        const double vn = gn.dot(qd), vt = gt.dot(qd);
        double       rho;
        if (std::abs(vt) > 2.0 * mu * wtt * dp)
          rho = mu * (vt > 0 ? 1.0 : -1.0);
        else
        {
          rho = -wtn / wtt;
          if (std::abs(rho) > mu)
            rho = mu * (rho > 0 ? 1.0 : -1.0);
          else
            stuck = stuck || mu > 0.0;
        }
        const Eigen::Vector3d next = qd - (an + rho * at) * dp;
        const double          vmid = 0.5 * (vn + gn.dot(next));
        if (!restitution)
        {
          compression += vmid * dp;
          if (gn.dot(next) <= 0.0)
            restitution = true;
        }
        else
          returned -= vmid * dp;
        qd = next;
        if (restitution && returned >= e * e * compression)
          break;
      }
      return qd;
    }

    struct ImpactCase
    {
      std::string law;
      double      cor;
      double      mu;
      double      tangential_speed; ///< v_y at impact, m/s
    };

    /// The engine's post-impact velocities (from the free flight after the impact) and the
    /// impulse solution, for a 20 m × 10 m rectangle turned by 5° striking the wall x = const
    /// with its leading corner, with k per metre `k`.
    void oblique_impact(const ImpactCase &ic,
                        const double      k,
                        Eigen::Vector3d  &engine,
                        Eigen::Vector3d  &reference,
                        Eigen::Vector3d  &initial,
                        bool             &stuck)
    {
      const double beta = 5.0 * pi / 180.0;
      PlanScene    scene;
      PlanLevel    l;
      l.mass = 1e6;
      l.outline.clear();
      for (const Point &p : rectangle(20.0, 10.0))
        l.outline.push_back(rotated(p, beta));
      l.mass_eccentricity          = Point(1.5, 0.8);
      scene.building.levels        = {l};
      scene.building.storeys       = {storey(0.0, 0.0, 0.0)};
      scene.building.damping_ratio = 0.0;
      double x_max                 = 0.0;
      for (const Point &p : l.outline)
        x_max = std::max(x_max, p.x());
      PlanMoat moat;
      moat.wall           = {Point(-12.0, -8.0),
                             Point(x_max + 0.02, -8.0),
                             Point(x_max + 0.02, 8.0),
                             Point(-12.0, 8.0)};
      moat.law            = kimp::testing::contact_law(ic.law, k, ic.cor);
      moat.friction       = ic.mu;
      moat.stick_velocity = 1e-4;
      scene.moat          = moat;
      const PlanModel model(scene);
      PlanOptions     opt;
      opt.dt               = 2e-6;
      opt.output_interval  = 1e-3;
      initial              = Eigen::Vector3d(1.0, ic.tangential_speed, 0.02);
      opt.initial_velocity = {initial(0), initial(1), initial(2)};
      const PlanResponse r = PlanCentralDifference(model, opt)
                               .run(along_angle(kimp::testing::zero_motion(1e-3, 0.25), 0.0));
      ASSERT_EQ(r.n_impacts(), 1u);
      // Free flight at the end: velocity from the last two samples (exact for constant speed).
      const auto       &h    = r.history;
      const std::size_t last = h.time.size() - 1;
      for (int i = 0; i < 3; ++i)
        engine(i) = (h.displacement[last * 3 + static_cast<std::size_t>(i)] -
                     h.displacement[(last - 1) * 3 + static_cast<std::size_t>(i)]) /
                    (h.time[last] - h.time[last - 1]);
      // The striking point: the one whose contact recorded the impact.
      const PlanContact *hit = nullptr;
      for (std::size_t c = 0; c < r.contacts.size(); ++c)
        if (!r.contacts[c].impacts.empty())
          hit = &model.contacts()[c];
      ASSERT_NE(hit, nullptr);
      double e = ic.cor;
      if (ic.law == "kelvin_voigt")
      {
        // The KV oscillator of the point's normal mass 1/W_nn with w·k and w·c.
        const Eigen::Vector3d m = model.masses();
        const double          wnn =
          hit->normal_row.cwiseProduct(hit->normal_row).cwiseQuotient(m.transpose()).sum();
        const double xi =
          kelvin_voigt_damping_ratio(ic.cor) * std::sqrt(hit->weight * hit->effective_mass * wnn);
        e = std::exp(-xi * pi / std::sqrt(1.0 - xi * xi));
      }
      reference = impulse_solution(model.masses(),
                                   hit->normal_row,
                                   hit->tangent_row,
                                   initial,
                                   ic.mu,
                                   e,
                                   stuck);
    }
  } // namespace

  TEST(PlanClosedForm, ObliqueImpactWithFrictionMatchesTheImpulseSolution)
  {
    constexpr double tol = 0.02;
    for (const ImpactCase &ic : {ImpactCase{"linear", 1.0, 0.3, 0.8},
                                 ImpactCase{"linear", 1.0, 0.5, 0.05},
                                 ImpactCase{"kelvin_voigt", 0.6, 0.0, 0.5}})
    {
      SCOPED_TRACE(ic.law + " mu " + std::to_string(ic.mu));
      for (const double k : {1e8, 1e9, 1e10})
      {
        Eigen::Vector3d engine, reference, initial;
        bool            stuck = false;
        oblique_impact(ic, k, engine, reference, initial, stuck);
        // Velocity error relative to the approach speed, spin error relative to the spin change.
        const double v_error =
          (engine.head<2>() - reference.head<2>()).norm() / initial.head<2>().norm();
        const double w_error =
          std::abs(engine(2) - reference(2)) / std::abs(reference(2) - initial(2));
        EXPECT_LT(std::max(v_error, w_error), tol) << "k " << k << " engine " << engine.transpose()
                                                   << " reference " << reference.transpose();
        // The cases cover sliding throughout and sticking.
        EXPECT_EQ(stuck, ic.mu > 0.0 && ic.tangential_speed < 0.1);
      }
    }
  }
} // namespace kimp::lumped::plan

namespace kimp::lumped::plan
{
  TEST(PlanClosedForm, EdgeBouncesElasticallyOffAReentrantWallCorner)
  {
    // A 20 m × 10 m slab at 1 m/s towards a buttress whose tip (a re-entrant corner of the
    // wall) faces the middle of its right edge, 30 cm away: the edge meets the tip on the line
    // through the centre of mass, a linear law returns the speed (−1 m/s, no spin) and the peak
    // force is v·√(m·w·k) of the half-edge spring.
    PlanScene scene;
    PlanLevel l;
    l.mass                       = 1e6;
    l.outline                    = rectangle(20.0, 10.0);
    scene.building.levels        = {l};
    scene.building.storeys       = {storey(0.0, 0.0, 0.0)};
    scene.building.damping_ratio = 0.0;
    PlanMoat moat;
    moat.wall  = kimp::testing::notched_wall(12.0, 7.0, 10.3);
    moat.law   = kimp::testing::contact_law("linear", 1e9);
    scene.moat = moat;
    const PlanModel model(scene);
    std::size_t     corners = 0;
    for (const PlanContact &c : model.contacts())
      corners += c.name.find("wallcorner") != std::string::npos ? 1 : 0;
    EXPECT_EQ(corners, 1u);
    PlanOptions opt;
    opt.dt               = 1e-5;
    opt.output_interval  = 1e-3;
    opt.initial_velocity = {1.0, 0.0, 0.0};
    const PlanResponse r = PlanCentralDifference(model, opt)
                             .run(along_angle(kimp::testing::zero_motion(1e-3, 0.6), 0.0));
    ASSERT_EQ(r.n_impacts(), 1u);
    const auto       &h    = r.history;
    const std::size_t last = h.time.size() - 1;
    const double      dtau = h.time[last] - h.time[last - 1];
    EXPECT_NEAR((h.displacement[last * 3] - h.displacement[(last - 1) * 3]) / dtau, -1.0, 1e-3);
    EXPECT_NEAR(r.peak_displacement[2], 0.0, 1e-12);
    const double k = 1e9 * 10.0;
    for (const PlanContactResult &c : r.contacts)
      if (!c.impacts.empty())
      {
        EXPECT_NE(c.name.find("wallcorner"), std::string::npos) << c.name;
        EXPECT_NEAR(c.peak_normal_force, std::sqrt(1e6 * 0.5 * k), 1e-3 * std::sqrt(1e6 * 0.5 * k));
      }
  }
} // namespace kimp::lumped::plan
