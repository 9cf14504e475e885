// The numerical failure of an FEM solver (impact, static plasticity, wall SDOF): a plain
// exception naming where (time or load factor, step) the solution failed.
#pragma once

#include <stdexcept>
#include <string>

namespace kimp::fem
{
  /** A numerical failure (divergence, non-convergence) at `time` (s, or a load factor) and `step`.
   */
  class NumericalError : public std::runtime_error
  {
  public:
    NumericalError(const std::string &what, double time, unsigned long step)
      : std::runtime_error(what)
      , time(time)
      , step(step)
    {
    }
    double        time; ///< s
    unsigned long step;
  };
} // namespace kimp::fem
