// Helpers shared by `kimp mesh`, `kimp fem` and `kimp study`; see fem_commands.h.
#include "app/fem/fem_common.h"

#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <tuple>

#include "app/fem/fem_quantities.h"
#include "base/errors.h"

namespace kimp::app
{
  LogLines::int_type LogLines::overflow(int_type c)
  {
    if (traits_type::eq_int_type(c, traits_type::eof()))
      return traits_type::not_eof(c);
    if (traits_type::to_char_type(c) != '\n')
    {
      line_ += traits_type::to_char_type(c);
      return c;
    }
    const std::string line = std::move(line_);
    line_.clear();
    sink_(line);
    return c;
  }

  using namespace kimp::io;
  std::string error_message(const std::exception &error)
  {
    const std::string text   = error.what();
    const std::string marker = "Additional information:";
    const std::size_t begin  = text.find(marker);
    if (begin == std::string::npos)
      return base::error_text(error); // one line; "out of memory" rather than std::bad_alloc
    // deal.II frames its message with a line of dashes and may append a stack trace.
    std::string       rest = text.substr(begin + marker.size());
    const std::size_t end  = rest.find("\n----");
    if (end != std::string::npos)
      rest.resize(end);
    const std::size_t trace = rest.find("Stacktrace:");
    if (trace != std::string::npos)
      rest.resize(trace);
    std::istringstream words(rest);
    std::string        word, message;
    while (words >> word)
      message += (message.empty() ? "" : " ") + word;
    return message;
  }

  FemScene single_height_scene(const FemScene &scene, double wall_height)
  {
    FemScene single     = scene;
    single.wall_heights = {wall_height};
    return single;
  }

  FemCaseSpec resolve_fem_case(const FemScene              &scene,
                               double                       wall_height,
                               const std::string           &name,
                               const std::filesystem::path &mesh_file,
                               const std::filesystem::path &vtu_dir)
  {
    FemCaseSpec spec;
    spec.name        = name;
    spec.wall_height = wall_height;
    spec.scene       = single_height_scene(scene, wall_height);
    spec.geometry    = scene_geometry(spec.scene, wall_height);
    spec.mesh_file   = mesh_file;
    spec.parameters  = impact_parameters(spec.scene, wall_height, mesh_file, vtu_dir);
    return spec;
  }

