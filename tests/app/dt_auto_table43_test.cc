// `dt: auto` (variable-step central differences) on the Table 4.3 scene, all twelve cases: the
// peaks within 0.5 % of the Δt → 0 reference at no more than twice the steps of `dt: stable`
// (the fixed stability-limited step auto used to take). The references are Richardson
// extrapolations 2·P(5e-6 s) − P(1e-5 s) of fixed-step runs (bench/dt_auto_bench prints them);
// the test skips without the Kobe record.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <optional>
#include <string>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_run.h"
#include "app/lumped/lumped_scene.h"
#include "tests/support/files.h"

namespace
{
  using namespace kimp::io;
  using namespace kimp::app;

  /// Peak impact force (N, largest over both walls), base and roof |ü + ü_g| (m/s²), base and
  /// roof |u| (m) at Δt → 0.
  struct Reference
  {
    double force, base_acc, roof_acc, base_u, roof_u;
  };

  const std::map<std::string, Reference> &references()
  {
    static const std::map<std::string, Reference> table = {
      {"linear", {1.75853e+07, 51.3414, 28.3177, 0.157034, 0.216762}},
      {"kelvin_voigt", {1.58379e+07, 47.4188, 27.4383, 0.156239, 0.213834}},
      {"modified_kelvin_voigt", {1.58379e+07, 47.4188, 27.3989, 0.156239, 0.21396}},
      {"jankowski", {1.39639e+07, 42.5016, 26.2122, 0.156824, 0.212919}},
      {"hertzdamp", {1.66528e+07, 50.3447, 26.1059, 0.157683, 0.212548}},
      {"hysteretic", {1.84495e+07, 51.9242, 26.4678, 0.158458, 0.210955}},
      {"linear_scaled", {1.65089e+07, 45.9426, 24.2441, 0.156604, 0.186383}},
      {"kelvin_voigt_scaled", {1.4278e+07, 39.0022, 20.4492, 0.155631, 0.186361}},
      {"modified_kelvin_voigt_scaled", {1.43178e+07, 39.4935, 20.7742, 0.155646, 0.186361}},
      {"jankowski_scaled", {1.18744e+07, 33.1149, 20.4943, 0.156026, 0.186386}},
      {"hertzdamp_scaled", {1.39714e+07, 41.2133, 21.4474, 0.156822, 0.186416}},
      {"hysteretic_scaled", {1.46409e+07, 42.6133, 20.8633, 0.15725, 0.186428}}};
    return table;
  }

  /// The target of `dt: auto`: every peak within 0.5 % of Δt → 0 (measured: 0.29 % at most).
  constexpr double tolerance = 0.005;
  /// At most twice the steps of `dt: stable`, the error-estimate re-runs included (measured:
  /// 1.40-1.48×).
  constexpr double cost_factor = 2.0;

  /// The scene's record, or nothing if it is not available (the tests then skip).
  std::optional<kimp::lumped::GroundMotion> record_of(const LumpedScene &scene)
  {
    const auto dir = scene_records_directory(scene.ground_motion);
    if (!dir || !std::filesystem::exists(*dir / (scene.ground_motion.record + ".AT2")))
      return std::nullopt;
    return load_ground_motion(scene.ground_motion);
  }

  /// One case with `dt: auto` and with `dt: stable` (no companion run).
  struct AutoAndStable
  {
    LumpedCaseResult var, old;
    double           steps = 0; ///< auto's steps with the error-estimate re-runs
  };
  /// Both runs of one case, which must succeed (auto with its adaptive report); call it inside
  /// ASSERT_NO_FATAL_FAILURE().
  void run_auto_and_stable(const std::string                &name,
                           LumpedScene                       resolved,
                           const kimp::lumped::GroundMotion &motion,
                           double                            scale,
                           AutoAndStable                    &r)
  {
    resolved.integration.companion = false;
    resolved.integration.dt        = "auto";
    r.var                          = run_lumped_case(name, resolved, motion, scale);
    resolved.integration.dt        = "stable";
    r.old                          = run_lumped_case(name, resolved, motion, scale);
    ASSERT_TRUE(r.var.ok()) << r.var.status;
    ASSERT_TRUE(r.old.ok()) << r.old.status;
    ASSERT_TRUE(r.var.adaptive.has_value()) << name;
    r.steps = static_cast<double>(r.var.response.n_steps + r.var.adaptive->estimate_steps);
  }

  /// The shipped scene data/scenes/`file`.
  LumpedScene shipped_scene(const std::string &file)
  {
    return load_scene<LumpedScene>(kimp::testing::source_dir() / "data" / "scenes" / file);
  }

