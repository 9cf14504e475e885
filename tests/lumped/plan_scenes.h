// Scenes of the tests of the 3D (plan) lumped engine: the thesis' isolated building as rigid
// diaphragms, rotated by an angle, with four quarter isolators at the corners of a square and a
// moat at equal gaps; the planar scene it must reproduce; a moat wall with a re-entrant corner.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/plan/plan_central_difference.h"
#include "lumped/structure/pounding_model.h"
#include "lumped/structure/shear_building.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::testing
{
  /// Plan width (and depth) of the slabs of the reference building, m.
  inline constexpr double plan_width = 20.0;

  /**
   * A rectangular moat wall about the origin, half extents `half_x` and `half_y` (m), with a
   * buttress in its +x face: its tip, a re-entrant corner of the wall, at (tip_x, 0), its flanks
   * meeting the face at y = ±1 m.
   */
  inline lumped::plan::Polygon notched_wall(double half_x, double half_y, double tip_x)
  {
    using lumped::plan::Point;
    return {Point(-half_x, -half_y),
            Point(half_x, -half_y),
            Point(half_x, -1.0),
            Point(tip_x, 0.0),
            Point(half_x, 1.0),
            Point(half_x, half_y),
            Point(-half_x, half_y)};
  }

  /**
   * The thesis' 4-storey isolated building (reference_isolated_building(4)) in plan, turned by
   * `angle` (rad) about the origin: square slabs of plan_width, storeys of 600 MN/m in every
   * direction at the centre with k_θ = 600 MN/m · plan_width²/6, the bilinear isolator split in
   * four at the corners of a 16 m square. Without eccentricity every direction is that building.
   */
  inline lumped::plan::PlanBuilding plan_reference_building(const double angle = 0.0)
  {
    using namespace lumped::plan;
    const lumped::ShearBuilding planar = lumped::reference_isolated_building(4);
    const auto  &bilinear = dynamic_cast<const lumped::BilinearIsolator &>(*planar.isolator);
    PlanBuilding b;
    b.name                    = "plan";
    b.damping_ratio           = planar.damping_ratio;
    b.isolation_damping_ratio = planar.isolation_damping_ratio;
    Polygon outline           = rectangle(plan_width, plan_width);
    for (Point &p : outline)
      p = rotated(p, angle);
    for (const double m : planar.floor_masses)
    {
      PlanLevel l;
      l.mass    = m;
      l.outline = outline;
      b.levels.push_back(l);
    }
    for (const double k : planar.storey_stiffnesses)
      b.storeys.push_back(storey(k, k, k * plan_width * plan_width / 6.0));
    // Bilinear: K1 = 200 MN/m, K2 = 25 MN/m, Q = 0.1·W_tot formed as the planar building forms
    // it; a quarter at each corner.
    const double K1 = bilinear.initial_stiffness();
    const double K2 = 25e6;
    const double Q  = 0.1 * lumped::standard_gravity * planar.total_mass();
    auto         quarter =
      std::make_shared<PlanBilinearIsolator>(lumped::BilinearParameters{K1 / 4, K2 / 4, Q / 4});
    for (const Point &p : rectangle(16.0, 16.0))
      b.isolators.push_back({rotated(p, angle), quarter});
    return b;
  }

  /// A moat at `gap` (m) on every side of the building's base with law `law` of total stiffness
  /// `k_total` (the planar wall's, spread over the plan_width edge) and wall friction μ.
  inline lumped::plan::PlanMoat plan_moat(const lumped::plan::PlanBuilding &b,
                                          const std::string                &law,
                                          const double                      k_total,
                                          const double                      gap,
                                          const double                      mu = 0.0)
  {
    lumped::plan::PlanMoat moat;
    moat.wall     = lumped::plan::moat_around(b, {gap});
    moat.law      = contact_law(law, k_total / plan_width);
    moat.friction = mu;
    return moat;
  }

  /// Largest |a_i − b_i| over the largest |b_i| (0/0 := 0).
  /// The plan run's contact force on wall segments 3 (left, x < 0) and 1 (right) at record `k`.
  template <class PlanRun>
  std::pair<double, double> plan_side_forces(const PlanRun &p3, const std::size_t k)
  {
    double right = 0.0, left = 0.0;
    for (std::size_t q = 0; q < p3.contacts.size(); ++q)
    {
      const double f = p3.history.contact_force[k * p3.contacts.size() + q];
      if (p3.contacts[q].segment == 1)
        right += f;
      else if (p3.contacts[q].segment == 3)
        left += f;
    }
    return {left, right};
  }

  inline double relative_difference(const std::vector<double> &a, const std::vector<double> &b)
  {
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    {
      diff  = std::max(diff, std::abs(a[i] - b[i]));
      scale = std::max(scale, std::abs(b[i]));
    }
    return scale > 0.0 ? diff / scale : diff;
  }
} // namespace kimp::testing
