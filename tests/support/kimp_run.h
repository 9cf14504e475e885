// kimp::testing::run_kimp(): the built `kimp` executable (KIMP_BINARY_DIR "/kimp", a definition
// every test gets from kimp_add_test) run in a directory with its output captured, in the
// background, or under a file size limit; any shell command with its output captured to a log
// file or discarded.
#pragma once

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
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
} // namespace kimp::testing
