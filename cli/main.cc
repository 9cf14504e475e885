// kimp: impact stiffness for pounding of seismically isolated buildings (command-line entry).
#include <csignal>
#include <exception>
#include <iostream>
#include <memory>
#include <mpi.h>
#include <string>

#include "app/session.h"
#include "base/errors.h"
#include "base/logging.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace
{
  /// An error on one rank of a multi-rank job would leave the others waiting in a collective
  /// call (a barrier, MPI_Finalize) forever: end the whole job instead. Finished sweep cases
  /// are journaled, so a rerun resumes.
  void abort_other_ranks(int exit_code)
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

  int report(const std::string &message)
  {
    std::cerr << "error: " << message << std::endl;
    abort_other_ranks(1);
    return 1;
  }

  int report(const std::exception &error)
  {
    return report(kimp::base::error_text(error));
  }
} // namespace

int main(int argc, char **argv)
{
  // A closed pipe (`kimp ... | head -1`) must not kill the run before it writes its files: writes
  // to the pipe then fail quietly instead.
  std::signal(SIGPIPE, SIG_IGN);
  // MPI (and p4est) once per process for `kimp fem`, also under mpirun; only rank 0 logs.
  std::unique_ptr<kimp::app::Session> session;
  try
  {
    session = std::make_unique<kimp::app::Session>(argc, argv);
    kimp::base::set_rank(static_cast<int>(session->rank()));
  }
  catch (const std::exception &error)
  {
    return report(error);
  }
  try
  {
    const auto app = kimp::cli::make_app();
    kimp::cli::register_commands(*app);
    const int exit_code = kimp::cli::run_app(*app, argc, argv, std::cout, std::cerr);
    if (exit_code != 0)
      abort_other_ranks(exit_code);
    return exit_code;
  }
  catch (const std::exception &error)
  {
    // Before the MPI session ends: MPI_Finalize would wait for ranks that are still running.
    return report(error);
  }
  catch (...)
  {
    return report("unexpected failure (not a standard exception)");
  }
}
