// Directionality of the response in plan (docs/physics.md "Pounding in plan"): one record rotated
// to each angle of incidence, the peaks that matter for the moat against the angle.
#pragma once

#include <vector>

#include "lumped/plan/plan_central_difference.h"

namespace kimp::lumped::plan
{
  /// The peaks of one run at one angle of incidence.
  struct DirectionalPeaks
  {
    double      angle                    = 0.0; ///< rad, counter-clockwise from x
    double      base_corner_displacement = 0.0; ///< largest corner displacement of level 0, m
    double      corner_impact_force      = 0.0; ///< largest w·F of any contact point, N
    double      wall_force               = 0.0; ///< largest force on one wall face, N
    double      top_acceleration         = 0.0; ///< horizontal, top level's centre of mass, m/s²
    double      corner_drift             = 0.0; ///< largest corner drift of any storey, m
    double      rotation                 = 0.0; ///< largest |θ| of any level, rad
    std::size_t impacts                  = 0;
  };

  /**
   * Run `integrator` (its model and options) under `record` turned to each of `angles` (rad;
   * along_angle()) and collect the peaks.
   * @throws what PlanCentralDifference::run throws, and std::invalid_argument for a non-finite
   *         angle.
   */
  std::vector<DirectionalPeaks> directionality(const PlanCentralDifference &integrator,
                                               const GroundMotion          &record,
                                               const std::vector<double>   &angles);
} // namespace kimp::lumped::plan
