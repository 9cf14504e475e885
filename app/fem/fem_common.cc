// Helpers shared by `kimp mesh`, `kimp fem` and `kimp study`; see fem_commands.h.
#include "app/fem/fem_common.h"

#include <fmt/format.h>
#include <sstream>
#include <tuple>

#include "base/errors.h"

namespace kimp::app
{
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
    c.impact_velocity               = scene.slab.velocity;
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
    c.summary.n_dofs                = static_cast<double>(s.n_dofs);
    c.summary.n_cells               = static_cast<double>(s.n_cells);
    c.summary.n_steps               = static_cast<double>(s.n_steps);
    c.summary.n_newton              = static_cast<double>(s.n_newton);
    c.summary.n_step_halvings       = static_cast<double>(s.n_step_halvings);
    c.summary.n_linear_solves       = static_cast<double>(s.n_linear_solves);
    c.summary.linear_solver_seconds = s.linear_solver_seconds;
    c.summary.linear_setup_seconds  = s.linear_setup_seconds;
    c.summary.n_ranks               = static_cast<double>(s.n_ranks);
    c.summary.dt                    = s.dt;
    c.summary.dt_stable             = s.dt_stable;
    c.summary.wall_seconds          = s.wall_seconds;
    c.summary_units                 = {{"n_newton", "1"},
                                       {"n_step_halvings", "1"},
                                       {"n_linear_solves", "1"},
                                       {"linear_solver_seconds", "s"},
                                       {"linear_setup_seconds", "s"},
                                       {"n_ranks", "1"}};
    c.labels                        = {{"integrator",
                 scene.dynamics.integrator == fem::ImpactParameters::Integrator::implicit_newmark ?
                                          "implicit" :
                                          "explicit"},
                                       {"slab", scene.slab.rigid ? "rigid" : "elastic"},
                                       {"mesh_level", std::to_string(scene.mesh.level)},
                                       {"penalty_factor", fmt::format("{}", scene.contact.penalty_factor)},
                                       {"stopped_on", s.separated ? "separation" : "end_time"},
                                       {"geostatic", geostatic_enabled(scene) ? "on" : "off"},
                                       {"interface",
                 scene.interface.model == FemInterface::Model::contact ? "contact" : "bonded"}};
    if (scene.boundary.far == FemBoundary::Far::absorbing)
    {
      c.summary.set("radiated_energy", s.radiated_energy);
      c.summary_units["radiated_energy"] = "J/m";
      c.labels["far_boundary"]           = "absorbing";
    }
    // After the impact (fem::ImpactSummary): dissipation, the COR it implies, the wall's state.
    c.summary.set("plastic_dissipation", s.plastic_dissipation);
    c.summary.set("damage_dissipation", s.damage_dissipation);
    c.summary.set("contact_dissipation", s.contact_dissipation);
    if (has_inelastic_materials(scene))
    {
      // Where the material dissipation happened: plastic work of soil, bars and concrete, and
      // the concrete's damage, per body.
      const char *body[3] = {"slab", "wall", "soil"};
      for (unsigned int b = 0; b < 3; ++b)
        for (const auto &[what, value] :
             {std::pair<const char *, double>{"plastic", s.plastic_dissipation_by_body[b]},
              {"damage", s.damage_dissipation_by_body[b]}})
        {
          const std::string key = fmt::format("{}_dissipation_{}", what, body[b]);
          c.summary.set(key, value);
          c.summary_units[key] = "J/m";
        }
    }
    c.summary.set("residual_energy", s.residual_energy);
    c.summary.set("dissipation_cor", s.dissipation_cor);
    c.summary.set("permanent_indentation", s.permanent_indentation);
    c.summary.set("wall_residual_displacement", s.wall_residual_displacement);
    if (geostatic_enabled(scene))
    {
      // The static step before the impact (fem::ImpactSummary geostatic_*).
      for (const auto &[key, value, units] :
           {std::tuple<const char *, double, const char *>{"geostatic_weight",
                                                           s.geostatic_weight,
                                                           "N/m"},
            {"geostatic_residual", s.geostatic_residual, "1"},
            {"geostatic_iterations", static_cast<double>(s.geostatic_iterations), "1"},
            {"geostatic_plastic_dissipation", s.geostatic_plastic_dissipation, "J/m"},
            {"geostatic_wall_displacement", s.geostatic_wall_displacement, "m"}})
      {
        c.summary.set(key, value);
        c.summary_units[key] = units;
      }
    }
    if (scene.interface.model == FemInterface::Model::contact)
    {
      c.summary.set("interface_normal_force", s.interface_normal_force);
      c.summary_units["interface_normal_force"] = "N/m";
      c.summary.set("friction_dissipation", s.friction_dissipation);
      c.summary_units["friction_dissipation"] = "J/m";
    }
    return c;
  }
} // namespace kimp::app
