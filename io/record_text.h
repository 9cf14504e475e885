// The text layer shared by the ground-motion readers of io/at2_reader.h (private to io/): lines
// split at any terminator, the check for empty or binary files, Fortran reals, numeric tokens.
// Every failure is a GroundMotionFileError naming the file and line.
#pragma once

#include <cctype>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "io/at2_reader.h"

namespace kimp::io::detail
{
  /// What an AT2 file holds, the "(expected ...)" of its messages.
  inline constexpr const char *at2_expectation =
    "expected 3 header lines, then an NPTS/DT line such as 'NPTS=  4000, DT= .01000 SEC' or "
    "'4000    0.0100    NPTS, DT', then NPTS values in the unit the header states";

  /// `value` with 10 significant digits, for messages.
  std::string format_number(double value);

  [[noreturn]] inline void
  fail(const std::string &source, std::size_t line, const std::string &message)
  {
    throw GroundMotionFileError(source, line, message);
  }

  inline bool is_blank(char c)
  {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
  }

  inline bool is_digit(char c)
  {
    return c >= '0' && c <= '9';
  }

  inline bool is_word_char(char c)
  {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
  }

  struct Line
  {
    std::string_view text;   // without the line terminator
    std::size_t      number; // 1-based
  };

  struct SplitText
  {
    std::vector<Line> lines;
    bool              ends_with_newline = false;
  };

  /// The lines of `content`; terminators LF, CRLF and a lone CR (classic Mac files) all end one.
  SplitText split_lines(std::string_view content);

  /// Empty content and binary junk are reported before any format decision.
  void check_text(std::string_view content, const std::string &source);

  /**
   * Scan one Fortran real starting at `pos` (no leading blanks): [sign] mantissa with at least
   * one digit and at most one '.', then an optional exponent [EeDd][sign]digits, or a
   * letterless 3-digit exponent "±ddd" after a mantissa with '.', as Fortran writes |exp| >= 100.
   * Returns the end position, or npos if no valid number starts at `pos`.
   */
  std::size_t scan_real(std::string_view s, std::size_t pos, double &value);

  /// The whole file as bytes; a directory or an unreadable file is a GroundMotionFileError.
  std::string read_file(const std::filesystem::path &file);

  /// Numeric tokens of a two-column line (comment already removed); on a non-numeric token,
  /// `ok` is false and the token is returned in `bad`.
  std::vector<double> split_numbers(std::string_view s, std::string &bad, bool &ok);

  /// `s` up to its first '#'.
  std::string_view strip_comment(std::string_view s);

  /// The file stem of `source`: the record's name.
  std::string stem_of(const std::string &source);
} // namespace kimp::io::detail
