// Bidirectional isolators of the 3D lumped model (docs/physics.md "Pounding in plan",
// "Isolators in plan"): the restoring force f(u, u̇) of one device between the ground and the
// isolation level, u and f vectors in plan, with the trial/commit state of the planar isolators
// (lumped/isolators/isolator.h). Each reduces exactly to its planar counterpart under motion along
// one axis.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/bouc_wen_isolator.h"
#include "lumped/isolators/friction_pendulum_isolator.h"
#include "lumped/isolators/isolator.h"
#include "lumped/plan/plan_geometry.h"
#include "lumped/trial_commit.h"

namespace kimp::lumped::plan
{
  /**
   * A bidirectional isolator law with trial/commit state.
   *
   * Contract (as lumped::Isolator): `set_trial(u, u̇)` starts from the committed state every
   * time (idempotent) and returns the restoring force, N (in the direction of u for a spring);
   * `commit()` accepts the last trial, `revert_to_last_commit()` discards it,
   * `revert_to_start()` returns to the virgin state, `clone()` copies both states. The explicit
   * integrator needs the force only; its stable step uses initial_stiffness().
   */
  class PlanIsolator : public TrialCommit
  {
  public:
    /// Force, N, at the trial displacement u (m, relative to the ground) and velocity u̇ (m/s).
    virtual Point set_trial(const Point &displacement, const Point &velocity) = 0;

    /// Initial (elastic) stiffness in every direction, N/m.
    virtual double initial_stiffness() const = 0;
    /// Linear viscous coefficient of the device in every direction, N·s/m.
    virtual double viscous_coefficient() const = 0;
    /// Recoverable energy at the committed state, J.
    virtual double stored_energy() const = 0;
    /// Hysteretic energy dissipated up to the last commit, J (>= 0).
    virtual double dissipated_energy() const = 0;
    /// Force at the committed state, N.
    virtual Point committed_force() const = 0;

    virtual std::string                   name() const  = 0;
    virtual std::unique_ptr<PlanIsolator> clone() const = 0;
  };

  /// The hysteretic isolators' base in plan (lumped::HystereticIsolatorLaw: committed and trial
  /// `State`, the device dashpot c).
  template <class Derived, class State>
  using PlanHystereticIsolator = HystereticIsolatorLaw<PlanIsolator, Derived, State>;

  /// History of a PlanBilinearIsolator.
  struct PlanBilinearState
  {
    Point  u          = Point::Zero(); ///< m
    Point  f_ep       = Point::Zero(); ///< elastic-perfectly-plastic force, |f_ep| <= Q, N
    double dissipated = 0.0;           ///< Q·Σ|Δu_p|, J
  };

  /**
   * Bilinear isolator with a circular yield surface: F = K2·u + f_ep, f_ep elastic-perfectly
   * plastic of stiffness K1 − K2 and yield force Q in every direction (|f_ep| <= Q), updated by
   * radial return. Parameters and checks as lumped::BilinearIsolator (K1 > 0, 0 <= K2 < K1,
   * Q > 0, c >= 0); uniaxial motion gives its force to round-off.
   */
  class PlanBilinearIsolator final
    : public PlanHystereticIsolator<PlanBilinearIsolator, PlanBilinearState>
  {
  public:
    /// @throws std::invalid_argument naming the parameter (lumped::BilinearIsolator's checks).
    explicit PlanBilinearIsolator(const BilinearParameters &parameters, double c = 0.0);

    Point       set_trial(const Point &displacement, const Point &velocity) override;
    double      initial_stiffness() const override { return p_.K1; }
    double      stored_energy() const override;
    Point       committed_force() const override { return p_.K2 * committed_.u + committed_.f_ep; }
    std::string name() const override { return "bilinear"; }

  private:
    BilinearParameters p_;
  };

