// kimp: impact stiffness for pounding of seismically isolated buildings (command-line entry).
#include <exception>
#include <iostream>

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

int main(int argc, char **argv)
{
  try
  {
#ifdef KIMP_WITH_FEM
    // MPI (and p4est) once per process for `kimp fem`, also under mpirun; only rank 0 logs.
    const kimp::fem::MpiSession mpi(argc, argv);
    kimp::pipeline::set_rank(static_cast<int>(mpi.rank()));
#endif
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
    return kimp::pipeline::run_app(*app, argc, argv, std::cout, std::cerr);
  }
  catch (const std::exception &error)
  {
    std::cerr << "error: " << error.what() << '\n';
    return 1;
  }
}
