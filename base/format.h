// Numbers for people: a few significant figures in reports and log lines (full precision stays in
// HDF5, JSON and CSV).
#pragma once

#include <string>

namespace kimp::base
{
  /// Significant figures of numbers in reports and log lines.
  inline constexpr int readable_digits = 4;

  /**
   * `value` with `digits` significant figures: fixed notation for 1e-3 <= |value| < 1e6
   * (166.827 -> "166.8", 0.156019 -> "0.1560", 57.5 -> "57.50"), scientific outside
   * (2.5e9 -> "2.500e+09"); "0" for zero, "nan", "inf", "-inf".
   */
  std::string sig(double value, int digits = readable_digits);
} // namespace kimp::base
