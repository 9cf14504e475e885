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
    fem_case.summary.apparent_cor = -0.79; // measured with a plain-concrete wall at 1 m/s
    const std::string status      = kimp::app::fem_fit_verdict(fem_case, good_fit());
    EXPECT_EQ(status.rfind("failed: the slab does not rebound (apparent COR -0.79)", 0), 0u)
      << status;
    fem_case.summary.apparent_cor = 0.0; // comes to rest against the wall: no rebound either
    EXPECT_EQ(kimp::app::fem_fit_verdict(fem_case, good_fit()).rfind("failed:", 0), 0u);
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
