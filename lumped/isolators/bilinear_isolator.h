// Bilinear isolator with kinematic hardening (thesis §3.1, docs/physics.md §2/§3): elastic K1 up to
// F_y = Q/(1 − K2/K1), post-yield K2; written as a K2 spring in parallel with an elastic-perfectly
// plastic spring (stiffness K1 − K2, yield force Q), so the hysteretic energy is exactly Q·Σ|Δu_p|.
#pragma once

#include "lumped/isolators/isolator.h"

namespace kimp::lumped
{
  /// The parameters of the bilinear law (BilinearIsolator, plan::PlanBilinearIsolator; table
  /// below).
  struct BilinearParameters
  {
    double K1 = 0.0; ///< N/m
    double K2 = 0.0; ///< N/m
    double Q  = 0.0; ///< N

    /// @throws std::invalid_argument naming the parameter, its value and the admissible range.
    void check() const;
  };

  /// History of a BilinearIsolator, held committed and trial.
  struct BilinearState
  {
    double u          = 0.0; ///< displacement, m
    double f_ep       = 0.0; ///< force of the elastic-perfectly-plastic branch, N (|f_ep| <= Q)
    double dissipated = 0.0; ///< Q·Σ|Δu_p|, J
  };

  /**
   * Bilinear hysteretic isolator (lead-rubber bearing idealisation), rate independent.
   *
   * | parameter | unit | admissible | meaning                                                   |
   * |-----------|------|------------|-----------------------------------------------------------|
   * | K1        | N/m  | > 0        | initial (elastic) stiffness                               |
   * | K2        | N/m  | [0, K1)    | post-yield stiffness                                      |
   * | Q         | N    | > 0        | characteristic strength (zero-displacement intercept of   |
   * |           |      |            | the post-yield branch)                                    |
   * | c         | N·s/m| >= 0       | device dashpot added to C[0,0] (default 0)                |
   *
   * Yield force F_y = Q/(1 − K2/K1), yield displacement u_y = F_y/K1 = Q/(K1 − K2). A closed
   * symmetric cycle of amplitude D > u_y dissipates the loop area 4·Q·(D − u_y).
   */
  class BilinearIsolator final : public HystereticIsolator<BilinearIsolator, BilinearState>
  {
  public:
    /// @throws std::invalid_argument naming the parameter, its value and the admissible range.
    BilinearIsolator(double K1, double K2, double Q, double c = 0.0);

    IsolatorResponse set_trial(double displacement, double velocity) override;

    double initial_stiffness() const override { return K1_; }
    double stored_energy() const override
    {
      return 0.5 * K2_ * committed_.u * committed_.u +
             0.5 * committed_.f_ep * committed_.f_ep * inv_k_ep_;
    }

    /// Yield force F_y = Q/(1 − K2/K1), N.
    double yield_force() const { return Q_ / (1.0 - K2_ / K1_); }
    /// Yield displacement u_y = Q/(K1 − K2), m.
    double yield_displacement() const { return Q_ / (K1_ - K2_); }
    /// Force at the committed state, N.
    double committed_force() const override { return K2_ * committed_.u + committed_.f_ep; }

    std::string name() const override { return "bilinear"; }

  private:
    double K1_;
    double K2_;
    double Q_;
    double inv_k_ep_; ///< 1/(K1 − K2)
  };

  inline IsolatorResponse BilinearIsolator::set_trial(const double displacement,
                                                      const double velocity)
  {
    (void)velocity;
    // The trial state is formed in registers and stored once: field-by-field stores into trial_
    // followed by commit()'s wide copy stall the store forwarding of the next load (measured in
    // the variable-step kernel, where the isolator is called every step).
    const double k_ep    = K1_ - K2_;
    const double f_trial = committed_.f_ep + k_ep * (displacement - committed_.u);
    if (f_trial > Q_ || f_trial < -Q_)
    {
      const double f_yield = f_trial > 0.0 ? Q_ : -Q_;
      // Plastic slip |Δu_p| = |f_trial − f_yield|/k_ep dissipates Q per unit slip.
      trial_ = {displacement,
                f_yield,
                committed_.dissipated +
                  Q_ * (f_trial - f_yield) / k_ep * (f_trial > 0.0 ? 1.0 : -1.0)};
      return {K2_ * displacement + f_yield, K2_, 0.0};
    }
    trial_ = {displacement, f_trial, committed_.dissipated};
    return {K2_ * displacement + f_trial, K1_, 0.0};
  }
} // namespace kimp::lumped
