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
   * (collective: every rank must call it). It is not removed: the files in it are read until
   * the end of the job, and the process id keeps concurrent jobs apart.
   */
  inline std::filesystem::path shared_temp_dir(const std::string &tag, MPI_Comm comm)
  {
    int pid = static_cast<int>(::getpid());
    MPI_Bcast(&pid, 1, MPI_INT, 0, comm);
    const std::filesystem::path dir = process_temp_path(tag, pid);
    std::filesystem::create_directories(dir);
    return dir;
  }
} // namespace kimp::testing
