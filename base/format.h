// Numbers and quoted values for people: a few significant figures in reports and log lines (full
// precision stays in HDF5, JSON and CSV), and a bad value quoted in a message at most so long.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

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

  /// Most characters of a value that a message quotes (a scene value, a command-line argument).
  inline constexpr std::size_t quoted_value_limit = 80;

  /**
   * `text` as a message quotes it: unchanged up to `limit` bytes, else its beginning (cut at a
   * UTF-8 character boundary) followed by "... (N bytes)", `limit` bytes in all, so that a 1 MB
   * value in a scene or on the command line gives a message of one readable line.
   */
  std::string excerpt(std::string_view text, std::size_t limit = quoted_value_limit);

  /// `message` with every word (a run without blanks) longer than quoted_value_limit shortened by
  /// excerpt(): for messages of libraries that quote a bad value whole (CLI11).
  std::string shorten_long_words(std::string_view message);
} // namespace kimp::base
