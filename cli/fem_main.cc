// kimp-fem: the `kimp` executable with the FEM engine (deal.II, gmsh, MPI). The lean `kimp` execs
// it, with the same arguments and environment, for the commands mesh, fem and study.
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>
#include <sys/resource.h>

#include "app/session.h"
#include "base/logging.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/main_support.h"
#include "io/output_dir.h"

namespace
{
  /**
   * Under a file size limit (`ulimit -f`) the MPI start-up of a process not started by mpirun
   * fails on files of its own (Open MPI's helper daemon and shared-memory segment, the PMIx
   * store), with a page of MPI errors: such a process, a singleton, needs none of them (isolated,
   * no shared-memory transport, PMIx data in memory), so they are switched off unless the
   * environment says otherwise. The limit then meets kimp's own files, which report it in one
   * line.
   */
  void keep_mpi_start_up_within_file_size_limit()
  {
    struct rlimit limit
    {
    };
    if (::getrlimit(RLIMIT_FSIZE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
      return;
    for (const char *launched : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
      if (std::getenv(launched) != nullptr)
        return; // started by a launcher, which chose the transports
    ::setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
    ::setenv("OMPI_MCA_btl", "self", 0);
    ::setenv("PMIX_MCA_gds", "hash", 0);
  }
} // namespace

int main(int argc, char **argv)
{
  using kimp::cli::report_error;
  // SIGPIPE ignored (outputs are still written when stdout is a closed pipe), SIGTERM and SIGINT
  // remove the run's temporary files and lock (io/output_dir.h).
  kimp::io::install_signal_handlers();
  keep_mpi_start_up_within_file_size_limit();
  // MPI (and p4est) once per process, also under mpirun; only rank 0 logs.
  std::unique_ptr<kimp::app::Session> session;
  try
  {
    session = std::make_unique<kimp::app::Session>(argc, argv);
    kimp::base::set_rank(static_cast<int>(session->rank()));
    // MPI's start-up installs its own handlers (SIGPIPE back to its default): ours again.
    kimp::io::install_signal_handlers();
  }
  catch (const std::exception &error)
  {
    return report_error(error);
  }
  // Within the MPI session: an error is reported (and the other ranks ended) before MPI_Finalize,
  // which would wait for ranks that are still running.
  const int exit_code = kimp::cli::run_main(argc,
                                            argv,
                                            [](CLI::App &app)
                                            {
                                              kimp::cli::register_fem_commands(app);
                                              kimp::cli::register_commands(app);
                                            });
  // MPI ends first; then a closed stdout pipe ends the process as it would a Unix filter.
  session.reset();
  return kimp::cli::end_process(exit_code);
}
