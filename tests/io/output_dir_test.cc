// The output set of a run is all or nothing: a command that fails after committing some files
// (a results file fits on the disk, the CSV after it does not) removes them again, except the
// files kept on failure (a cache); a SIGTERM removes the temporary files being written and the
// lock; temporary names with the writer's extension are recognised as stale.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "io/output_dir.h"
#include "io/results_file.h"
#include "io/summary.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::io;
  using kimp::testing::files_below;
  using kimp::testing::TempDir;

  /// A command's run into `dir`: a results file, then a CSV that cannot be written (its
  /// directory is a file, as a full disk makes the write fail), so the command throws.
  void run_failing_after_the_results_file(const fs::path &dir, bool keep_the_results_file)
  {
    const OutputDir output(dir);
    ResultsFile     file(output.file("lumped.h5"), "scene: {}", "{}");
    file.root().group("lumped").set_attribute("status", "ok");
    file.commit();
    if (keep_the_results_file)
      kimp::io::keep_on_failure(output.file("lumped.h5"));
    kimp::io::write_text_atomic(output.file("summary.json"), "{}\n");
    std::ofstream(dir / "blocked") << "a file where a directory is needed";
    kimp::io::write_csv_atomic(dir / "blocked" / "peaks.csv", {"a"}, {{"1"}});
  }


  TEST(OutputDir, AFailedRunRemovesTheFilesItHadWritten)
  {
    const TempDir dir;
    EXPECT_THROW(run_failing_after_the_results_file(dir.path(), false), OutputError);
    EXPECT_EQ(files_below(dir.path()), std::vector<std::string>{"blocked"});
  }

  TEST(OutputDir, AFileKeptOnFailureStays)
  {
    const TempDir dir;
    EXPECT_THROW(run_failing_after_the_results_file(dir.path(), true), OutputError);
    EXPECT_TRUE(fs::exists(dir.path() / "lumped.h5"));
    EXPECT_FALSE(fs::exists(dir.path() / "summary.json"));
  }

  TEST(OutputDir, AnErrorCaughtInsideTheRunKeepsItsFiles)
  {
    const TempDir dir;
    {
      const OutputDir output(dir.path());
      kimp::io::write_text_atomic(output.file("summary.json"), "{}\n");
      try
      {
        // A writer of the same directory fails, the command carries on (a warning).
        const OutputDir inner(dir.path());
        throw std::runtime_error("charts failed");
      }
      catch (const std::runtime_error &)
      {
      }
    }
    EXPECT_TRUE(fs::exists(dir.path() / "summary.json"));
    EXPECT_FALSE(fs::exists(dir.path() / kimp::io::output_lock_name));
  }

  TEST(OutputDir, AResultKeptAsWrittenStaysWhenTheCommandThenFails)
  {
    const TempDir dir;
    try
    {
      const OutputDir output(dir.path());
      kimp::io::write_text_atomic(output.file("summary.json"), "{}\n");
      output.keep_written(); // a complete result recording a failed case
      kimp::io::write_text_atomic(output.file("charts.txt"), "x");
      throw std::runtime_error("1 of 2 cases failed");
    }
    catch (const std::runtime_error &)
    {
    }
    EXPECT_TRUE(fs::exists(dir.path() / "summary.json")) << "written before keep_written()";
    EXPECT_FALSE(fs::exists(dir.path() / "charts.txt")) << "written after it: removed";
    EXPECT_FALSE(fs::exists(dir.path() / kimp::io::output_lock_name));
  }

  TEST(OutputDir, FilesOutsideEveryOutputDirAreNotTracked)
  {
    const TempDir dir;
    try
    {
      const OutputDir output(dir.path() / "out");
      kimp::io::write_text_atomic(dir.path() / "notes.txt", "x");
      throw std::runtime_error("failed");
    }
    catch (const std::runtime_error &)
    {
    }
    EXPECT_TRUE(fs::exists(dir.path() / "notes.txt"));
  }

  TEST(OutputDir, TemporaryNamesWithTheWritersExtensionAreStale)
  {
    const TempDir     dir;
    const std::string other = std::to_string(::getppid());
    fs::create_directories(dir.path() / "mesh");
    const auto png = dir.write("H1.25.png.tmp-" + other + ".png", "partial");
    const auto msh = dir.write("mesh/H1.25.msh.tmp-" + other + ".msh", "partial");
    const auto two = dir.write("a.tmp-" + other + ".x.y", "kept: not a temporary name");
    EXPECT_EQ(kimp::io::temporary_path(dir.path() / "H1.25.png", true),
              dir.path() / ("H1.25.png.tmp-" + std::to_string(::getpid()) + ".png"));
    const OutputDir out(dir.path());
    EXPECT_FALSE(fs::exists(png));
    EXPECT_FALSE(fs::exists(msh));
    EXPECT_TRUE(fs::exists(two));
  }

  // The handler runs in a child: a temporary file being written, a committed file of the
  // running command and the lock are removed, and the child ends by SIGTERM.
  TEST(OutputDir, SigtermRemovesTheTemporaryFilesTheOutputsAndTheLock)
  {
    const TempDir  dir;
    const fs::path out   = dir.path() / "out";
    const pid_t    child = ::fork();
    if (child == 0)
    {
      kimp::io::install_signal_handlers();
      const OutputDir output(out);
      kimp::io::write_text_atomic(output.file("summary.json"), "{}\n");
      const kimp::io::TemporaryFile temporary(output.file("fem.h5"));
      std::ofstream(temporary.path()) << "being written";
      ::raise(SIGTERM);
      ::_exit(3); // not reached if the handler ends the process
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "status " << status;
    ASSERT_TRUE(fs::is_directory(out));
    EXPECT_TRUE(files_below(out).empty()) << "left: " << files_below(out).front();
  }
} // namespace
