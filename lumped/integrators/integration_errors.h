// Typed errors of the lumped time integrators (docs/architecture.md "Scenes and errors"): a time
// step above the stability limit of the central difference method (Δt_cr = 2/ω_max, thesis
// eq. 3.12-3.13), divergence, and non-convergence of Newton in the implicit method. Each carries
// its context as members.
#pragma once

#include <stdexcept>
#include <string>

namespace kimp::lumped
{
  /**
   * A requested time step Δt above the stable limit Δt_cr of the explicit method. It is bad input,
   * hence derived from std::invalid_argument; what() names both numbers and the governing bound.
   */
  class TimeStepError : public std::invalid_argument
  {
  public:
    TimeStepError(const std::string &message, double dt_, double dt_critical_)
      : std::invalid_argument(message)
      , dt(dt_)
      , dt_critical(dt_critical_)
    {
    }

    double dt;          ///< requested step, s
    double dt_critical; ///< stability limit, s
  };

  /// A run that stopped at a step; carries where: its time and step index.
  class StepError : public std::runtime_error
  {
  public:
    StepError(const std::string &message, double time_, long step_)
      : std::runtime_error(message)
      , time(time_)
      , step(step_)
    {
    }

    double time; ///< s
    long   step; ///< step index n (t = n·Δt; Newmark: the macro step that failed)
  };

  /**
   * The solution became non-finite or the mechanical energy grew far beyond the energy put in
   * (a numerical instability, not physics).
   */
  class DivergenceError : public StepError
  {
  public:
    DivergenceError(const std::string &message, double time_, long step_, int dof_)
      : StepError(message, time_, step_)
      , dof(dof_)
    {
    }

    int dof; ///< global degree of freedom with the offending value
  };

  /// Newton did not converge even after the allowed number of step halvings.
  class ConvergenceError : public StepError
  {
  public:
    ConvergenceError(const std::string &message, double time_, long step_, double residual_norm_)
      : StepError(message, time_, step_)
      , residual_norm(residual_norm_)
    {
    }

    double residual_norm; ///< last residual norm, N
  };
} // namespace kimp::lumped
