// Small result files for scripting: summary.json and CSV tables, written atomically
// (temporary file in the same directory, then rename), and the output directory of a command.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace kimp::io
{
  /// Failure to create an output directory or to write a file; names the path and the reason.
  class OutputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * Write `text` to `<path>.tmp-<pid>` and rename it to `path`, so readers see either the old
   * file or the complete new one, never a partial file.
   * @throws OutputError (the temporary file is removed).
   */
  void write_text_atomic(const std::filesystem::path &path, std::string_view text);

  /// write_text_atomic() of `value` dumped with 2-space indentation and a final newline.
  void write_json_atomic(const std::filesystem::path &path, const nlohmann::json &value);

  /**
   * CSV (RFC 4180: fields with ',', '"' or line breaks are quoted, '"' doubled), written
   * atomically. Every row must have header.size() fields.
   * @throws OutputError naming the row whose length differs.
   */
  void write_csv_atomic(const std::filesystem::path                 &path,
                        const std::vector<std::string>              &header,
                        const std::vector<std::vector<std::string>> &rows);

  /**
   * The CSV column name of a quantity, kimp's one header convention `name_unit`: the unit
   * with '/' written "_per_", '^' and spaces dropped and '*' written '_' ("peak_force", "N" ->
   * "peak_force_N"; "m/s^2" -> "_m_per_s2"; "kN/mm^1.5/m" -> "_kN_per_mm1.5_per_m"); a
   * dimensionless quantity (unit "1" or "") has no suffix.
   */
  std::string csv_column(std::string_view name, std::string_view unit);

  /// csv_column() of a "name [unit]" label (a sweep metric); a label without "[unit]" is kept.
  std::string csv_column(std::string_view label);

  /// Numeric CSV; values printed with the shortest text that reads back to the same double.
  void write_csv_atomic(const std::filesystem::path            &path,
                        const std::vector<std::string>         &header,
                        const std::vector<std::vector<double>> &rows);

  namespace detail
  {
    class DirectoryLock;
  }

  /**
   * The output directory of a command, created (with parents) on construction and checked
   * before any computation:
   * - it must be writable (a probe file is created and removed), else OutputError at once;
   * - on MPI rank 0 (base::rank()) it is locked for the lifetime of the last OutputDir of this
   *   process naming it: `flock` on `DIR/.kimp.lock`, which holds the owner's pid and is removed
   *   on release. Another process finding the lock taken gets OutputError naming that pid, so
   *   two runs never write into one directory at the same time;
   * - temporary files `<name>.tmp-<pid>` left below it by a process that no longer runs (a run
   *   killed while writing) are removed, each with a warning.
   */
  class OutputDir
  {
  public:
    /// @throws OutputError if `path` exists and is not a directory, cannot be created, is not
    /// writable or is locked by another process.
    explicit OutputDir(std::filesystem::path path);
    ~OutputDir();
    OutputDir(const OutputDir &);
    OutputDir &operator=(const OutputDir &);

    const std::filesystem::path &path() const { return path_; }
    /// `path() / name`, creating parent directories of `name` inside path() if needed.
    std::filesystem::path file(const std::filesystem::path &name) const;

  private:
    std::filesystem::path                  path_;
    std::shared_ptr<detail::DirectoryLock> lock_;
  };

  /// Name of the lock file inside a locked output directory.
  inline constexpr const char *output_lock_name = ".kimp.lock";

  /**
   * Remove the temporary files `<name>.tmp-<pid>` below `dir` whose process `pid` has ended.
   * @return the removed files.
   */
  std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path &dir);
} // namespace kimp::io
