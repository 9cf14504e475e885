// Small result files for scripting: summary.json and CSV tables, written atomically
// (temporary file in the same directory, then rename; io/output_dir.h).
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/output_dir.h"

namespace kimp::io
{
  /**
   * The first keys of every command's summary.json, in this order: "command" (`command`, as
   * typed after kimp) and "kimp" (base::version_line()). The caller adds its own keys after them.
   */
  nlohmann::ordered_json summary_preamble(std::string_view command);

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
} // namespace kimp::io
