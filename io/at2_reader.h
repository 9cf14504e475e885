// Ground-motion files: PEER .AT2 (3 header lines, an NPTS/DT line, NPTS values in the unit the
// header states, Fortran E format) and plain two-column "time acceleration" text. Format variants:
// docs/physics.md "Ground-motion records".
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace kimp::io
{
  /// An acceleration record as read from a file: uniform samples in SI. The app makes it a
  /// lumped::GroundMotion (app::ground_motion_of), which gives its duration and PGA.
  struct AccelerationRecord
  {
    double              dt = 0.0;     ///< sampling interval, s
    std::vector<double> acceleration; ///< ü_g at t_i = i·dt, m/s²
    std::string         name;         ///< the file stem (or the source label)
  };

  /**
   * A ground-motion file that cannot be read. what() is
   * "<file>:<line>: <problem> (expected <what a valid file has>)"; line() is 1-based, 0 when the
   * problem concerns the whole file (it cannot be opened).
   */
  class GroundMotionFileError : public std::runtime_error
  {
  public:
    GroundMotionFileError(const std::string &file, std::size_t line, const std::string &message);

    /// The file name or label the error refers to.
    const std::string &file() const { return file_; }

    /// 1-based line number, 0 for the whole file.
    std::size_t line() const { return line_; }

  private:
    std::string file_;
    std::size_t line_;
  };

  /// Sampling interval of a plausible ground-motion record, s: a DT outside [1e-4 s, 0.1 s] is a
  /// misread header or time column, refused by both readers (DT = 1e-7 s would make a 0.75 ms
  /// record, DT = 100 s a run of 1e8 steps).
  inline constexpr double min_record_dt = 1e-4;
  inline constexpr double max_record_dt = 0.1;
  /// Length of a plausible ground motion as run (after trimming), s: 1 s to 1 h.
  inline constexpr double min_record_duration = 1.0;
  inline constexpr double max_record_duration = 3600.0;

  /// Lines searched for the NPTS/DT line of an AT2 file (it is line 4 in every known variant).
  inline constexpr std::size_t at2_max_header_lines = 10;

  /// Two-column times may deviate from the uniform grid t_i = i·dt by this fraction of dt.
  inline constexpr double two_column_time_tolerance = 1e-3;

  /**
   * Read a PEER AT2 file; values are converted to m/s² from the unit the header states
   * ("ACCELERATION TIME SERIES IN UNITS OF G": × 9.80665; CM/S/S, CM/SEC/SEC, CM/S^2 or GAL:
   * × 0.01; MM/S/S: × 0.001; M/S/S: × 1; IN/S/S: × 0.0254; FT/S/S: × 0.3048; SEC and S, "^2",
   * "**2" and "2" are interchangeable, any case). name = file stem.
   *
   * Accepted: the NPTS/DT line anywhere in lines 1-10, found by its keywords (NPTS and DT as
   * words, any case) and never by number; keyword forms "NPTS= 4000, DT= .01000 SEC" with or
   * without commas and with any trailing text (e.g. filter corners), or the numbers-first form
   * "4000 0.0100 NPTS, DT"; values after that line, any number per line, separated by blanks or
   * touching (Fortran fields such as "-.1E-02-.2E-02" or ".1E-02.2E-02"), mantissas without a
   * leading zero, exponent letters E or D, a partial last line, trailing blanks, CRLF or LF.
   * Numbers in the free-text header lines are never read.
   *
   * @throws GroundMotionFileError for: a file that cannot be opened, an empty file, binary data
   *   (NUL or control bytes), a file that ends before the NPTS/DT line, no NPTS/DT line, NPTS not
   *   a positive integer, DT not a positive number or outside [min_record_dt, max_record_dt], a
   *   non-numeric token (quoted), fewer or more
   *   values than NPTS, a VELOCITY or DISPLACEMENT series, a header without "UNITS OF <unit>"
   *   and an unknown unit (a unit is never assumed). The message names the file and the line
   *   (for the unit: the header line, quoted).
   */
  AccelerationRecord read_at2(const std::filesystem::path &file);

  /// read_at2() on text already in memory; `source` names it in messages and becomes the name.
  AccelerationRecord parse_at2(std::string_view content, const std::string &source);

  /**
   * Read plain text with one "time acceleration" pair per line (blank, tab, comma or semicolon
   * separated); '#' starts a comment; blank lines are skipped. Times must start at 0 and be
   * uniform: |t_i − i·dt| <= two_column_time_tolerance·dt with dt = (t_last − t_0)/(n − 1).
   *
   * @param[in] file              the text file
   * @param[in] acceleration_unit SI value of one unit of the second column, m/s²
   *                              (9.80665 for g, 1 for m/s², 0.01 for cm/s²); > 0
   * @throws GroundMotionFileError naming file and line for fewer than 2 rows, a row without
   *   exactly 2 numbers, a non-numeric token, non-increasing or non-uniform times, t_0 != 0, a
   *   time step outside [min_record_dt, max_record_dt].
   * @throws std::invalid_argument for acceleration_unit <= 0.
   */
  AccelerationRecord read_two_column(const std::filesystem::path &file, double acceleration_unit);

  /// read_two_column() on text already in memory; `source` names it in messages.
  AccelerationRecord
  parse_two_column(std::string_view content, const std::string &source, double acceleration_unit);

  /**
   * Read either format, chosen by content: an NPTS/DT line within the first
   * at2_max_header_lines lines means AT2; otherwise a first data line (after comments and blank
   * lines) holding exactly two numbers means two-column text, which needs `two_column_unit`
   * (m/s² per unit of the second column), since such files do not state their unit.
   * @throws GroundMotionFileError when the content is neither, or a two-column file is given
   *   without a unit, or the chosen reader fails.
   */
  AccelerationRecord read_ground_motion(const std::filesystem::path &file,
                                        std::optional<double> two_column_unit = std::nullopt);
} // namespace kimp::io
