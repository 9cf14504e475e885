// Linear isolator f = k·u: parameter checks.
#include "lumped/isolators/linear_isolator.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kimp::lumped
{
  LinearIsolator::LinearIsolator(const double k, const double c)
    : k_(k)
    , c_(c)
  {
    if (!(std::isfinite(k) && k > 0.0))
    {
      std::ostringstream msg;
      msg << "isolator.k = " << k << " N/m (must be > 0 and finite)";
      throw std::invalid_argument(msg.str());
    }
    if (!(std::isfinite(c) && c >= 0.0))
    {
      std::ostringstream msg;
      msg << "isolator.c = " << c << " N*s/m (must be >= 0 and finite)";
      throw std::invalid_argument(msg.str());
    }
  }
} // namespace kimp::lumped
