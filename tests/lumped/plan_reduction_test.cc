// Reduction of the 3D (plan) engine to the planar one: a symmetric building under one component
// against walls perpendicular to it reproduces the planar run (displacements, absolute
// accelerations, impact forces and times to 1e-9 relative), its rotation and the motion across
// stay at round-off; the same along y and with the whole scene turned by an angle.
#include <cmath>
#include <gtest/gtest.h>

#include "lumped/integrators/central_difference.h"
#include "tests/lumped/plan_scenes.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double reproduction_tol = 1e-9;  // relative to the planar peak
    constexpr double round_off_tol    = 1e-12; // motion that must vanish, relative to the peak
    constexpr double dt               = 1e-4;
    constexpr double pi               = 3.14159265358979323846;

    struct Case
    {
      std::string law;
      double      k_total;
    };

    /// Planar run of the reference building between two walls at `gap`.
    Response planar_run(const Case &c, const double gap, const GroundMotion &g)
    {
      PoundingScene            scene = kimp::testing::walled_scene(c.law, c.k_total, gap);
      CentralDifferenceOptions opt;
      opt.dt = dt;
      return CentralDifference(PoundingModel(scene), opt).run(g);
    }

    /// The plan run of the same building turned by `angle`, the record along `angle`.
    PlanResponse plan_run(const Case &c, const double gap, const GroundMotion &g, double angle)
    {
      PlanScene scene;
      scene.building = kimp::testing::plan_reference_building(angle);
      scene.moat     = kimp::testing::plan_moat(scene.building, c.law, c.k_total, gap);
      PlanOptions opt;
      opt.dt = dt;
      return PlanCentralDifference(PlanModel(scene), opt).run(along_angle(g, angle));
    }

    /// Check the plan run against the planar one, the response seen along `angle` (the wall
    /// faces: 1 along +angle, 3 along −angle).
    void expect_reproduces(const Response &p2, const PlanResponse &p3, const double angle)
    {
      const std::size_t n_levels = p2.n_dofs;
      const std::size_t ns       = p2.history.time.size();
      ASSERT_EQ(p3.history.time.size(), ns);
      ASSERT_EQ(p3.n_levels, n_levels);
      const double        c = std::cos(angle), s = std::sin(angle);
      std::vector<double> u_along, u_across, theta, a_along, f_right, f_left;
      for (std::size_t k = 0; k < ns; ++k)
      {
        for (std::size_t i = 0; i < n_levels; ++i)
        {
          const double *u = &p3.history.displacement[(k * n_levels + i) * 3];
          const double *a = &p3.history.absolute_acceleration[(k * n_levels + i) * 3];
          u_along.push_back(c * u[0] + s * u[1]);
          u_across.push_back(-s * u[0] + c * u[1]);
          theta.push_back(u[2]);
          a_along.push_back(c * a[0] + s * a[1]);
        }
        const auto [left, right] = kimp::testing::plan_side_forces(p3, k);
        f_left.push_back(left);
        f_right.push_back(right);
      }
      std::vector<double> f2_left, f2_right;
      for (std::size_t k = 0; k < ns; ++k)
      {
        f2_left.push_back(p2.history.contact_force[k * 2]);
        f2_right.push_back(p2.history.contact_force[k * 2 + 1]);
      }
      const double u_peak =
        *std::max_element(p2.peak_displacement.begin(), p2.peak_displacement.end());
      EXPECT_LT(kimp::testing::relative_difference(u_along, p2.history.displacement),
                reproduction_tol);
      EXPECT_LT(kimp::testing::relative_difference(a_along, p2.history.absolute_acceleration),
                reproduction_tol);
      EXPECT_LT(kimp::testing::relative_difference(f_right, f2_right), reproduction_tol);
      EXPECT_LT(kimp::testing::relative_difference(f_left, f2_left), reproduction_tol);
      double across = 0.0, rot = 0.0;
      for (std::size_t q = 0; q < u_across.size(); ++q)
      {
        across = std::max(across, std::abs(u_across[q]));
        rot    = std::max(rot, std::abs(theta[q]) * 0.5 * kimp::testing::plan_width);
      }
      EXPECT_LT(across, round_off_tol * u_peak);
      EXPECT_LT(rot, round_off_tol * u_peak);

      // Peak impact forces over every step and the impacts (each corner of the striking edge
      // records the planar wall's impacts).
      EXPECT_NEAR(p3.peak_wall_force[1],
                  p2.contacts[1].peak_force,
                  reproduction_tol * p2.contacts[1].peak_force);
      EXPECT_NEAR(p3.peak_wall_force[3],
                  p2.contacts[0].peak_force,
                  reproduction_tol * std::max(p2.contacts[0].peak_force, 1.0));
      for (const PlanContactResult &r : p3.contacts)
        if (r.segment == 1 || r.segment == 3)
        {
          const ContactResult &planar = p2.contacts[r.segment == 1 ? 1 : 0];
          ASSERT_EQ(r.impacts.size(), planar.impacts.size()) << r.name;
          for (std::size_t q = 0; q < r.impacts.size(); ++q)
          {
            EXPECT_DOUBLE_EQ(r.impacts[q].time, planar.impacts[q].time) << r.name;
            EXPECT_NEAR(r.impacts[q].velocity,
                        planar.impacts[q].velocity,
                        reproduction_tol * std::abs(planar.impacts[q].velocity))
              << r.name;
          }
        }
        else
          EXPECT_TRUE(r.impacts.empty()) << r.name;
      // Peaks over every step of the corners and the drifts (no rotation: the corners move as
      // the centre, the drift at the centre and at the corners is the planar drift).
      for (std::size_t i = 0; i < n_levels; ++i)
        EXPECT_NEAR(p3.peak_corner_displacement[i],
                    p2.peak_displacement[i],
                    reproduction_tol * u_peak)
          << "level " << i;
      ASSERT_EQ(p3.peak_corner_drift.size(), p2.peak_interstorey_drift.size());
      for (std::size_t st = 0; st < p2.peak_interstorey_drift.size(); ++st)
      {
        const double d = p2.peak_interstorey_drift[st];
        EXPECT_NEAR(p3.peak_corner_drift[st], d, reproduction_tol * d) << "storey " << st;
        if (angle == 0.0)
        {
          EXPECT_NEAR(p3.peak_drift_x[st], d, reproduction_tol * d) << "storey " << st;
          EXPECT_LT(p3.peak_drift_y[st], round_off_tol * d) << "storey " << st;
        }
      }
      // Peak accelerations along the record over every step (angle 0: the x DOFs).
      if (angle == 0.0)
        for (std::size_t i = 0; i < n_levels; ++i)
        {
          EXPECT_NEAR(p3.peak_displacement[3 * i],
                      p2.peak_displacement[i],
                      reproduction_tol * u_peak);
          EXPECT_NEAR(p3.peak_absolute_acceleration[3 * i],
                      p2.peak_absolute_acceleration[i],
                      reproduction_tol * p2.peak_absolute_acceleration[i]);
        }
    }
  } // namespace

  TEST(PlanReduction, AlongXReproducesThePlanarRunForEveryLaw)
  {
    const GroundMotion g = kimp::testing::near_fault_motion(8.0);
    for (const Case &c : {Case{"linear", 2.5e9},
                          Case{"kelvin_voigt", 2.5e9},
                          Case{"modified_kelvin_voigt", 2.5e9},
                          Case{"jankowski", 4e10},
                          Case{"hertzdamp", 4e10},
                          Case{"hysteretic", 4e10}})
    {
      SCOPED_TRACE(c.law);
      const Response     p2 = planar_run(c, 0.10, g);
      const PlanResponse p3 = plan_run(c, 0.10, g, 0.0);
      ASSERT_GT(p2.n_impacts(), 0u);
      expect_reproduces(p2, p3, 0.0);
    }
  }

  TEST(PlanReduction, AlongYReproducesThePlanarRun)
  {
    const GroundMotion g  = kimp::testing::near_fault_motion(8.0);
    const Case         c  = {"hysteretic", 4e10};
    const Response     p2 = planar_run(c, 0.10, g);
    // The building and the record turned by 90°: the planar x is the plan's y.
    const PlanResponse p3 = plan_run(c, 0.10, g, 0.5 * pi);
    ASSERT_GT(p2.n_impacts(), 0u);
    expect_reproduces(p2, p3, 0.5 * pi);
  }

  TEST(PlanReduction, TurnedByAnAngleTheResponseTurnsWithIt)
  {
    const GroundMotion g  = kimp::testing::near_fault_motion(8.0);
    const Case         c  = {"kelvin_voigt", 2.5e9};
    const Response     p2 = planar_run(c, 0.10, g);
    for (const double degrees : {30.0, 127.0})
    {
      SCOPED_TRACE(degrees);
      const double angle = degrees * pi / 180.0;
      expect_reproduces(p2, plan_run(c, 0.10, g, angle), angle);
    }
  }
} // namespace kimp::lumped::plan
