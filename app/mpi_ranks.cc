// The MPI ranks of app/mpi_ranks.h, with MPI.
#include "app/mpi_ranks.h"

#include <exception>
#include <mpi.h>

#include "io/output_dir.h"

namespace kimp::app
{
  MpiRanks::MpiRanks()
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized && launched_by_mpi())
    {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
      io::install_signal_handlers(); // MPI's start-up replaces them (SIGPIPE, SIGTERM)
      owned_      = true;
      initialized = 1;
    }
    if (initialized)
    {
      active_ = true;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
      MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
  }

  MpiRanks::~MpiRanks()
  {
    int finalized = 0;
    MPI_Finalized(&finalized);
    // While an exception unwinds, MPI_Finalize would wait for the other ranks; main() reports
    // the error and aborts the job instead.
    if (owned_ && !finalized && std::uncaught_exceptions() == 0)
      MPI_Finalize();
  }

  std::function<void()> MpiRanks::barrier() const
  {
    if (!active_ || size_ < 2)
      return {};
    return []() { MPI_Barrier(MPI_COMM_WORLD); };
  }

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
} // namespace kimp::app
