// End-to-end failures that must not damage anything: a full disk (file size limit), a read-only
// output directory, a run killed or terminated while writing, two runs into one directory and a
// closed pipe each end with exit 1 and one clean line (or, for the pipe, a normal run) and leave
// no files; a command's outputs are all or nothing. Runs above their cost budget are refused
// before they start, with the estimate.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/types.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/messages.h"
#include "tests/support/scene_texts.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  /// Two cases, 6 s of the synthetic motion: lumped.h5 is about 1.4 MB.
  const std::string small_scene = two_case_walled_scene("0.002 s");

  /// Six cases of 2e7 steps each: several seconds of computing, time to meet the lock.
  const char *long_scene = "ground_motion:\n"
                           "  record: synthetic\n"
                           "  duration: \"20 s\"\n"
                           "integration:\n"
                           "  dt: \"1e-6 s\"\n"
                           "  output_interval: \"0.05 s\"\n"
                           "cases:\n"
                           "  - name: a\n"
                           "  - name: b\n"
                           "  - name: c\n"
                           "  - name: d\n"
                           "  - name: e\n"
                           "  - name: f\n";

  /// Starts `kimp lumped` of long_scene (long.yaml in `dir`) into `out` in the background, its
  /// log in `dir`/`log_name`, and waits for it to take the lock of `out`; its pid in `pid`.
  void
  start_long_run(const TempDir &dir, const fs::path &out, const std::string &log_name, pid_t &pid)
  {
    pid =
      start_kimp("lumped " + dir.write("long.yaml", long_scene).string() + " -o " + out.string(),
                 dir.path() / log_name);
    ASSERT_TRUE(wait_for_file(out / ".kimp.lock", 60)) << read_text(dir.path() / log_name);
  }

  /// `kimp lumped` of small_scene (scene.yaml in `dir`) into `out`.
  KimpRun run_small_scene(const TempDir &dir, const fs::path &out)
  {
    return run_kimp("lumped " + dir.write("scene.yaml", small_scene).string() + " -o " +
                      out.string(),
                    dir.path());
  }
} // namespace

// A disk that fills while the results file is written: write() fails (EFBIG under a file size
// limit, as ENOSPC on a full disk). Before, HDF5 kept the failed file open and crashed at exit
// (exit 139).
TEST(FailsafeCli, FullDiskExitsOneWithOneLineAndLeavesNoFile)
{
  KIMP_SKIP_WITHOUT_PROGRAM("prlimit", "util-linux");
  TempDir dir("e2e_failsafe_full");
  dir.write("scene.yaml", small_scene);
  // SIGXFSZ ignored: the write that crosses the 60 kB limit returns EFBIG instead of killing.
  std::string line;
  ASSERT_NO_FATAL_FAILURE(
    one_line_under_file_limit("lumped scene.yaml -o out", dir.path(), 60000, line));
  expect_results_file_too_large_error(line, dir.path() / "out");
}

