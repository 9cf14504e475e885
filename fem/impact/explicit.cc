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
    for (;; ++n)
    {
      const double t = n * dt;
      // Contact at (u_n, v_{n-1/2}): the damping lags half a step, which keeps the scheme
      // explicit.
      const auto [cu, cv]          = gather_compact(u, u_r, v_half, v_r);
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
      scatter_add(fc, a);
      a.scale(inverse_mass);
      if (absorbing)
        apply_dashpots_explicit(n == 0, v_half, a);
      const double a_r = prm.rigid_slab ? fc.back() / prm.slab_mass : 0;

      // v_{n+1/2} = v_{n-1/2} + dt a_n (half a step at the start); v_n = mean of the two.
      const double h = n == 0 ? 0.5 * dt : dt;
      v_n            = v_half;
      if (n > 0)
        v_n.add(0.5 * dt, a);
      v_half.add(h, a);
      const double v_r_n = v_r + (n > 0 ? 0.5 * dt * a_r : 0.0);
      v_r += h * a_r;

      record({n, t, u, v_n, Ku, u_r, v_r_n, ev, cu});
      if (prm.progress && n % prm.progress_interval == 0 && n > 0 &&
          Utilities::MPI::this_mpi_process(comm) == 0)
        prm.progress(t, prm.end_time);
      if (steps.write_vtu && n % steps.vtu_every == 0)
        output_results(t, u, v_n, fc);
      if (frame_due(n, t, ev.total_force))
        record_frame(t, u, ev);

      if (ev.total_force > 0)
      {
        started    = true;
        zero_since = n + 1;
      }
      // Over once the force stayed zero for the hold time, the slab no longer comes in and wall
      // and soil have given back their energy or the slab rebounds
      // (ImpactParameters::stored_energy_fraction).
      if (started && n + 1 - zero_since >= steps.hold_steps && ev.total_force == 0)
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
    }
    n_steps_done = n;
    compute_residual_state(u, u_r);
  }
} // namespace kimp::fem::internal
