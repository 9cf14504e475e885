// RAII MPI/p4est initialisation through deal.II's Utilities::MPI::MPI_InitFinalize.
#include "fem/mpi_session.h"

#include <deal.II/base/mpi.h>

namespace kimp::fem
{
  struct MpiSession::Impl
  {
    Impl(int &argc, char **&argv)
      : init(argc, argv, 1)
    {
    }
    dealii::Utilities::MPI::MPI_InitFinalize init;
  };

  MpiSession::MpiSession(int &argc, char **&argv)
    : impl(std::make_unique<Impl>(argc, argv))
  {
  }

  MpiSession::~MpiSession() = default;

  unsigned int MpiSession::rank() const
  {
    return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  }

  unsigned int MpiSession::n_ranks() const
  {
    return dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  }
} // namespace kimp::fem
