// The process-wide runtime a kimp command runs in: MPI, p4est and Trilinos for a build with the
// FEM engine (fem::MpiSession), nothing for a lumped-only build (a sweep initialises MPI itself).
#pragma once

#include <memory>

namespace kimp::app
{
  /// One per process, created at the top of main() before any command runs.
  class Session
  {
  public:
    Session(int &argc, char **&argv);
    ~Session();
    Session(const Session &)            = delete;
    Session &operator=(const Session &) = delete;

    /// This process's MPI rank (0 without MPI).
    unsigned int rank() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl;
  };
} // namespace kimp::app
