// Single friction pendulum bearing (docs/physics.md §2, "Isolators"): pendulum restoring force
// W/R·u plus velocity-dependent Coulomb friction μ(v)·W (Constantinou et al. 1990), regularised
// by an elastic sliding stiffness and a return mapping as in OpenSees' singleFPBearing.
#pragma once

#include "lumped/isolators/isolator.h"

namespace kimp::lumped
{
  /// The parameters of the friction pendulum (FrictionPendulumIsolator,
  /// plan::PlanFrictionPendulumIsolator; table below).
  struct FrictionPendulumParameters
  {
    double W       = 0.0; ///< N
    double R       = 0.0; ///< m
    double mu_slow = 0.0;
    double mu_fast = 0.0;
    double rate    = 0.0; ///< s/m
    double k_init  = 0.0; ///< N/m

    /// μ(v) = μ_fast − (μ_fast − μ_slow)·exp(−a·v) at the sliding speed v >= 0 (m/s).
    double mu(const double speed) const
    {
      return mu_fast - (mu_fast - mu_slow) * std::exp(-rate * speed);
    }

    /// @throws std::invalid_argument naming the parameter, its value and the admissible range.
    void check() const;
  };

  /// History of a FrictionPendulumIsolator, held committed and trial.
  struct FrictionPendulumState
  {
    double u          = 0.0;   ///< displacement, m
    double f_s        = 0.0;   ///< friction force, N (|f_s| <= μ·W)
    double dissipated = 0.0;   ///< Σ μ·W·|Δu_slip|, J
    bool   sliding    = false; ///< the last update slipped (f_s = ±μ·W)
  };

  /**
   * Single concave friction pendulum, small-angle approximation:
   *   F = W/R·u + f_s,  f_s elastic-perfectly-plastic with stiffness k_init and yield force
   *   μ(v)·W,  μ(v) = μ_fast − (μ_fast − μ_slow)·exp(−a·|v|).
   * f_s = μ(v)·W·z with the sliding variable z ∈ [−1, 1]; k_init regularises the stick phase
   * (OpenSees' kInit). While sliding, dF/du = W/R and dF/du̇ = ±W·dμ/dv; while sticking
   * dF/du = k_init + W/R and dF/du̇ = 0 (exact derivatives of the update).
   *
   * | parameter | unit  | admissible        | meaning                                         |
   * |-----------|-------|-------------------|-------------------------------------------------|
   * | W         | N     | > 0               | weight carried by the bearing(s)                |
   * | R         | m     | > 0               | effective radius of the concave surface         |
   * | mu_slow   | -     | [0, 1)            | friction coefficient at zero sliding velocity   |
   * | mu_fast   | -     | [mu_slow, 1)      | friction coefficient at high sliding velocity   |
   * | rate      | s/m   | >= 0              | a, transition rate of μ(v)                      |
   * | k_init    | N/m   | > 0               | elastic stiffness before sliding                |
   * | c         | N·s/m | >= 0              | device dashpot added to C[0,0] (default 0)      |
   *
   * Free vibration with μ → 0 has the pendulum period T = 2π·√(R/g) (m = W/g); a closed cycle
   * of amplitude D at constant μ dissipates 4·μ·W·(D − μ·W/k_init) → 4·μ·W·D (rigid-plastic).
   */
  class FrictionPendulumIsolator final
    : public HystereticIsolator<FrictionPendulumIsolator, FrictionPendulumState>
  {
  public:
    /// @throws std::invalid_argument naming the parameter, its value and the admissible range.
    explicit FrictionPendulumIsolator(const FrictionPendulumParameters &parameters, double c = 0.0);

    IsolatorResponse set_trial(double displacement, double velocity) override;

    double initial_stiffness() const override { return p_.k_init + k_pendulum_; }
    double stored_energy() const override
    {
      return 0.5 * k_pendulum_ * committed_.u * committed_.u +
             0.5 * committed_.f_s * committed_.f_s / p_.k_init;
    }
    double committed_force() const override { return k_pendulum_ * committed_.u + committed_.f_s; }
    bool   stick_slip() const override { return true; }
    bool   sticking() const override { return !committed_.sliding; }

    /// Friction coefficient μ(v) at sliding velocity v (m/s).
    double friction_coefficient(double velocity) const;
    /// Pendulum stiffness W/R, N/m.
    double pendulum_stiffness() const { return k_pendulum_; }

    std::string name() const override { return "friction_pendulum"; }

  private:
    FrictionPendulumParameters p_;
    double                     k_pendulum_; ///< W/R
  };
} // namespace kimp::lumped
