// Reads any kimp results file (HDF5) into JSON for the HTML report and the GUI: every group with
// its attributes and every numeric or text dataset with its shape and units.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace kimp::io
{
  /**
   * The whole of the HDF5 file `path` as JSON:
   * `{"groups": {"/lumped/a": {"status": "ok", ...attributes}}, "datasets": {"/lumped/a/x":
   * {"shape": [n, w], "units": "m", "stride": s, "data": [...]}}}`. Numeric datasets are float64
   * row-major (rows of a 2-D dataset as arrays); a dataset with more than `max_rows` rows keeps
   * every s-th row (s = "stride", always including the last) so a report stays small; text
   * datasets keep their strings. Values are SI, as stored. Throws ResultsError naming the file
   * when it cannot be read.
   */
  nlohmann::json results_to_json(const std::filesystem::path &path, std::size_t max_rows = 6000);
} // namespace kimp::io
