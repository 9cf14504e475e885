// The data behind `kimp report` and the GUI's results view, read from a result directory, and the
// one self-contained HTML file that shows it (docs/architecture.md "Report and GUI").
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace kimp::report
{
  /**
   * Everything the page shows about the result directory `dir` of any command (lumped, collide,
   * fem, fit, study, sweep): `{"title", "kind", "summary": summary.json, "csv": {name: text},
   * "h5": {name: io::results_to_json()}}`. Time series are decimated to about 6000 rows; values
   * are SI. `kind` is the command, found from the results file present ("study" for study.h5...);
   * an export-opensees directory is kind "export-opensees" with its OpenSees files as
   * `"text": {name: text}`.
   * @throws std::invalid_argument naming `dir` when it is not a directory or holds no results
   *   file nor summary.json.
   */
  nlohmann::json report_data(const std::filesystem::path &dir);

  /// The self-contained HTML page (styles, uPlot, page code and `data` inlined; no network
  /// request) showing `data` as built by report_data().
  std::string report_html(const nlohmann::json &data);

  /**
   * Write report_html(report_data(dir)) to `output` (default `dir`/report.html) atomically.
   * @return the path written.
   */
  std::filesystem::path write_report(const std::filesystem::path &dir,
                                     const std::filesystem::path &output = {});

  /// The GUI's main page (gui/src/gui.html with styles and scripts served from /assets/).
  std::string gui_html();
} // namespace kimp::report
