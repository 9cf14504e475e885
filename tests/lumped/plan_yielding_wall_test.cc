// Yielding wall faces in plan: the symmetric building along x against two yielding faces
// reproduces the planar run between two yielding walls (displacements, contact forces, the walls'
// peak and permanent displacements, plastic and radiated work, failure time; 1e-9), the energy
// balance of an eccentric run at 30° with friction closes with the walls' work, and bad input is
// refused naming the field.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <limits>
#include <stdexcept>

#include "lumped/integrators/central_difference.h"
#include "tests/lumped/plan_scenes.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double tol = 1e-9;
    constexpr double dt  = 5e-5;
    constexpr double pi  = 3.14159265358979323846;

    /// The wall-and-backfill part of both planar walls and of every face in plan: k = 500 MN/m,
    /// capacity 3 MN, α = 2 %, k_ur = 1 GN/m, pull-back 3 MN, c_r = 10 MN·s/m, a DOF of 100 t.
    WallBackfillParams backfill(const double failure = std::numeric_limits<double>::infinity())
    {
      WallBackfillParams p;
      p.stiffness            = 500e6;
      p.capacity             = 3e6;
      p.hardening_ratio      = 0.02;
      p.unloading_stiffness  = 1e9;
      p.tension_capacity     = 3e6;
      p.radiation_damping    = 10e6;
      p.mass                 = 100e3;
      p.failure_displacement = failure;
      return p;
    }

    Response planar_run(const GroundMotion &g, const double failure)
    {
      PoundingScene scene = kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, 0.10);
      for (auto *wall : {&scene.left_wall, &scene.right_wall})
      {
        (*wall)->yielding  = backfill(failure);
        (*wall)->sdof_mass = 100e3;
      }
      CentralDifferenceOptions opt;
      opt.dt = dt;
      return CentralDifference(PoundingModel(scene), opt).run(g);
    }

    PlanScene plan_scene(const double failure, const double mu = 0.0)
    {
      PlanScene scene;
      scene.building = kimp::testing::plan_reference_building();
      scene.moat =
        kimp::testing::plan_moat(scene.building, "modified_kelvin_voigt", 2.5e9, 0.10, mu);
      for (std::size_t j = 0; j < 4; ++j)
        scene.moat->yielding.push_back({j, backfill(failure)});
      return scene;
    }

    PlanResponse plan_run(const PlanScene &scene, const PlanGroundMotion &g)
    {
      PlanOptions opt;
      opt.dt = dt;
      return PlanCentralDifference(PlanModel(scene), opt).run(g);
    }
  } // namespace

  TEST(PlanYieldingWall, AlongXReproducesThePlanarYieldingWallRun)
  {
    // Failure at 2 cm: both runs must report the same face failed at the same time.
    const double       failure = 0.02;
    const GroundMotion g       = kimp::testing::near_fault_motion(8.0);
    const Response     p2      = planar_run(g, failure);
    const PlanResponse p3      = plan_run(plan_scene(failure), along_angle(g, 0.0));
    ASSERT_EQ(p2.contacts.size(), 4u); // left_wall, right_wall, and their backfill pairs
    ASSERT_GT(p2.n_impacts(), 0u);
    ASSERT_EQ(p3.yielding_walls.size(), 4u);
    const std::size_t ns = p2.history.time.size(), nl = p2.n_dofs - 2; // the walls' two DOFs
    ASSERT_EQ(p3.history.time.size(), ns);
    std::vector<double> u2, u3, f2, f3;
    for (std::size_t k = 0; k < ns; ++k)
    {
      for (std::size_t i = 0; i < nl; ++i)
      {
        u2.push_back(p2.history.displacement[k * p2.n_dofs + i]);
        u3.push_back(p3.history.displacement[(k * nl + i) * 3]);
      }
      const auto [left, right] = kimp::testing::plan_side_forces(p3, k);
      f3.push_back(left);
      f3.push_back(right);
      f2.push_back(p2.history.contact_force[k * 4]);
      f2.push_back(p2.history.contact_force[k * 4 + 1]);
    }
    const double du = kimp::testing::relative_difference(u3, u2);
    const double df = kimp::testing::relative_difference(f3, f2);
    std::printf("displacements %.3g, wall forces %.3g of their peaks\n", du, df);
    EXPECT_LT(du, tol);
    EXPECT_LT(df, tol);
    // Face 1 is the planar right wall (pair 3), face 3 the left one (pair 2).
    for (const auto &[face, pair] : {std::pair<std::size_t, std::size_t>{1, 3}, {3, 2}})
    {
      const PlanYieldingWallResult &y = p3.yielding_walls[face];
      const ContactResult          &c = p2.contacts[pair];
      ASSERT_EQ(y.segment, face);
      EXPECT_GT(c.peak_deformation, 0.0);
      EXPECT_NEAR(y.peak_displacement, c.peak_deformation, tol * c.peak_deformation);
      EXPECT_NEAR(y.permanent_set, c.permanent_indentation, tol * c.peak_deformation);
      EXPECT_NEAR(y.plastic_work, c.plastic_work, tol * p2.energy.input);
      EXPECT_NEAR(y.radiated_work, c.radiated_work, tol * p2.energy.input);
      EXPECT_NEAR(y.peak_resistance, c.peak_resistance, tol * c.peak_resistance);
      ASSERT_EQ(y.failure_time.has_value(), c.failure_time.has_value()) << "face " << face;
      if (c.failure_time)
      {
        EXPECT_DOUBLE_EQ(*y.failure_time, *c.failure_time);
      }
    }
    EXPECT_TRUE(p3.yielding_walls[1].failure_time || p3.yielding_walls[3].failure_time);
    // The faces along x are never struck.
    for (const std::size_t face : {0u, 2u})
      EXPECT_EQ(p3.yielding_walls[face].plastic_work, 0.0);
  }

  TEST(PlanYieldingWall, EnergyBalanceClosesWithTheWallsWork)
  {
    // The eccentric building at 30° with friction μ = 0.3 against four yielding faces.
    PlanScene scene = plan_scene(std::numeric_limits<double>::infinity(), 0.3);
    for (PlanLevel &l : scene.building.levels)
      l.mass_eccentricity = Point(0.05, 0.025) * kimp::testing::plan_width;
    const PlanResponse r =
      plan_run(scene, along_angle(kimp::testing::near_fault_motion(8.0), 30.0 * pi / 180.0));
    const PlanEnergy &e = r.energy;
    std::printf("max residual %.3g of the input, wall plastic %.4g J, radiated %.4g J, wall work "
                "%.4g J, input %.4g J\n",
                e.max_relative_error,
                e.wall_plastic,
                e.wall_radiated,
                e.wall_work,
                e.input);
    ASSERT_GT(r.n_impacts(), 0u);
    EXPECT_GT(e.wall_plastic, 0.0);
    EXPECT_GT(e.wall_radiated, 0.0);
    EXPECT_GT(e.friction, 0.0);
    EXPECT_LT(e.max_relative_error, 1e-4);
    EXPECT_LT(e.relative_error, 1e-4);
    // The work on the walls is their dissipation plus what their branches still store.
    EXPECT_GE(e.wall_work, (e.wall_plastic + e.wall_radiated) * (1.0 - 1e-6));
  }

  TEST(PlanYieldingWall, BadYieldingFacesAreRefused)
  {
    const auto refused = [](PlanScene scene, const std::string &needle)
    {
      try
      {
        (void)PlanModel(scene);
        ADD_FAILURE() << "accepted, expected: " << needle;
      }
      catch (const std::invalid_argument &e)
      {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      }
    };
    PlanScene bad                 = plan_scene(1.0);
    bad.moat->yielding[3].segment = 7;
    refused(bad, "moat.yielding[3].segment = 7");
    bad                           = plan_scene(1.0);
    bad.moat->yielding[2].segment = 0;
    refused(bad, "that face already has a yielding wall");
    bad                               = plan_scene(1.0);
    bad.moat->yielding[0].params.mass = 0.0;
    refused(bad, "moat.yielding[0].mass");
    bad                                   = plan_scene(1.0);
    bad.moat->yielding[1].params.capacity = -1.0;
    refused(bad, "moat.yielding[1]");
    // A wall with a re-entrant corner (a notch in the +x face).
    bad            = plan_scene(1.0);
    bad.moat->wall = kimp::testing::notched_wall(10.1, 10.1, 10.05);
    refused(bad, "needs a convex wall polygon");
  }
} // namespace kimp::lumped::plan
