// Cost estimate and step budget of an FEM case; see fem_estimate.h.
#include "app/fem/fem_estimate.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/step_budget.h"
#include "base/logging.h"
#include "fem/impact.h"
#include "geometry/scene_ids.h"
#include "geometry/scene_layout.h"

namespace kimp::app
{
  namespace
  {
    /// The smallest spacing of sorted grid lines (infinity for fewer than two).
    double min_spacing(const std::vector<double> &lines)
    {
      double h = std::numeric_limits<double>::infinity();
      for (std::size_t i = 1; i < lines.size(); ++i)
        h = std::min(h, lines[i] - lines[i - 1]);
      return h;
    }

    double cell_size(const std::vector<double> &x, const std::vector<double> &y)
    {
      return std::min(min_spacing(x), min_spacing(y));
    }
  } // namespace

  std::string FemEstimate::text() const
  {
    return fmt::format("{:.3g} DoFs, up to {:.3g} steps of {:.3g} s over {:.3g} s = {:.3g} "
                       "DoF-steps, ~{:.2g} s, ~{:.2g} GB",
                       n_dofs,
                       n_steps,
                       dt,
                       end_time,
                       n_dofs * n_steps,
                       seconds,
                       memory / 1e9);
  }

  void FemCost::add(const std::string &name, const FemEstimate &estimate)
  {
    if (n_cases == 0 || estimate.n_dofs > largest_estimate.n_dofs)
    {
      largest          = name;
      largest_estimate = estimate;
    }
    ++n_cases;
    max_memory = std::max(max_memory, estimate.memory);
    steps += estimate.n_steps;
    seconds += estimate.seconds;
  }

  std::string FemCost::text() const
  {
    return fmt::format("{} FEM case(s), up to {:.3g} steps, ~{:.2g} s on one core ({:.2g} h), "
                       "~{:.2g} GB at most; largest {}: {}",
                       n_cases,
                       steps,
                       seconds,
                       seconds / 3600.0,
                       max_memory / 1e9,
                       largest,
                       largest_estimate.text());
  }

  void check_cost(const std::string &command,
                  const FemCost     &cost,
                  const CostLimits  &limits,
                  const bool         with_time,
                  const bool         accept)
  {
    std::vector<std::string> passed;
    if (!(cost.largest_estimate.n_dofs <= limits.max_dofs))
      passed.push_back(fmt::format("{:.3g} DoFs in {} > {:.3g}",
                                   cost.largest_estimate.n_dofs,
                                   cost.largest,
                                   limits.max_dofs));
    if (with_time && !(cost.max_memory <= limits.max_memory))
      passed.push_back(fmt::format("~{:.2g} GB > {:.2g} GB of memory",
                                   cost.max_memory / 1e9,
                                   limits.max_memory / 1e9));
    if (with_time && !(cost.seconds <= limits.max_seconds))
      passed.push_back(fmt::format("~{:.2g} h > {:.2g} h on one core",
                                   cost.seconds / 3600.0,
                                   limits.max_seconds / 3600.0));
    if (passed.empty())
      return;
    std::string which;
    for (const std::string &p : passed)
      which += (which.empty() ? "" : ", ") + p;
    if (accept)
    {
      base::logger().warn("{}: estimated cost above the limits ({}), going ahead (--accept-cost)",
                          command,
                          which);
      return;
    }
    throw std::invalid_argument(fmt::format(
      "{}: estimated cost above the limits ({}): {} (a coarser mesh.h_contact or mesh.h_max, "
      "fewer wall heights or a shorter dynamics.end_time; --accept-cost runs it anyway)",
      command,
      which,
      cost.text()));
  }

  FemCost estimate_fem_scene(const FemScene &scene)
  {
    FemCost cost;
    for (const double height : scene.wall_heights)
    {
      const std::string name = fem_case_name(height);
      FemEstimate       e    = estimate_fem_case(resolve_fem_case(scene, height, name, {}));
      if (scene.output.frame_interval > 0.0)
        e.memory += std::floor(e.end_time / scene.output.frame_interval + 1.0) * e.n_dofs *
                    fem_frame_bytes_per_dof;
      cost.add(name, e);
    }
    return cost;
  }

