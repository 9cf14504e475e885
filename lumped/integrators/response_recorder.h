// ResponseRecorder: what every integrator records into a Response, written once (run header,
// impacts, peak contact forces, energy-balance checks, history samples, end-of-run summary).
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "lumped/integrators/response.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::lumped
{
  /**
   * Records the Response of one run of an integrator (CentralDifference, NewmarkIntegrator):
   *  - start(): the run's header (Δt, N, DOFs, storeys), zeroed peaks, one ContactResult per
   *    contact and the history interval;
   *  - impact(), contact_force(): first-contact events and the peak force per contact;
   *  - supplied(), check_energy(): the energy balance at a check point, its residual relative to
   *    the largest energy supplied so far, max_t (E_0 + W_in), and the largest residual;
   *  - sample(): one row of the histories;
   *  - finish(): the Response with the laws' own results and the relative errors.
   * The peaks of u, ü + ü_g and the drifts stay with the integrator (the central difference
   * kernels keep them per vector lane); it writes them into response() directly.
   */
  class ResponseRecorder
  {
  public:
    /**
     * Starts an empty Response for `model`.
     * @param dt       time step, s
     * @param n_steps  N, the index of the last step (duration = N·Δt)
     * @param every    steps between history samples (0: no histories)
     */
    void start(const PoundingModel &model, double dt, long n_steps, long every);

    Response       &response() { return r_; }
    const Response &response() const { return r_; }

    /// Contact `c` entered contact at `t` (s) with closing rate `rate` (m/s).
    /// Not recorded for a permanent pair (ContactPair::permanent).
    void impact(const std::size_t c, const double t, const double rate)
    {
      if (!r_.contacts[c].permanent)
        r_.contacts[c].impacts.push_back({t, rate});
    }

    /// Force of contact `c` (N) at deformation δ (m) at a step at time `t` (s): the maxima of
    /// both are the peak force and deformation, the first δ beyond the pair's
    /// failure_deformation gives its failure time, and non-zero forces of impact contacts are
    /// kept at full rate with their deformation
    /// (ContactResult::pulse_time/pulse_force/pulse_deformation).
    void contact_force(const std::size_t c, const double force, const double delta, const double t)
    {
      peak_force_[c]      = std::max(peak_force_[c], force);
      ContactResult &cr   = r_.contacts[c];
      cr.peak_deformation = std::max(cr.peak_deformation, delta);
      if (delta > failure_deformation_[c] && !cr.failure_time)
        cr.failure_time = t;
      if (force != 0.0 && !cr.permanent)
      {
        cr.pulse_time.push_back(t);
        cr.pulse_force.push_back(force);
        cr.pulse_deformation.push_back(delta);
      }
    }

    /// Isolator force at a step, N (committed): its peak magnitude and the value sampled next.
    void isolator_force(const double force)
    {
      isolator_force_        = force;
      r_.peak_isolator_force = std::max(r_.peak_isolator_force, std::abs(force));
    }

    /// The energy supplied so far, E_0 + W_in (J), at a step; its maximum scales the errors.
    void supplied(const double energy) { max_supplied_ = std::max(max_supplied_, energy); }

    /// max_t (E_0 + W_in) so far, J.
    double max_supplied() const { return max_supplied_; }

    /**
     * Energy balance at a check point: stores `terms` (initial, input, kinetic, strain, viscous,
     * hysteretic, contact_work; its end-of-run fields are set at the end) in the Response and
     * keeps the largest residual.
     * @return the residual divided by max_supplied() (the history's energy_error)
     */
    double check_energy(const EnergyBalance &terms);

    /**
     * One history row at `t` (s): u(i) and a(i) for every DOF (m, m/s²), drift(s) for every
     * storey (m), the contact forces (N), E_0 + W_in (J) and the relative energy error; also the
     * last isolator_force() (N) and the hysteretic energy of the last check_energy() (J).
     */
    template <class Displacement, class Acceleration, class Drift>
    void sample(const double               t,
                Displacement             &&u,
                Acceleration             &&a,
                Drift                    &&drift,
                const std::vector<double> &contact_forces,
                const double               energy_input,
                const double               energy_error)
    {
      push_row(t,
               u,
               a,
               drift,
               contact_forces.data(),
               contact_forces.size(),
               isolator_force_,
               r_.energy.hysteretic,
               energy_input,
               energy_error);
    }

    /**
     * One history row at `t` (s) from values given explicitly (the variable-step run's rows
     * interpolated between two steps): u and a per DOF (m, m/s²), drift per storey (m), the
     * contact forces (N), the isolator force (N), the hysteretic energy (J), E_0 + W_in (J) and
     * the relative energy error.
     */
    void sample_row(const double  t,
                    const double *u,
                    const double *a,
                    const double *drift,
                    const double *contact_forces,
                    const double  isolator_force,
                    const double  hysteretic_energy,
                    const double  energy_input,
                    const double  energy_error)
    {
      push_row(
        t,
        [u](const std::size_t i) { return u[i]; },
        [a](const std::size_t i) { return a[i]; },
        [drift](const std::size_t s) { return drift[s]; },
        contact_forces,
        r_.contacts.size(),
        isolator_force,
        hysteretic_energy,
        energy_input,
        energy_error);
    }

    /// The last isolator_force(), N.
    double last_isolator_force() const { return isolator_force_; }

    /// The Response so far with the peak contact forces, each law's permanent indentation and
    /// dissipated energy (laws in contact order), the final and the maximum relative errors.
    Response finish(const std::vector<std::unique_ptr<ForceLaw>> &laws) const;
    /// finish(), the histories moved out instead of copied: the recorder is left empty.
    Response release(const std::vector<std::unique_ptr<ForceLaw>> &laws);
    /// Room for `n_samples` history rows (start() reserves N/every + 1).
    void reserve_samples(std::size_t n_samples);

    /**
     * Take over what `prefix` recorded: a run without histories of the same model without
     * contacts, stopped before any of this recorder's contacts could act (FreeRunPrefix). Its
     * energies, checks and isolator peak are copied; this recorder's contacts stay untouched.
     */
    void continue_from(const ResponseRecorder &prefix);

  private:
    void complete(Response &out, const std::vector<std::unique_ptr<ForceLaw>> &laws) const;

    /// Appends one history row (sample() and sample_row()).
    template <class Displacement, class Acceleration, class Drift>
    void push_row(const double   t,
                  Displacement &&u,
                  Acceleration &&a,
                  Drift        &&drift,
                  const double  *contact_forces,
                  std::size_t    n_contacts,
                  const double   isolator_force,
                  const double   hysteretic_energy,
                  const double   energy_input,
                  const double   energy_error)
    {
      ResponseHistory &h = r_.history;
      h.time.push_back(t);
      for (std::size_t i = 0; i < r_.n_dofs; ++i)
        h.displacement.push_back(u(i));
      for (std::size_t i = 0; i < r_.n_dofs; ++i)
        h.absolute_acceleration.push_back(a(i));
      for (std::size_t s = 0; s < r_.n_storeys; ++s)
        h.interstorey_drift.push_back(drift(s));
      h.contact_force.insert(h.contact_force.end(), contact_forces, contact_forces + n_contacts);
      h.isolator_force.push_back(isolator_force);
      h.hysteretic_energy.push_back(hysteretic_energy);
      h.energy_input.push_back(energy_input);
      h.energy_error.push_back(energy_error);
    }

    Response            r_;
    std::vector<double> peak_force_;
    std::vector<double> failure_deformation_; ///< per contact, m (ContactPair)
    double              max_supplied_   = 0.0;
    double              max_residual_   = 0.0;
    double              isolator_force_ = 0.0;
  };
} // namespace kimp::lumped
