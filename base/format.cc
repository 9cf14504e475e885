// Numbers for people; see format.h.
#include "base/format.h"

#include <cmath>
#include <fmt/format.h>

namespace kimp::base
{
  std::string sig(double value, int digits)
  {
    if (std::isnan(value))
      return "nan";
    if (std::isinf(value))
      return value > 0 ? "inf" : "-inf";
    if (value == 0.0)
      return "0";
    digits                 = digits < 1 ? 1 : digits;
    const double magnitude = std::fabs(value);
    if (magnitude < 1e-3 || magnitude >= 1e6)
      return fmt::format("{:.{}e}", value, digits - 1);
    // Decimals from the exponent of the rounded value (9.99996 prints as 10.00, not 10.000).
    int exponent = static_cast<int>(std::floor(std::log10(magnitude)));
    int decimals = digits - 1 - exponent;
    if (decimals > 0 &&
        std::fabs(std::round(value * std::pow(10.0, decimals))) >= std::pow(10.0, digits))
      --decimals;
    return fmt::format("{:.{}f}", value, decimals < 0 ? 0 : decimals);
  }
} // namespace kimp::base