  FemEstimate estimate_fem_case(const FemCaseSpec &spec)
  {
    const geometry::SceneLayout    layout = geometry::SceneLayout::build(spec.geometry);
    const geometry::SceneGeometry &g      = spec.geometry;
    const fem::ImpactParameters   &p      = spec.parameters;
    const bool                     slab   = g.mesh_slab && !p.rigid_slab;
    const fem::Material           &wall   = p.materials.at(geometry::wall_material);

    // Nodes as build_scene_mesh() numbers them: a bonded soil shares the wall's back column.
    const auto nodes = [](const std::vector<double> &x, const std::vector<double> &y)
    { return static_cast<double>(x.size()) * static_cast<double>(y.size()); };
    double n_nodes = nodes(layout.wall_x, layout.wall_y);
    if (g.with_backfill)
      n_nodes += nodes(layout.soil_x, layout.soil_y) -
                 (g.interface_contact ? 0.0 : static_cast<double>(layout.soil_y.size()));
    if (g.mesh_slab)
      n_nodes += nodes(layout.slab_x, layout.slab_y);

    FemEstimate e;
    e.n_dofs   = 2.0 * n_nodes; // as the solver counts them (a rigid slab's DoF apart)
    e.end_time = p.end_time;

    // Mesh: omega = 2 c_p / h of the smallest cell of each body.
    double omega_mesh = 2.0 * fem::p_wave_speed(wall) / cell_size(layout.wall_x, layout.wall_y);
    if (g.with_backfill)
      omega_mesh = std::max(omega_mesh,
                            2.0 * fem::p_wave_speed(p.materials.at(geometry::soil_material)) /
                              cell_size(layout.soil_x, layout.soil_y));
    if (slab)
      omega_mesh = std::max(omega_mesh,
                            2.0 * fem::p_wave_speed(p.materials.at(geometry::slab_material)) /
                              cell_size(layout.slab_x, layout.slab_y));

    // Penalty: k = penalty_factor E_wall / h_contact l per node of tributary length l; a face
    // node's lumped mass is rho h_x l / 2 (h_x: the cell width behind the face), so
    // k / m = 2 penalty_factor E_wall / (h_contact rho h_x) whatever l is.
    const double h_contact    = slab ?
                                  std::min(min_spacing(layout.wall_y), min_spacing(layout.slab_y)) :
                                  min_spacing(layout.wall_y);
    const double k_per_length = p.penalty_factor * wall.youngs_modulus / h_contact;
    const double wall_h_x     = layout.wall_x.size() > 1 ? layout.wall_x[1] - layout.wall_x[0] :
                                                           std::numeric_limits<double>::infinity();
    double       k_over_m     = 2.0 * k_per_length / (wall.density * wall_h_x);
    if (slab)
    {
      const fem::Material &slab_material = p.materials.at(geometry::slab_material);
      const std::size_t    n             = layout.slab_x.size();
      const double         slab_h_x      = layout.slab_x[n - 1] - layout.slab_x[n - 2];
      k_over_m += 2.0 * k_per_length / (slab_material.density * slab_h_x);
    }
    else if (p.slab_mass > 0.0)
      k_over_m += k_per_length * h_contact / p.slab_mass;
    // penalty_step_ratio: the penalty whose omega is r omega_mesh (the factor above ignored).
    const double omega_penalty =
      p.penalty_step_ratio > 0.0 ?
        fem::penalty_omega_ratio_for_step(p.penalty_step_ratio, p.contact_damping_ratio) *
          omega_mesh :
        std::sqrt(k_over_m);

    const double omega     = std::hypot(omega_mesh, omega_penalty);
    const double xi        = p.contact_damping_ratio * omega_penalty / omega;
    const double dt_stable = 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
    const bool   implicit  = p.integrator == fem::ImpactParameters::Integrator::implicit_newmark;
    // Contact sub-cycling: the mesh's step (the sub-steps cost little: the contact alone).
    const double limit =
      p.contact_subcycles != 1 && !implicit ?
        fem::subcycled_step(omega_mesh, omega_penalty, dt_stable, p.contact_subcycles).limit :
        dt_stable;
    if (p.dt > 0.0)
      e.dt = p.dt;
    else if (implicit)
      e.dt = p.implicit_options.dt_factor * dt_stable;
    else if (p.explicit_options.dt_over_limit > 0.0)
      e.dt = p.explicit_options.dt_over_limit * limit;
    else
      e.dt = p.explicit_options.cfl_safety * limit;
    e.n_steps = std::ceil(e.end_time / e.dt);

    const double per_dof_step = implicit ? fem_implicit_seconds_per_dof_step :
                                has_inelastic_materials(spec.scene) ?
                                           fem_inelastic_seconds_per_dof_step :
                                           fem_explicit_seconds_per_dof_step;
    e.seconds                 = e.n_dofs * e.n_steps * per_dof_step;
    e.memory =
      fem_fixed_bytes + e.n_dofs * (implicit ? fem_implicit_bytes_per_dof : fem_bytes_per_dof);
    return e;
  }

  void check_fem_budget(const std::string &name, const FemEstimate &estimate, double max_steps)
  {
    check_step_budget(name,
                      estimate.text(),
                      estimate.n_steps,
                      max_steps,
                      "dynamics.max_steps = {:.3g} (a coarser mesh.h_contact, a shorter "
                      "dynamics.end_time, or a larger dynamics.max_steps if the run is intended)");
  }
} // namespace kimp::app
