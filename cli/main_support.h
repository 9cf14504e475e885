// What both `kimp` executables do around a command: parse the command line, run the command, end
// every rank of an MPI job on an error (MPI_Abort) and print "error: <what>".
#pragma once

#include <CLI/CLI.hpp>
#include <exception>
#include <functional>
#include <iostream>
#include <mpi.h>
#include <sstream>
#include <string>

#include "base/errors.h"
#include "cli/cli.h"
#include "io/scene_source.h"

namespace kimp::cli
{
  /// An error on one rank of a multi-rank job would leave the others waiting in a collective
  /// call (a barrier, MPI_Finalize) forever: end the whole job instead. Finished sweep cases
  /// are journaled, so a rerun resumes. Does nothing where MPI was never initialised.
  inline void abort_other_ranks(int exit_code)
  {
    int initialized = 0;
    int finalized   = 0;
    MPI_Initialized(&initialized);
    MPI_Finalized(&finalized);
    if (!initialized || finalized)
      return;
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size > 1)
      MPI_Abort(MPI_COMM_WORLD, exit_code);
  }

  /// Prints "error: <message>", ends the other ranks and returns exit code 1.
  inline int report_error(const std::string &message)
  {
    std::cerr << "error: " << message << std::endl;
    abort_other_ranks(1);
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
    abort_other_ranks(1);
    return 1;
  }

  /// The body of main() in both executables: the `kimp` app with the commands `add_commands`
  /// registers, run on the command line; a failed command or an error ends the other ranks, an
  /// error is printed (report_error()). Returns main()'s exit code.
  inline int run_main(int argc, char **argv, const std::function<void(CLI::App &)> &add_commands)
  {
    try
    {
      const auto app = make_app();
      add_commands(*app);
      const int exit_code = run_app(*app, argc, argv, std::cout, std::cerr);
      if (exit_code != 0)
        abort_other_ranks(exit_code);
      return exit_code;
    }
    catch (const std::exception &error)
    {
      return report_error(error);
    }
    catch (...)
    {
      return report_error("unexpected failure (not a standard exception)");
    }
  }
} // namespace kimp::cli
