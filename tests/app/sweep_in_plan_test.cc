// Sweeps of scenes in plan: each case one run of the plan engine, its peaks as metrics; the swept
// angle of incidence and eccentricity reach the engine (a symmetric building answers 0° and 90°
// alike, an eccentric one turns), and a row holds what a run of its scene alone gives.
#include <cmath>
#include <gtest/gtest.h>
#include <string>

#include "app/lumped/plan_run.h"
#include "app/sweep/sweep_engine.h"
#include "app/sweep/sweep_estimate.h"
#include "base/logging.h"
#include "io/scene_io.h"
#include "tests/app/lumped_sweeps.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::app::SweepPlan;
  using kimp::app::SweepTable;

  /// The default building in a moat at 4 cm with μ = 0.3 under 6 s of the synthetic motion.
  const std::string base_scene = "ground_motion:\n"
                                 "  duration: \"6 s\"\n"
                                 "integration:\n"
                                 "  dt: \"2e-4 s\"\n"
                                 "  output_interval: \"0 s\"\n"
                                 "plan:\n"
                                 "  moat:\n"
                                 "    gap: \"4 cm\"\n"
                                 "    friction: 0.3\n";

  double metric(const SweepTable &t, std::size_t row, const std::string &name)
  {
    for (std::size_t m = 0; m < t.metric_names.size(); ++m)
      if (t.metric_names[m] == name)
        return t.rows.at(row).metrics.at(m);
    ADD_FAILURE() << "no metric " << name;
    return NAN;
  }

  /// The row whose parameter values are `angle` and `eccentricity`.
  std::size_t row_of(const SweepTable &t, const std::string &angle, const std::string &ecc)
  {
    for (std::size_t r = 0; r < t.rows.size(); ++r)
      if (t.rows[r].values.at(0) == angle && t.rows[r].values.at(1) == ecc)
        return r;
    ADD_FAILURE() << "no row " << angle << ", " << ecc;
    return 0;
  }
} // namespace

TEST(SweepInPlan, AngleAndEccentricityReachThePlanEngine)
{
  kimp::base::set_verbosity(kimp::base::Verbosity::quiet);
  const SweepPlan              plan = SweepPlan::parse("scene: base.yaml\n"
                                                       "parameters:\n"
                                                       "  plan.angle: [0, 30, 90]\n"
                                                       "  plan.eccentricity_x: [0 m, 2 m]\n",
                                          "plan.yaml",
                                          base_scene,
                                          "base.yaml");
  const kimp::testing::TempDir temp_dir("sweep_in_plan");
  const SweepTable t = kimp::testing::run_lumped_sweep(plan, temp_dir.path() / "out", false, 2);
  ASSERT_EQ(t.rows.size(), 6U);
  for (const auto &r : t.rows)
    ASSERT_EQ(r.status, "ok") << r.id;

  // Symmetric building: along y at 90° what it does along x at 0°, without turning.
  const std::size_t s0 = row_of(t, "0", "0 m"), s90 = row_of(t, "90", "0 m");
  for (const char *name : {"base_corner_displacement [m]",
                           "corner_impact_force [N]",
                           "top_acceleration [m/s^2]",
                           "corner_drift [m]",
                           "n_impacts"})
    EXPECT_NEAR(metric(t, s90, name), metric(t, s0, name), 1e-9 * std::abs(metric(t, s0, name)))
      << name;
  EXPECT_NEAR(metric(t, s90, "peak_displacement_level0_y [m]"),
              metric(t, s0, "peak_displacement_level0_x [m]"),
              1e-9 * metric(t, s0, "peak_displacement_level0_x [m]"));
  EXPECT_LT(metric(t, s0, "peak_displacement_level0_y [m]"),
            1e-12 * metric(t, s0, "peak_displacement_level0_x [m]"));
  EXPECT_GT(metric(t, s0, "n_impacts"), 0.0) << "the 4 cm moat must be struck";
  const double r_symmetric = metric(t, s90, "rotation [rad]");
  EXPECT_LT(r_symmetric, 1e-12);

  // Mass 2 m off the centroid along x, shaken along y: the building turns.
  const std::size_t e90 = row_of(t, "90", "2 m");
  EXPECT_GT(metric(t, e90, "rotation [rad]"), 1e-4);
  EXPECT_GT(metric(t, e90, "peak_displacement_level0_theta [rad]"), 1e-4);

  // A row is the run of its scene alone (angle 30°, eccentric).
  const std::size_t e30 = row_of(t, "30", "2 m");
  const auto        c   = plan.case_at(t.rows[e30].index);
  const auto        alone =
    kimp::app::run_plan(kimp::io::load_scene_text<kimp::app::PlanLumpedScene>(c.scene_text,
                                                                              c.scene_name),
                        c.scene_name,
                        c.scene_text);
  EXPECT_EQ(metric(t, e30, "base_corner_displacement [m]"),
            alone.response.peak_corner_displacement.front());
  EXPECT_EQ(metric(t, e30, "isolator_force [N]"), alone.response.peak_isolator_force);
  EXPECT_EQ(metric(t, e30, "friction_work [J]"), alone.response.energy.friction);
}

TEST(SweepInPlan, EstimateCountsThePlanDofs)
{
  kimp::base::set_verbosity(kimp::base::Verbosity::quiet);
  const auto e = kimp::app::estimate_sweep(13, base_scene, "base.yaml", std::nullopt);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->runs_per_case, 1U);
  EXPECT_EQ(e->base.n_dofs, 15U); // 5 levels × (u_x, u_y, θ)
  EXPECT_NEAR(e->base.n_steps, 6.0 / 2e-4, 1.0);
  EXPECT_NEAR(e->total_steps, 13.0 * e->base.n_steps, 1e-6 * e->total_steps);
}
