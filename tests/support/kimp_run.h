// kimp::testing::run_kimp(): the built `kimp` executable (KIMP_BINARY_DIR "/kimp", a definition
// every test gets from kimp_add_test) run in a directory with its output captured, in the
// background, under a file size limit, or as a measured process (peak memory, ending signal,
// stdout a pipe nobody reads); any shell command with its output captured to a log file or
// discarded.
#pragma once

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/support/files.h"

namespace kimp::testing
{
  /// The path of the built `kimp` executable.
  inline std::string kimp_executable()
  {
    return KIMP_BINARY_DIR "/kimp";
  }

  /// The exit code of a std::system() status (-1 if the command did not exit normally).
  inline int exit_code_of(int status)
  {
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  /// The exit code of the shell command `command`, its stdout and stderr written to `log`.
  inline int run_command(const std::string &command, const std::filesystem::path &log)
  {
    return exit_code_of(std::system((command + " > '" + log.string() + "' 2>&1").c_str()));
  }

  /// Whether the shell command `command` exits with 0, its output discarded.
  inline bool command_succeeds(const std::string &command)
  {
    return run_command(command, "/dev/null") == 0;
  }

  /// What a run of `kimp` gave back.
  struct KimpRun
  {
    int         exit_code = -1;
    std::string out; ///< stdout
    std::string err; ///< stderr (the log)

    /// stdout followed by stderr, for a failure message or a search in either.
    std::string output() const { return out + err; }
  };

  /// `kimp <arguments>` run in `dir`, stdout and stderr captured to stdout.txt and stderr.txt
  /// there.
  inline KimpRun run_kimp(const std::string &arguments, const std::filesystem::path &dir)
  {
    const std::string command = "cd '" + dir.string() + "' && " + kimp_executable() + " " +
                                arguments + " > stdout.txt 2> stderr.txt";
    KimpRun run;
    run.exit_code = exit_code_of(std::system(command.c_str()));
    run.out       = read_text(dir / "stdout.txt");
    run.err       = read_text(dir / "stderr.txt");
    return run;
  }

  /// `kimp <arguments> 2>&1 | head -1` in `dir` (log.txt there gets what head lets through);
  /// returns kimp's exit code.
  inline int run_kimp_into_closed_pipe(const std::string           &arguments,
                                       const std::filesystem::path &dir)
  {
    const std::string command = "cd '" + dir.string() + "' && " + kimp_executable() + " " +
                                arguments + " 2>&1 | head -1; exit ${PIPESTATUS[0]}";
    return run_command("bash -c '" + command + "'", dir / "log.txt");
  }

  /// Whether `program` is on the PATH.
  inline bool have_program(const std::string &program)
  {
    return command_succeeds("command -v " + program);
  }

/// GoogleTest: skips the test (or fixture) unless `program` (of the Debian package `package`) is
/// on the PATH.
#define KIMP_SKIP_WITHOUT_PROGRAM(program, package) \
  if (!kimp::testing::have_program(program))        \
  GTEST_SKIP() << program << " (" << package << ") is not installed"

  /// Starts `kimp <arguments>` in the background (output to `log`); returns its pid.
  inline pid_t start_kimp(const std::string &arguments, const std::filesystem::path &log)
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

  /// kill -9 and reap `pid`.
  inline void kill_hard(pid_t pid)
  {
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
  }

  /// `kimp <arguments>` in `dir` with a file size limit of `bytes` (SIGXFSZ ignored, so that a
  /// write across the limit fails with EFBIG as on a full disk); returns the exit code, the log
  /// (stdout and stderr) in `log`. The limit holds for every file the process and its children
  /// write: the MPI start-up of kimp-fem is kept from its helper daemon and shared-memory files
  /// (isolated singleton, no PMIx store, no shared-memory transport), which would not fit.
  inline int run_kimp_with_file_limit(const std::string           &arguments,
                                      const std::filesystem::path &dir,
                                      long                         bytes,
                                      std::string                 &log)
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

  /**
   * `kimp <arguments>` in `dir` under a file size limit of `bytes` as a user sets it (`ulimit -f`,
   * here prlimit): SIGXFSZ keeps its default action and MPI its usual start-up, unlike
   * run_kimp_with_file_limit(). Returns the exit code (-1 if killed by a signal), the log (stdout
   * and stderr) in `log`.
   */
  inline int run_kimp_under_ulimit(const std::string           &arguments,
                                   const std::filesystem::path &dir,
                                   long                         bytes,
                                   std::string                 &log)
  {
    const std::string command = "cd '" + dir.string() +
                                "' && prlimit --fsize=" + std::to_string(bytes) + " " +
                                kimp_executable() + " " + arguments;
    const int exit_code = run_command(command, dir / "log.txt");
    log                 = read_text(dir / "log.txt");
    return exit_code;
  }

  /// What a process run by run_kimp_process() gave back.
  struct KimpProcess
  {
    int         exit_code  = -1; ///< -1 if ended by a signal
    int         signal     = 0;  ///< the signal that ended it, 0 if it exited
    long        max_rss_kb = 0;  ///< peak resident memory (kB)
    std::string out;             ///< stdout (empty for StdoutTo::closed_pipe)
    std::string err;             ///< stderr
  };

  /// Where run_kimp_process() sends stdout.
  enum class StdoutTo
  {
    file,       ///< stdout.txt in the directory
    closed_pipe ///< a pipe whose read end is closed before kimp starts: every write gets EPIPE
  };

  /**
   * `kimp <arguments>` as a child of this process (through `sh -c 'exec ...'`, so the child is
   * kimp itself), in `dir`, stderr to stderr.txt there; returns its exit code or signal and its
   * peak resident memory (wait4()).
   */
  inline KimpProcess run_kimp_process(const std::string           &arguments,
                                      const std::filesystem::path &dir,
                                      StdoutTo                     stdout_to = StdoutTo::file)
  {
    int pipe_ends[2] = {-1, -1};
    if (stdout_to == StdoutTo::closed_pipe)
    {
      if (::pipe(pipe_ends) != 0)
        return {};
      ::close(pipe_ends[0]); // no reader from the start, whatever the timing
    }
    const std::string command = "cd '" + dir.string() + "' && exec " + kimp_executable() + " " +
                                arguments + " 2> stderr.txt" +
                                (stdout_to == StdoutTo::file ? " > stdout.txt" : "");
    const pid_t pid = ::fork();
    if (pid == 0)
    {
      if (stdout_to == StdoutTo::closed_pipe)
      {
        ::dup2(pipe_ends[1], STDOUT_FILENO);
        ::close(pipe_ends[1]);
      }
      ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char *>(nullptr));
      ::_exit(127);
    }
    if (stdout_to == StdoutTo::closed_pipe)
      ::close(pipe_ends[1]);
    KimpProcess   run;
    int           status = 0;
    struct rusage usage
    {
    };
    if (pid < 0 || ::wait4(pid, &status, 0, &usage) != pid)
      return run;
    run.exit_code  = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.signal     = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    run.max_rss_kb = usage.ru_maxrss;
    if (stdout_to == StdoutTo::file)
      run.out = read_text(dir / "stdout.txt");
    run.err = read_text(dir / "stderr.txt");
    return run;
  }
} // namespace kimp::testing
