// What both `kimp` executables do around a command: parse the command line, run the command, end
// every rank of an MPI job on an error (MPI_Abort) and print "error: <what>"; standard output
// written with checked writes, so that a full disk or a closed pipe is not a silent exit 0.
#pragma once

#include <CLI/CLI.hpp>
#include <array>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <functional>
#include <iostream>
#include <sstream>
#include <streambuf>
#include <string>
#include <unistd.h>

#include "app/mpi_ranks.h"
#include "base/errors.h"
#include "cli/cli.h"
#include "io/output_dir.h"
#include "io/scene_source.h"

namespace kimp::cli
{
  /// Prints "error: <message>", ends the other ranks and returns exit code 1.
  inline int report_error(const std::string &message)
  {
    std::cerr << "error: " << message << std::endl;
    kimp::app::abort_other_ranks(1);
    return 1;
  }

  /// Prints the error as one line ("out of memory" rather than "std::bad_alloc"); the errors of a
  /// scene or sweep file, one per line in file order, each as its own "error: " line.
  inline int report_error(const std::exception &error)
  {
    if (dynamic_cast<const kimp::io::SceneError *>(&error) == nullptr)
      return report_error(kimp::base::error_text(error));
    std::istringstream lines(error.what());
    std::string        line;
    while (std::getline(lines, line))
      if (!line.empty())
        std::cerr << "error: " << line << '\n';
    std::cerr << std::flush;
    kimp::app::abort_other_ranks(1);
    return 1;
  }

  /**
   * The buffer of std::cout while a command runs: bytes go to file descriptor 1 with checked
   * writes (io::write_all()), and the first failure is kept with its errno. (The C library's
   * stdout forgets the errno of a failed write of a full buffer, and a later flush then
   * succeeds: `kimp lumped --print-defaults > /dev/full` would exit 0 with the file cut at 4 kB.)
   * After a failure nothing more is written.
   */
  class CheckedStdout : public std::streambuf
  {
  public:
    CheckedStdout() { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
    CheckedStdout(const CheckedStdout &)            = delete;
    CheckedStdout &operator=(const CheckedStdout &) = delete;

    /// The errno of the first failed write, 0 while every write succeeded.
    int error() const { return error_; }

  protected:
    int_type overflow(int_type c) override
    {
      if (!flush_buffer())
        return traits_type::eof();
      if (!traits_type::eq_int_type(c, traits_type::eof()))
      {
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
      }
      return traits_type::not_eof(c);
    }

    int sync() override { return flush_buffer() ? 0 : -1; }

  private:
    bool flush_buffer()
    {
      const auto size = static_cast<std::size_t>(pptr() - pbase());
      setp(buffer_.data(), buffer_.data() + buffer_.size());
      if (error_ == 0 && size > 0)
        error_ = io::write_all(STDOUT_FILENO, buffer_.data(), size);
      return error_ == 0;
    }

    std::array<char, 65536> buffer_{};
    int                     error_ = 0;
  };

  /// main()'s exit code for "ended by a closed pipe on stdout": end_process() then ends the
  /// process by SIGPIPE, as a Unix filter whose reader went away (`... | head -1`).
  inline constexpr int broken_pipe_exit_code = 128 + SIGPIPE;

  /**
   * Flushes std::cout (and C's stdout) and closes file descriptor 1 (/dev/null takes its place,
   * for what MPI or a library may still print); returns `exit_code`, or after a failed write or
   * close 1 with the line "error: cannot write to standard output: <reason>", or
   * broken_pipe_exit_code, silently, when the reader of a pipe has gone (EPIPE: SIGPIPE is
   * ignored so that a run still writes its files). A command that failed keeps its exit code.
   */
  inline int finish_stdout(CheckedStdout &buffer, int exit_code)
  {
    std::cout.flush();
    int error = buffer.error();
    if (std::fflush(stdout) != 0 && error == 0)
      error = errno != 0 ? errno : EIO;
    // Close errors (a remote file system) are write errors too; stdout closed at the start
    // (`>&-`) with nothing written is not.
    if (::close(STDOUT_FILENO) != 0 && errno != EBADF && error == 0)
      error = errno;
    if (const int null = ::open("/dev/null", O_WRONLY); null >= 0 && null != STDOUT_FILENO)
    {
      ::dup2(null, STDOUT_FILENO);
      ::close(null);
    }
    if (error == 0)
      return exit_code;
    if (error == EPIPE)
      return exit_code == 0 ? broken_pipe_exit_code : exit_code;
    if (exit_code == 0)
      std::cerr << "error: cannot write to standard output: " << std::strerror(error) << std::endl;
    return exit_code == 0 ? 1 : exit_code;
  }

  /// Returns `exit_code` for main() to return, except broken_pipe_exit_code: then the process
  /// ends by SIGPIPE (default action restored), status 141 in a shell, without a message.
  inline int end_process(int exit_code)
  {
    if (exit_code == broken_pipe_exit_code)
    {
      std::signal(SIGPIPE, SIG_DFL);
      std::raise(SIGPIPE);
    }
    return exit_code;
  }

  /// The body of main() in both executables: the `kimp` app with the commands `add_commands`
  /// registers, run on the command line, std::cout through CheckedStdout; a failed command or
  /// an error ends the other ranks, an error is printed (report_error()), and so is a failed
  /// write to stdout (finish_stdout()). Returns main()'s exit code, for end_process().
  inline int run_main(int argc, char **argv, const std::function<void(CLI::App &)> &add_commands)
  {
    CheckedStdout   buffer;
    std::streambuf *previous  = std::cout.rdbuf(&buffer);
    int             exit_code = 0;
    try
    {
      const auto app = make_app();
      add_commands(*app);
      exit_code = run_app(*app, argc, argv, std::cout, std::cerr);
      if (exit_code != 0)
        kimp::app::abort_other_ranks(exit_code);
    }
    catch (const std::exception &error)
    {
      exit_code = report_error(error);
    }
    catch (...)
    {
      exit_code = report_error("unexpected failure (not a standard exception)");
    }
    exit_code = finish_stdout(buffer, exit_code);
    std::cout.rdbuf(previous);
    return exit_code;
  }
} // namespace kimp::cli