  /// Base and roof peak |ü + ü_g| and |u| of `r` relative to the reference (%), and the steps
  /// of `run` against those of `dt: stable`, as one line.
  std::string differences(const AutoAndStable &run, const Reference &ref)
  {
    const kimp::lumped::Response &r = run.var.response;
    const long                    n = run.old.response.n_steps;
    char                          line[256];
    std::snprintf(line,
                  sizeof line,
                  "base acc %+.3f %%, roof acc %+.3f %%, base u %+.4f %%, roof u %+.4f %%; %.0f "
                  "steps = %.2f x stable (%ld)",
                  100 * (r.peak_absolute_acceleration[0] / ref.base_acc - 1),
                  100 * (r.peak_absolute_acceleration[4] / ref.roof_acc - 1),
                  100 * (r.peak_displacement[0] / ref.base_u - 1),
                  100 * (r.peak_displacement[4] / ref.roof_u - 1),
                  run.steps,
                  run.steps / static_cast<double>(n),
                  n);
    return line;
  }

  /// Base and roof peak |ü + ü_g| and |u| of auto within `tolerance` of the reference, at no
  /// more than cost_factor times the steps of `dt: stable`, with the energy balance closed.
  void expect_near_at_cost(const AutoAndStable &run, const Reference &ref, const std::string &name)
  {
    const kimp::lumped::Response &r = run.var.response;
    EXPECT_NEAR(r.peak_absolute_acceleration[0], ref.base_acc, tolerance * ref.base_acc) << name;
    EXPECT_NEAR(r.peak_absolute_acceleration[4], ref.roof_acc, tolerance * ref.roof_acc) << name;
    EXPECT_NEAR(r.peak_displacement[0], ref.base_u, tolerance * ref.base_u) << name;
    EXPECT_NEAR(r.peak_displacement[4], ref.roof_u, tolerance * ref.roof_u) << name;
    EXPECT_LE(run.steps, cost_factor * static_cast<double>(run.old.response.n_steps)) << name;
    EXPECT_LT(r.energy.max_relative_error, 1e-3) << name;
  }
} // namespace

TEST(DtAuto, Table43EveryCaseWithinHalfAPercentAtTwiceTheStableCost)
{
  const LumpedScene scene  = shipped_scene("table_4_3_kobe_gap15.yaml");
  const auto        motion = record_of(scene);
  if (!motion)
    GTEST_SKIP() << "record " << scene.ground_motion.record << " not available";
  for (const auto &[name, resolved] : resolve_cases(scene))
  {
    AutoAndStable run;
    ASSERT_NO_FATAL_FAILURE(
      run_auto_and_stable(name, resolved, *motion, scene.ground_motion.scale, run));
    const LumpedCaseResult &var = run.var;
    EXPECT_EQ(var.dt_policy, "variable");
    EXPECT_EQ(run.old.dt_policy, "stable");
    const Reference &ref   = references().at(name);
    double           force = 0.0;
    for (const auto &c : var.response.contacts)
      force = std::max(force, c.peak_force);
    std::printf("%-28s force %+.3f %%, %s; estimated force error %.3f %%\n",
                name.c_str(),
                100 * (force / ref.force - 1),
                differences(run, ref).c_str(),
                100 * var.adaptive->force_error);
    EXPECT_NEAR(force, ref.force, tolerance * ref.force) << name;
    expect_near_at_cost(run, ref, name);
    // The estimate (windows only, first order assumed) is reported; measured 0.09-0.85 %, an
    // over-estimate for the linear-family laws, near the true error for the others.
    EXPECT_GT(var.adaptive->force_error, 0.0) << name;
    EXPECT_LT(var.adaptive->force_error, 0.02) << name;
  }
}

TEST(DtAuto, FrictionPendulumWithinHalfAPercentOfTheConvergedPeaks)
{
  // The friction pendulum on Kobe (no impact: the gaps stay open): its peaks are set by the
  // stick-slip of the bearing, whose velocity reversals `dt: auto` locates within a step and
  // whose stick phases it integrates at Δt_stick. Reference: Richardson 2·P(5e-6 s) − P(1e-5 s)
  // of fixed-step runs (bench/dt_auto_bench); measured: base acc +0.37 %, roof acc +0.08 %, base
  // and roof u +0.06 %, 1.61x the steps of `dt: stable` (before: +1.38 % / +1.02 %).
  const LumpedScene scene  = shipped_scene("friction_pendulum_kobe_gap15.yaml");
  const auto        motion = record_of(scene);
  if (!motion)
    GTEST_SKIP() << "record " << scene.ground_motion.record << " not available";
  const Reference ref = {0.0, 4.62223, 5.70558, 0.145406, 0.156328};
  for (const auto &[name, resolved] : resolve_cases(scene))
  {
    AutoAndStable run;
    ASSERT_NO_FATAL_FAILURE(
      run_auto_and_stable(name, resolved, *motion, scene.ground_motion.scale, run));
    EXPECT_EQ(run.var.response.n_impacts(), 0u);
    std::printf("friction pendulum: %s\n", differences(run, ref).c_str());
    expect_near_at_cost(run, ref, name);
  }
}
