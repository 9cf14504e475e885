// Numbers and quoted values for people; see format.h.
#include "base/format.h"

#include <algorithm>
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

  std::string excerpt(std::string_view text, std::size_t limit)
  {
    if (text.size() <= limit)
      return std::string(text);
    const std::string tail = fmt::format("... ({} bytes)", text.size());
    std::size_t       keep = limit > tail.size() ? limit - tail.size() : 0;
    // Not inside a UTF-8 sequence: back up over continuation bytes (10xxxxxx).
    while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0u) == 0x80u)
      --keep;
    return std::string(text.substr(0, keep)) + tail;
  }

  std::string shorten_long_words(std::string_view message)
  {
    std::string out;
    std::size_t i = 0;
    while (i < message.size())
    {
      const std::size_t end = std::min(message.find_first_of(" \t\n", i), message.size());
      out += excerpt(message.substr(i, end - i));
      if (end < message.size())
        out += message[end];
      i = end + 1;
    }
    return out;
  }
} // namespace kimp::base
