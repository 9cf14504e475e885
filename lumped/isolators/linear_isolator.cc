// Linear isolator f = k·u: parameter checks.
#include "lumped/isolators/linear_isolator.h"

#include <cmath>

namespace kimp::lumped
{
  LinearIsolator::LinearIsolator(const double k, const double c)
    : k_(k)
    , c_(c)
  {
    require_isolator(std::isfinite(k) && k > 0.0, "k", k, "N/m", "must be > 0 and finite");
    require_isolator(std::isfinite(c) && c >= 0.0, "c", c, "N*s/m", "must be >= 0 and finite");
  }
} // namespace kimp::lumped
