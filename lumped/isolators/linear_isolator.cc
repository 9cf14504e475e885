// Linear isolator f = k·u: parameter checks.
#include "lumped/isolators/linear_isolator.h"

#include <cmath>

namespace kimp::lumped
{
  LinearIsolator::LinearIsolator(const double k, const double c)
    : k_(k)
    , c_(c)
  {
    require_positive_isolator("k", k, "N/m");
    require_non_negative_isolator("c", c, "N*s/m");
  }
} // namespace kimp::lumped
