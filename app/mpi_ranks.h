// The MPI ranks of a command that may run as an MPI job without the FEM engine (`kimp sweep`),
// and the ending of a job on an error. Two implementations, chosen per executable at link time
// (app/CMakeLists.txt): with MPI (mpi_ranks.cc: kimp-fem, the lumped-only build's kimp, the
// tests), and one rank without MPI (mpi_ranks_single.cc: the lean `kimp` of a build with the FEM
// engine, which execs kimp-fem when an MPI launcher started it, so that it never loads MPI).
#pragma once

#include <cstdlib>
#include <functional>

namespace kimp::app
{
  /// True when an MPI launcher (mpirun, srun) started this process.
  inline bool launched_by_mpi()
  {
    for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
      if (std::getenv(name) != nullptr)
        return true;
    return false;
  }

  /// MPI for the duration of a command, initialised here when an MPI launcher started the process
  /// and nobody initialised it before (finalised at destruction, unless an exception unwinds);
  /// rank 0 of 1 otherwise.
  class MpiRanks
  {
  public:
    /// @throws std::runtime_error when launched by MPI in an executable without MPI
    MpiRanks();
    ~MpiRanks();
    MpiRanks(const MpiRanks &)            = delete;
    MpiRanks &operator=(const MpiRanks &) = delete;

    int  rank() const { return rank_; }
    int  size() const { return size_; }
    bool active() const { return active_; }
    /// A barrier of all ranks (nothing for one rank).
    std::function<void()> barrier() const;

  private:
    bool owned_  = false;
    bool active_ = false;
    int  rank_   = 0;
    int  size_   = 1;
  };

  /// An error on one rank of a multi-rank job would leave the others waiting in a collective call
  /// (a barrier, MPI_Finalize) forever: end the whole job instead (MPI_Abort). Does nothing where
  /// MPI was never initialised or the job has one rank.
  void abort_other_ranks(int exit_code);
} // namespace kimp::app
