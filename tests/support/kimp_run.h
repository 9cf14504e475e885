// kimp::testing::run_kimp(): the built `kimp` executable (KIMP_BINARY_DIR "/kimp", a definition
// every test gets from kimp_add_test) run in a directory with its output captured; and any shell
// command with its output captured to a log file or discarded.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>

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
} // namespace kimp::testing
