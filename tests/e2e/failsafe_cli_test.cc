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
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  /// Two cases, 6 s of the synthetic motion: lumped.h5 is about 1.4 MB.
  const char *small_scene = "walls:\n"
                            "  left:\n"
                            "    gap: \"4 cm\"\n"
                            "  right:\n"
                            "    gap: \"4 cm\"\n"
                            "ground_motion:\n"
                            "  record: synthetic\n"
                            "  duration: \"6 s\"\n"
                            "integration:\n"
                            "  dt: \"1e-4 s\"\n"
                            "  output_interval: \"0.002 s\"\n"
                            "cases:\n"
                            "  - name: mkv\n"
                            "  - name: hysteretic\n"
                            "    law: hysteretic\n"
                            "    k: \"750 kN/mm^1.5\"\n";

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

  /// The files below `dir` (recursively), as paths relative to it.
  std::vector<std::string> files_below(const fs::path &dir)
  {
    std::vector<std::string> files;
    if (!fs::exists(dir))
      return files;
    for (const auto &entry : fs::recursive_directory_iterator(dir))
      if (entry.is_regular_file())
        files.push_back(fs::relative(entry.path(), dir).string());
    return files;
  }

  /// The lines of `text` that are not "info: ..." log lines.
  std::vector<std::string> non_info_lines(const std::string &text)
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

  bool have(const std::string &program)
  {
    return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0;
  }

  /// Starts `kimp <arguments>` in the background (output to `log`); returns its pid.
  pid_t start_kimp(const std::string &arguments, const fs::path &log)
  {
    const pid_t pid = ::fork();
    if (pid == 0)
    {
      const std::string command =
        "exec " + kimp_executable() + " " + arguments + " > '" + log.string() + "' 2>&1";
      ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char *>(nullptr));
      ::_exit(127);
    }
    return pid;
  }

  /// Waits up to `seconds` for `file` to exist and be non-empty.
  bool wait_for(const fs::path &file, double seconds)
  {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end)
    {
      std::error_code error;
      if (fs::exists(file, error) && fs::file_size(file, error) > 0 && !error)
        return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  /// kill -9 and reap `pid`.
  void kill_hard(pid_t pid)
  {
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
  }
} // namespace

