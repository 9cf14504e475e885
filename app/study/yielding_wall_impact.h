// A slab striking a yielding wall element, per metre of wall (docs/validation.md "Yielding wall
// element against the dynamic FEM"): the lumped counterpart of one `kimp fem` impact, to set the
// element's parameters, frozen, against the FE model.
#pragma once

#include "app/study/yielding_wall_element.h"

namespace kimp::app
{
  /// What the element gives for one impact, per metre of wall (SI).
  struct SlabImpactResult
  {
    double peak_contact_force     = 0.0; ///< N/m, the contact part's
    double slab_peak_displacement = 0.0; ///< m, from the first touch
    double time_to_stop           = 0.0; ///< s from the first touch to the slab's first stop
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
} // namespace kimp::app
