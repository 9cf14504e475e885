// Directionality of the 3D (plan) response: the symmetries a sweep over the angle of incidence
// must respect (a square symmetric building repeats every 90° and mirrors about the axes, one
// with its mass off centre along x still mirrors about x), its angle 0 against the planar run, and
// the directionality table of docs/validation.md (printed).
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

#include "lumped/integrators/central_difference.h"
#include "lumped/plan/plan_directionality.h"
#include "tests/lumped/plan_scenes.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double pi  = 3.14159265358979323846;
    constexpr double tol = 1e-6; // relative: equal problems integrated in another frame

    PlanCentralDifference integrator(const double eccentricity, const double mu, const double dt)
    {
      PlanScene scene;
      scene.building = kimp::testing::plan_reference_building();
      for (PlanLevel &l : scene.building.levels)
        l.mass_eccentricity = Point(eccentricity * kimp::testing::plan_width, 0.0);
      scene.moat =
        kimp::testing::plan_moat(scene.building, "modified_kelvin_voigt", 2.5e9, 0.15, mu);
      PlanOptions opt;
      opt.dt              = dt;
      opt.output_interval = 0.0;
      return PlanCentralDifference(PlanModel(scene), opt);
    }

    void expect_same(const DirectionalPeaks &a, const DirectionalPeaks &b, const char *what)
    {
      const auto near = [&](const double x, const double y, const char *name)
      { EXPECT_NEAR(x, y, tol * std::max(std::abs(y), 1e-300)) << what << ": " << name; };
      near(a.base_corner_displacement, b.base_corner_displacement, "base corner displacement");
      near(a.corner_impact_force, b.corner_impact_force, "corner impact force");
      near(a.wall_force, b.wall_force, "wall force");
      near(a.top_acceleration, b.top_acceleration, "top acceleration");
      near(a.corner_drift, b.corner_drift, "corner drift");
      EXPECT_EQ(a.impacts, b.impacts) << what;
    }
  } // namespace

  TEST(PlanDirectionality, SymmetriesOfTheSweep)
  {
    const GroundMotion g = kimp::testing::near_fault_motion(8.0);
    {
      // Square, symmetric: θ, θ + 90° and −θ are the same problem.
      const auto peaks =
        directionality(integrator(0.0, 0.3, 1e-4), g, {0.3, 0.3 + 0.5 * pi, -0.3, 0.3 + pi});
      ASSERT_GT(peaks[0].impacts, 0u);
      expect_same(peaks[1], peaks[0], "symmetric, +90 deg");
      expect_same(peaks[2], peaks[0], "symmetric, mirrored");
      expect_same(peaks[3], peaks[0], "symmetric, +180 deg");
      // Off the axes a symmetric building still turns: the moat's friction and the corners.
      EXPECT_GT(peaks[0].rotation, 0.0);
    }
    {
      // Mass eccentric along x: still mirrored about x (−θ), no longer θ + 90° (nor θ + 180°: the
      // building is no longer point-symmetric about its centre of mass).
      const auto peaks =
        directionality(integrator(0.10, 0.3, 1e-4), g, {0.3, -0.3, 0.3 + 0.5 * pi});
      expect_same(peaks[1], peaks[0], "eccentric, mirrored");
      EXPECT_GT(std::abs(peaks[2].base_corner_displacement - peaks[0].base_corner_displacement),
                1e-3 * peaks[0].base_corner_displacement);
      EXPECT_GT(peaks[0].rotation * kimp::testing::plan_width,
                1e-2 * peaks[0].base_corner_displacement);
    }
  }

  TEST(PlanDirectionality, AngleZeroIsThePlanarRun)
  {
    const GroundMotion       g     = kimp::testing::near_fault_motion(8.0);
    const auto               peaks = directionality(integrator(0.0, 0.3, 1e-4), g, {0.0});
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;
    const Response planar =
      CentralDifference(PoundingModel(
                          kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, 0.15)),
                        opt)
        .run(g);
    ASSERT_GT(planar.n_impacts(), 0u);
    EXPECT_NEAR(peaks[0].base_corner_displacement,
                planar.peak_displacement[0],
                1e-9 * planar.peak_displacement[0]);
    const double f = std::max(planar.contacts[0].peak_force, planar.contacts[1].peak_force);
    EXPECT_NEAR(peaks[0].wall_force, f, 1e-9 * f);
    // Each corner of the striking edge carries half of the wall's force.
    EXPECT_NEAR(peaks[0].corner_impact_force, 0.5 * f, 1e-9 * f);
    EXPECT_NEAR(peaks[0].top_acceleration,
                planar.peak_absolute_acceleration.back(),
                1e-9 * planar.peak_absolute_acceleration.back());
    EXPECT_EQ(peaks[0].rotation, 0.0);
  }

  TEST(PlanDirectionality, TableOfTheSyntheticMotion)
  {
    // docs/validation.md: the thesis' building in a moat at 15 cm (Table 4.3 walls, μ = 0.3),
    // the synthetic near-fault motion (20 s), eccentricity 0, 5 and 10 % of the plan along x,
    // 0-180° in 15° steps, Δt = 1e-4 s.
    const GroundMotion  g = kimp::testing::near_fault_motion(20.0);
    std::vector<double> angles;
    for (int a = 0; a <= 180; a += 15)
      angles.push_back(a * pi / 180.0);
    std::printf("ecc angle base_corner_cm corner_force_MN wall_force_MN top_acc_g drift_mm "
                "rotation_mrad impacts\n");
    for (const double e : {0.0, 0.05, 0.10})
    {
      const auto peaks = directionality(integrator(e, 0.3, 1e-4), g, angles);
      for (const DirectionalPeaks &p : peaks)
        std::printf("%.2f %3.0f %.4g %.4g %.4g %.4g %.4g %.4g %zu\n",
                    e,
                    p.angle * 180.0 / pi,
                    p.base_corner_displacement * 100.0,
                    p.corner_impact_force / 1e6,
                    p.wall_force / 1e6,
                    p.top_acceleration / standard_gravity,
                    p.corner_drift * 1e3,
                    p.rotation * 1e3,
                    p.impacts);
      // Angles 0 and 180° are the same problem (odd laws).
      expect_same(peaks.back(), peaks.front(), "0 and 180 deg");
    }
  }
} // namespace kimp::lumped::plan
