// Directionality of the response in plan: one run per angle of incidence.
#include "lumped/plan/plan_directionality.h"

#include <algorithm>
#include <cmath>

namespace kimp::lumped::plan
{
  std::vector<DirectionalPeaks> directionality(const PlanCentralDifference &integrator,
                                               const GroundMotion          &record,
                                               const std::vector<double>   &angles)
  {
    std::vector<DirectionalPeaks> out;
    for (const double angle : angles)
    {
      const PlanResponse r = integrator.run(along_angle(record, angle));
      DirectionalPeaks   p;
      p.angle                    = angle;
      p.base_corner_displacement = r.peak_corner_displacement.front();
      p.top_acceleration         = r.peak_horizontal_acceleration.back();
      for (const PlanContactResult &c : r.contacts)
        p.corner_impact_force = std::max(p.corner_impact_force, c.peak_normal_force);
      for (const double f : r.peak_wall_force)
        p.wall_force = std::max(p.wall_force, f);
      for (const double d : r.peak_corner_drift)
        p.corner_drift = std::max(p.corner_drift, d);
      for (std::size_t i = 2; i < r.peak_displacement.size(); i += 3)
        p.rotation = std::max(p.rotation, r.peak_displacement[i]);
      p.impacts = r.n_impacts();
      out.push_back(p);
    }
    return out;
  }
} // namespace kimp::lumped::plan
