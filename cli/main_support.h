// What both `kimp` executables do around a command: end every rank of an MPI job on an error
// (MPI_Abort) and print "error: <what>".
#pragma once

#include <exception>
#include <iostream>
#include <mpi.h>
#include <sstream>
#include <string>

#include "base/errors.h"
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
} // namespace kimp::cli
