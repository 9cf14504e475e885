// Small result files for scripting: summary.json and CSV tables, written atomically
// (temporary file in the same directory, then rename), and the output directory of a command.
#pragma once

#include <filesystem>
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

  /// Numeric CSV; values printed with the shortest text that reads back to the same double.
  void write_csv_atomic(const std::filesystem::path            &path,
                        const std::vector<std::string>         &header,
                        const std::vector<std::vector<double>> &rows);

  /// The output directory of a command, created (with parents) on construction.
  class OutputDir
  {
  public:
    /// @throws OutputError if `path` exists and is not a directory, or cannot be created.
    explicit OutputDir(std::filesystem::path path);

    const std::filesystem::path &path() const { return path_; }
    /// `path() / name`, creating parent directories of `name` inside path() if needed.
    std::filesystem::path file(const std::filesystem::path &name) const;

  private:
    std::filesystem::path path_;
  };
} // namespace kimp::io