  /// History of a PlanBoucWenIsolator.
  // In the header, so that a caller holding a PlanBilinearIsolator can inline it.
  inline Point PlanBilinearIsolator::set_trial(const Point &displacement,
                                               const Point & /*velocity*/)
  {
    const double k_ep    = p_.K1 - p_.K2;
    const Point  f_trial = committed_.f_ep + k_ep * (displacement - committed_.u);
    trial_.u             = displacement;
    trial_.dissipated    = committed_.dissipated;
    // |f_trial| <= 0.9·Q for sure (no root needed) while |f_trial|² <= 0.81·Q².
    const double sq = f_trial.squaredNorm();
    if (sq <= 0.81 * p_.Q * p_.Q)
    {
      trial_.f_ep = f_trial;
      return p_.K2 * displacement + trial_.f_ep;
    }
    const double norm = std::sqrt(sq);
    if (norm > p_.Q)
    {
      // Radial return: plastic slip |Δu_p| = (|f_trial| − Q)/k_ep along f_trial.
      trial_.f_ep = p_.Q * (f_trial / norm);
      trial_.dissipated += p_.Q * (norm - p_.Q) / k_ep;
    }
    else
      trial_.f_ep = f_trial;
    return p_.K2 * displacement + trial_.f_ep;
  }
  struct PlanBoucWenState
  {
    Point  u          = Point::Zero(); ///< m
    Point  z          = Point::Zero(); ///< hysteretic variable
    double dissipated = 0.0;           ///< J
  };

  /**
   * Bouc-Wen isolator with the Park-Wen biaxial coupling (Park, Wen & Ang 1986, EESD 14(4);
   * Nagarajaiah, Reinhorn & Constantinou 1991, J. Struct. Eng. 117(7)):
   *   F = α·K1·u + (1 − α)·F_y·z,
   *   u_y·ż = A·u̇ − |z|^(n−2)·z·[(γ + β·sgn(u̇_x z_x))·z_x u̇_x + (γ + β·sgn(u̇_y z_y))·z_y u̇_y],
   * which for n = 2 is Park-Wen's equation and for uniaxial motion the uniaxial Bouc-Wen law of
   * exponent n (lumped::BoucWenIsolator). Each trial integrates z by backward Euler (Newton on
   * the 2×2 residual, the increment halved until it converges). Parameters and checks as
   * lumped::BoucWenIsolator. Dissipation per step Q/A·|z|^n·w ≥ 0 for β >= |γ|, w the bracket.
   */
  class PlanBoucWenIsolator final
    : public PlanHystereticIsolator<PlanBoucWenIsolator, PlanBoucWenState>
  {
  public:
    /// @throws std::invalid_argument naming the parameter (BoucWenParameters::check()).
    explicit PlanBoucWenIsolator(const BoucWenParameters &parameters, double c = 0.0);

    Point  set_trial(const Point &displacement, const Point &velocity) override;
    double initial_stiffness() const override
    {
      return p_.K1 * (p_.alpha + (1.0 - p_.alpha) * p_.A);
    }
    double stored_energy() const override;
    Point  committed_force() const override
    {
      return p_.alpha * p_.K1 * committed_.u + p_.strength() * committed_.z;
    }
    /// z at the committed state.
    Point       committed_z() const { return committed_.z; }
    std::string name() const override { return "bouc_wen"; }

  private:
    /// z after the increment du from z_c (backward Euler); adds the dissipation to `dissipated`.
    Point update(const Point &z_c, const Point &du, double &dissipated, int depth) const;

    BoucWenParameters p_;
  };

  /// History of a PlanFrictionPendulumIsolator.
  struct PlanFrictionPendulumState
  {
    Point  u          = Point::Zero(); ///< m
    Point  f_s        = Point::Zero(); ///< friction force, |f_s| <= μ·W, N
    double dissipated = 0.0;           ///< Σ μ·W·|Δu_slip|, J
  };

  /**
   * Friction pendulum with a 2D slider (Mokha, Constantinou & Reinhorn 1991): F = W/R·u + f_s,
   * f_s elastic-perfectly plastic of stiffness k_init with the circular yield surface
   * |f_s| <= μ(|u̇|)·W, μ(v) = μ_fast − (μ_fast − μ_slow)·exp(−a·v), by radial return. Parameters
   * and checks as lumped::FrictionPendulumIsolator.
   */
  class PlanFrictionPendulumIsolator final
    : public PlanHystereticIsolator<PlanFrictionPendulumIsolator, PlanFrictionPendulumState>
  {
  public:
    /// @throws std::invalid_argument naming the parameter (FrictionPendulumParameters::check()).
    explicit PlanFrictionPendulumIsolator(const FrictionPendulumParameters &parameters,
                                          double                            c = 0.0);

    Point  set_trial(const Point &displacement, const Point &velocity) override;
    double initial_stiffness() const override { return p_.k_init + k_pendulum_; }
    double stored_energy() const override;
    Point  committed_force() const override { return k_pendulum_ * committed_.u + committed_.f_s; }
    std::string name() const override { return "friction_pendulum"; }

  private:
    FrictionPendulumParameters p_;
    double                     k_pendulum_; ///< W/R
  };
} // namespace kimp::lumped::plan
