// Variable-step central differences for `dt: auto`: large steps while every contact is open and
// far, small steps that resolve each contact pulse (onset located within the step), and a
// step-factor error estimate of the peaks over every contact window (docs/physics.md §2).
#pragma once

#include <string>
#include <vector>

#include "lumped/excitation/ground_motion.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/response.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::lumped
{
  /**
   * | option          | unit | default | meaning                                                |
   * |-----------------|------|---------|--------------------------------------------------------|
   * | structure_step  | -    | 0.6     | ω_structure·Δt_large (and Δt_large <= the `stable`     |
   * |                 |      |         | step safety·Δt_cr), reduced to divide the record's dt  |
   * | approach_steps  | -    | 48      | steps per shortest structural period 2π/ω_structure    |
   * |                 |      |         | while a gap closes within approach_time: Δt_a          |
   * | approach_time   | s    | 1.0     | horizon of the approach prediction (present rate)      |
   * | contact_steps   | -    | 100     | steps per contact half-period π/ω_imp (ω_imp at the    |
   * |                 |      |         | expected penetration): Δt_c = π/(contact_steps·ω_imp)  |
   * | lookahead       | -    | 3       | a gap closing within this many Δt_large switches to    |
   * |                 |      |         | Δt_c                                                   |
   * | tail            | s    | 0.02    | Δt_c kept this long after the last contact separated   |
   * | error_estimate  | -    | true    | re-run every window at estimate_factor times its steps |
   * | estimate_factor | -    | 4       | (step-factor re-run, >= 2)                              |
   * | reference_kernel| -    | false   | run the reference path (dynamic-size products, an LU   |
   * |                 |      |         | solve per step, every law every step): the oracle of   |
   * |                 |      |         | the fast path in the tests, not for production         |
   * | stick_step      | -    | 0.3     | ω_structure·Δt_stick, the largest step while a         |
   * |                 |      |         | stick-slip isolator sticks (Isolator::stick_slip())    |
   *
   * The fast path (the default) runs fixed-size products for models of up to 8 DOFs, one cached
   * inverse of the effective matrix per step size, and skips the laws while their gap is open;
   * its peaks agree with the reference path's to rounding (tests/lumped/adaptive_step_test.cc).
   */
  struct AdaptiveStepOptions
  {
    double structure_step   = 0.6;
    double approach_steps   = 40.0;
    double approach_time    = 1.0;
    double contact_steps    = 80.0;
    double lookahead        = 3.0;
    double tail             = 0.02;
    bool   error_estimate   = true;
    double estimate_factor  = 4.0;
    bool   reference_kernel = false;
    double stick_step       = 0.3;
  };

  /// What a variable-step run did: its steps and its estimated errors.
  struct AdaptiveStepReport
  {
    double dt_large            = 0.0; ///< step while every contact is open and far, s
    double dt_approach         = 0.0; ///< step while a gap closes within approach_time, s
    double dt_contact          = 0.0; ///< step while a contact is active or imminent, s
    double dt_min              = 0.0; ///< smallest step taken (onsets, reversals, end of run), s
    long   steps               = 0;   ///< steps of the run (force evaluations but the first)
    long   contact_steps_taken = 0;   ///< of which below Δt_large (approach, contact), count
    long   estimate_steps      = 0;   ///< extra steps of the error-estimate re-runs
    int    windows             = 0;   ///< windows of steps below Δt_large
    /// Estimated relative errors of the peaks: every window is integrated again from a copy of
    /// its first state with estimate_factor (f) times its steps, and |P_h − P_fh|/(f − 1)
    /// (first order assumed, so an over-estimate for a second-order run) relative to the run's
    /// peak is reported, largest over contacts (force) and DOFs (absolute acceleration,
    /// displacement). It covers the windows only, not the large steps before them.
    double force_error        = 0.0;
    double acceleration_error = 0.0;
    double displacement_error = 0.0;
    /// "variable: ..." summary for logs and reports.
    std::string text() const;
  };

  /**
   * Variable-step central difference method (`dt: auto`), in the leap-frog form
   *   v_{n+1/2} solves (M/h̄_n + w₊·C)·v_{n+1/2} = (M/h̄_n − w₋·C)·v_{n−1/2} + p_n − K·u_n − f_nl,n,
   *   u_{n+1} = u_n + h_n·v_{n+1/2},
   * h̄_n = (h_{n−1} + h_n)/2, w₊ = h_{n−1}/(h_{n−1} + h_n), w₋ = h_n/(h_{n−1} + h_n) (the velocity
   * at t_n interpolated between the half steps, v_n = w₋·v_{n−1/2} + w₊·v_{n+1/2}). With a
   * constant step it is algebraically the central difference step of CentralDifference
   * (M/h² + C/(2h))·u_{n+1} = ...; with a changing step its truncation error is O(h²·|h_n −
   * h_{n−1}|) per step, so a bounded number of step changes keeps it second order. Contact and
   * isolator forces are explicit at u_n with the rate of the three-point formula for unequal
   * steps, δ̇_n ≈ s₁ + h_{n−1}/(h_{n−1} + h_{n−2})·(s₁ − s₂), s₁ = (δ_n − δ_{n−1})/h_{n−1},
   * s₂ = (δ_{n−1} − δ_{n−2})/h_{n−2} (second order; the options' law_velocity is not used: the
   * run aims at the Δt → 0 response, the same for both rates). The
   * recorded acceleration is (v_{n+1/2} − v_{n−1/2})/h̄_n + ü_g(t_n).
   *
   * Step choice at t_n (after the forces at t_n are evaluated), three tiers:
   *  - Δt_large = min(the `stable` step safety·Δt_cr, structure_step/ω_structure reduced to
   *    divide the record's dt) while every gap is open and not closing within approach_time;
   *  - Δt_a = min(Δt_large/3, 2π/(approach_steps·ω_structure)) while a gap closes within
   *    approach_time at its present rate: the impact velocity carries the error of the whole
   *    approach (high modes of the superstructure), so it is integrated finely too;
   *  - Δt_c = min(π/(contact_steps·ω_imp), Δt_a, safety·Δt_cr) while any contact is in contact,
   *    its gap is closed, holds a force, or closes within lookahead·Δt_large, and for `tail`
   *    seconds after;
   *  - a step that would close a gap is shortened to end where the gap closes at the present
   *    rate (contact onset located within the step, down to Δt_c/16);
   *  - with a stick-slip isolator (a friction pendulum): a step that would carry the isolator's
   *    velocity through zero (at its last acceleration) is shortened to end there (down to
   *    Δt_large/16), where the friction force has a kink (μ(|u̇|), the stick branch starts),
   *    and the step is at most Δt_stick = min(Δt_large, stick_step/ω_structure) while the
   *    isolator sticks (the stiff k_init branch);
   *  - the step grows by at most 2× per step; the last step ends at the end of the run. The
   *    history samples do not constrain the steps: a row every output_interval is interpolated
   *    linearly between the two steps around it (u is linear within a central-difference step),
   *    or taken at a step that falls on it; peaks are taken at every step.
   * Error estimate: every window (the steps below Δt_large) is integrated again from a copy of
   * its first state (laws cloned) with estimate_factor times the steps (AdaptiveStepReport).
   *
   * The Response is that of CentralDifference with dt = Δt_large and n_steps the number of
   * steps taken; histories have a row every output_interval (interpolated between steps).
   */
  class AdaptiveCentralDifference
  {
  public:
    /// `cdm.dt` must be 0 (the step is chosen here). @throws std::invalid_argument.
    AdaptiveCentralDifference(PoundingModel            model,
                              CentralDifferenceOptions cdm,
                              AdaptiveStepOptions      options = {});

    const StabilityLimit &stability() const { return stability_; }

    /// Δt_large for a record sampled every `record_dt` s.
    double large_step(double record_dt) const;
    /// Δt_c, s (∞ without contacts).
    double contact_step() const { return dt_contact_; }

    /**
     * @param[out] report what the run did (optional)
     * @param[out] steps  the steps h_0, h_1, ... it took (optional; for replay())
     * @throws DivergenceError, std::invalid_argument.
     */
    Response run(const GroundMotion  &motion,
                 AdaptiveStepReport  *report = nullptr,
                 std::vector<double> *steps  = nullptr) const;

    /**
     * The same model under `motion` with the steps of another run (e.g. the run with contacts, for
     * its companion without contacts: where no contact closed, both are then identical, and
     * amplification factors are exactly 1), no error estimate. Steps beyond `steps` are chosen.
     */
    Response replay(const GroundMotion &motion, const std::vector<double> &steps) const;

    const PoundingModel &model() const { return model_; }

  private:
    Response run_with(const GroundMotion        &motion,
                      AdaptiveStepReport        *report,
                      const std::vector<double> *replay,
                      std::vector<double>       *taken) const;

    PoundingModel            model_;
    CentralDifferenceOptions cdm_;
    AdaptiveStepOptions      options_;
    StabilityLimit           stability_;
    double                   dt_contact_  = 0.0;
    double                   dt_approach_ = 0.0;
  };
} // namespace kimp::lumped
