// Two-body collision lab, central difference method (thesis eqs. 3.9-3.11, 2.2-2.3).
#include "lumped/collision/two_body.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace kimp::lumped
{
  CollisionError::CollisionError(const std::string &what, double time, std::size_t step)
    : std::runtime_error(what)
    , time_(time)
    , step_(step)
  {
  }

  double TwoBodySetup::effective_mass() const
  {
    if (std::isinf(mass_2))
      return mass_1;
    return mass_1 * mass_2 / (mass_1 + mass_2);
  }

  void TwoBodySetup::validate() const
  {
    const auto fail = [](const std::string &name, double value, const std::string &expected)
    {
      std::ostringstream msg;
      msg << "two-body set-up: " << name << " = " << value << " (" << expected << ")";
      throw std::invalid_argument(msg.str());
    };
    if (!(std::isfinite(mass_1) && mass_1 > 0.0))
      fail("mass_1", mass_1, "must be > 0 kg and finite");
    if (!(mass_2 > 0.0))
      fail("mass_2", mass_2, "must be > 0 kg, or infinity for a rigid wall");
    if (std::isinf(mass_2) && velocity_2 != 0.0)
      fail("velocity_2", velocity_2, "must be 0 m/s against a rigid wall");
    if (!(std::isfinite(velocity_1) && std::isfinite(velocity_2) && velocity_1 > velocity_2))
      fail("velocity_1 - velocity_2", velocity_1 - velocity_2, "must be > 0 m/s: approaching");
    if (!(std::isfinite(time_step) && time_step > 0.0))
      fail("time_step", time_step, "must be > 0 s");
  }

  TwoBodyResult simulate_two_body(const ForceLaw &prototype, const TwoBodySetup &setup)
  {
    setup.validate();
    const auto law = prototype.clone();
    law->revert_to_start();

    const double dt     = setup.time_step;
    const double dt2    = dt * dt;
    const bool   wall   = std::isinf(setup.mass_2);
    const double inv_m1 = 1.0 / setup.mass_1;
    const double inv_m2 = wall ? 0.0 : 1.0 / setup.mass_2;
    const double v_rel  = setup.velocity_1 - setup.velocity_2;
    const bool   second = setup.velocity_estimate == VelocityEstimate::second_order;
    const double ke_2   = wall ? 0.0 : 0.5 * setup.mass_2 * setup.velocity_2 * setup.velocity_2;
    const double ke_0   = 0.5 * setup.mass_1 * setup.velocity_1 * setup.velocity_1 + ke_2;
    const double p_0 =
      wall ? 0.0 : setup.mass_1 * setup.velocity_1 + setup.mass_2 * setup.velocity_2;

    // Touching at t = 0 with no force, so u_{−1} = u_0 − Δt·v_0 is exact.
    double u1_n = 0.0, u1_nm1 = -dt * setup.velocity_1;
    double u2_n = 0.0, u2_nm1 = -dt * setup.velocity_2;
    double delta_nm1 = -dt * v_rel, delta_nm2 = -2.0 * dt * v_rel;

    TwoBodyResult result;
    bool          touched         = false;
    std::size_t   n_contact_steps = 0;
    for (std::size_t n = 0; n < setup.max_steps; ++n)
    {
      const double delta_n = u1_n - u2_n;
      const double rate    = second ? (3.0 * delta_n - 4.0 * delta_nm1 + delta_nm2) / (2.0 * dt) :
                                      (delta_n - delta_nm1) / dt;
      const double force   = law->set_trial(delta_n, rate).force;
      law->commit();

      const double u1_np1 = 2.0 * u1_n - u1_nm1 - dt2 * force * inv_m1;
      const double u2_np1 = 2.0 * u2_n - u2_nm1 + dt2 * force * inv_m2;
      if (!std::isfinite(u1_np1) || !std::isfinite(u2_np1))
        throw CollisionError("two-body collision: non-finite displacement with law '" +
                               law->name() + "'",
                             n * dt,
                             n);

      const bool contact = law->in_contact();
      if (contact || (touched && force != 0.0))
      {
        touched = true;
        ++n_contact_steps;
        result.peak_force      = std::max(result.peak_force, force);
        result.min_force       = std::min(result.min_force, force);
        result.max_penetration = std::max(result.max_penetration, delta_n);
      }
      if (setup.record_history && (touched || contact))
      {
        result.history.time.push_back(n * dt);
        result.history.deformation.push_back(delta_n);
        result.history.rate.push_back(rate);
        result.history.force.push_back(force);
      }
      if (touched && !contact && force == 0.0)
      {
        // No force from step n on: the half-step velocities are final.
        result.velocity_1_after = (u1_np1 - u1_n) / dt;
        result.velocity_2_after = wall ? 0.0 : (u2_np1 - u2_n) / dt;
        result.n_steps          = n + 1;
        break;
      }
      delta_nm2 = delta_nm1;
      delta_nm1 = delta_n;
      u1_nm1    = u1_n;
      u1_n      = u1_np1;
      u2_nm1    = u2_n;
      u2_n      = u2_np1;
    }
    if (result.n_steps == 0)
    {
      std::ostringstream msg;
      msg << "two-body collision with law '" << law->name() << "' did not separate within "
          << setup.max_steps << " steps of " << dt << " s";
      throw CollisionError(msg.str(), setup.max_steps * dt, setup.max_steps);
    }

    const double v1 = result.velocity_1_after, v2 = result.velocity_2_after;
    const double ke_1 = 0.5 * setup.mass_1 * v1 * v1 + (wall ? 0.0 : 0.5 * setup.mass_2 * v2 * v2);
    result.effective_cor         = (v2 - v1) / v_rel;
    result.contact_duration      = n_contact_steps * dt;
    result.impact_velocity       = law->impact_velocity();
    result.kinetic_energy_before = ke_0;
    result.kinetic_energy_loss   = ke_0 - ke_1;
    result.dissipated_energy     = law->dissipated_energy();
    result.permanent_indentation = law->permanent_indentation();
    if (!wall)
      result.momentum_error = std::abs(setup.mass_1 * v1 + setup.mass_2 * v2 - p_0) / std::abs(p_0);
    return result;
  }

  std::vector<CorTableRow> effective_cor_table(const std::vector<ForceLawSpec> &laws,
                                               const std::vector<double>       &cor_grid,
                                               const TwoBodySetup              &setup)
  {
    TwoBodySetup quiet   = setup;
    quiet.record_history = false;
    std::vector<CorTableRow> rows;
    rows.reserve(laws.size() * cor_grid.size());
    for (const ForceLawSpec &base : laws)
      for (const double cor : cor_grid)
      {
        ForceLawSpec spec       = base;
        spec.cor                = cor;
        spec.effective_mass     = setup.effective_mass();
        const auto          law = make_force_law(spec);
        const TwoBodyResult r   = simulate_two_body(*law, quiet);
        CorTableRow         row;
        row.law              = spec.law;
        row.nominal_cor      = cor;
        row.effective_cor    = r.effective_cor;
        row.relative_error   = (r.effective_cor - cor) / cor;
        row.peak_force       = r.peak_force;
        row.contact_duration = r.contact_duration;
        row.max_penetration  = r.max_penetration;
        row.energy_error =
          std::abs(r.kinetic_energy_loss - r.dissipated_energy) / r.kinetic_energy_before;
        rows.push_back(row);
      }
    return rows;
  }
} // namespace kimp::lumped