// A read-only output directory is an error before any computation, in one line. As root the
// permission bits do not stop writes, so the run drops to user nobody when possible.
TEST(FailsafeCli, ReadOnlyOutputDirectoryFailsBeforeComputing)
{
  const fs::path root = process_temp_path("e2e_failsafe_ro");
  fs::remove_all(root);
  fs::create_directories(root / "ro");
  std::ofstream(root / "scene.yaml") << small_scene;
  fs::permissions(root,
                  fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                    fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(root / "ro",
                  fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                    fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  std::string as_user;
  if (::geteuid() == 0)
  {
    if (!have_program("setpriv"))
    {
      fs::remove_all(root);
      GTEST_SKIP() << "running as root without setpriv: cannot make a directory read-only";
    }
    as_user = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
  }
  const fs::path log  = process_temp_path("e2e_failsafe_ro_log");
  const int exit_code = run_command("cd '" + root.string() + "' && " + as_user + kimp_executable() +
                                      " lumped scene.yaml -o ro",
                                    log);
  const std::string text = read_text(log);
  fs::remove(log);
  fs::permissions(root / "ro", fs::perms::owner_all);
  const std::vector<std::string> left = files_below(root / "ro");
  fs::remove_all(root);
  std::string line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(exit_code, text, line));
  EXPECT_EQ(line, "error: output directory 'ro' is not writable: Permission denied");
  EXPECT_EQ(text.find("case 1/2"), std::string::npos) << "computed before failing:\n" << text;
  EXPECT_TRUE(left.empty());
}

// kill -9 while a run writes leaves its temporary file behind (nothing can delete it); the next
// run into the directory removes it, and the killed run's lock does not block it.
TEST(FailsafeCli, KilledRunLeavesNoOrphanAfterTheNextRun)
{
  TempDir        dir("e2e_failsafe_kill");
  const fs::path out = dir.path() / "out";
  pid_t          pid = -1;
  ASSERT_NO_FATAL_FAILURE(start_long_run(dir, out, "killed.txt", pid));
  // What a kill during the write leaves: the temporary results file of that process.
  const fs::path orphan = out / ("lumped.h5.tmp-" + std::to_string(pid));
  std::ofstream(orphan) << "partial HDF5 file";
  fs::create_directories(out / "sub");
  const fs::path nested_orphan = out / "sub" / ("peaks.csv.tmp-" + std::to_string(pid));
  std::ofstream(nested_orphan) << "partial CSV";
  kill_hard(pid);
  ASSERT_TRUE(fs::exists(orphan));

  const KimpRun run = run_small_scene(dir, out);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_FALSE(fs::exists(orphan));
  EXPECT_FALSE(fs::exists(nested_orphan));
  EXPECT_NE(run.err.find("warning: removed '" + orphan.string() + "'"), std::string::npos)
    << run.err;
  EXPECT_TRUE(fs::exists(out / "lumped.h5"));
  for (const std::string &file : files_below(out))
    EXPECT_EQ(file.find(".tmp-"), std::string::npos) << file;
  EXPECT_FALSE(fs::exists(out / ".kimp.lock")) << "the lock file is removed at the end";
}

// A second kimp writing into a directory in use is refused at once, naming the first one.
TEST(FailsafeCli, SecondRunIntoTheSameDirectoryIsRefused)
{
  TempDir        dir("e2e_failsafe_lock");
  const fs::path out = dir.path() / "out";
  pid_t          pid = -1;
  ASSERT_NO_FATAL_FAILURE(start_long_run(dir, out, "first.txt", pid));
  const KimpRun second              = run_small_scene(dir, out);
  int           status              = 0;
  const bool    first_still_running = ::waitpid(pid, &status, WNOHANG) == 0;
  kill_hard(pid);
  ASSERT_TRUE(first_still_running) << "the first run ended too early to test the lock";
  std::string line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(second.exit_code, second.err, line));
  EXPECT_EQ(line,
            "error: output directory '" + out.string() + "' is in use by another kimp (pid " +
              std::to_string(pid) + "); wait for it to finish or choose another output directory");
  EXPECT_FALSE(fs::exists(out / "lumped.h5"));
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

// `kimp ... | head -1`: the pipe closes after the first log line; the run still writes its
// outputs and exits 0 (before: killed by SIGPIPE, exit 141, nothing written).
TEST(FailsafeCli, ClosedPipeDoesNotStopTheRun)
{
  TempDir dir("e2e_failsafe_pipe");
  dir.write("scene.yaml", small_scene);
  const fs::path out = dir.path() / "out";
  const int      exit_code =
    run_kimp_into_closed_pipe("lumped scene.yaml -o " + out.string(), dir.path());
  EXPECT_EQ(exit_code, 0) << read_text(dir.path() / "log.txt");
  EXPECT_TRUE(fs::exists(out / "lumped.h5"));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "peaks.csv"));
}


// SIGINT (Ctrl-C) while a run computes: the handler removes the lock and the process ends by the
// signal. Before, the lock file stayed until the next run into the directory.
TEST(FailsafeCli, InterruptedRunRemovesItsLock)
{
  TempDir        dir("e2e_failsafe_int");
  const fs::path out = dir.path() / "out";
  pid_t          pid = -1;
  ASSERT_NO_FATAL_FAILURE(start_long_run(dir, out, "log.txt", pid));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
  EXPECT_TRUE(files_below(out).empty()) << "left: " << files_below(out).front();
}

// A temporary file whose pid belongs to a live process that is not a kimp writing there (pids are
// reused): the lock proves that no other kimp writes into the directory, so it is removed with a
// warning (before, it was kept silently). A sub-directory locked by another kimp is left alone.
TEST(FailsafeCli, TemporaryOfALiveUnrelatedProcessIsRemovedUnderTheLock)
{
  TempDir        dir("e2e_failsafe_stale");
  const fs::path out = dir.path() / "out";
  fs::create_directories(out / "sub");
  const std::string live   = std::to_string(::getpid()); // this test: alive, not a kimp
  const fs::path    stale  = out / ("lumped.h5.tmp-" + live);
  const fs::path    nested = out / "sub" / ("peaks.csv.tmp-" + live);
  std::ofstream(stale) << "partial HDF5 file";
  std::ofstream(nested) << "partial CSV";
  // Another kimp writing below, into out/busy: its temporary files are its own.
  pid_t other = -1;
  ASSERT_NO_FATAL_FAILURE(start_long_run(dir, out / "busy", "other.txt", other));
  const fs::path busy = out / "busy" / ("peaks.csv.tmp-" + std::to_string(other));
  std::ofstream(busy) << "being written";

  const KimpRun run       = run_small_scene(dir, out);
  const bool    busy_kept = exists_now(busy);
  kill_hard(other);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_FALSE(exists_now(stale));
  EXPECT_FALSE(exists_now(nested));
  EXPECT_NE(run.err.find("warning: removed '" + stale.string() + "'"), std::string::npos)
    << run.err;
  EXPECT_TRUE(busy_kept) << "the temporary file of a kimp running below was removed";
}

