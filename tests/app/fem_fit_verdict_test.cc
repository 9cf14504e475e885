// The FEM-level status of a fit (app::fem_fit_verdict): a run whose slab does not rebound
// (apparent COR <= 0, the wall or the backfill gives way) has no impact stiffness, however well
// a law fits its force; otherwise the status is fit::fit_verdict()'s.
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

  TEST(FemFitVerdict, NoReboundFailsWhateverTheFit)
  {
    kimp::io::FemCase fem_case;
    fem_case.labels["stopped_on"] = "separation";
    fem_case.slab_mass            = 3840.0; // kg/m, at 1 m/s: E0 = 1920 J/m
    fem_case.impact_velocity      = 1.0;
    // measured with a plain-concrete wall at 1 m/s: damage 105.5 J/m, COR -0.79
    fem_case.summary.extra["damage_dissipation"] = 105.5;
    fem_case.summary.apparent_cor                = -0.79;
    const std::string status                     = kimp::app::fem_fit_verdict(fem_case, good_fit());
    EXPECT_EQ(status.rfind("failed: the slab does not rebound (apparent COR -0.79)", 0), 0u)
      << status;
    fem_case.summary.apparent_cor = 0.0; // comes to rest against the wall: no rebound either
    EXPECT_EQ(kimp::app::fem_fit_verdict(fem_case, good_fit()).rfind("failed:", 0), 0u);
    // A run stopped at its end time (a rigid slab still chattering) has no rebound velocity:
    // its slab velocity at that instant says nothing, the fit decides.
    fem_case.labels["stopped_on"] = "end_time";
    fem_case.summary.apparent_cor = -0.6;
    EXPECT_EQ(kimp::app::fem_fit_verdict(fem_case, good_fit()), "ok");
    // A linear wall (no material dissipation) that sends a rigid slab off still moving in
    // (measured: H = 2 m, 10 cm mesh, COR -0.617): chatter, not failure.
    fem_case.labels["stopped_on"]                = "separation";
    fem_case.summary.extra["damage_dissipation"] = 0.0;
    EXPECT_EQ(kimp::app::fem_fit_verdict(fem_case, good_fit()), "ok");
  }

  TEST(FemFitVerdict, ReboundingRunIsJudgedByTheFit)
  {
    kimp::io::FemCase fem_case;
    fem_case.summary.apparent_cor = 0.75;
    EXPECT_EQ(kimp::app::fem_fit_verdict(fem_case, good_fit()), "ok");
    FitResult unbounded        = good_fit();
    unbounded.stiffness.upper  = std::numeric_limits<double>::infinity();
    const std::string from_fit = kimp::fit::fit_verdict(unbounded);
    EXPECT_EQ(kimp::app::fem_fit_verdict(fem_case, unbounded), from_fit);
    fem_case.summary.apparent_cor.reset(); // a result file without it: the fit decides
    EXPECT_EQ(kimp::app::fem_fit_verdict(fem_case, good_fit()), "ok");
  }
} // namespace
