// FEM scene validation and its translation to geometry/ and fem/ parameters; see fem_scene.h.
#include "app/fem/fem_scene.h"

#include <cmath>
#include <fmt/format.h>
#include <set>
#include <stdexcept>
#include <utility>

#include "fem/inelastic_laws.h"
#include "fem/material_law.h"
#include "geometry/scene_ids.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::io;
  namespace
  {
    std::string indexed(std::string_view key, std::size_t index)
    {
      return fmt::format("{}[{}]", key, index);
    }

    /// A text that must be "auto" or a time > 0 (fem/ reads 0 as automatic: not accepted).
    void validate_auto_time(const std::string &text, std::string_view key, ValidationContext &ctx)
    {
      const std::string expected = "must be 'auto' or a time > 0 like '2e-6 s'";
      try
      {
        const std::optional<double> value = parse_auto_time(text);
        if (value)
          ctx.check(*value > 0, std::string(key), "'" + text + "'", expected);
      }
      catch (const UnitError &error)
      {
        ctx.fail(std::string(key), "'" + text + "'", expected + " (" + error.what() + ")");
      }
    }

    /// Geometry rules that involve the wall height of case `i`.
    void validate_height(const FemScene &s, std::size_t i, ValidationContext &ctx)
    {
      const double      height     = s.wall_heights[i];
      const std::string height_key = indexed("wall_heights", i);
      const std::string height_text =
        fmt::format("{} = {}", height_key, format_quantity(height, "m"));
      if (!(height > 0)) // its range is refused
        return;

      const geometry::SceneGeometry &g = s.geometry;
      if (g.backfill_height)
        ctx.check(*g.backfill_height <= height,
                  "geometry.backfill_height",
                  format_quantity(*g.backfill_height, "m"),
                  "must be <= " + height_text);
      if (g.slab_top)
      {
        ctx.check(*g.slab_top <= height,
                  "geometry.slab_top",
                  format_quantity(*g.slab_top, "m"),
                  "must be <= " + height_text + " (the slab must face the wall)");
        ctx.check(*g.slab_top - g.slab_thickness >= 0,
                  "geometry.slab_top",
                  format_quantity(*g.slab_top, "m"),
                  "must be >= slab_thickness = " + format_quantity(g.slab_thickness, "m") +
                    " (the slab must be above the ground)");
      }
      else
        ctx.check(g.slab_thickness <= height,
                  "geometry.slab_thickness",
                  format_quantity(g.slab_thickness, "m"),
                  "must be <= " + height_text +
                    " (the slab top is flush with the wall top, its bottom above the ground)");
    }
  } // namespace

  std::optional<double> parse_auto_time(const std::string &text)
  {
    if (text == "auto")
      return std::nullopt;
    return parse_quantity_as(text, "s");
  }

  std::string fem_case_name(double wall_height)
  {
    std::string name = fmt::format("{:.2f}", wall_height);
    if (std::abs(std::stod(name) - wall_height) > 1e-12 * std::abs(wall_height))
      name = fmt::format("{}", wall_height);
    return "H" + name;
  }

  void validate(const FemScene &s, ValidationContext &ctx)
  {
    ctx.check(!s.wall_heights.empty(), "wall_heights", "[]", "must list at least one height");
    std::set<std::string> names;
    for (std::size_t i = 0; i < s.wall_heights.size(); ++i)
    {
      const std::string name = fem_case_name(s.wall_heights[i]);
      ctx.check(names.insert(name).second,
                indexed("wall_heights", i),
                format_quantity(s.wall_heights[i], "m"),
                "must differ from the other heights (case " + name + " appears twice)");
    }

    if (s.boundary.far != FemBoundary::Far::rollers)
      ctx.check(s.geometry.with_backfill,
                "boundary.far",
                far_boundary_name(s.boundary.far),
                "needs a backfill (geometry.with_backfill: true): the dashpots sit on the soil");
    for (const auto &[key, alpha] :
         {std::pair{"boundary.spring_normal", s.boundary.spring_normal},
          std::pair{"boundary.spring_tangential", s.boundary.spring_tangential}})
      if (alpha)
        ctx.check(s.boundary.far == FemBoundary::Far::viscous_spring,
                  key,
                  fmt::format("{:g}", *alpha),
                  "needs boundary.far: viscous_spring (the other far sides have no springs)");
    {
      const auto scope = ctx.section("materials");
      validate(s.materials, ctx);
    }
    if (s.interface.model == FemInterface::Model::contact)
    {
      ctx.check(s.solver.integrator ==
                  fem::ImpactParameters::Integrator::explicit_central_difference,
                "interface.model",
                "contact",
                "needs dynamics.integrator: explicit (the implicit Newton has no frictional "
                "interface tangent)");
      ctx.check(s.geometry.with_backfill,
                "interface.model",
                "contact",
                "needs geometry.with_backfill: true");
    }
    {
      const auto                     scope = ctx.section("mesh");
      const geometry::SceneGeometry &g     = s.geometry;
      if (g.h_contact > 0) // else its range is refused
      {
        ctx.check(g.h_max >= g.h_contact,
                  "h_max",
                  format_quantity(g.h_max, "cm"),
                  "must be >= h_contact = " + format_quantity(g.h_contact, "cm"));
        ctx.check(g.h_contact <= g.wall_thickness,
                  "h_contact",
                  format_quantity(g.h_contact, "cm"),
                  "must be <= geometry.wall_thickness = " +
                    format_quantity(g.wall_thickness, "cm"));
        ctx.check(g.h_contact <= g.slab_thickness,
                  "h_contact",
                  format_quantity(g.h_contact, "cm"),
                  "must be <= geometry.slab_thickness = " +
                    format_quantity(g.slab_thickness, "cm"));
      }
    }
    if (s.rigid_slab_mass)
      ctx.check(s.solver.rigid_slab,
                "slab.mass",
                format_quantity(*s.rigid_slab_mass, "kg/m"),
                "is only for a rigid slab (slab.rigid: true); an elastic slab's mass is "
                "rho x length x thickness");
    if (s.solver.slab_damping_ratio > 0)
    {
      const auto scope = ctx.section("slab");
      ctx.check(!s.solver.rigid_slab,
                "damping_ratio",
                fmt::format("{:g}", s.solver.slab_damping_ratio),
                "is only for an elastic slab (a rigid slab does not vibrate)");
      ctx.check(s.solver.integrator ==
                  fem::ImpactParameters::Integrator::explicit_central_difference,
                "damping_ratio",
                fmt::format("{:g}", s.solver.slab_damping_ratio),
                "needs dynamics.integrator: explicit (the implicit path has no slab damping)");
    }
    {
      const auto scope = ctx.section("contact");
      validate_auto_time(s.smoothing_window, "smoothing_window", ctx);
      ctx.check(s.solver.contact_subcycles == 1 ||
                  s.solver.integrator ==
                    fem::ImpactParameters::Integrator::explicit_central_difference,
                "subcycles",
                std::to_string(s.solver.contact_subcycles),
                "must be 1 (off) with dynamics.integrator: implicit (sub-cycling is explicit)");
    }
    {
      const auto scope = ctx.section("dynamics");
      validate_auto_time(s.dt, "dt", ctx);
    }

    for (std::size_t i = 0; i < s.wall_heights.size(); ++i)
      validate_height(s, i, ctx);
    // A refused key makes the engine's rules below repeat it: they wait for a scene without.
    if (!ctx.failures().empty())
      return;
    // The geometry's own rules are a superset of the above; any left are reported per case.
    for (std::size_t i = 0; i < s.wall_heights.size(); ++i)
    {
      try
      {
        scene_geometry(s, s.wall_heights[i]).validate();
      }
      catch (const std::invalid_argument &error)
      {
        ctx.fail(indexed("wall_heights", i),
                 format_quantity(s.wall_heights[i], "m"),
                 std::string("gives an invalid scene: ") + error.what());
      }
    }
  }

  bool has_inelastic_materials(const FemScene &scene)
  {
    return scene.materials.concrete.model != FemConcrete::Model::elastic ||
           (scene.geometry.with_backfill && scene.materials.soil.model != FemSoil::Model::elastic);
  }

  double slab_mass(const FemScene &scene)
  {
    if (scene.solver.rigid_slab && scene.rigid_slab_mass)
      return *scene.rigid_slab_mass;
    return scene.materials.concrete.density * scene.geometry.slab_length *
           scene.geometry.slab_thickness;
  }

  bool geostatic_enabled(const FemScene &scene)
  {
    switch (scene.geostatic)
    {
      case FemGeostatic::on:
        return true;
      case FemGeostatic::off:
        return false;
      case FemGeostatic::auto_:
        break;
    }
    return scene.geometry.with_backfill && (scene.materials.soil.model != FemSoil::Model::elastic ||
                                            scene.interface.model == FemInterface::Model::contact);
  }

  fem::ImpactParameters default_fem_solver()
  {
    fem::ImpactParameters solver;
    solver.log_interval = 100;
    return solver;
  }

  geometry::SceneGeometry scene_geometry(const FemScene &scene, double wall_height)
  {
    geometry::SceneGeometry g = scene.geometry;
    g.wall_height             = wall_height;
    g.mesh_slab               = !scene.solver.rigid_slab;
    g.interface_contact = g.with_backfill && scene.interface.model == FemInterface::Model::contact;
    if (!g.wall_aspect_max && scene.materials.concrete.model != FemConcrete::Model::elastic)
      g.wall_aspect_max = inelastic_wall_aspect_max;
    return geometry::refined(g, scene.mesh_level);
  }

  fem::ImpactParameters impact_parameters(const FemScene              &scene,
                                          double                       wall_height,
                                          const std::filesystem::path &mesh_file,
                                          const std::filesystem::path &vtu_dir)
  {
    const geometry::SceneGeometry g = scene_geometry(scene, wall_height);

    // The scene's solver options as written; what follows derives the rest of the case.
    fem::ImpactParameters p              = scene.solver;
    p.mesh_file                          = mesh_file;
    const FemConcrete &c                 = scene.materials.concrete;
    const auto [concrete, concrete_law]  = concrete_material(c, c.wall_reinforcement);
    const auto [soil, soil_law]          = soil_material(scene.materials.soil);
    p.materials[geometry::wall_material] = concrete;
    if (concrete_law)
      p.material_laws[geometry::wall_material] = concrete_law;
    if (!p.rigid_slab)
    {
      // The slab's own bars: a second law only when they differ from the wall's.
      const fem::ReinforcementParameters &w = c.wall_reinforcement, &r = c.slab_reinforcement;
      const bool                          same = w.ratio_x == r.ratio_x && w.ratio_y == r.ratio_y &&
                        w.yield_stress == r.yield_stress && w.youngs_modulus == r.youngs_modulus &&
                        w.hardening == r.hardening;
      p.materials[geometry::slab_material] = concrete;
      if (concrete_law)
        p.material_laws[geometry::slab_material] =
          same ? concrete_law : concrete_material(c, r).second;
    }
    if (scene.geometry.with_backfill)
    {
      p.materials[geometry::soil_material] = soil;
      if (soil_law)
        p.material_laws[geometry::soil_material] = soil_law;
    }

    if (scene.boundary.far != FemBoundary::Far::rollers && scene.geometry.with_backfill)
      p.absorbing_boundaries = {geometry::fixed_base, geometry::soil_far_side};
    if (scene.boundary.far == FemBoundary::Far::viscous_spring && scene.geometry.with_backfill)
    {
      p.boundary_spring_normal = scene.boundary.spring_normal.value_or(default_spring_normal);
      p.boundary_spring_tangential =
        scene.boundary.spring_tangential.value_or(default_spring_tangential);
    }

    p.slab_mass        = p.rigid_slab ? slab_mass(scene) : 0.0;
    p.slab_face_y0     = g.slab_bottom();
    p.slab_face_y1     = g.resolved_slab_top();
    p.slab_front_x     = g.slab_front_x();
    p.smoothing_window = parse_auto_time(scene.smoothing_window).value_or(0.0);
    p.dt               = parse_auto_time(scene.dt).value_or(0.0);
    if (scene.geometry.with_backfill && scene.interface.model == FemInterface::Model::contact)
    {
      const fem::SoilParameters sp  = soil_parameters(scene.materials.soil);
      p.wall_soil_interface.contact = true;
      p.wall_soil_interface.friction =
        scene.interface.friction.value_or(std::tan(2.0 / 3.0 * sp.friction_angle));
    }
    if (geostatic_enabled(scene))
    {
      p.geostatic.enabled = true;
      if (scene.geometry.with_backfill)
      {
        const fem::SoilParameters sp = soil_parameters(scene.materials.soil);
        p.geostatic.initial_stress_K0[geometry::soil_material] =
          scene.materials.soil.K0.value_or(1 - std::sin(sp.friction_angle));
      }
    }
    if (scene.output.vtu_interval > 0 && !vtu_dir.empty())
    {
      p.vtu_interval = scene.output.vtu_interval;
      p.vtu_dir      = vtu_dir;
    }
    return p;
  }
} // namespace kimp::app