  FemCase to_fem_case(const FemCaseSpec &spec, const fem::ImpactResult &result)
  {
    const std::string        &name   = spec.name;
    const double              height = spec.wall_height;
    const FemScene           &scene  = spec.scene;
    const fem::ImpactHistory &h      = result.history;
    const fem::ImpactSummary &s      = result.summary;
    FemCase                   c;
    c.name                          = name;
    c.wall_height                   = height;
    c.slab_mass                     = slab_mass(scene);
    c.impact_velocity               = scene.solver.initial_velocity;
    c.time                          = h.time;
    c.contact_force                 = h.contact_force;
    c.smoothed_contact_force        = h.smoothed_contact_force;
    c.indentation                   = h.indentation;
    c.slab_displacement             = h.slab_displacement;
    c.slab_velocity                 = h.slab_velocity;
    c.wall_displacement             = h.wall_displacement;
    c.summary.peak_force            = s.peak_force;
    c.summary.peak_force_raw        = s.peak_force_raw;
    c.summary.contact_start         = s.contact_start;
    c.summary.contact_duration      = s.contact_duration;
    c.summary.impulse               = s.impulse;
    c.summary.rebound_velocity      = s.rebound_velocity;
    c.summary.apparent_cor          = s.apparent_cor;
    c.summary.energy_error          = s.energy_error;
    c.summary.smoothing_window      = s.smoothing_window;
    c.summary.max_penetration       = s.max_penetration;
    c.summary.mean_penetration      = s.mean_penetration;
    c.summary.initial_gap           = s.initial_gap;
    c.summary.penalty_stiffness     = s.penalty_stiffness;
    c.summary.mesh_level            = scene.mesh_level;
    c.summary.penalty_factor        = s.penalty_factor;
    c.summary.contact_subcycles     = static_cast<std::int64_t>(s.contact_subcycles);
    c.summary.n_dofs                = static_cast<std::int64_t>(s.n_dofs);
    c.summary.n_cells               = static_cast<std::int64_t>(s.n_cells);
    c.summary.n_steps               = static_cast<std::int64_t>(s.n_steps);
    c.summary.n_newton              = static_cast<std::int64_t>(s.n_newton);
    c.summary.n_step_halvings       = static_cast<std::int64_t>(s.n_step_halvings);
    c.summary.n_linear_solves       = static_cast<std::int64_t>(s.n_linear_solves);
    c.summary.linear_solver_seconds = s.linear_solver_seconds;
    c.summary.linear_setup_seconds  = s.linear_setup_seconds;
    c.summary.n_ranks               = static_cast<std::int64_t>(s.n_ranks);
    c.summary.dt                    = s.dt;
    c.summary.dt_stable             = s.dt_stable;
    c.summary.wall_time             = s.wall_seconds;
    c.labels                        = {{"integrator",
                 scene.solver.integrator == fem::ImpactParameters::Integrator::implicit_newmark ?
                                          "implicit" :
                                          "explicit"},
                                       {"slab", scene.solver.rigid_slab ? "rigid" : "elastic"},
                                       {"stopped_on", s.separated ? "separation" : "end_time"},
                                       {"geostatic", geostatic_enabled(scene) ? "on" : "off"},
                                       {"interface",
                 scene.interface.model == FemInterface::Model::contact ? "contact" : "bonded"}};
    if (scene.solver.slab_damping_ratio > 0)
      c.summary.slab_damping_dissipation = s.slab_damping_dissipation;
    if (scene.boundary.far != FemBoundary::Far::rollers)
    {
      c.summary.radiated_energy = s.radiated_energy;
      c.labels["far_boundary"]  = far_boundary_name(scene.boundary.far);
    }
    if (scene.boundary.far == FemBoundary::Far::viscous_spring)
      c.summary.boundary_spring_energy = s.boundary_spring_energy;
    // After the impact (fem::ImpactSummary): dissipation, the COR it implies, the wall's state.
    FemSummary &sum                = c.summary;
    sum.plastic_dissipation        = s.plastic_dissipation;
    sum.damage_dissipation         = s.damage_dissipation;
    sum.contact_dissipation        = s.contact_dissipation;
    sum.residual_energy            = s.residual_energy;
    sum.stored_energy_share        = s.stored_energy_share;
    sum.dissipation_cor            = s.dissipation_cor;
    sum.permanent_indentation      = s.permanent_indentation;
    sum.wall_residual_displacement = s.wall_residual_displacement;
    if (has_inelastic_materials(scene))
    {
      // Where the material dissipation happened: plastic work of soil, bars and concrete, and
      // the concrete's damage, per body (0 slab, 1 wall, 2 soil).
      sum.plastic_dissipation_slab = s.plastic_dissipation_by_body[0];
      sum.plastic_dissipation_wall = s.plastic_dissipation_by_body[1];
      sum.plastic_dissipation_soil = s.plastic_dissipation_by_body[2];
      sum.damage_dissipation_slab  = s.damage_dissipation_by_body[0];
      sum.damage_dissipation_wall  = s.damage_dissipation_by_body[1];
      sum.damage_dissipation_soil  = s.damage_dissipation_by_body[2];
    }
    if (geostatic_enabled(scene))
    {
      // The static step before the impact (fem::ImpactSummary geostatic_*).
      sum.geostatic_weight              = s.geostatic_weight;
      sum.geostatic_residual            = s.geostatic_residual;
      sum.geostatic_iterations          = static_cast<std::int64_t>(s.geostatic_iterations);
      sum.geostatic_plastic_dissipation = s.geostatic_plastic_dissipation;
      sum.geostatic_wall_displacement   = s.geostatic_wall_displacement;
    }
    if (scene.interface.model == FemInterface::Model::contact)
    {
      sum.interface_normal_force = s.interface_normal_force;
      sum.friction_dissipation   = s.friction_dissipation;
    }
    // The engineer's quantities of the record and its impulse-momentum check.
    if (std::isfinite(s.max_bar_strain_ratio))
    {
      sum.max_bar_strain_ratio  = s.max_bar_strain_ratio;
      sum.max_bar_strain_height = s.max_bar_strain_height;
      c.labels["bars_yield"]    = s.max_bar_strain_ratio >= 1.0 ? "yes" : "no";
    }
    if (std::isfinite(s.max_bar_gauge_strain_ratio))
    {
      sum.max_bar_gauge_strain_ratio    = s.max_bar_gauge_strain_ratio;
      sum.max_bar_gauge_strain_height   = s.max_bar_gauge_strain_height;
      sum.bar_gauge_length              = s.bar_gauge_length;
      c.labels["bars_yield_over_gauge"] = s.max_bar_gauge_strain_ratio >= 1.0 ? "yes" : "no";
    }
    set_engineer_quantities(c);
    c.labels["impulse_momentum"] = impulse_momentum_status(c);
    return c;
  }
} // namespace kimp::app
