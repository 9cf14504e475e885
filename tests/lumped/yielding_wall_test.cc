// Yielding moat walls in the pounding model (docs/physics.md §2 "Yielding moat wall"): the
// model's DOFs and permanent pairs, an impact against closed forms of energy (peak wall
// displacement, permanent set, a second impact from the displaced wall), failure with its time,
// the mirrored response of two walls, and the energy balance of a building run with the walls'
// plastic and radiated work.
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <string>
#include <utility>

#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/wall_backfill_law.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::lumped
{
  namespace
  {
    /// Balance closure of a building run: the element's acceptance criterion.
    constexpr double balance_tol = 1e-4;

    /// Wall part of the single-mass tests: k = 100 MN/m, F_y = 1 MN, α = 5 %, k_ur = 200 MN/m,
    /// pull-back up to 1 MN, a light dashpot (ζ ≈ 1 % of the 1 t wall on k_ur).
    WallBackfillParams wall_part()
    {
      WallBackfillParams p = kimp::testing::bilinear_wall_part(100e6, 1e6, 0.05, 200e6);
      p.tension_capacity   = 1e6;
      p.radiation_damping  = 1e4;
      return p;
    }

    /// A 100 t mass (a one-storey building on a 1 N/m storey, undamped) between a rigid elastic
    /// wall on the left and a yielding wall of 1 t on the right, both 5 cm away, contact springs
    /// of 1 GN/m.
    PoundingScene single_mass_scene(const WallBackfillParams &part)
    {
      PoundingScene scene;
      scene.building.name               = "building";
      scene.building.floor_masses       = {100e3};
      scene.building.storey_stiffnesses = {1.0};
      scene.building.damping_ratio      = 0.0;
      const ForceLawSpec contact        = kimp::testing::contact_law("linear", 1e9);
      scene.left_wall                   = kimp::testing::moat_wall(0.05, contact);
      scene.right_wall                  = kimp::testing::moat_wall(0.05, contact);
      scene.right_wall->sdof_mass       = 1e3;
      scene.right_wall->yielding        = part;
      return scene;
    }

    /// The mass at 1 m/s towards the right wall, no ground motion, `duration` s.
    Response run_single_mass(const PoundingScene &scene, const double duration)
    {
      CentralDifferenceOptions opt;
      opt.dt               = 2e-6;
      opt.output_interval  = 1e-4;
      opt.initial_velocity = {1.0, 0.0};
      const PoundingModel m(scene);
      return CentralDifference(m, opt).run(kimp::testing::zero_motion(1e-3, duration));
    }

    /// w_max reached by kinetic energy `energy` (J) from a wall at rest at its set after w_max,0
    /// (0: virgin): the line back to w_max,0, the envelope beyond, plus the contact spring's
    /// energy F²/(2k_c) at the peak (quasi-static: wall inertia and dashpot neglected).
    double peak_from_energy(const WallBackfillLaw &law,
                            const double           energy,
                            const double           w_max0,
                            const double           k_contact)
    {
      const double kur     = law.parameters().unloading_stiffness;
      const auto   work_to = [&](const double w)
      {
        const double e0 = law.envelope(w_max0);
        const double e  = law.envelope(w);
        return 0.5 * e0 * e0 / kur + law.envelope_work(w) - law.envelope_work(w_max0) +
               0.5 * e * e / k_contact;
      };
      double lo = w_max0, hi = 1.0;
      for (int i = 0; i < 200; ++i)
      {
        const double mid                  = 0.5 * (lo + hi);
        (work_to(mid) < energy ? lo : hi) = mid;
      }
      return lo;
    }

    /// The wall DOF's displacement (m) in the history at the last sample before `t` (s).
    double wall_displacement_at(const Response &r, const std::size_t dof, const double t)
    {
      std::size_t row = 0;
      while (row + 1 < r.history.time.size() && r.history.time[row + 1] <= t)
        ++row;
      return r.history.displacement[row * r.n_dofs + dof];
    }
  } // namespace

  TEST(YieldingWall, ModelHasTheWallDofAndAPermanentBackfillPair)
  {
    const PoundingModel model(single_mass_scene(wall_part()));
    ASSERT_EQ(model.n_dofs(), 2u);
    EXPECT_EQ(model.masses()[1], 1e3);
    EXPECT_EQ(model.stiffness().diag[1], 0.0); // held by the wall part only
    EXPECT_EQ(model.damping().diag[1], 0.0);   // its dashpot is in the wall part
    ASSERT_EQ(model.contacts().size(), 3u);
    const ContactPair &contact = model.contacts()[1];
    EXPECT_EQ(contact.name, "right_wall");
    EXPECT_EQ(contact.left_dof, 0);
    EXPECT_EQ(contact.right_dof, 1);
    EXPECT_FALSE(contact.permanent);
    const ContactPair &part = model.contacts()[2];
    EXPECT_EQ(part.name, "right_wall_backfill");
    EXPECT_EQ(part.left_dof, 1); // w = u_wall: pushed towards +x into the backfill
    EXPECT_EQ(part.right_dof, -1);
    EXPECT_TRUE(part.permanent);
    EXPECT_EQ(part.law->name(), "wall_backfill");
    // The companion run keeps the wall part, not the impact contacts.
    const PoundingModel free = model.without_contacts();
    ASSERT_EQ(free.contacts().size(), 1u);
    EXPECT_EQ(free.contacts()[0].name, "right_wall_backfill");

    PoundingScene both        = single_mass_scene(wall_part());
    both.right_wall->flexible = true;
    EXPECT_THROW(PoundingModel{both}, std::invalid_argument);
  }

  TEST(YieldingWall, ImpactYieldsTheWallToTheEnergyPeakAndLeavesItsSet)
  {
    const PoundingScene scene = single_mass_scene(wall_part());
    WallBackfillParams  p     = wall_part();
    p.mass                    = 1e3;
    const WallBackfillLaw law(p);
    // First impact: ½·m·v² = 50 kJ into the wall part and the contact spring.
    const double w1 = peak_from_energy(law, 0.5 * 100e3 * 1.0, 0.0, 1e9);
    const double e1 = law.envelope(w1);
    const double s1 = w1 - e1 / p.unloading_stiffness;

    const Response       r           = run_single_mass(scene, 0.4); // the first impact only
    const ContactResult &part        = r.contacts[2];
    constexpr double     dynamic_tol = 0.02; // wall inertia (1 % of the mass) and dashpot neglected
    EXPECT_NEAR(part.peak_deformation, w1, dynamic_tol * w1);
    EXPECT_NEAR(part.permanent_indentation, s1, dynamic_tol * w1);
    EXPECT_NEAR(part.peak_force, e1, dynamic_tol * e1 + p.radiation_damping * 1.0);
    // The wall rests at its set (the light dashpot has damped its vibration).
    EXPECT_NEAR(wall_displacement_at(r, 1, 0.4), part.permanent_indentation, 0.05 * s1);
    EXPECT_GT(part.plastic_work, 0.0);
    EXPECT_GT(part.radiated_work, 0.0);
    EXPECT_FALSE(part.failure_time);
    EXPECT_TRUE(part.impacts.empty());
    EXPECT_TRUE(part.pulse_time.empty());
    // Contact at 5 cm and 1 m/s (the 1 t wall may rattle against the mass while it is pushed).
    ASSERT_GE(r.contacts[1].impacts.size(), 1u);
    EXPECT_NEAR(r.contacts[1].impacts.front().time, 0.05, 1e-4);

    // Second impact: the mass comes back from the elastic left wall and meets the wall where it
    // was left, at 5 cm + s1: the gap has grown by the set. It brings back only what the wall
    // returned (its line's E²/(2k_ur) and the contact spring's E²/(2k_c)), so the wall goes back
    // to w1 along its unloading line and no farther, and keeps its set.
    const Response r2 = run_single_mass(scene, 1.6);
    double         t2 = 0.0; // the second push: the first contact after the mass left the wall
    for (const ImpactEvent &ev : r2.contacts[1].impacts)
      if (ev.time > 0.5 && t2 == 0.0)
        t2 = ev.time;
    ASSERT_GT(t2, 0.0);
    EXPECT_NEAR(wall_displacement_at(r2, 0, t2), 0.05 + s1, dynamic_tol * w1);
    EXPECT_NEAR(wall_displacement_at(r2, 1, t2 - 1e-3), s1, dynamic_tol * w1);
    EXPECT_NEAR(r2.contacts[2].peak_deformation, w1, dynamic_tol * w1);
    EXPECT_NEAR(r2.contacts[2].permanent_indentation, part.permanent_indentation, 1e-3 * s1);
  }

  TEST(YieldingWall, WallPushedPastItsLimitIsReportedFailedWithTheTime)
  {
    WallBackfillParams p      = wall_part();
    p.failure_displacement    = 0.02;
    const Response       r    = run_single_mass(single_mass_scene(p), 0.09);
    const ContactResult &part = r.contacts[2];
    ASSERT_TRUE(part.failure_time);
    // Contact starts at 0.05 s (5 cm at 1 m/s); the wall reaches 2 cm a few ms later, before
    // its peak (the mass still moves at most 1 m/s: at least 20 ms after contact).
    EXPECT_GT(*part.failure_time, 0.05 + 0.02 / 1.0);
    EXPECT_LT(*part.failure_time, 0.09);
    EXPECT_GT(part.peak_deformation, 0.02);

    WallBackfillParams strong   = wall_part();
    strong.failure_displacement = 1.0;
    EXPECT_FALSE(run_single_mass(single_mass_scene(strong), 0.09).contacts[2].failure_time);
  }

  namespace
  {
    /// The thesis building between two equal yielding walls at 10 cm: contact part modified
    /// Kelvin-Voigt 2.5 GN/m, wall part k = 500 MN/m, capacity 3 MN, α = 2 %, k_ur = 1 GN/m,
    /// pull-back 3 MN, c_r = 10 MN·s/m, 100 t.
    PoundingScene yielding_building_scene()
    {
      PoundingScene      scene = kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, 0.10);
      WallBackfillParams p     = kimp::testing::bilinear_wall_part(500e6, 3e6, 0.02, 1e9);
      p.tension_capacity       = 3e6;
      p.radiation_damping      = 10e6;
      for (auto *wall : {&scene.left_wall, &scene.right_wall})
      {
        (*wall)->yielding  = p;
        (*wall)->sdof_mass = 100e3;
      }
      return scene;
    }
  } // namespace

  TEST(YieldingWall, BuildingRunClosesTheEnergyBalanceWithPlasticAndRadiatedWork)
  {
    CentralDifferenceOptions opt;
    opt.dt                    = 5e-5;
    const PoundingModel model = PoundingModel(yielding_building_scene());
    const Response r = CentralDifference(model, opt).run(kimp::testing::near_fault_motion(12.0));
    const EnergyBalance &e = r.energy;
    ASSERT_GT(r.n_impacts(), 0u);
    std::cout << "relative error " << e.relative_error << ", max " << e.max_relative_error
              << ", input " << e.input << " J, wall plastic " << e.wall_plastic << " J, radiated "
              << e.wall_radiated << " J, impact " << e.impact_dissipated << " J\n";
    EXPECT_LT(e.relative_error, balance_tol);
    EXPECT_LT(e.max_relative_error, balance_tol);
    EXPECT_GT(e.wall_plastic, 0.0);
    EXPECT_GT(e.wall_radiated, 0.0);
    // The walls' work is part of the contact work (with the impact laws' dissipation and what
    // the laws still store at the end).
    EXPECT_GT(e.contact_work, e.wall_plastic + e.wall_radiated);
    EXPECT_LT(e.contact_work - (e.wall_plastic + e.wall_radiated + e.impact_dissipated),
              0.01 * e.input);
  }

  TEST(YieldingWall, TwoEqualWallsMirrorUnderTheNegatedRecord)
  {
    CentralDifferenceOptions opt;
    opt.dt                    = 5e-5;
    const PoundingModel model = PoundingModel(yielding_building_scene());
    GroundMotion        g     = kimp::testing::near_fault_motion(8.0);
    const Response      a     = CentralDifference(model, opt).run(g);
    for (double &x : g.acceleration)
      x = -x;
    const Response b = CentralDifference(model, opt).run(g);
    ASSERT_EQ(a.contacts.size(), 4u); // left_wall, right_wall, left_wall_backfill, right_...
    for (const auto &[l, rr] : {std::pair<std::size_t, std::size_t>{0, 1}, {2, 3}})
    {
      EXPECT_NEAR(a.contacts[l].peak_force,
                  b.contacts[rr].peak_force,
                  1e-9 * a.contacts[l].peak_force + 1e-6);
      EXPECT_NEAR(a.contacts[l].peak_deformation, b.contacts[rr].peak_deformation, 1e-12);
      EXPECT_NEAR(a.contacts[l].permanent_indentation, b.contacts[rr].permanent_indentation, 1e-12);
    }
    EXPECT_GT(a.contacts[2].plastic_work + a.contacts[3].plastic_work, 0.0);
  }

  TEST(YieldingWall, NewmarkAgreesWithTheCentralDifference)
  {
    const PoundingScene scene = single_mass_scene(wall_part());
    const Response      cdm   = run_single_mass(scene, 0.09);
    NewmarkOptions      opt;
    opt.dt               = 2e-6;
    opt.output_interval  = 1e-4;
    opt.initial_velocity = {1.0, 0.0};
    const Response nm =
      NewmarkIntegrator(PoundingModel(scene), opt).run(kimp::testing::zero_motion(1e-3, 0.09));
    EXPECT_NEAR(nm.contacts[2].peak_deformation,
                cdm.contacts[2].peak_deformation,
                1e-3 * cdm.contacts[2].peak_deformation);
    EXPECT_NEAR(nm.contacts[2].permanent_indentation,
                cdm.contacts[2].permanent_indentation,
                1e-2 * cdm.contacts[2].permanent_indentation);
    EXPECT_LT(nm.energy.relative_error, balance_tol);
  }
} // namespace kimp::lumped
