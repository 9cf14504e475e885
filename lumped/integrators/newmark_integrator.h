// Implicit Newmark method, average acceleration (β = 1/4, γ = 1/2; Newmark 1959), with Newton
// iterations on the non-linear isolator and contact forces: unconditionally stable for the
// linear part, so Δt is not bounded by the contact stiffness (only accuracy is).
#pragma once

#include <vector>

#include "lumped/excitation/ground_motion.h"
#include "lumped/integrators/response.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::lumped
{
  /**
   * | option               | unit | default | meaning                                          |
   * |----------------------|------|---------|--------------------------------------------------|
   * | dt                   | s    | 0       | macro step; 0 = the record's dt                  |
   * | duration             | s    | 0       | analysis length; 0 = the record's length         |
   * | output_interval      | s    | 0.01    | history sampling (rounded to whole steps); 0: none|
   * | displacement_tolerance | m  | 1e-10   | Newton stops when max |Δu| is below this        |
   * | max_iterations       | -    | 25      | Newton iterations per attempt                    |
   * | max_halvings         | -    | 10      | step cuts (Δt/2^k) before ConvergenceError       |
   * | initial_displacement | m    | zeros   | u(0)                                             |
   * | initial_velocity     | m/s  | zeros   | u̇(0)                                             |
   */
  struct NewmarkOptions
  {
    double              dt                     = 0.0;
    double              duration               = 0.0;
    double              output_interval        = 0.01;
    double              displacement_tolerance = 1e-10;
    int                 max_iterations         = 25;
    int                 max_halvings           = 10;
    std::vector<double> initial_displacement;
    std::vector<double> initial_velocity;
  };

  /**
   * Newmark average-acceleration integrator for a PoundingModel.
   *
   * Step contract: from the committed state (u_n, u̇_n, ü_n) at t_n, solve
   *   M·ü_{n+1} + C·u̇_{n+1} + K·u_{n+1} + f_nl(u_{n+1}, u̇_{n+1}) = −M·1·ü_g(t_{n+1})
   * with ü_{n+1} = 4(u_{n+1} − u_n)/Δt² − 4u̇_n/Δt − ü_n, u̇_{n+1} = u̇_n + Δt(ü_n + ü_{n+1})/2,
   * by Newton with the laws' exact tangents (stiffness + 2/Δt·damping). The laws and the
   * isolator are committed only after convergence; on failure they are reverted and the step is
   * retried as two half steps, recursively, up to max_halvings (docs/architecture.md "Time
   * integration").
   *
   * Recorded: the same Response as CentralDifference (accelerations ü_{n+1} + ü_g, velocities of
   * the method); peaks and energies include sub-steps, histories are sampled at macro steps.
   */
  class NewmarkIntegrator
  {
  public:
    /// @throws std::invalid_argument for invalid options.
    explicit NewmarkIntegrator(PoundingModel model, NewmarkOptions options = {});

    /// @throws ConvergenceError naming the time, the step and the residual norm.
    Response run(const GroundMotion &motion) const;

  private:
    PoundingModel  model_;
    NewmarkOptions options_;
  };
} // namespace kimp::lumped
