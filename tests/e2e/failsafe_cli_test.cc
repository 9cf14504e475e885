// End-to-end failures that must not damage anything: a full disk (file size limit), a read-only
// output directory, a run killed while writing, two runs into one directory and a closed pipe
// each end with exit 1 and one clean line (or, for the pipe, a normal run) and leave no files.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
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
