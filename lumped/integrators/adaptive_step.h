// Variable-step central differences for `dt: auto`: large steps while every contact is open and
// far, small steps that resolve each contact pulse (onset located within the step), and a
// step-doubling error estimate of the peaks over every contact window (docs/physics.md §2).
#pragma once

#include <string>

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
   * | approach_time   | s    | 1.0     | horizontal prediction of the approach (present rate)   |
   * | contact_steps   | -    | 100     | steps per contact half-period π/ω_imp (ω_imp at the    |
   * |                 |      |         | expected penetration): Δt_c = π/(contact_steps·ω_imp)  |
   * | lookahead       | -    | 3       | a gap closing within this many Δt_large switches to    |
   * |                 |      |         | Δt_c                                                   |
   * | tail            | s    | 0.02    | Δt_c kept this long after the last contact separated   |
   * | error_estimate  | -    | true    | re-run every window at estimate_factor times its steps |
   * | estimate_factor | -    | 4       | (step-factor re-run, >= 2)                              |
   */
  struct AdaptiveStepOptions
  {
    double structure_step  = 0.6;
    double approach_steps  = 40.0;
    double approach_time   = 1.0;
    double contact_steps   = 80.0;
    double lookahead       = 3.0;
    double tail            = 0.02;
    bool   error_estimate  = true;
    double estimate_factor = 4.0;
  };

  /// What a variable-step run did: its steps and its estimated errors.
  struct AdaptiveStepReport
  {
    double dt_large            = 0.0; ///< step while every contact is open and far, s
    double dt_contact          = 0.0; ///< step while a contact is active or imminent, s
    double dt_min              = 0.0; ///< smallest step taken (onset location, sample times), s
    long   steps               = 0;   ///< steps of the run (force evaluations but the first)
    long   contact_steps_taken = 0;   ///< of which at Δt_c (and the steps growing back), count
    long   estimate_steps      = 0;   ///< extra steps of the step-doubling re-runs
    int    windows             = 0;   ///< contact windows (first onset to tail end)
    /// Estimated relative errors of the peaks (step doubling over every window: the peak at
    /// Δt_c minus the peak at 2·Δt_c, relative to the run's peak; first order in Δt is assumed
    /// for the backward law velocity, so the difference itself is the estimate), largest over
    /// contacts (force) and DOFs (absolute acceleration, displacement).
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
   * isolator forces are explicit at u_n with the law velocity of the options (backward:
   * (δ_n − δ_{n−1})/h_{n−1}; second order: the three-point formula for unequal steps). The
   * recorded acceleration is (v_{n+1/2} − v_{n−1/2})/h̄_n + ü_g(t_n).
   *
   * Step choice at t_n (after the forces at t_n are evaluated):
   *  - Δt_large = safety·2/ω_structure (contacts open), reduced to divide the record's dt;
   *  - Δt_c = min(π/(contact_steps·ω_imp), safety·Δt_cr with every contact closed) while any
   *    contact is in contact, its gap is closed, or it closes within lookahead·Δt_large at its
   *    present closing rate, and for `tail` seconds after;
   *  - a step that would close a gap is shortened to end where the gap closes at the present
   *    rate (contact onset located within the step);
   *  - after a window the step grows by at most 2× per step; steps end on every history sample
   *    and at the end of the run.
   * Error estimate: every contact window (from the step that switched to Δt_c to the end of its
   * tail) is integrated again from a copy of the state at 2·Δt_c, and the change of the window's
   * peaks is reported (AdaptiveStepReport).
   *
   * The Response is that of CentralDifference with dt = Δt_large and n_steps the number of
   * steps taken; histories are sampled every output_interval.
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

    /// @throws DivergenceError, std::invalid_argument.
    Response run(const GroundMotion &motion, AdaptiveStepReport *report = nullptr) const;

    const PoundingModel &model() const { return model_; }

  private:
    PoundingModel            model_;
    CentralDifferenceOptions cdm_;
    AdaptiveStepOptions      options_;
    StabilityLimit           stability_;
    double                   dt_contact_  = 0.0;
    double                   dt_approach_ = 0.0;
  };
} // namespace kimp::lumped
