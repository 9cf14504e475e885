// Cost of one FEM impact case known before it is meshed (DoFs, time step, steps, seconds) and the
// step budget `dynamics.max_steps` that refuses a case above it.
#pragma once

#include <string>

#include "app/fem/fem_common.h"

namespace kimp::app
{
  /// Measured cost of one explicit step per DoF, s (docs/performance.md "fem/": 95 us per step at
  /// 3366 DoFs, elastic; an inelastic step about 0.5 ms).
  inline constexpr double fem_explicit_seconds_per_dof_step  = 3e-8;
  inline constexpr double fem_inelastic_seconds_per_dof_step = 1.5e-7;
  /// Implicit Newmark with the direct solver: 2.4-3.1 s for 1518 steps at 3366 DoFs.
  inline constexpr double fem_implicit_seconds_per_dof_step = 6e-7;

  /// Cost of one FEM case, from its grid (geometry::SceneLayout) before it is meshed.
  struct FemEstimate
  {
    double n_dofs   = 0.0; ///< 2 per node
    double dt       = 0.0; ///< s: the step the solver will take (its stability limit rule)
    double end_time = 0.0; ///< s
    double n_steps  = 0.0; ///< end_time / dt: at most this many (a run stops at separation)
    double seconds  = 0.0; ///< rough wall time on one core

    /// "6.5e+04 DoFs, up to 2.3e+05 steps of 2.2e-07 s over 0.05 s, ~4.4e+02 s".
    std::string text() const;
  };

  /**
   * The cost of `spec` before meshing: nodes of its grid, and the explicit stability limit the
   * solver computes (fem/impact/setup.cc): omega_mesh = 2 c_p / h of the smallest cell per body,
   * the contact penalty omega = sqrt(k / m_red) with k = penalty_factor E_wall / h_contact times
   * the tributary length and the lumped node masses of the contact face (the wall-soil interface
   * springs are left out), the damped limit 2 / omega (sqrt(1 + xi^2) - xi), times cfl_safety (or
   * the implicit dt factor), or the scene's own dt.
   */
  FemEstimate estimate_fem_case(const FemCaseSpec &spec);

  /**
   * @throws std::invalid_argument "<name>: the estimate (<estimate>) exceeds the step budget
   *         dynamics.max_steps = N ..." when estimate.n_steps > max_steps.
   */
  void check_fem_budget(const std::string &name, const FemEstimate &estimate, double max_steps);
} // namespace kimp::app