// A disk that fills while the results file is written: write() fails (EFBIG under a file size
// limit, as ENOSPC on a full disk). Before, HDF5 kept the failed file open and crashed at exit
// (exit 139).
TEST(FailsafeCli, FullDiskExitsOneWithOneLineAndLeavesNoFile)
{
  if (!have("prlimit"))
    GTEST_SKIP() << "prlimit (util-linux) is not installed";
  TempDir dir("e2e_failsafe_full");
  dir.write("scene.yaml", small_scene);
  const fs::path out = dir.path() / "out";
  // SIGXFSZ ignored: the write that crosses the 60 kB limit returns EFBIG instead of killing.
  const std::string command = "cd '" + dir.path().string() + "' && trap '' XFSZ && prlimit " +
                              "--fsize=60000 " + kimp_executable() + " lumped scene.yaml -o " +
                              out.string();
  const int         exit_code = run_command("bash -c \"" + command + "\"", dir.path() / "log.txt");
  const std::string log       = read_text(dir.path() / "log.txt");
  EXPECT_EQ(exit_code, 1) << log;
  const std::vector<std::string> lines = non_info_lines(log);
  ASSERT_EQ(lines.size(), 1u) << log;
  EXPECT_EQ(lines[0].rfind("error: results file '", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("File too large"), std::string::npos) << lines[0];
  EXPECT_TRUE(files_below(out).empty()) << "left behind: " << files_below(out).front();
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
    if (!have("setpriv"))
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
  EXPECT_EQ(exit_code, 1) << text;
  const std::vector<std::string> lines = non_info_lines(text);
  ASSERT_EQ(lines.size(), 1u) << text;
  EXPECT_EQ(lines[0], "error: output directory 'ro' is not writable: Permission denied");
  EXPECT_EQ(text.find("case 1/2"), std::string::npos) << "computed before failing:\n" << text;
  EXPECT_TRUE(left.empty());
}

// kill -9 while a run writes leaves its temporary file behind (nothing can delete it); the next
// run into the directory removes it, and the killed run's lock does not block it.
TEST(FailsafeCli, KilledRunLeavesNoOrphanAfterTheNextRun)
{
  TempDir dir("e2e_failsafe_kill");
  dir.write("long.yaml", long_scene);
  dir.write("scene.yaml", small_scene);
  const fs::path out = dir.path() / "out";
  const pid_t pid = start_kimp("lumped " + dir.file("long.yaml").string() + " -o " + out.string(),
                               dir.path() / "killed.txt");
  ASSERT_TRUE(wait_for(out / ".kimp.lock", 60)) << read_text(dir.path() / "killed.txt");
  // What a kill during the write leaves: the temporary results file of that process.
  const fs::path orphan = out / ("lumped.h5.tmp-" + std::to_string(pid));
  std::ofstream(orphan) << "partial HDF5 file";
  fs::create_directories(out / "sub");
  const fs::path nested_orphan = out / "sub" / ("peaks.csv.tmp-" + std::to_string(pid));
  std::ofstream(nested_orphan) << "partial CSV";
  kill_hard(pid);
  ASSERT_TRUE(fs::exists(orphan));

  const KimpRun run =
    run_kimp("lumped " + dir.file("scene.yaml").string() + " -o " + out.string(), dir.path());
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
  TempDir dir("e2e_failsafe_lock");
  dir.write("long.yaml", long_scene);
  dir.write("scene.yaml", small_scene);
  const fs::path out = dir.path() / "out";
  const pid_t pid = start_kimp("lumped " + dir.file("long.yaml").string() + " -o " + out.string(),
                               dir.path() / "first.txt");
  ASSERT_TRUE(wait_for(out / ".kimp.lock", 60)) << read_text(dir.path() / "first.txt");
  const KimpRun second =
    run_kimp("lumped " + dir.file("scene.yaml").string() + " -o " + out.string(), dir.path());
  int        status              = 0;
  const bool first_still_running = ::waitpid(pid, &status, WNOHANG) == 0;
  kill_hard(pid);
  ASSERT_TRUE(first_still_running) << "the first run ended too early to test the lock";
  EXPECT_EQ(second.exit_code, 1) << second.err;
  const std::vector<std::string> lines = non_info_lines(second.err);
  ASSERT_EQ(lines.size(), 1u) << second.err;
  EXPECT_EQ(lines[0],
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
  const fs::path    out     = dir.path() / "out";
  const std::string command = "cd '" + dir.path().string() + "' && " + kimp_executable() +
                              " lumped scene.yaml -o " + out.string() +
                              " 2>&1 | head -1; exit ${PIPESTATUS[0]}";
  const int exit_code = run_command("bash -c '" + command + "'", dir.path() / "log.txt");
  EXPECT_EQ(exit_code, 0) << read_text(dir.path() / "log.txt");
  EXPECT_TRUE(fs::exists(out / "lumped.h5"));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "peaks.csv"));
}

namespace
{
  /// `kimp <arguments>` in `dir` with a file size limit of `bytes` (SIGXFSZ ignored, so that a
  /// write across the limit fails with EFBIG as on a full disk); returns the exit code, the log
  /// (stdout and stderr) in `log`. The limit holds for every file the process and its children
  /// write: the MPI start-up of kimp-fem is kept from its helper daemon and shared-memory files
  /// (isolated singleton, no PMIx store, no shared-memory transport), which would not fit.
  int run_kimp_with_file_limit(const std::string &arguments,
                               const fs::path    &dir,
                               long               bytes,
                               std::string       &log)
  {
    const std::string command =
      "cd '" + dir.string() +
      "' && trap '' XFSZ && OMPI_MCA_ess_singleton_isolated=1 PMIX_MCA_gds=hash "
      "OMPI_MCA_btl=self prlimit --fsize=" +
      std::to_string(bytes) + " " + kimp_executable() + " " + arguments;
    const int exit_code = run_command("bash -c \"" + command + "\"", dir / "log.txt");
    log                 = read_text(dir / "log.txt");
    return exit_code;
  }

  bool exists_now(const fs::path &file)
  {
    std::error_code error;
    return fs::exists(file, error);
  }
} // namespace

