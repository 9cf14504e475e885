// The static collapse load (M_p + M_soil)/h_c of a moat wall with its backfill.
#include "app/study/wall_capacity.h"

#include <cmath>

#include "app/fem/fem_materials.h"

namespace kimp::app
{
  WallCapacityEstimate wall_capacity_estimate(const FemScene &scene, const double wall_height)
  {
    constexpr double                    gravity  = 9.80665; // m/s², standard gravity
    const geometry::SceneGeometry       g        = scene_geometry(scene, wall_height);
    const fem::ConcreteParameters       concrete = concrete_parameters(scene.materials.concrete);
    const fem::ReinforcementParameters &bars     = scene.materials.concrete.wall_reinforcement;
    const double                        t        = g.wall_thickness;
    WallCapacityEstimate                e;
    if (bars.ratio_y > 0.0)
    {
      const double a_s = 0.5 * bars.ratio_y * t; // m² per metre: the tension half
      const double d   = 0.9 * t;
      const double a   = a_s * bars.yield_stress / (0.85 * concrete.f_cm);
      e.plastic_moment = a_s * bars.yield_stress * (d - 0.5 * a);
    }
    else
      e.plastic_moment = concrete.f_ctm * t * t / 6.0;
    const fem::SoilParameters soil = soil_parameters(scene.materials.soil);
    const double              s    = std::sin(soil.friction_angle);
    const double              k_p  = (1.0 + s) / (1.0 - s);
    const double              h_b  = g.resolved_backfill_height();
    const double              w    = soil.density * gravity;
    e.passive_force  = 0.5 * k_p * w * h_b * h_b + 2.0 * soil.cohesion * std::sqrt(k_p) * h_b;
    e.passive_moment = k_p * w * h_b * h_b * h_b / 6.0 + soil.cohesion * std::sqrt(k_p) * h_b * h_b;
    e.contact_height = g.resolved_slab_top() - 0.5 * g.slab_thickness;
    e.per_metre      = (e.plastic_moment + e.passive_moment) / e.contact_height;
    return e;
  }
} // namespace kimp::app
