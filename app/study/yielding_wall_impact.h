// A slab striking a yielding wall element, per metre of wall (docs/validation.md "Yielding wall
// element against the dynamic FEM"): the lumped counterpart of one `kimp fem` impact, to set the
// element's parameters, frozen, against the FE model.
#pragma once

#include <string>

#include "app/study/yielding_wall_element.h"

namespace kimp::app
{
  /// What the element gives for one impact, per metre of wall (SI).
  struct SlabImpactResult
  {
    double peak_contact_force     = 0.0; ///< N/m, the contact part's
    double slab_peak_displacement = 0.0; ///< m, from the first touch
    double time_to_stop           = 0.0; ///< s from the first touch to the slab's first stop
    /// s from the first touch to 95 % of the slab's largest travel (the FEM's
    /// time_to_95_travel, app/fem/fem_quantities.h stop_travel_fraction)
    double time_to_95_travel      = 0.0;
    double wall_peak_displacement = 0.0; ///< m
    double wall_residual          = 0.0; ///< the wall's permanent set at the end, m
    double slab_velocity_after    = 0.0; ///< m/s at the end (< 0: rebounding)
  };

  /**
   * A free slab of `slab_mass` kg/m at `velocity` m/s against one yielding wall of `element`
   * (per metre, its width taken as 1 m), starting at touch, for `duration` s at the time step
   * `dt` s (central difference, lumped::CentralDifference; no ground motion).
   * @throws std::invalid_argument for a non-positive mass, velocity, duration or step.
   */
  SlabImpactResult slab_impact(const YieldingWallElement &element,
                               double                     slab_mass,
                               double                     velocity,
                               double                     duration,
                               double                     dt);
  /// `element` with its radiation dashpot replaced by `damping` N·s/m per m (the element's and
  /// its wall-and-backfill part's).
  YieldingWallElement with_radiation_damping(const YieldingWallElement &element, double damping);

  /// The dashpot fitted to one impact's slab travel (fit_radiation_damping()).
  struct DashpotFit
  {
    double damping = 0.0; ///< c_r, N·s/m per m
    double travel  = 0.0; ///< the element's slab travel with it, m
    /// "" when the travel is matched; else why not (the target is outside the travels of
    /// c_r = 0 and of the largest c_r, which is then returned).
    std::string note;
  };

  /**
   * The radiation dashpot c_r in [0, `largest`] N·s/m per m with which the slab of `slab_mass`
   * kg/m striking `element` at `velocity` m/s travels `travel` m (the dynamic FEM's slab travel),
   * by bisection to 1e-4 of `travel` (the travel falls as c_r grows); every other parameter of
   * `element` frozen. slab_impact() runs each trial for `duration` s at `dt` s.
   * @throws std::invalid_argument for a non-positive travel or largest c_r.
   */
  DashpotFit fit_radiation_damping(const YieldingWallElement &element,
                                   double                     slab_mass,
                                   double                     velocity,
                                   double                     travel,
                                   double                     largest,
                                   double                     duration,
                                   double                     dt);
} // namespace kimp::app
