// kimp::testing::shared_temp_dir(): one scratch directory for all ranks of an MPI job (the FEM
// tests and benchmarks write a mesh on rank 0 that every rank reads).
#pragma once

#include <filesystem>
#include <mpi.h>
#include <string>
#include <unistd.h>

namespace kimp::testing
{
  /**
   * The directory kimp_<tag>_<process id of rank 0> under the system temporary directory,
   * created on every rank of `comm` (collective: every rank must call it). It is left in place
   * for the rest of the job; the process id keeps concurrent jobs apart.
   */
  inline std::filesystem::path shared_temp_dir(const std::string &tag, MPI_Comm comm)
  {
    int pid = static_cast<int>(::getpid());
    MPI_Bcast(&pid, 1, MPI_INT, 0, comm);
    const auto dir =
      std::filesystem::temp_directory_path() / ("kimp_" + tag + "_" + std::to_string(pid));
    std::filesystem::create_directories(dir);
    return dir;
  }
} // namespace kimp::testing
