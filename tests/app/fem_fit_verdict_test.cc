// The FEM-level status of a fit (app::fem_fit_verdict): a run whose wall breaks (the slab passes
// through) has no impact stiffness however well a law fits its force; a wall that yields and
// stops the slab gives a k flagged as a yielding wall's; otherwise fit::fit_verdict() decides.
#include <gtest/gtest.h>
#include <limits>
#include <string>

#include "app/fit_run.h"
#include "fit/fit_config.h"

namespace
{
  using kimp::fit::FitResult;

  FitResult good_fit()
  {
    FitResult f;
    f.stiffness            = {1e8, 0.99e8, 1.01e8, true};
    f.cor                  = {0.7, 0.7, 0.7, false};
    f.exponent             = {1.0, 1.0, 1.0, false};
    f.fem_contact_duration = 0.02;
    f.contact_extent       = 0.02;
    return f;
  }

  bool starts_with(const std::string &text, const std::string &prefix)
  {
    return text.rfind(prefix, 0) == 0;
  }

  /// The default scene's slab at 1 m/s (E0 = 1920 J/m), run ended on separation.
  kimp::io::FemCase separated_case(double cor, double damage, double plastic)
  {
    kimp::io::FemCase c;
    c.labels["stopped_on"]                 = "separation";
    c.slab_mass                            = 3840.0;
    c.impact_velocity                      = 1.0;
    c.summary.apparent_cor                 = cor;
    c.summary.extra["damage_dissipation"]  = damage;
    c.summary.extra["plastic_dissipation"] = plastic;
    return c;
  }

  TEST(FemFitVerdict, ABrokenWallFailsAYieldingOneWarns)
  {
    // Plain concrete, measured: cracked through at the base, the slab keeps 80 % of its speed.
    const std::string broken =
      kimp::app::fem_fit_verdict(separated_case(-0.79, 105.5, 0.0), good_fit());
    EXPECT_TRUE(
      starts_with(broken, "failed: the slab passes through (apparent COR -0.79: it keeps 62.4 %"))
      << broken;
    // Reinforced wall, measured: it yields and stops the slab (1419 of 1920 J/m dissipated).
    const std::string yields =
      kimp::app::fem_fit_verdict(separated_case(-0.132, 608.0, 811.0), good_fit());
    EXPECT_TRUE(starts_with(yields,
                            "warning: the wall yields: the slab is stopped, not rebounded "
                            "(apparent COR -0.132; material dissipation 73.9 %"))
      << yields;
    // Comes to rest against the wall: no rebound either.
    EXPECT_TRUE(
      starts_with(kimp::app::fem_fit_verdict(separated_case(0.0, 608.0, 811.0), good_fit()),
                  "warning: the wall yields"));
    // A fit that fails on its own stays failed.
    FitResult unbounded       = good_fit();
    unbounded.stiffness.upper = std::numeric_limits<double>::infinity();
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(-0.132, 608.0, 811.0), unbounded),
              kimp::fit::fit_verdict(unbounded));
  }

  TEST(FemFitVerdict, ReboundOrNoMaterialDissipationIsJudgedByTheFit)
  {
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(0.75, 600.0, 800.0), good_fit()), "ok");
    FitResult unbounded       = good_fit();
    unbounded.stiffness.upper = std::numeric_limits<double>::infinity();
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(0.75, 0.0, 0.0), unbounded),
              kimp::fit::fit_verdict(unbounded));
    // A linear wall that sends a rigid slab off still moving in (measured: H = 2 m, 10 cm mesh,
    // COR -0.617): chatter, not failure.
    EXPECT_EQ(kimp::app::fem_fit_verdict(separated_case(-0.617, 0.0, 0.0), good_fit()), "ok");
    // A run stopped at its end time (a rigid slab still chattering) has no rebound velocity.
    kimp::io::FemCase at_end    = separated_case(-0.79, 105.5, 0.0);
    at_end.labels["stopped_on"] = "end_time";
    EXPECT_EQ(kimp::app::fem_fit_verdict(at_end, good_fit()), "ok");
    // A result file without the COR: the fit decides.
    kimp::io::FemCase no_cor = separated_case(-0.79, 105.5, 0.0);
    no_cor.summary.apparent_cor.reset();
    EXPECT_EQ(kimp::app::fem_fit_verdict(no_cor, good_fit()), "ok");
  }
} // namespace