// SIGINT (Ctrl-C) while a run computes: the handler removes the lock and the process ends by the
// signal. Before, the lock file stayed until the next run into the directory.
TEST(FailsafeCli, InterruptedRunRemovesItsLock)
{
  TempDir dir("e2e_failsafe_int");
  dir.write("long.yaml", long_scene);
  const fs::path out = dir.path() / "out";
  const pid_t pid = start_kimp("lumped " + dir.file("long.yaml").string() + " -o " + out.string(),
                               dir.path() / "log.txt");
  ASSERT_TRUE(wait_for(out / ".kimp.lock", 60)) << read_text(dir.path() / "log.txt");
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
  TempDir dir("e2e_failsafe_stale");
  dir.write("long.yaml", long_scene);
  dir.write("scene.yaml", small_scene);
  const fs::path out = dir.path() / "out";
  fs::create_directories(out / "sub");
  const std::string live   = std::to_string(::getpid()); // this test: alive, not a kimp
  const fs::path    stale  = out / ("lumped.h5.tmp-" + live);
  const fs::path    nested = out / "sub" / ("peaks.csv.tmp-" + live);
  std::ofstream(stale) << "partial HDF5 file";
  std::ofstream(nested) << "partial CSV";
  // Another kimp writing below, into out/busy: its temporary files are its own.
  const pid_t other =
    start_kimp("lumped " + dir.file("long.yaml").string() + " -o " + (out / "busy").string(),
               dir.path() / "other.txt");
  ASSERT_TRUE(wait_for(out / "busy" / ".kimp.lock", 60)) << read_text(dir.path() / "other.txt");
  const fs::path busy = out / "busy" / ("peaks.csv.tmp-" + std::to_string(other));
  std::ofstream(busy) << "being written";

  const KimpRun run =
    run_kimp("lumped " + dir.file("scene.yaml").string() + " -o " + out.string(), dir.path());
  const bool busy_kept = exists_now(busy);
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
  const KimpRun                  run   = run_kimp("report out", dir.path());
  const std::vector<std::string> lines = non_info_lines(run.err);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_EQ(lines[0].rfind("error: ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("lumped.h5"), std::string::npos) << lines[0];
}

// `dt: auto` interpolates a history row every output_interval, also between steps: 1e-20 s over
// 6 s is 6e20 rows. Before, the estimate capped the rows at the steps (400) and the run then
// filled the memory (4.6 GB in 8 s); now the case is refused with the numbers.
TEST(FailsafeCli, HistoryRowsAboveTheMemoryBudgetAreRefused)
{
  TempDir     dir("e2e_failsafe_rows");
  std::string scene = small_scene;
  scene.replace(scene.find("dt: \"1e-4 s\""), 12, "dt: auto");
  scene.replace(scene.find("0.002 s"), 7, "1e-20 s");
  dir.write("scene.yaml", scene);
  const KimpRun                  run   = run_kimp("lumped scene.yaml -o out", dir.path());
  const std::vector<std::string> lines = non_info_lines(run.err);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_NE(lines[0].find("case mkv: 6e+20 history rows (integration.output_interval = 1e-20 s "
                          "over 6 s) need ~"),
            std::string::npos)
    << lines[0];
  EXPECT_NE(lines[0].find("GB of memory, above the budget of 2 GB"), std::string::npos) << lines[0];
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
  const std::vector<std::string> lines = non_info_lines(run.err);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_NE(lines[0].find("12 cases x 2 run(s) x (1.2e+03 steps of 0.005 s over 6 s"),
            std::string::npos)
    << lines[0];
  EXPECT_NE(lines[0].find("= 2.88e+04 steps"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("exceeds the step budget of the sweep (--max-steps = 1e+03"),
            std::string::npos)
    << lines[0];
  EXPECT_FALSE(fs::exists(dir.path() / "out")) << "refused after planning";
}

// A disk that fills while the sweep journals its first case (a journal line is about 2.3 kB, the
// log below 1.5 kB then): no torn line and no empty journal is left.
TEST(FailsafeCli, SweepOnAFullDiskLeavesNoFile)
{
  if (!have("prlimit"))
    GTEST_SKIP() << "prlimit (util-linux) is not installed";
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

#ifdef KIMP_WITH_FEM
namespace
{
  /// data/scenes/fem_quick.yaml: rigid slab, 5 cm at the contact, about a second of FEM.
  const char *fem_quick_scene = "wall_heights: [\"1.25 m\"]\n"
                                "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
                                "slab: {rigid: true, velocity: \"1.0 m/s\"}\n"
                                "dynamics: {end_time: \"40 ms\", output_interval: \"0.02 ms\"}\n";

  /// A one-height study on the quick FEM scene, without charts or extra studies.
  const char *quick_study = "fem:\n"
                            "  wall_heights: [\"1.0 m\"]\n"
                            "  mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
                            "  slab: {rigid: true}\n"
                            "  dynamics: {end_time: \"40 ms\", output_interval: \"0.02 ms\"}\n"
                            "  fidelity: fixed\n"
                            "  velocities: []\n"
                            "records:\n"
                            "  - record: synthetic\n"
                            "    duration: \"4 s\"\n"
                            "fit:\n"
                            "  separation_fraction: 10\n"
                            "peer_records: false\n"
                            "charts: false\n"
                            "stability_map: false\n"
                            "accuracy_study: false\n";

  /// The quick scene running for about 15 s (3e6 steps): a long end time, no stop at separation.
  const char *fem_long_scene =
    "wall_heights: [\"1.25 m\"]\n"
    "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
    "slab: {rigid: true, velocity: \"1.0 m/s\"}\n"
    "dynamics: {end_time: \"20 s\", separation_hold_time: \"20 s\", output_interval: \"1 ms\", "
    "max_steps: 1e7}\n"
    "output: {frame_interval: \"0 s\"}\n";

  /// The files below `dir` whose name marks a temporary file or the lock.
  std::vector<std::string> temporaries_below(const fs::path &dir)
  {
    std::vector<std::string> found;
    for (const std::string &file : files_below(dir))
      if (file.find(".tmp-") != std::string::npos || file.find(".kimp.lock") != std::string::npos)
        found.push_back(file);
    return found;
  }

  /// `kimp <arguments> 2>&1 | head -1` in `dir`; returns kimp's exit code.
  int run_kimp_into_closed_pipe(const std::string &arguments, const fs::path &dir)
  {
    const std::string command = "cd '" + dir.string() + "' && " + kimp_executable() + " " +
                                arguments + " 2>&1 | head -1; exit ${PIPESTATUS[0]}";
    return run_command("bash -c '" + command + "'", dir / "log.txt");
  }
} // namespace

// The FEM commands run in kimp-fem, whose MPI start-up put SIGPIPE back to its default: `kimp fem
// ... | head -1` died with exit 141 and left fem.h5.tmp-<pid>. Now they finish and write
// everything.
TEST(FailsafeCli, ClosedPipeDoesNotStopMeshFemOrStudy)
{
  TempDir dir("e2e_failsafe_pipe_fem");
  dir.write("scene.yaml", fem_quick_scene);
  dir.write("study.yaml", quick_study);
  EXPECT_EQ(run_kimp_into_closed_pipe("mesh scene.yaml -o mesh_out", dir.path()), 0)
    << read_text(dir.path() / "log.txt");
  for (const char *file : {"summary.json", "mesh/H1.25.msh", "mesh/H1.25.vtu"})
    EXPECT_TRUE(fs::exists(dir.path() / "mesh_out" / file)) << file;
  EXPECT_EQ(run_kimp_into_closed_pipe("fem scene.yaml -o fem_out", dir.path()), 0)
    << read_text(dir.path() / "log.txt");
  for (const char *file : {"fem.h5", "summary.json", "fem_histories.csv", "mesh/H1.25.msh"})
    EXPECT_TRUE(fs::exists(dir.path() / "fem_out" / file)) << file;
  EXPECT_EQ(run_kimp_into_closed_pipe("study study.yaml -o study_out", dir.path()), 0)
    << read_text(dir.path() / "log.txt");
  for (const char *file : {"k_table.csv", "summary.json", "report.md", "fem/H1.00.h5"})
    EXPECT_TRUE(fs::exists(dir.path() / "study_out" / file)) << file;
  for (const char *out : {"mesh_out", "fem_out", "study_out"})
    EXPECT_TRUE(temporaries_below(dir.path() / out).empty())
      << out << ": " << temporaries_below(dir.path() / out).front();
}

// SIGTERM (the GUI's cancel) while the FEM runs: the handler removes the temporary results file,
// the mesh this run wrote and the lock, and the process ends by the signal. Before,
// fem.h5.tmp-<pid> and the lock stayed until the next run.
TEST(FailsafeCli, TerminatedFemRunLeavesNoFile)
{
  TempDir dir("e2e_failsafe_term");
  dir.write("long.yaml", fem_long_scene);
  const fs::path out = dir.path() / "out";
  const pid_t    pid = start_kimp("fem " + dir.file("long.yaml").string() + " -o " + out.string(),
                               dir.path() / "log.txt");
  ASSERT_TRUE(wait_for(out / "mesh" / "H1.25.msh", 60)) << read_text(dir.path() / "log.txt");
  ASSERT_TRUE(exists_now(out / ("fem.h5.tmp-" + std::to_string(pid))));
  ASSERT_TRUE(exists_now(out / ".kimp.lock"));
  std::this_thread::sleep_for(std::chrono::milliseconds(500)); // into the time loop
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM)
    << "status " << status << "\n"
    << read_text(dir.path() / "log.txt");
  EXPECT_TRUE(files_below(out).empty()) << "left: " << files_below(out).front();
}

// A full disk while `kimp mesh` writes: at 5 kB the mesh file itself cannot be written (gmsh
// reports nothing; the file is checked); at 20 kB the mesh (9.7 kB) and its VTU preview (4 kB) fit
// but the PNG (65 kB) does not, and the mesh and VTU written before are removed again. Before, a
// 0-byte H1.25.msh (and the VTU and an empty PNG) stayed under the final names.
TEST(FailsafeCli, MeshOnAFullDiskLeavesNoFile)
{
  if (!have("prlimit"))
    GTEST_SKIP() << "prlimit (util-linux) is not installed";
  TempDir dir("e2e_failsafe_mesh_full");
  dir.write("scene.yaml", fem_quick_scene);
  std::string log;
  EXPECT_EQ(run_kimp_with_file_limit("mesh scene.yaml -o small", dir.path(), 5000, log), 1) << log;
  const std::vector<std::string> lines = non_info_lines(log);
  ASSERT_EQ(lines.size(), 1u) << log;
  EXPECT_NE(lines[0].find("could not write the mesh file"), std::string::npos) << lines[0];
  EXPECT_TRUE(files_below(dir.path() / "small").empty())
    << "left: " << files_below(dir.path() / "small").front();

  EXPECT_EQ(run_kimp_with_file_limit("mesh scene.yaml -o larger", dir.path(), 20000, log), 1)
    << log;
  EXPECT_NE(log.find("failed to draw"), std::string::npos) << log;
  EXPECT_TRUE(files_below(dir.path() / "larger").empty())
    << "left: " << files_below(dir.path() / "larger").front();
}

// `kimp fem` with room for the mesh (9.7 kB) but not for fem.h5 (0.4 MB): the mesh written before
// is removed, so the command leaves nothing (before: mesh/H1.25.msh stayed).
TEST(FailsafeCli, FemOnAFullDiskLeavesNoFile)
{
  if (!have("prlimit"))
    GTEST_SKIP() << "prlimit (util-linux) is not installed";
  TempDir dir("e2e_failsafe_fem_full");
  dir.write("scene.yaml", fem_quick_scene);
  std::string log;
  EXPECT_EQ(run_kimp_with_file_limit("fem scene.yaml -o out", dir.path(), 100000, log), 1) << log;
  const std::vector<std::string> lines = non_info_lines(log);
  ASSERT_EQ(lines.size(), 1u) << log;
  EXPECT_EQ(lines[0].rfind("error: results file '", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("File too large"), std::string::npos) << lines[0];
  EXPECT_TRUE(files_below(dir.path() / "out").empty())
    << "left: " << files_below(dir.path() / "out").front();
}

namespace
{
  /// The numbers of the log line "<case>: estimate N DoFs, up to S steps of DT s ...".
  struct LoggedEstimate
  {
    double n_dofs = 0.0, n_steps = 0.0, dt = 0.0;
  };

  LoggedEstimate logged_estimate(const std::string &log, const std::string &case_name)
  {
    const std::string marker = case_name + ": estimate ";
    const std::size_t at     = log.find(marker);
    LoggedEstimate    e;
    if (at == std::string::npos)
      return e;
    std::istringstream in(log.substr(at + marker.size()));
    std::string        word;
    in >> e.n_dofs >> word >> word >> word >> e.n_steps >> word >> word >> e.dt;
    return e;
  }
} // namespace

// The FEM estimate logged before meshing against what the solver then did: the DoFs exactly, the
// time step (the solver's stability limit times cfl_safety, from the grid and the penalty) within
// the 3 significant digits of the log line, for a rigid slab (wall face nodes are the slaves)
// and an elastic one (slab front nodes against the wall). Steps: end_time / dt, an upper bound.
TEST(FailsafeCli, FemEstimateMatchesTheSolver)
{
  constexpr double digits = 5e-3; // relative: the log prints 3 significant digits
  for (const bool rigid : {true, false})
  {
    TempDir     dir("e2e_failsafe_estimate");
    std::string scene = fem_quick_scene;
    if (!rigid)
      scene.replace(scene.find("rigid: true"), 11, "rigid: false");
    dir.write("scene.yaml", scene);
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const LoggedEstimate  e       = logged_estimate(run.err, "H1.25");
    const nlohmann::json  summary = read_json(dir.path() / "out" / "summary.json");
    const nlohmann::json &c       = summary.at("cases").at(0);
    EXPECT_EQ(e.n_dofs, c.at("n_dofs").get<double>()) << "rigid " << rigid << "\n" << run.err;
    EXPECT_NEAR(e.dt, c.at("dt").get<double>(), digits * c.at("dt").get<double>())
      << "rigid " << rigid;
    EXPECT_NEAR(e.n_steps, 0.04 / c.at("dt").get<double>(), digits * e.n_steps)
      << "rigid " << rigid;
    EXPECT_GE(e.n_steps, c.at("n_steps").get<double>()) << "rigid " << rigid;
  }
}

// mesh.h_contact: 1e-6 m is about 1e11 DoFs and 3e8 steps: refused before meshing with the
// estimate. With the budget lifted the mesher runs out of memory, which is one line too (before:
// "error: H1.25: meshing: std::bad_alloc").
TEST(FailsafeCli, AbsurdFemMeshIsRefusedOrOneLine)
{
  TempDir     dir("e2e_failsafe_fem_budget");
  std::string scene = fem_quick_scene;
  scene.replace(scene.find("\"5 cm\""), 6, "\"1e-6 m\"");
  dir.write("scene.yaml", scene);
  const KimpRun                  run   = run_kimp("fem scene.yaml -o out", dir.path());
  const std::vector<std::string> lines = non_info_lines(run.err);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_EQ(lines[0].rfind("error: H1.25: the estimate (1e+11 DoFs, up to 2.95e+08 steps of ", 0),
            0u)
    << lines[0];
  EXPECT_NE(lines[0].find("exceeds the step budget dynamics.max_steps = 1e+06"), std::string::npos)
    << lines[0];
  EXPECT_TRUE(files_below(dir.path() / "out").empty());

  if (!have("prlimit"))
    GTEST_SKIP() << "prlimit (util-linux) is not installed";
  scene.replace(scene.find("dynamics: {"), 11, "dynamics: {max_steps: 1e30, ");
  dir.write("lifted.yaml", scene);
  // 8 GB of address space at most, so the allocation fails at once whatever the machine.
  const int exit_code = run_command("cd '" + dir.path().string() + "' && prlimit --as=8000000000 " +
                                      kimp_executable() + " fem lifted.yaml -o lifted",
                                    dir.path() / "log.txt");
  const std::string              log    = read_text(dir.path() / "log.txt");
  const std::vector<std::string> lifted = non_info_lines(log);
  EXPECT_EQ(exit_code, 1) << log;
  ASSERT_EQ(lifted.size(), 1u) << log;
  EXPECT_EQ(lifted[0].rfind("error: H1.25: meshing: out of memory: ", 0), 0u) << lifted[0];
  EXPECT_TRUE(files_below(dir.path() / "lifted").empty());
}

// A truncated FEM cache file (a copy cut short, a full disk before the writes were atomic) made
// every later `kimp study` into the directory fail; now it is computed again with a warning.
TEST(FailsafeCli, DamagedFemCacheIsComputedAgain)
{
  TempDir dir("e2e_failsafe_cache");
  dir.write("study.yaml", quick_study);
  ASSERT_EQ(run_kimp("study study.yaml -o out", dir.path()).exit_code, 0);
  const fs::path    cache = dir.path() / "out" / "fem" / "H1.00.h5";
  const std::size_t full  = fs::file_size(cache);
  fs::resize_file(cache, full / 3);
  const KimpRun again = run_kimp("study study.yaml -o out", dir.path());
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("warning: H1.00: FEM cache out/fem/H1.00.h5 is unreadable"),
            std::string::npos)
    << again.err;
  EXPECT_EQ(fs::file_size(cache), full) << "the cache was not written again";
  EXPECT_EQ(again.err.find("FEM result reused"), std::string::npos) << again.err;
}
#endif
