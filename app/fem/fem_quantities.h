// The engineer's quantities of one FEM impact record (docs/physics.md "Engineer's quantities"):
// first peak force and its impulse, slab and wall displacement, energy-equivalent resistance,
// time to stop, and the impulse-momentum check of the record. Computed from the histories of an
// io::FemCase, so that they are the record's own numbers (what the files hold). Built only with
// KIMP_WITH_FEM.
#pragma once

#include <string>

#include "io/fem_results.h"

namespace kimp::app
{
  /** Largest |∫F dt / (m (v_in + v_out)) − 1| of a sound record. */
  constexpr double impulse_momentum_tolerance = 0.02;

  /**
   * The fraction of its largest travel at which the slab counts as stopped for
   * time_to_95_travel: the slab covers the last 5 % of its travel while it creeps to rest (a
   * yielding wall brings it in at under 0.1 m/s over the last 3-5 ms), so the time it reaches
   * 95 % is read while it still moves at a fraction of v_in and is insensitive to that tail
   * (docs/physics.md "Engineer's quantities").
   */
  constexpr double stop_travel_fraction = 0.95;

  /**
   * Sets the engineer's quantities of `fem_case.summary` from its histories (time, the smoothed
   * contact force, else the raw one, slab displacement and velocity, wall displacement),
   * slab_mass and impact_velocity. Each is left unset when the record cannot show it (no
   * contact, the slab never stops within the record, no mass or velocity):
   * The first contact is summary.contact_start if set (the solver's, from every step), else
   * the sample before the first non-zero force.
   * - first_peak_force, first_peak_time (after the first contact), first_peak_impulse: the
   *   first pulse of the smoothed force ends at the first local minimum after the force has
   *   fallen to half its running maximum (the whole record if it never does); its peak is that
   *   maximum, its impulse the trapezoid ∫F dt from the first contact to that minimum;
   * - max_slab_displacement: the slab's largest travel after the first contact;
   * - energy_equivalent_resistance: E_0 / max_slab_displacement, E_0 = m v_in² / 2 (the
   *   constant force that stops the slab over the same travel);
   * - max_wall_displacement: the largest displacement of the wall face in the contact range
   *   (+x, away from the slab);
   * - time_to_stop: first contact to the first sample at which the slab's velocity is <= 0
   *   (the zero-velocity instant; ill-conditioned when the slab creeps to rest);
   * - time_to_95_travel: first contact to the instant the slab's travel first reaches
   *   stop_travel_fraction of max_slab_displacement (linear interpolation between samples;
   *   unset, like time_to_stop, when the slab has not stopped within the record);
   * - impulse_momentum_ratio: the trapezoid ∫F dt over the record over m (v_in − v_end),
   *   v_end the slab's velocity at the end (−v_out for a rebound).
   */
  void set_engineer_quantities(io::FemCase &fem_case);

  /**
   * The impulse-momentum verdict of a record with impulse_momentum_ratio set: "ok" if
   * |ratio − 1| <= impulse_momentum_tolerance, else "warning: ..." naming the ratio and what
   * it means; "not checked: ..." when the ratio is not set.
   */
  std::string impulse_momentum_status(const io::FemCase &fem_case);
} // namespace kimp::app
