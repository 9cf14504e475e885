// kimp::testing checks of error messages: the message of the exception a call throws, a message
// that must contain every one of some parts, the one error line of a failed run's log (also of a
// run under a file size limit) and that line when the results file met the limit.
// Needs GoogleTest.
#pragma once

#include <exception>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "tests/support/files.h"
#include "tests/support/kimp_run.h"

namespace kimp::testing
{
  /// The message of the `Exception` that `function()` throws; a failure of the test, and "", if
  /// it throws none (an exception of another type is not caught).
  template <class Exception = std::exception, class Function>
  std::string thrown_message(Function &&function)
  {
    try
    {
      function();
    }
    catch (const Exception &error)
    {
      return error.what();
    }
    ADD_FAILURE() << "no exception of the expected type thrown";
    return {};
  }

  /// Expects `text` to contain every one of `parts`.
  inline void expect_contains(const std::string &text, const std::vector<std::string> &parts)
  {
    for (const std::string &part : parts)
      EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in:\n" << text;
  }

  /// The lines of `text` that are not "info: ..." log lines.
  inline std::vector<std::string> non_info_lines(const std::string &text)
  {
    std::vector<std::string> lines;
    std::size_t              begin = 0;
    while (begin < text.size())
    {
      std::size_t end = text.find('\n', begin);
      if (end == std::string::npos)
        end = text.size();
      const std::string line = text.substr(begin, end - begin);
      if (!line.empty() && line.rfind("info: ", 0) != 0)
        lines.push_back(line);
      begin = end + 1;
    }
    return lines;
  }

  /// Expects a run that ended with `exit_code` and wrote `log` to have failed with exit code 1
  /// and one line besides the info lines: that line in `line` (a fatal failure if there is not
  /// exactly one).
  inline void one_error_line(int exit_code, const std::string &log, std::string &line)
  {
    EXPECT_EQ(exit_code, 1) << log;
    const std::vector<std::string> lines = non_info_lines(log);
    ASSERT_EQ(lines.size(), 1u) << log;
    line = lines[0];
  }

  /// `kimp <arguments>` in `dir` under a file size limit of `bytes` (run_kimp_with_file_limit()),
  /// which must exit 1 with one line besides the info lines: that line in `line`.
  inline void one_line_under_file_limit(const std::string           &arguments,
                                        const std::filesystem::path &dir,
                                        long                         bytes,
                                        std::string                 &line)
  {
    std::string log;
    const int   exit_code = run_kimp_with_file_limit(arguments, dir, bytes, log);
    ASSERT_NO_FATAL_FAILURE(one_error_line(exit_code, log, line));
  }

  /// Expects the one error line of a run that wrote its results across a file size limit to name
  /// the results file and EFBIG ("File too large"), and the run to have left nothing below `out`.
  inline void expect_results_file_too_large_error(const std::string           &line,
                                                  const std::filesystem::path &out)
  {
    EXPECT_EQ(line.rfind("error: results file '", 0), 0u) << line;
    EXPECT_NE(line.find("File too large"), std::string::npos) << line;
    EXPECT_TRUE(files_below(out).empty()) << "left behind: " << files_below(out).front();
  }
} // namespace kimp::testing
