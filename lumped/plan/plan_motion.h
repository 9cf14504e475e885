// Ground motion in two horizontal components (docs/physics.md "Pounding in plan", "Ground
// motion in plan"): one record rotated to an angle of incidence, or two records (the second
// orthogonal to the first) rotated together.
#pragma once

#include <string>
#include <vector>

#include "lumped/excitation/ground_motion.h"

namespace kimp::lumped::plan
{
  /// ü_g,x(t_i) and ü_g,y(t_i), t_i = i·dt, m/s²; piecewise linear between samples, zero after
  /// the last (as lumped::GroundMotion).
  struct PlanGroundMotion
  {
    double              dt = 0.0;
    std::vector<double> x;
    std::vector<double> y;
    std::string         name;

    double duration() const { return dt * static_cast<double>(x.size()); }
  };

  /**
   * One record along the direction at `angle` (rad, counter-clockwise from x):
   * ü_x = ü·cos θ, ü_y = ü·sin θ (angle 0 gives exactly the record along x and zero along y).
   * @throws std::invalid_argument for an invalid record or a non-finite angle.
   */
  PlanGroundMotion along_angle(const GroundMotion &record, double angle);

  /**
   * Two records, `first` along the direction at `angle` and `second` along angle + 90°:
   * ü_x = ü_1·cos θ − ü_2·sin θ, ü_y = ü_1·sin θ + ü_2·cos θ. The shorter record is padded
   * with zeros.
   * @throws std::invalid_argument for an invalid record, a missing second component (empty),
   *         different sampling intervals (both named) or a non-finite angle.
   */
  PlanGroundMotion
  two_components(const GroundMotion &first, const GroundMotion &second, double angle);

  /// Check a two-component record (dt > 0, equal non-empty lengths, finite samples).
  void validate(const PlanGroundMotion &motion);
} // namespace kimp::lumped::plan
