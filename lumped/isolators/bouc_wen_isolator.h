// Bouc-Wen isolator (lead-rubber bearing; docs/physics.md §2, "Isolators"): post-yield spring
// α·K1·u plus a smooth hysteretic force (1 − α)·F_y·z whose variable z follows the Bouc-Wen
// equation, integrated implicitly (backward Euler) inside set_trial, as in OpenSees'
// elastomericBearingBoucWen.
#pragma once

#include "lumped/isolators/isolator.h"

namespace kimp::lumped
{
  /// The parameters of the Bouc-Wen law (BoucWenIsolator, plan::PlanBoucWenIsolator; table
  /// below).
  struct BoucWenParameters
  {
    double K1    = 0.0; ///< N/m
    double alpha = 0.0; ///< K2/K1
    double F_y   = 0.0; ///< N
    double A     = 1.0;
    double beta  = 0.5;
    double gamma = 0.5;
    double n     = 1.0;

    /// Characteristic strength Q = (1 − α)·F_y, N.
    double strength() const { return (1.0 - alpha) * F_y; }
    /// Yield displacement u_y = F_y/K1, m.
    double yield_displacement() const { return F_y / K1; }

    /// @throws std::invalid_argument naming the parameter, its value and the admissible range.
    void check() const;
  };

  /// History of a BoucWenIsolator, held committed and trial.
  struct BoucWenState
  {
    double u          = 0.0; ///< displacement, m
    double z          = 0.0; ///< hysteretic variable
    double dissipated = 0.0; ///< J
  };

  /**
   * Bouc-Wen hysteretic isolator, rate independent:
   *   F = α·K1·u + (1 − α)·F_y·z,
   *   dz/du = (A − |z|^n·(γ + β·sgn(z·du)))/u_y,  u_y = F_y/K1.
   * Each trial solves the backward-Euler update z − z_c − Δu/u_y·(A − |z|^n·Ψ(z)) = 0 by a
   * bracketed Newton iteration; the tangent dF/du is the exact derivative of that update.
   * With A = 1 and β + γ = 1, |z| <= 1 and the initial stiffness is K1; for n → ∞ and β = γ
   * the loop tends to the bilinear one (K1, K2 = α·K1, Q = (1 − α)·F_y).
   *
   * | parameter | unit  | admissible      | meaning                                          |
   * |-----------|-------|-----------------|--------------------------------------------------|
   * | K1        | N/m   | > 0             | initial (elastic) stiffness                      |
   * | alpha     | -     | [0, 1)          | post-yield stiffness ratio K2/K1                 |
   * | F_y       | N     | > 0             | yield force                                      |
   * | A         | -     | > 0             | Bouc-Wen A (1 for a yield force F_y)             |
   * | beta      | -     | >= abs(gamma)   | Bouc-Wen β (β >= |γ| keeps the dissipation >= 0) |
   * | gamma     | -     | β + γ > 0       | Bouc-Wen γ                                       |
   * | n         | -     | >= 1            | sharpness of the yield transition                |
   * | c         | N·s/m | >= 0            | device dashpot added to C[0,0] (default 0)       |
   *
   * Stored energy of the hysteretic spring: (1 − α)·F_y·u_y·z²/(2A) (its elastic deformation is
   * u_y·z/A); the rest of its work, Σ (1 − α)·F_y·z·Δu·|z|^n·Ψ/A per step, is dissipated.
   */
  class BoucWenIsolator final : public HystereticIsolator<BoucWenIsolator, BoucWenState>
  {
  public:
    /// @throws std::invalid_argument naming the parameter, its value and the admissible range.
    explicit BoucWenIsolator(const BoucWenParameters &parameters, double c = 0.0);

    IsolatorResponse set_trial(double displacement, double velocity) override;

    double initial_stiffness() const override
    {
      return p_.K1 * (p_.alpha + (1.0 - p_.alpha) * p_.A);
    }
    double stored_energy() const override
    {
      return 0.5 * p_.alpha * p_.K1 * committed_.u * committed_.u +
             0.5 * Q_ * u_y_ * committed_.z * committed_.z / p_.A;
    }
    double committed_force() const override
    {
      return p_.alpha * p_.K1 * committed_.u + Q_ * committed_.z;
    }

    /// Characteristic strength Q = (1 − α)·F_y, N.
    double characteristic_strength() const { return Q_; }
    /// Yield displacement u_y = F_y/K1, m.
    double yield_displacement() const { return u_y_; }
    /// Hysteretic variable z at the committed state.
    double committed_z() const { return committed_.z; }

    std::string name() const override { return "bouc_wen"; }

  private:
    BoucWenParameters p_;
    double            Q_;     ///< (1 − α)·F_y
    double            u_y_;   ///< F_y/K1
    double            z_max_; ///< (A/(β + γ))^(1/n), the bound of |z|
    int               n_int_; ///< n when it is a small integer (|z|^n by multiplication), else 0

    /// |z|^n for a = |z| >= 0.
    double power(double a) const;
  };
} // namespace kimp::lumped
