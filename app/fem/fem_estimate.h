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

  /// Measured peak memory of one FEM case per DoF, bytes, beside a fixed part (deal.II, MPI and
  /// the libraries: docs/performance.md "Cost limits"): explicit 0.75 kB, implicit with the
  /// direct solver 2.8 kB; the frames of `kimp fem` add 16 bytes per DoF and frame
  /// (displacements per vertex, stresses per cell).
  inline constexpr double fem_bytes_per_dof          = 1e3;
  inline constexpr double fem_implicit_bytes_per_dof = 3e3;
  inline constexpr double fem_fixed_bytes            = 2e8;
  inline constexpr double fem_frame_bytes_per_dof    = 16.0;

  /// Cost of one FEM case, from its grid (geometry::SceneLayout) before it is meshed.
  struct FemEstimate
  {
    double n_dofs   = 0.0; ///< 2 per node
    double dt       = 0.0; ///< s: the step the solver will take (its stability limit rule)
    double end_time = 0.0; ///< s
    double n_steps  = 0.0; ///< end_time / dt: at most this many (a run stops at separation)
    double seconds  = 0.0; ///< rough wall time on one core
    double memory   = 0.0; ///< bytes: rough peak of the process while the case runs

    /// "6.5e+04 DoFs, up to 2.3e+05 steps of 2.2e-07 s over 0.05 s, ~4.4e+02 s, ~0.5 GB".
    std::string text() const;
  };

  /**
   * Limits of the estimated cost past which `kimp fem`, `kimp mesh` and `kimp study` refuse to
   * start (`--accept-cost` goes ahead): far above every shipped scene and the default study (the
   * largest, the inelastic study, is estimated at ~2 h), far below a slip of the unit (a 1 mm
   * contact mesh: 1.1e7 DoFs, ~42 h).
   */
  struct CostLimits
  {
    double max_dofs    = 1e6;      ///< DoFs of one case (also what `kimp mesh` meshes)
    double max_memory  = 8e9;      ///< bytes of one case
    double max_seconds = 6 * 3600; ///< s: every case of the command on one core
  };

  /// The cost of a command's FEM cases: its largest case and the sums over all of them.
  struct FemCost
  {
    std::size_t n_cases = 0;
    std::string largest;          ///< name of the case of most DoFs
    FemEstimate largest_estimate; ///< its estimate
    double      max_memory = 0.0; ///< bytes, the largest case's peak
    double      steps      = 0.0; ///< sum over the cases
    double      seconds    = 0.0; ///< sum over the cases, one core

    void add(const std::string &name, const FemEstimate &estimate);
    /// "4 FEM cases, ~1.2e+02 s on one core; largest H1.25: <its estimate>".
    std::string text() const;
  };

  /**
   * Refuses `cost` when it passes `limits` (DoFs or memory of one case, the time of all; the
   * time only with `with_time`: `kimp mesh` runs no case), unless `accept` (then a warning).
   * @throws std::invalid_argument "<command>: estimated cost above the limits: <cost>: <which
   *         limit> (a coarser mesh.h_contact, fewer wall heights or a shorter dynamics.end_time;
   *         --accept-cost runs it anyway)".
   */
  void check_cost(const std::string &command,
                  const FemCost     &cost,
                  const CostLimits  &limits,
                  bool               with_time,
                  bool               accept);

  /// The cost of `kimp fem` (and `kimp mesh`) on `scene`: one case per wall height, with the
  /// frames of output.frame_interval.
  FemCost estimate_fem_scene(const FemScene &scene);

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
