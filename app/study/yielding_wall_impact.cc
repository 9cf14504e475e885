// A slab striking a yielding wall element: a one-DOF "building" (the slab on a negligible
// isolator) and one yielding wall, integrated by the lumped engine from the touch.
#include "app/study/yielding_wall_impact.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>

#include "app/fem/fem_quantities.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/isolators/linear_isolator.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::app
{
  namespace
  {
    /// The slab alone on a nearly free isolator (1 N/m: its period is thousands of seconds).
    lumped::ShearBuilding slab_building(double slab_mass)
    {
      lumped::ShearBuilding b;
      b.name                    = "slab";
      b.floor_masses            = {slab_mass};
      b.isolator                = std::make_shared<lumped::LinearIsolator>(1.0);
      b.damping_ratio           = 0.0;
      b.isolation_damping_ratio = 0.0;
      return b;
    }

    /// The element's wall on the right at a clear gap of 1 µm (the slab starts at the touch).
    lumped::MoatWall element_wall(const YieldingWallElement &e)
    {
      YieldingWallScene backfill = e.backfill;
      backfill.width             = 1.0; // per metre
      lumped::MoatWall wall;
      wall.gap       = 1e-6;
      wall.mass      = e.wall_mass;
      wall.sdof_mass = e.wall_mass;
      wall.yielding  = backfill.resolved();
      lumped::ForceLawSpec contact;
      contact.law       = "linear";
      contact.stiffness = e.contact_stiffness;
      wall.law          = lumped::force_law_factory(contact);
      return wall;
    }
  } // namespace

  SlabImpactResult slab_impact(const YieldingWallElement &element,
                               const double               slab_mass,
                               const double               velocity,
                               const double               duration,
                               const double               dt)
  {
    if (!(slab_mass > 0.0) || !(velocity > 0.0) || !(duration > 0.0) || !(dt > 0.0))
      throw std::invalid_argument("slab_impact: slab mass, velocity, duration and time step must "
                                  "be positive");
    lumped::PoundingScene scene;
    scene.building   = slab_building(slab_mass);
    scene.right_wall = element_wall(element);
    lumped::CentralDifferenceOptions opt;
    opt.dt               = dt;
    opt.duration         = duration;
    opt.output_interval  = dt;
    opt.initial_velocity = {velocity, 0.0};
    lumped::GroundMotion ground;
    ground.dt   = dt;
    ground.name = "none";
    ground.acceleration.assign(static_cast<std::size_t>(std::ceil(duration / dt)) + 1, 0.0);
    const lumped::CentralDifference cdm(lumped::PoundingModel(scene), opt);
    const lumped::Response          r = cdm.run(ground);

    SlabImpactResult  out;
    const std::size_t n_dofs = r.n_dofs;
    const auto       &u      = r.history.displacement;
    std::size_t       stop   = 0;
    for (std::size_t i = 1; i * n_dofs < u.size(); ++i)
      if (u[i * n_dofs] > u[stop * n_dofs])
        stop = i;
    out.slab_peak_displacement = u[stop * n_dofs];
    out.time_to_stop           = r.history.time.at(stop);
    // The first sample at 95 % of the travel, interpolated back to the crossing.
    const double target = stop_travel_fraction * out.slab_peak_displacement;
    for (std::size_t i = 1; i <= stop; ++i)
      if (u[i * n_dofs] >= target)
      {
        const double x0 = u[(i - 1) * n_dofs], x1 = u[i * n_dofs];
        const double w = x1 > x0 ? std::clamp((target - x0) / (x1 - x0), 0.0, 1.0) : 1.0;
        out.time_to_95_travel =
          r.history.time[i - 1] + w * (r.history.time[i] - r.history.time[i - 1]);
        break;
      }
    for (const lumped::ContactResult &c : r.contacts)
    {
      if (c.permanent)
      {
        out.wall_peak_displacement = c.peak_deformation;
        out.wall_residual          = c.permanent_indentation;
      }
      else
        out.peak_contact_force = std::max(out.peak_contact_force, c.peak_force);
    }
    const std::size_t last  = u.size() / n_dofs - 1;
    out.slab_velocity_after = last > 0 ? (u[last * n_dofs] - u[(last - 1) * n_dofs]) /
                                           (r.history.time[last] - r.history.time[last - 1]) :
                                         0.0;
    return out;
  }

  YieldingWallElement with_radiation_damping(const YieldingWallElement &element,
                                             const double               damping)
  {
    YieldingWallElement e        = element;
    e.radiation_damping          = damping;
    e.backfill.radiation_damping = damping;
    return e;
  }

  DashpotFit fit_radiation_damping(const YieldingWallElement &element,
                                   const double               slab_mass,
                                   const double               velocity,
                                   const double               travel,
                                   const double               largest,
                                   const double               duration,
                                   const double               dt)
  {
    if (!(travel > 0.0) || !(largest > 0.0))
      throw std::invalid_argument("fit_radiation_damping: the travel and the largest dashpot "
                                  "must be positive");
    const auto travel_with = [&](double c)
    {
      return slab_impact(with_radiation_damping(element, c), slab_mass, velocity, duration, dt)
        .slab_peak_displacement;
    };
    DashpotFit   fit;
    const double free_travel = travel_with(0.0);
    if (free_travel <= travel)
    {
      fit.travel = free_travel;
      fit.note   = fmt::format("without a dashpot the slab travels {:.4g} mm, not farther than "
                               "the target {:.4g} mm: c_r = 0",
                             free_travel * 1e3,
                             travel * 1e3);
      return fit;
    }
    const double damped_travel = travel_with(largest);
    if (damped_travel >= travel)
    {
      fit.damping = largest;
      fit.travel  = damped_travel;
      fit.note    = fmt::format("with the largest dashpot {:.4g} kN*s/m^2 the slab still travels "
                                "{:.4g} mm, farther than the target {:.4g} mm",
                             largest / 1e3,
                             damped_travel * 1e3,
                             travel * 1e3);
      return fit;
    }
    double low = 0.0, high = largest; // travel(low) > target > travel(high)
    fit.travel = damped_travel;
    for (int i = 0; i < 60 && std::abs(fit.travel - travel) > 1e-4 * travel; ++i)
    {
      fit.damping                        = 0.5 * (low + high);
      fit.travel                         = travel_with(fit.damping);
      (fit.travel > travel ? low : high) = fit.damping;
    }
    return fit;
  }
} // namespace kimp::app
