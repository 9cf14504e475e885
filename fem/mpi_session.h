// RAII initialisation of MPI, p4est and Trilinos for kimp::fem (wraps deal.II's MPI_InitFinalize).
#pragma once

#include <memory>

namespace kimp::fem
{
  /**
   * Initialises MPI (and p4est/Zoltan through deal.II) for the lifetime of the object; one per
   * process, created at the top of main() before any run_impact(). Threads are limited to one
   * per rank so that 1 and N ranks compute in the same order.
   */
  class MpiSession
  {
  public:
    MpiSession(int &argc, char **&argv);
    ~MpiSession();
    MpiSession(const MpiSession &)            = delete;
    MpiSession &operator=(const MpiSession &) = delete;

    unsigned int rank() const;
    unsigned int n_ranks() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl;
  };
} // namespace kimp::fem