// `kimp report` on a damaged results file (cut short by a copy or a full disk): one line, not
// HDF5's error stack (9 lines of HDF5-DIAG before).
TEST(FailsafeCli, DamagedResultsFileIsOneLineInTheReport)
{
  TempDir dir("e2e_failsafe_report");
  dir.write("scene.yaml", small_scene);
  const fs::path out = dir.path() / "out";
  ASSERT_EQ(run_kimp("lumped scene.yaml -o out", dir.path()).exit_code, 0);
  fs::resize_file(out / "lumped.h5", fs::file_size(out / "lumped.h5") / 2);
  const KimpRun run = run_kimp("report out", dir.path());
  std::string   line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_EQ(line.rfind("error: ", 0), 0u) << line;
  EXPECT_NE(line.find("lumped.h5"), std::string::npos) << line;
}

// `dt: auto` interpolates a history row every output_interval, also between steps: 1e-20 s over
// 6 s is 6e20 rows. Before, the estimate capped the rows at the steps (400) and the run then
// filled the memory (4.6 GB in 8 s); now the case is refused with the numbers.
TEST(FailsafeCli, HistoryRowsAboveTheMemoryBudgetAreRefused)
{
  TempDir dir("e2e_failsafe_rows");
  dir.write("scene.yaml",
            replaced(replaced(small_scene, "dt: \"1e-4 s\"", "dt: auto"), "0.002 s", "1e-20 s"));
  const KimpRun run = run_kimp("lumped scene.yaml -o out", dir.path());
  std::string   line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_NE(line.find("case mkv: 6e+20 history rows (integration.output_interval = 1e-20 s "
                      "over 6 s) need ~"),
            std::string::npos)
    << line;
  EXPECT_NE(line.find("GB of memory, above the budget of 2 GB"), std::string::npos) << line;
  EXPECT_TRUE(files_below(dir.path() / "out").empty());
}

// A sweep says its cost before enumerating its cases (200,000 cases took a silent minute) and is
// refused above --max-steps with the estimate: 12 cases of the quick scene, each run with and
// without walls (companion), 6 s / 0.005 s (the large step of dt: auto) = 1200 steps per run.
TEST(FailsafeCli, SweepAboveTheStepBudgetIsRefusedBeforePlanning)
{
  TempDir           dir("e2e_failsafe_sweep_budget");
  const std::string sweep = (source_dir() / "data/studies/quick_gap_sweep.yaml").string();
  const KimpRun     run =
    run_kimp("sweep " + sweep + " -o out --no-charts --max-steps 1000", dir.path());
  std::string line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_NE(line.find("12 cases x 2 run(s) x (1.2e+03 steps of 0.005 s over 6 s"),
            std::string::npos)
    << line;
  EXPECT_NE(line.find("= 2.88e+04 steps"), std::string::npos) << line;
  EXPECT_NE(line.find("exceeds the step budget of the sweep (--max-steps = 1e+03"),
            std::string::npos)
    << line;
  EXPECT_FALSE(fs::exists(dir.path() / "out")) << "refused after planning";
}

// A disk that fills while the sweep journals its first case (a journal line is about 2.3 kB, the
// log below 1.5 kB then): no torn line and no empty journal is left.
TEST(FailsafeCli, SweepOnAFullDiskLeavesNoFile)
{
  KIMP_SKIP_WITHOUT_PROGRAM("prlimit", "util-linux");
  TempDir           dir("e2e_failsafe_sweep_full");
  const std::string sweep = (source_dir() / "data/studies/quick_gap_sweep.yaml").string();
  std::string       log;
  const int         exit_code =
    run_kimp_with_file_limit("sweep " + sweep + " -o out --no-charts -t 1", dir.path(), 1500, log);
  EXPECT_EQ(exit_code, 1) << log;
  EXPECT_NE(log.find("File too large"), std::string::npos) << log;
  EXPECT_TRUE(files_below(dir.path() / "out").empty())
    << "left behind: " << files_below(dir.path() / "out").front();
}
