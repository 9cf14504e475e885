// Helper programs kimp runs (chart and preview scripts under scripts/, through /usr/bin/python3):
// where to find them and how to run them without a shell.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace kimp::app
{
  /**
   * scripts/<file_name>: $KIMP_DATA_DIR/scripts/, $KIMP_DATA_DIR/../scripts/, then the scripts/
   * directory of the source tree kimp was built from. Empty path if none exists.
   */
  std::filesystem::path find_helper_script(const std::string &file_name);

  /// Where a helper program's stdout and stderr go.
  enum class ProgramOutput
  {
    inherit, ///< kimp's own stdout/stderr
    errors,  ///< stdout to /dev/null, stderr kimp's own (a closed stdout pipe cannot fail it)
    discard, ///< /dev/null
    append   ///< appended to a log file (stderr joined to stdout)
  };

  /**
   * Run `arguments` (argv[0] is an absolute path; no shell) and wait for it.
   * @param[in] log the log file for ProgramOutput::append, ignored otherwise
   * @return its exit status, or -1 if it could not be started or did not exit normally
   */
  int run_program(const std::vector<std::string> &arguments,
                  ProgramOutput                   output,
                  const std::filesystem::path    &log = {});

  /** Outcome of run_chart_script(). */
  struct ChartScriptRun
  {
    std::filesystem::path script;      ///< empty if scripts/<name> was not found (nothing ran)
    std::filesystem::path log;         ///< DIR/charts/charts.log (stdout and stderr of the script)
    int                   status = -1; ///< exit status (0: charts written)
  };

  /**
   * `/usr/bin/python3 scripts/<script_name> DIR` for an output directory DIR, its output in a
   * fresh DIR/charts/charts.log; the caller decides whether a failure is an error or a warning.
   */
  ChartScriptRun run_chart_script(const std::string           &script_name,
                                  const std::filesystem::path &output_dir);

  /**
   * run_chart_script() for charts that are a bonus: a script not found or failed is a warning
   * "<what> skipped: <why>" (naming the script, its exit status and log); true when it drew them.
   */
  bool draw_optional_charts(const std::string           &script_name,
                            const std::filesystem::path &output_dir,
                            std::string_view             what);
} // namespace kimp::app
