// The explicit impact solver holds the geostatic state: the reinforced wall with its
// Mohr-Coulomb backfill (the docs/validation.md scene: medium_dense_sand, K0 = 1 - sin(phi),
// concrete from f_cm = 38 MPa with the wall's bars, wall-soil contact interface), no impact,
// stays at rest for 1 s of explicit time. Numbers: docs/validation.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <memory>
#include <string>

#include "fem/inelastic_laws.h"
#include "tests/fem/impact_test_support.h"
#include "tests/fem/inelastic_scenes.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  /** The scene on the coarsest ladder mesh (5 cm at the contact, 20 cm elsewhere), rigid slab
   *  5 cm away at 1 cm/s (contact after 5 s: none in the run), interface contact or bonded. */
  ImpactParameters resting_wall(const std::string &name, bool interface)
  {
    auto                    p  = geostatic_scene(name, true, 0.05, interface);
    const auto              cp = ConcreteParameters::from_f_cm(38e6);
    ReinforcementParameters bars;
    bars.ratio_x                        = 0.002;
    bars.ratio_y                        = 0.008;
    p.materials[ids::wall_material]     = Material{cp.youngs_modulus, cp.poisson_ratio, 2400};
    p.material_laws[ids::wall_material] = std::make_shared<const ConcreteDamageLaw>(cp, bars);
    p.slab_mass                         = 1e9;
    p.slab_front_x                      = -0.05;
    p.initial_velocity                  = 0.01;
    p.end_time                          = 1.0;
    p.separation_hold_time              = p.end_time;
    p.output_interval                   = 1e-3;
    return p;
  }

  /** Largest |wall face displacement| (m) over the run. */
  double largest_wall_move(const ImpactResult &r)
  {
    double m = 0;
    for (const double w : r.history.wall_displacement)
      m = std::max(m, std::abs(w));
    return m;
  }

  // The geostatic state is the explicit operator's equilibrium (the same internal force, with the
  // soil's B-bar, balances gravity and the initial stress to 1e-8 of the weight): without an
  // impact the wall face stays within 0.1 mm of it for 1 s. The coarsest ladder mesh keeps the
  // 1 s (about 1.5e5 steps) affordable in the unit suite.
  TEST(GeostaticWall, StaysAtRestForOneSecond)
  {
    constexpr double limit = 1e-4; // m
    for (const bool interface : {true, false})
    {
      const auto p = resting_wall(interface ? "rest_interface.msh" : "rest_bonded.msh", interface);
      const auto r = run_impact(p, MPI_COMM_WORLD, nullptr);
      const double moved = largest_wall_move(r);
      const double k0    = p.geostatic.initial_stress_K0.at(ids::soil_material);
      const double gamma = p.materials.at(ids::soil_material).density * p.geostatic.gravity;
      const double H     = 1.25;
      if (rank() == 0)
        std::printf("%s: geostatic residual %.2e of the weight, wall face %.4g mm after the "
                    "static step; over %.3g s (%lu steps of %.3g us, %.1f s): largest move "
                    "%.4g mm, at the end %.4g mm; interface normal force %.5g kN/m against "
                    "K0 gamma H^2 / 2 = %.5g kN/m; plastic dissipation %.3g J/m\n",
                    interface ? "interface" : "bonded",
                    r.summary.geostatic_residual,
                    r.summary.geostatic_wall_displacement * 1e3,
                    r.history.time.back(),
                    r.summary.n_steps,
                    r.summary.dt * 1e6,
                    r.summary.wall_seconds,
                    moved * 1e3,
                    r.history.wall_displacement.back() * 1e3,
                    r.summary.interface_normal_force / 1e3,
                    0.5 * k0 * gamma * H * H / 1e3,
                    r.summary.plastic_dissipation);
      EXPECT_GE(r.history.time.back(), 0.999);
      EXPECT_EQ(r.summary.impulse, 0.0);
      EXPECT_LT(moved, limit);
    }
  }
} // namespace
