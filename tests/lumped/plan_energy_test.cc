// Energy balance of the 3D (plan) engine, E_0 + W_in = E_kin + E_strain + E_viscous +
// E_hysteretic + W_contact + W_friction: an eccentric building under two components at an angle,
// pounding a moat all round with friction, for every impact law and every isolator in plan.
#include <cmath>
#include <gtest/gtest.h>

#include "tests/lumped/plan_scenes.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double balance_tol = 1e-4; // of the energy supplied

    /// The reference building with its masses 5 % (x) and 2.5 % (y) of the plan off centre.
    PlanBuilding eccentric_building()
    {
      PlanBuilding b = kimp::testing::plan_reference_building();
      for (PlanLevel &l : b.levels)
        l.mass_eccentricity = Point(0.05, 0.025) * kimp::testing::plan_width;
      return b;
    }

    PlanGroundMotion two_component_motion()
    {
      SyntheticMotionSpec second;
      second.duration = 6.0;
      second.seed     = 2;
      second.pga      = 0.5 * standard_gravity;
      return two_components(kimp::testing::near_fault_motion(6.0),
                            synthetic_near_fault(second),
                            30.0 * 3.14159265358979323846 / 180.0);
    }

    PlanResponse run(const PlanBuilding &b, const ForceLawSpec &law_per_metre, const double mu)
    {
      PlanScene scene;
      scene.building = b;
      PlanMoat moat  = kimp::testing::plan_moat(b, "linear", 1.0, 0.08, mu);
      moat.law       = law_per_metre;
      scene.moat     = moat;
      PlanOptions opt;
      opt.dt = 2e-5;
      return PlanCentralDifference(PlanModel(scene), opt).run(two_component_motion());
    }

    void expect_balanced(const PlanResponse &r, const std::string &what, const bool friction)
    {
      const PlanEnergy &e = r.energy;
      EXPECT_GT(r.n_impacts(), 0u) << what;
      EXPECT_LT(e.max_relative_error, balance_tol) << what;
      EXPECT_GT(e.input, 0.0) << what;
      EXPECT_GE(e.viscous, 0.0) << what;
      EXPECT_GE(e.hysteretic, 0.0) << what;
      if (friction)
      {
        EXPECT_GT(e.friction, 1e-4 * e.input) << what;
      }
      // The eccentric building turns.
      double theta = 0.0;
      for (std::size_t i = 2; i < r.peak_displacement.size(); i += 3)
        theta = std::max(theta, r.peak_displacement[i]);
      EXPECT_GT(theta * kimp::testing::plan_width, 1e-3 * r.peak_displacement[0]) << what;
    }

    ForceLawSpec per_metre(const std::string &law, const double k_total)
    {
      return kimp::testing::contact_law(law, k_total / kimp::testing::plan_width);
    }
  } // namespace

  TEST(PlanEnergy, BalancesWithFrictionForEveryLaw)
  {
    const PlanBuilding b = eccentric_building();
    ForceLawSpec       bumper;
    bumper.law                         = "bumper";
    bumper.stiffness                   = 4.0 * 2.25 * 0.0225 * 55835e3 / std::pow(0.05, 2.65);
    bumper.bumper_ultimate_deformation = 0.75 * 0.05;
    bumper.bumper_wall_stiffness       = 1.5e9;
    bumper.stiffness /= kimp::testing::plan_width;
    bumper.bumper_wall_stiffness /= kimp::testing::plan_width;
    for (const ForceLawSpec &law : {per_metre("linear", 2.5e9),
                                    per_metre("kelvin_voigt", 2.5e9),
                                    per_metre("modified_kelvin_voigt", 2.5e9),
                                    per_metre("jankowski", 4e10),
                                    per_metre("hertzdamp", 4e10),
                                    per_metre("hysteretic", 4e10),
                                    bumper})
    {
      const PlanResponse r = run(b, law, 0.3);
      expect_balanced(r, law.law, true);
      std::printf("%-22s residual %.2e of the input (friction %.3g J, contact %.3g J, input "
                  "%.3g J)\n",
                  law.law.c_str(),
                  r.energy.max_relative_error,
                  r.energy.friction,
                  r.energy.contact_work,
                  r.energy.input);
    }
  }

  TEST(PlanEnergy, BalancesForEveryIsolatorInPlan)
  {
    PlanBuilding bw = eccentric_building();
    PlanBuilding fp = bw;
    const double w  = standard_gravity * 1530e3 / 4.0;
    for (PlanIsolatorSpec &iso : bw.isolators)
      iso.law = std::make_shared<PlanBoucWenIsolator>(
        BoucWenParameters{50e6, 0.125, 1.7e6 / 4, 1.0, 0.5, 0.5, 2.0});
    for (PlanIsolatorSpec &iso : fp.isolators)
      iso.law = std::make_shared<PlanFrictionPendulumIsolator>(
        FrictionPendulumParameters{w, 2.2, 0.04, 0.08, 30.0, 2e8});
    for (const auto &[b, name] :
         {std::pair<const PlanBuilding &, const char *>{bw, "bouc_wen"}, {fp, "friction_pendulum"}})
    {
      const PlanResponse r = run(b, per_metre("hysteretic", 4e10), 0.3);
      expect_balanced(r, name, true);
      EXPECT_GT(r.energy.hysteretic, 0.05 * r.energy.input) << name;
      std::printf("%-22s residual %.2e of the input (hysteretic %.3g J of %.3g J)\n",
                  name,
                  r.energy.max_relative_error,
                  r.energy.hysteretic,
                  r.energy.input);
    }
  }
} // namespace kimp::lumped::plan

