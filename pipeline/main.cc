// kimp: impact stiffness for pounding of seismically isolated buildings (command-line entry).
#include <exception>
#include <iostream>
#include <memory>
#include <mpi.h>

#include "pipeline/cli.h"
#include "pipeline/collide_command.h"
#include "pipeline/fit_command.h"
#include "pipeline/lumped_command.h"
#include "pipeline/sweep_command.h"
#ifdef KIMP_WITH_FEM
#  include "fem/mpi_session.h"
#  include "pipeline/with_fem/fem_commands.h"
#  include "pipeline/with_fem/study_command.h"
#endif

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

  int report(const std::exception &error)
  {
    std::cerr << "error: " << error.what() << std::endl;
    abort_other_ranks(1);
    return 1;
  }
} // namespace

int main(int argc, char **argv)
{
#ifdef KIMP_WITH_FEM
  // MPI (and p4est) once per process for `kimp fem`, also under mpirun; only rank 0 logs.
  std::unique_ptr<kimp::fem::MpiSession> mpi;
  try
  {
    mpi = std::make_unique<kimp::fem::MpiSession>(argc, argv);
    kimp::pipeline::set_rank(static_cast<int>(mpi->rank()));
  }
  catch (const std::exception &error)
  {
    return report(error);
  }
#endif
  try
  {
    const auto app = kimp::pipeline::make_app();
#ifdef KIMP_WITH_FEM
    kimp::pipeline::register_mesh_command(*app);
    kimp::pipeline::register_fem_command(*app);
    kimp::pipeline::register_study_command(*app);
#endif
    // Engines add their commands here as they land (register_<name>_command in cli.h).
    kimp::pipeline::register_lumped_command(*app);
    kimp::pipeline::register_collide_command(*app);
    kimp::pipeline::register_fit_command(*app);
    kimp::pipeline::register_sweep_command(*app);
    const int exit_code = kimp::pipeline::run_app(*app, argc, argv, std::cout, std::cerr);
    if (exit_code != 0)
      abort_other_ranks(exit_code);
    return exit_code;
  }
  catch (const std::exception &error)
  {
    // Before the MPI session ends: MPI_Finalize would wait for ranks that are still running.
    return report(error);
  }
}
