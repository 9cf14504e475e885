// kimp::testing::good_fit(): the impact-law fit the verdict tests start from and spoil one field
// of; and starts_with() for the verdicts they check. Only for targets linking kimp::fit.
#pragma once

#include <string>

#include "fit/fit_config.h"

namespace kimp::testing
{
  /// A converged, well-determined fit: k in [0.99, 1.01]·1e8, window = the whole contact.
  inline fit::FitResult good_fit()
  {
    fit::FitResult f;
    f.stiffness            = {1e8, 0.99e8, 1.01e8, true};
    f.cor                  = {0.7, 0.7, 0.7, false};
    f.exponent             = {1.0, 1.0, 1.0, false};
    f.fem_contact_duration = 0.02;
    f.contact_extent       = 0.02;
    return f;
  }

  /// Whether `text` begins with `prefix` (a verdict with its status word, for example).
  inline bool starts_with(const std::string &text, const std::string &prefix)
  {
    return text.rfind(prefix, 0) == 0;
  }
} // namespace kimp::testing