namespace kimp::lumped::plan
{
  TEST(PlanPeaks, CornerAndDriftPeaksAreThoseOfEveryStep)
  {
    // The engine skips corners that cannot beat the running peak; the histories of every step
    // give the peaks by brute force.
    PlanScene scene;
    scene.building = kimp::testing::plan_reference_building();
    for (PlanLevel &l : scene.building.levels)
      l.mass_eccentricity = Point(0.1, -0.05) * kimp::testing::plan_width;
    scene.moat = kimp::testing::plan_moat(scene.building, "hysteretic", 4e10, 0.08, 0.3);
    PlanOptions opt;
    opt.dt               = 1e-4;
    opt.output_interval  = 1e-4;
    const PlanResponse r = PlanCentralDifference(PlanModel(scene), opt)
                             .run(along_angle(kimp::testing::near_fault_motion(6.0), 0.4));
    ASSERT_GT(r.n_impacts(), 0u);
    const PlanBuilding &b  = scene.building;
    const std::size_t   nl = b.n_levels();
    std::vector<double> corner(nl, 0.0), drift(nl - 1, 0.0), dx(nl - 1, 0.0), dy(nl - 1, 0.0);
    const auto          at = [&](std::size_t k, std::size_t l, const Point &p)
    {
      const double *q = &r.history.displacement[(k * nl + l) * 3];
      const Point   c = b.levels[l].centre_of_mass();
      return Point(q[0] - q[2] * (p.y() - c.y()), q[1] + q[2] * (p.x() - c.x()));
    };
    for (std::size_t k = 0; k < r.history.time.size(); ++k)
    {
      for (std::size_t l = 0; l < nl; ++l)
        for (const Point &p : b.levels[l].outline)
          corner[l] = std::max(corner[l], at(k, l, p).norm());
      for (std::size_t s = 0; s + 1 < nl; ++s)
      {
        for (const Point &p : b.levels[s + 1].outline)
          drift[s] = std::max(drift[s], (at(k, s + 1, p) - at(k, s, p)).norm());
        const Point c = b.levels[s + 1].centre_of_mass();
        const Point d = at(k, s + 1, c) - at(k, s, c);
        dx[s]         = std::max(dx[s], std::abs(d.x()));
        dy[s]         = std::max(dy[s], std::abs(d.y()));
      }
    }
    for (std::size_t l = 0; l < nl; ++l)
      EXPECT_NEAR(r.peak_corner_displacement[l], corner[l], 1e-12 * corner[l]) << "level " << l;
    for (std::size_t s = 0; s + 1 < nl; ++s)
    {
      EXPECT_NEAR(r.peak_corner_drift[s], drift[s], 1e-12 * drift[s]) << "storey " << s;
      EXPECT_NEAR(r.peak_drift_x[s], dx[s], 1e-12 * drift[s]) << "storey " << s;
      EXPECT_NEAR(r.peak_drift_y[s], dy[s], 1e-12 * drift[s]) << "storey " << s;
      EXPECT_GT(r.peak_corner_drift[s], std::hypot(dx[s], dy[s]) * 0.999) << "storey " << s;
    }
  }
} // namespace kimp::lumped::plan
