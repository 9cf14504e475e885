// ResponseRecorder: the run header, the energy-balance check and the end-of-run summary shared by
// the integrators (docs/physics.md §5).
#include "lumped/integrators/response_recorder.h"

#include <cmath>
#include <utility>

#include "lumped/laws/wall_backfill_law.h"

namespace kimp::lumped
{
  void ResponseRecorder::start(const PoundingModel &model,
                               const double         dt,
                               const long           n_steps,
                               const long           every)
  {
    r_           = Response{};
    r_.dt        = dt;
    r_.n_steps   = n_steps;
    r_.duration  = static_cast<double>(n_steps) * dt;
    r_.n_dofs    = model.n_dofs();
    r_.n_storeys = model.storeys().size();
    r_.peak_displacement.assign(r_.n_dofs, 0.0);
    r_.peak_absolute_acceleration.assign(r_.n_dofs, 0.0);
    r_.peak_interstorey_drift.assign(r_.n_storeys, 0.0);
    for (const ContactPair &cp : model.contacts())
    {
      ContactResult cr;
      cr.name      = cp.name;
      cr.permanent = cp.permanent;
      r_.contacts.push_back(std::move(cr));
    }
    peak_force_.assign(r_.contacts.size(), 0.0);
    failure_deformation_.clear();
    for (const ContactPair &cp : model.contacts())
      failure_deformation_.push_back(cp.failure_deformation);
    max_supplied_   = 0.0;
    max_residual_   = 0.0;
    isolator_force_ = 0.0;
    if (every > 0)
    {
      r_.history.interval = static_cast<double>(every) * dt;
      reserve_samples(static_cast<std::size_t>(n_steps / every + 1));
    }
  }

  void ResponseRecorder::reserve_samples(const std::size_t n_samples)
  {
    ResponseHistory &h = r_.history;
    h.time.reserve(n_samples);
    h.displacement.reserve(n_samples * r_.n_dofs);
    h.absolute_acceleration.reserve(n_samples * r_.n_dofs);
    h.interstorey_drift.reserve(n_samples * r_.n_storeys);
    h.contact_force.reserve(n_samples * r_.contacts.size());
    h.isolator_force.reserve(n_samples);
    h.hysteretic_energy.reserve(n_samples);
    h.energy_input.reserve(n_samples);
    h.energy_error.reserve(n_samples);
  }

  double ResponseRecorder::check_energy(const EnergyBalance &terms)
  {
    // The terms of the balance at this check point; the end-of-run fields (errors, the laws'
    // dissipation) are complete()'s, which sets them all.
    r_.energy              = terms;
    const EnergyBalance &e = r_.energy;
    // Relative to the largest energy supplied so far, so that the first steps (where every term
    // is tiny) do not dominate the maximum.
    const double residual = std::abs(e.residual_relative_error() *
                                     std::max(std::abs(e.initial) + std::abs(e.input),
                                              e.kinetic + e.strain + std::abs(e.viscous) +
                                                std::abs(e.hysteretic) + std::abs(e.contact_work)));
    max_residual_         = std::max(max_residual_, residual);
    return residual / std::max(max_supplied_, 1e-300);
  }

  Response ResponseRecorder::finish(const std::vector<std::unique_ptr<ForceLaw>> &laws) const
  {
    Response out = r_;
    complete(out, laws);
    return out;
  }

  Response ResponseRecorder::release(const std::vector<std::unique_ptr<ForceLaw>> &laws)
  {
    Response out = std::move(r_);
    r_           = Response{};
    complete(out, laws);
    return out;
  }

  void ResponseRecorder::complete(Response                                     &out,
                                  const std::vector<std::unique_ptr<ForceLaw>> &laws) const
  {
    EnergyBalance &e     = out.energy;
    e.relative_error     = e.residual_relative_error();
    e.max_relative_error = max_residual_ / std::max(max_supplied_, 1e-300);
    e.impact_dissipated  = 0.0;
    e.wall_plastic       = 0.0;
    e.wall_radiated      = 0.0;
    for (std::size_t q = 0; q < laws.size(); ++q)
    {
      ContactResult &cr        = out.contacts[q];
      cr.peak_force            = peak_force_[q];
      cr.permanent_indentation = laws[q]->permanent_indentation();
      cr.dissipated_energy     = laws[q]->dissipated_energy();
      if (const auto *wall = dynamic_cast<const WallBackfillLaw *>(laws[q].get()))
      {
        cr.plastic_work    = wall->plastic_work();
        cr.peak_resistance = wall->peak_resistance();
        cr.radiated_work   = wall->radiated_work();
        e.wall_plastic += cr.plastic_work;
        e.wall_radiated += cr.radiated_work;
      }
      else
        e.impact_dissipated += cr.dissipated_energy;
    }
  }

  void ResponseRecorder::continue_from(const ResponseRecorder &prefix)
  {
    std::vector<ContactResult> contacts   = std::move(r_.contacts);
    std::vector<double>        peak_force = std::move(peak_force_);
    std::vector<double>        failure    = std::move(failure_deformation_);
    *this                                 = prefix;
    r_.contacts                           = std::move(contacts);
    peak_force_                           = std::move(peak_force);
    failure_deformation_                  = std::move(failure);
  }
} // namespace kimp::lumped
