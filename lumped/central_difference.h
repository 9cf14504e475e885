// Central difference method for the pounding system (thesis eq. 3.9-3.11):
//   (M/Δt² + C/(2Δt))·u_{n+1} = p_n − K·u_n − f_nl,n + (2M/Δt²)·u_n − (M/Δt² − C/(2Δt))·u_{n−1},
// stable for Δt < 2/ω_max (3.12) with ω_max including every contact's ω_imp = √(k_t/m_eff) (3.13).
#pragma once

#include <string>
#include <vector>

#include "lumped/ground_motion.h"
#include "lumped/pounding_model.h"
#include "lumped/response.h"

namespace kimp::lumped
{
  /**
   * Velocity handed to the impact laws and the isolator at step n. The central difference
   * velocity (u_{n+1} − u_{n−1})/(2Δt) needs u_{n+1}, which depends on the force being evaluated,
   * so an explicit scheme must use past displacements (PHYSICS.md §5):
   *  - backward: (u_n − u_{n−1})/Δt, first order, lags by Δt/2 (the thesis' choice);
   *  - backward_second_order: (3u_n − 4u_{n−1} + u_{n−2})/(2Δt), second order, no lag.
   * The viscous matrix C is integrated implicitly (central) in either case.
   */
  enum class LawVelocity
  {
    backward,
    backward_second_order
  };

  /**
   * | option                   | unit | default | meaning                                     |
   * |--------------------------|------|---------|---------------------------------------------|
   * | dt                       | s    | 0       | time step; 0 = auto: safety·Δt_cr, reduced  |
   * |                          |      |         | so that it divides the record's dt exactly  |
   * | safety                   | -    | 0.5     | (0, 1]; margin for contact damping and      |
   * |                          |      |         | stiffening beyond the expected penetration  |
   * | expected_max_penetration | m    | 0.05    | δ at which k_t = law.initial_stiffness(δ)   |
   * | duration                 | s    | 0       | analysis length; 0 = the record's length    |
   * | output_interval          | s    | 0.01    | history sampling; 0 = no histories          |
   * | law_velocity             | -    | backward| see LawVelocity                             |
   * | initial_displacement     | m    | zeros   | u(0), empty or one per DOF                  |
   * | initial_velocity         | m/s  | zeros   | u̇(0), empty or one per DOF                  |
   * | divergence_energy_factor | -    | 10      | stop when E_kin + E_strain exceeds this     |
   * |                          |      |         | times max(E_0 + W_in)                       |
   */
  struct CentralDifferenceOptions
  {
    double              dt                       = 0.0;
    double              safety                   = 0.5;
    double              expected_max_penetration = 0.05;
    double              duration                 = 0.0;
    double              output_interval          = 0.01;
    LawVelocity         law_velocity             = LawVelocity::backward;
    std::vector<double> initial_displacement;
    std::vector<double> initial_velocity;
    double              divergence_energy_factor = 10.0;
  };

  /// Stability limit of the central difference method for a model.
  struct StabilityLimit
  {
    double      omega_structure = 0.0; ///< ω_max of (K + K1·e0e0ᵀ, M), contacts open, rad/s
    double      omega_closed    = 0.0; ///< ω_max with every contact at its tangent k_t, rad/s
    double      omega_impact    = 0.0; ///< max_c √(k_t,c/m_eff,c), rad/s
    double      dt_critical     = 0.0; ///< 2/max(the three), s
    std::string governing;             ///< which bound governs (for messages)
  };

  /**
   * Δt_cr from the structure and every contact, with k_t = law.initial_stiffness(δ_max).
   * @param[in] expected_max_penetration δ_max, m (> 0)
   */
  StabilityLimit stability_limit(const PoundingModel &model, double expected_max_penetration);

  /**
   * Fixed-step central difference integrator with an allocation-free time loop. The effective
   * matrix A = M/Δt² + C/(2Δt) is block-tridiagonal (one block per building, no coupling between
   * blocks) and is inverted once: blocks of up to 16 DOFs keep a dense inverse (a short dependency
   * chain per step), larger ones the pre-factorised Thomas algorithm. For a single building of
   * 4-6 DOFs with a bilinear isolator the loop is instantiated with a compile-time size and
   * advances u_{n+1} = A⁻¹B·u_n + A⁻¹D·u_{n−1} − A⁻¹M·1·ü_g − A⁻¹·f_nl, where only the sparse
   * force term depends on the forces just evaluated. Contacts and the isolator are evaluated
   * explicitly at u_n (trial + commit every step); a law whose gap is open and which is not in
   * contact is not called, and is brought up to date with the last open state just before it
   * closes (so its first contact step starts from the true previous, open, deformation).
   *
   * Recorded at every t_n (n = 0..N): u_n, the step's acceleration (u_{n+1} − 2u_n + u_{n−1})/Δt²
   * + ü_g(t_n) (PHYSICS.md §5), the contact forces F_n, and the energy terms.
   */
  class CentralDifference
  {
  public:
    /// @throws std::invalid_argument for invalid options.
    explicit CentralDifference(PoundingModel model, CentralDifferenceOptions options = {});

    const StabilityLimit &stability() const { return stability_; }

    /**
     * The step used for a record sampled every `record_dt` seconds.
     * @throws TimeStepError when options.dt exceeds stability().dt_critical (both numbers named).
     */
    double time_step(double record_dt) const;

    /**
     * Integrate from rest (or the initial conditions) under ü_g (zero past the record's end).
     * @throws TimeStepError, DivergenceError (time, step and DoF named).
     */
    Response run(const GroundMotion &motion) const;

    const PoundingModel &model() const { return model_; }

  private:
    PoundingModel            model_;
    CentralDifferenceOptions options_;
    StabilityLimit           stability_;
  };
} // namespace kimp::lumped
