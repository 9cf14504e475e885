// The MPI ranks of app/mpi_ranks.h without MPI: one rank. The executable linking this (the lean
// `kimp` beside kimp-fem) execs kimp-fem when an MPI launcher started it (cli/main.cc).
#include <stdexcept>

#include "app/mpi_ranks.h"

namespace kimp::app
{
  MpiRanks::MpiRanks()
  {
    if (launched_by_mpi())
      throw std::runtime_error("this kimp executable has no MPI: run the MPI job with kimp-fem, "
                               "or with the `kimp` beside it, which starts kimp-fem");
  }

  MpiRanks::~MpiRanks() = default;

  std::function<void()> MpiRanks::barrier() const
  {
    return {};
  }

  void abort_other_ranks(int /*exit_code*/) {}
} // namespace kimp::app
