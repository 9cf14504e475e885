// The FEM-level status of a fit (app::fem_fit_verdict): a run whose wall breaks (the slab passes
// through) has no impact stiffness however well a law fits its force; a wall that yields and
// stops the slab (apparent COR < 0.1) gives a k flagged as a yielding wall's; otherwise
// fit::fit_verdict() decides.
#include <gtest/gtest.h>
#include <limits>
#include <string>

#include "app/laws/fit_run.h"
#include "fit/fit_config.h"
#include "tests/support/fit_results.h"

namespace
{
  using kimp::fit::FitResult;

  using kimp::testing::good_fit;
  using kimp::testing::starts_with;

  /// The default scene's slab at 1 m/s (E0 = 1920 J/m), run ended on separation.
  kimp::io::FemCase separated_case(double cor, double damage, double plastic)
  {
    kimp::io::FemCase c;
    c.labels["stopped_on"]        = "separation";
    c.slab_mass                   = 3840.0;
    c.impact_velocity             = 1.0;
    c.summary.apparent_cor        = cor;
    c.summary.damage_dissipation  = damage;
    c.summary.plastic_dissipation = plastic;
    return c;
  }

  /// The same, stopped at its end time.
  kimp::io::FemCase unfinished_case(double cor, double damage, double plastic)
  {
    kimp::io::FemCase c    = separated_case(cor, damage, plastic);
    c.labels["stopped_on"] = "end_time";
    return c;
  }

  /// Expects the verdict on `c` with a well-determined fit to start with `prefix`.
  void expect_verdict_starts_with(const kimp::io::FemCase &c, const std::string &prefix)
  {
    const std::string verdict = kimp::app::fem_fit_verdict(c, good_fit());
    EXPECT_TRUE(starts_with(verdict, prefix)) << verdict;
  }

  TEST(FemFitVerdict, ABrokenWallFailsAYieldingOneWarns)
  {
    // Plain concrete, measured: cracked through at the base, the slab keeps 80 % of its speed
    // until the end time (a run ends on separation only once the slab comes in at <= 5 % of
    // its impact speed).
    expect_verdict_starts_with(unfinished_case(-0.79, 105.5, 0.0),
                               "failed: the slab passes through (apparent COR -0.79 at the end "
                               "time: it keeps 62.4 %");
    // Reinforced wall, measured: it yields and stops the slab (1581 of 1920 J/m dissipated) and
    // leaves with 1.7 % of its speed.
    expect_verdict_starts_with(separated_case(0.0174, 613.0, 968.1),
                               "warning: the wall yields: the slab is stopped, not rebounded "
                               "(apparent COR 0.0174; material dissipation 82.3 %");
    // Comes to rest against the wall: no rebound either.
    expect_verdict_starts_with(separated_case(0.0, 608.0, 811.0), "warning: the wall yields");
    // Still pushing the wall at the end time, slower than half its impact speed.
    expect_verdict_starts_with(unfinished_case(-0.3, 608.0, 811.0),
                               "warning: the wall yields: the slab still moves in at the end "
                               "time (apparent COR -0.3 at the end time");
    // A fit that fails on its own stays failed.
    FitResult unbounded       = good_fit();
    unbounded.stiffness.upper = std::numeric_limits<double>::infinity();
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(0.0174, 608.0, 811.0), unbounded),
              kimp::fit::fit_verdict(unbounded));
  }

  TEST(FemFitVerdict, ReboundOrNoMaterialDissipationIsJudgedByTheFit)
  {
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(0.75, 600.0, 800.0), good_fit()), "ok");
    // Just above the threshold: the slab leaves with 1.2 % of the impact energy.
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(0.11, 600.0, 800.0), good_fit()), "ok");
    FitResult unbounded       = good_fit();
    unbounded.stiffness.upper = std::numeric_limits<double>::infinity();
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(0.75, 0.0, 0.0), unbounded),
              kimp::fit::fit_verdict(unbounded));
    // A linear wall still chattering with a rigid slab at the end time (measured before runs
    // waited for the slab to turn: H = 2 m, 10 cm mesh, COR -0.617): not failure.
    EXPECT_EQ(kimp::app::fem_fit_verdict(unfinished_case(-0.617, 0.0, 0.0), good_fit()), "ok");
    // A result file without the COR: the fit decides.
    kimp::io::FemCase no_cor = unfinished_case(-0.79, 105.5, 0.0);
    no_cor.summary.apparent_cor.reset();
    EXPECT_EQ(kimp::app::fem_fit_verdict(no_cor, good_fit()), "ok");
  }
} // namespace
