// One-dimensional contact force laws for pounding (impact laws 1-7 of docs/physics.md §1).
//
// Sign convention (the only one in kimp; no law branches on the sign of a parameter):
//   deformation δ = interpenetration of the two bodies, > 0 in contact, <= 0 with the gap open;
//                   the caller computes it as the relative displacement minus the clear gap;
//   rate δ̇       = dδ/dt, > 0 while approaching (closing), < 0 while restoring (opening);
//   force F      = compressive contact force, >= 0 pushes the bodies apart (a law may return
//                   F < 0 only where its model says so, e.g. Kelvin-Voigt near separation).
// All quantities SI: m, m/s, N, N/m^n, kg, J.
#pragma once

#include <memory>
#include <string>

#include "lumped/trial_commit.h"

namespace kimp::lumped
{
  /// Result of one trial evaluation.
  struct ForceResponse
  {
    double force     = 0.0; ///< F, N (compressive positive)
    double stiffness = 0.0; ///< dF/dδ at the trial state, N/m (exact derivative of `force`)
    double damping   = 0.0; ///< dF/dδ̇ at the trial state, N·s/m
  };

  /**
   * Contact force law with trial/commit state (docs/architecture.md "Force laws").
   *
   * Contract:
   *  - `set_trial(δ, δ̇)` starts from the committed state every time: repeated calls with the same
   *    arguments return the same result; it never changes committed state, does no I/O.
   *  - `commit()` accepts the last trial state (and accumulates dissipated work, trapezoid rule);
   *    `revert_to_last_commit()` discards it; `revert_to_start()` returns to the virgin state.
   *  - `clone()` returns an independent copy with identical committed and trial state.
   */
  class ForceLaw : public TrialCommit
  {
  public:
    /// Evaluate the law at a trial deformation δ (m) and rate δ̇ (m/s).
    virtual ForceResponse set_trial(double deformation, double rate) = 0;

    /// Stiffness k_t (N/m) that bounds the central difference time step for deformations up to
    /// `max_deformation`: stability_limit() takes ω_imp = sqrt(k_t/m_eff) and Δt_cr = 2/ω_max.
    /// It is the largest tangent stiffness the law can reach, raised for laws whose damping
    /// shortens the stable step: laws with a linear dashpot of known ratio ξ (2-4) divide it by
    /// (sqrt(1 + ξ²) − ξ)², so that 2/ω_imp is the damped central-difference limit, and Hertzdamp
    /// includes its rate term; see each law. Not an initial (zero-deformation) stiffness.
    virtual double stability_stiffness(double max_deformation) const = 0;
    /// Work dissipated by the law up to the last commit, J (>= 0).
    virtual double dissipated_energy() const = 0;
    /// Permanent indentation accumulated up to the last commit, m (0 for laws without it).
    virtual double permanent_indentation() const { return 0.0; }
    /// True while the committed state is in contact.
    virtual bool in_contact() const = 0;
    /// Elastic energy stored in the contact at the last commit, J (>= 0): the potential of the
    /// conservative part of the force, so that kinetic + strain + stored + dissipated balances.
    virtual double stored_energy() const { return 0.0; }
    /// Rate δ̇ (m/s) at the first trial of the current (or last) contact, as committed; 0 before
    /// the first contact. Laws 5-7 use it as v_imp.
    virtual double impact_velocity() const { return 0.0; }

    virtual std::string               name() const  = 0;
    virtual std::unique_ptr<ForceLaw> clone() const = 0;
  };
} // namespace kimp::lumped
