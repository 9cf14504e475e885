// kimp-fem: the `kimp` executable with the FEM engine (deal.II, gmsh, MPI). The lean `kimp` execs
// it, with the same arguments and environment, for the commands mesh, fem and study.
#include <exception>
#include <iostream>
#include <memory>

#include "app/session.h"
#include "base/logging.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/main_support.h"
#include "io/output_dir.h"

int main(int argc, char **argv)
{
  using kimp::cli::report_error;
  // SIGPIPE ignored (outputs are still written when stdout is a closed pipe), SIGTERM and SIGINT
  // remove the run's temporary files and lock (io/output_dir.h).
  kimp::io::install_signal_handlers();
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
  return kimp::cli::run_main(argc,
                             argv,
                             [](CLI::App &app)
                             {
                               kimp::cli::register_fem_commands(app);
                               kimp::cli::register_commands(app);
                             });
}
