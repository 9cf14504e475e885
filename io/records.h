// Where strong-motion records live and how a record is named: explicit directory > environment
// variable KIMP_RECORDS_DIR > ../shared/data/records (from the working or the source directory).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/at2_reader.h"

namespace kimp::io
{
  /// Environment variable naming the records directory.
  inline constexpr const char *records_dir_env_var = "KIMP_RECORDS_DIR";

  /// The records directory relative to the working directory or to the source directory.
  inline constexpr const char *default_records_subpath = "../shared/data/records";

  /**
   * Resolve the records directory from explicit inputs, highest priority first:
   *  1. `flag_value` (e.g. --records-dir): must be an existing directory;
   *  2. `env_value` (the value of KIMP_RECORDS_DIR; empty counts as unset): must be a directory;
   *  3. `current_dir`/../shared/data/records if it is a directory;
   *  4. `source_dir`/../shared/data/records if it is a directory.
   * A wrong explicit choice (1, 2) is an error rather than a silent fallback.
   * @return the directory (lexically normalised), or nullopt when 3 and 4 do not exist.
   * @throws std::invalid_argument naming the flag or the variable, the path and the expectation.
   */
  std::optional<std::filesystem::path>
  resolve_records_directory(const std::optional<std::filesystem::path> &flag_value,
                            const std::optional<std::string>           &env_value,
                            const std::filesystem::path                &current_dir,
                            const std::optional<std::filesystem::path> &source_dir);

  /**
   * resolve_records_directory() with env_value = getenv(KIMP_RECORDS_DIR) and
   * current_dir = std::filesystem::current_path().
   * @param[in] flag_value explicit directory from the command line or a scene, if any
   * @param[in] source_dir kimp's source directory (a compile-time constant of the executable), if
   *                       known
   */
  std::optional<std::filesystem::path>
  records_directory(const std::optional<std::filesystem::path> &flag_value,
                    const std::optional<std::filesystem::path> &source_dir = std::nullopt);

  /**
   * Load a record by path or by bare name.
   *
   * `name_or_path` is a path when it contains a directory separator or names an existing file;
   * it is then read with read_ground_motion() (AT2; two-column text needs `two_column_unit`).
   * Otherwise it is a bare record name looked up in `records_dir`: first exactly
   * ("RSN1106_KOBE_KJM000.AT2"), then with ".AT2" and ".at2" appended ("RSN1106_KOBE_KJM000").
   * @throws std::invalid_argument when a bare name is given without a records directory, or is
   *   not found there (the message lists the names tried and the available records, and ends
   *   with "did you mean '<name>'?" when closest_record_name() finds one).
   * @throws GroundMotionFileError from the readers.
   */
  AccelerationRecord load_record(const std::string                          &name_or_path,
                                 const std::optional<std::filesystem::path> &records_dir,
                                 std::optional<double> two_column_unit = std::nullopt);

  /**
   * The record name of `names` (stems such as RSN1106_KOBE_KJM000) a mistyped `name` most likely
   * meant: the first that contains it (any case, at least 3 characters), else the nearest by edit
   * distance if fewer than max(3, size/4 + 1) edits away; nullopt if none is close.
   */
  std::optional<std::string> closest_record_name(const std::string              &name,
                                                 const std::vector<std::string> &names);

  /// The .AT2 files (any case of the extension) directly in `directory`, sorted by name.
  std::vector<std::filesystem::path> list_records(const std::filesystem::path &directory);
} // namespace kimp::io
