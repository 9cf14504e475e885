// ImpactProblem explicit time loop: leap-frog with the Gauss-Lobatto lumped mass (Belytschko et
// al., Nonlinear Finite Elements, 2014, §6.2); the recording it shares with the implicit loop is in
// recording.cc.
#include <algorithm>
#include <cmath>

#include <deal.II/base/mpi.h>

#include "fem/impact/impact_problem.h"
#include "fem/impact/peak_frames.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  void ImpactProblem::run_explicit()
  {
    Vec u(locally_owned, comm), v_half(locally_owned, comm), v_n(locally_owned, comm);
    Vec Ku(locally_owned, comm), a(locally_owned, comm);
    if (geostatic_on)
      u = geostatic_u;
    // Initial velocity: the slab moves at +initial_velocity in x.
    double u_r = 0, v_r = prm.initial_velocity;
    set_initial_slab_velocity(v_half);
    v_n = v_half;

    const LoopSteps steps      = loop_steps();
    bool            started    = false;
    unsigned long   zero_since = 0;
    PeakFrames      frame_due(steps.frame_every);
    unsigned long   n = 0;
    separated_flag    = false;
    // Contact sub-cycling: the contact nodes' state lives in `sub` (v_half holds their
    // velocity at t_n - dt_contact / 2).
    const bool    subcycled = contact_substeps > 1;
    SubcycleState sub;
    if (subcycled)
      contact_inverse_mass = gather_compact(inverse_mass, prm.rigid_slab ? 1 / prm.slab_mass : 0);
    for (;; ++n)
    {
      const double t = n * dt;
      // Contact at (u_n, v_{n-1/2}): the damping lags half a step (sub-step), which keeps the
      // scheme explicit.
      auto [cu, cv]                = gather_compact(u, u_r, v_half, v_r);
      const auto                ev = contact->evaluate(cu, cv);
      const std::vector<double> fc = padded_force(ev, cu.size());

      // The points' energies are read at the sampled steps only (record()).
      point_energy_needed = n % sample_every == 0;
      internal_force(u, Ku);
      point_energy_needed = true;
      // Every evaluated point's trial history was rewritten: swapping commits it without a copy.
      if (!linear_laws)
        qp_history.commit_by_swap();
      if (interface)
        interface->commit();
      a.equ(-1.0, Ku);
      if (!subcycled)
        scatter_add(fc, a);
      a.scale(inverse_mass);
      if (absorbing)
        apply_dashpots_explicit(n == 0, u, v_half, a);
      if (slab_alpha > 0)
        apply_slab_damping(n == 0, v_half, a);
      const double a_r = prm.rigid_slab && !subcycled ? fc.back() / prm.slab_mass : 0;

      // v_{n+1/2} = v_{n-1/2} + dt a_n (half a step at the start); v_n = mean of the two.
      const double h = n == 0 ? 0.5 * dt : dt;
      v_n            = v_half;
      if (n > 0)
        v_n.add(0.5 * dt, a);
      v_half.add(h, a);
      double v_r_n = v_r + (n > 0 ? 0.5 * dt * a_r : 0.0);
      v_r += h * a_r;
      double contact_force = ev.total_force;
      if (subcycled)
      {
        sub.u = cu;
        sub.v = std::move(cv);
        sub.a = gather_compact(a, 0.0);
        write_compact(subcycled_velocity_at_step(n, fc, sub), v_n, v_r_n);
      }

      record({n, t, u, v_n, Ku, u_r, v_r_n, ev, cu, subcycled});
      if (subcycled)
      {
        // After record(): the sub-steps' contact work runs past t_n.
        advance_subcycled_contact(n, ev, sub);
        contact_force = raw_force.back(); // the step's mean over its sub-steps
      }
      if (prm.progress && n % prm.progress_interval == 0 && n > 0 &&
          Utilities::MPI::this_mpi_process(comm) == 0)
        prm.progress(t, prm.end_time);
      if (steps.write_vtu && n % steps.vtu_every == 0)
        output_results(t, u, v_n, fc);
      if (frame_due(n, t, contact_force))
        record_frame(t, u, ev);

      if (contact_force > 0)
      {
        started    = true;
        zero_since = n + 1;
      }
      // Over once the force stayed zero for the hold time, the slab no longer comes in and wall
      // and soil have given back their energy or the slab rebounds
      // (ImpactParameters::stored_energy_fraction).
      if (started && n + 1 - zero_since >= steps.hold_steps && contact_force == 0)
      {
        slab_v_end = slab_velocity(v_n, v_r_n);
        if (system_released_the_slab(slab_v_end))
        {
          separated_flag = true;
          break;
        }
      }
      if (n >= steps.n_max)
      {
        slab_v_end = slab_velocity(v_n, v_r_n);
        break;
      }
      u.add(dt, v_half);
      u_r += dt * v_r;
      if (subcycled)
      {
        write_compact(sub.u, u, u_r);
        write_compact(sub.v, v_half, v_r);
      }
    }
    n_steps_done = n;
    compute_residual_state(u, u_r);
  }

  std::vector<double> ImpactProblem::subcycled_velocity_at_step(unsigned long              n,
                                                                const std::vector<double> &fc,
                                                                const SubcycleState       &s) const
  {
    // The mean of the velocities either side of t_n's kick (v_0 itself at the start).
    std::vector<double> v_n = s.v;
    if (n > 0)
      for (std::size_t k = 0; k < v_n.size(); ++k)
        v_n[k] += 0.5 * (dt_contact * contact_inverse_mass[k] * fc[k] + dt * s.a[k]);
    return v_n;
  }

  void ImpactProblem::advance_subcycled_contact(unsigned long                     n,
                                                const PenaltyContact::Evaluation &ev0,
                                                SubcycleState                    &s)
  {
    // Multiple-time-step leap-frog ("impulse" form): the held acceleration a_c acts as the
    // step's impulse dt a_c at t_n, exactly as the mesh step applies it to every other node;
    // the penalty force acts at every sub-step. The first step starts with half kicks.
    const std::size_t          m          = s.u.size();
    const double               h          = dt_contact;
    const double               first_kick = n == 0 ? 0.5 : 1.0;
    double                     force_sum = 0, penetration_sum = 0;
    PenaltyContact::Evaluation ev_j;
    for (unsigned int j = 0; j < contact_substeps; ++j)
    {
      if (j > 0)
        ev_j = contact->evaluate(s.u, s.v);
      const PenaltyContact::Evaluation &ev = j == 0 ? ev0 : ev_j;
      const std::vector<double>         fc = padded_force(ev, m);
      accumulate_contact_work(fc, s.u);
      force_sum += ev.total_force;
      penetration_sum += ev.mean_penetration;
      max_penetration = std::max(max_penetration, ev.max_penetration);
      for (std::size_t k = 0; k < m; ++k)
      {
        const double a_c = contact_inverse_mass[k] * fc[k];
        s.v[k] += j == 0 ? first_kick * (h * a_c + dt * s.a[k]) : h * a_c;
        s.u[k] += h * s.v[k];
      }
    }
    // The step's raw force is the mean of its sub-steps': sum(raw force) dt is the impulse the
    // sub-steps delivered.
    raw_force.push_back(force_sum / contact_substeps);
    penetration_integral += penetration_sum * h;
  }

  void ImpactProblem::write_compact(const std::vector<double> &compact, Vec &v, double &rigid) const
  {
    for (std::size_t k = 0; k < contact_dofs.size(); ++k)
      if (locally_owned.is_element(contact_dofs[k]))
        v(contact_dofs[k]) = compact[k];
    v.compress(VectorOperation::insert);
    if (prm.rigid_slab)
      rigid = compact.back();
  }
} // namespace kimp::fem::internal
