// kimp::testing::shared_temp_dir(): one scratch directory for all ranks of an MPI job (the FEM
// tests and benchmarks write a mesh on rank 0 that every rank reads).
#pragma once

#include <filesystem>
#include <mpi.h>
#include <string>
#include <unistd.h>

#include "tests/support/temp_dir.h"

namespace kimp::testing
{
  /**
   * The directory process_temp_path(tag) of rank 0 of `comm`, created on every rank
   * (collective: every rank must call it). It lives until remove_shared_temp_dir() (the files in
   * it are read until the end of the job), and the process id keeps concurrent jobs apart.
   */
  inline std::filesystem::path shared_temp_dir(const std::string &tag, MPI_Comm comm)
  {
    int pid = static_cast<int>(::getpid());
    MPI_Bcast(&pid, 1, MPI_INT, 0, comm);
    const std::filesystem::path dir = process_temp_path(tag, pid);
    std::filesystem::create_directories(dir);
    return dir;
  }

  /**
   * Removes shared_temp_dir(tag, comm) with everything in it, if it was made, once every rank of
   * `comm` is done with it (collective; a test or benchmark main calls it before MPI ends).
   */
  inline void remove_shared_temp_dir(const std::string &tag, MPI_Comm comm)
  {
    MPI_Barrier(comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0)
    {
      std::error_code ignored; // a leftover directory must not fail the job
      std::filesystem::remove_all(process_temp_path(tag), ignored);
    }
  }
} // namespace kimp::testing
