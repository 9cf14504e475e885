// What both `kimp` executables do around a command: end every rank of an MPI job on an error
// (MPI_Abort) and print "error: <what>".
#pragma once

#include <exception>
#include <iostream>
#include <mpi.h>
#include <string>

#include "base/errors.h"

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

  /// Prints the error as one line ("out of memory" rather than "std::bad_alloc").
  inline int report_error(const std::exception &error)
  {
    return report_error(kimp::base::error_text(error));
  }
} // namespace kimp::cli
