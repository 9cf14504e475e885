// FEM scene validation and its translation to geometry/ and fem/ parameters; see fem_scene.h.
#include "app/fem/fem_scene.h"

#include <cmath>
#include <fmt/format.h>
#include <set>
#include <stdexcept>

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
      if (!ctx.check(height > 0, height_key, format_quantity(height, "m"), "must be > 0"))
        return;

      const FemGeometry &g = s.geometry;
      if (g.backfill_height)
        ctx.check(*g.backfill_height > 0 && *g.backfill_height <= height,
                  "geometry.backfill_height",
                  format_quantity(*g.backfill_height, "m"),
                  "must be in (0, " + height_text + "]");
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

    {
      const auto         scope = ctx.section("geometry");
      const FemGeometry &g     = s.geometry;
      if (g.with_backfill)
        ctx.check(g.backfill_width > 0,
                  "backfill_width",
                  format_quantity(g.backfill_width, "m"),
                  "must be > 0");
    }
    if (s.boundary.far == FemBoundary::Far::absorbing)
      ctx.check(s.geometry.with_backfill,
                "boundary.far",
                "absorbing",
                "needs a backfill (geometry.with_backfill: true): the dashpots sit on the soil");
    {
      const auto                scope = ctx.section("materials");
      const fem::SoilParameters soil  = soil_parameters(s.materials.soil);
      // A preset sets E, nu and rho: a value given beside it would be ignored, so it is refused.
      const FemSoil &given = s.materials.soil;
      const FemSoil  defaults;
      if (given.preset != "none")
      {
        const auto refuse = [&](bool same, const char *key, const std::string &value)
        {
          ctx.check(same,
                    std::string("soil.") + key,
                    value,
                    fmt::format("cannot be set with soil.preset {} (the preset sets E = {:g} MPa, "
                                "nu = {:g}, rho = {:g} kg/m^3; c, phi and psi may override it): "
                                "remove the preset or the key",
                                given.preset,
                                soil.youngs_modulus / 1e6,
                                soil.poisson_ratio,
                                soil.density));
        };
        refuse(given.youngs_modulus == defaults.youngs_modulus,
               "E",
               format_quantity(given.youngs_modulus, "MPa"));
        refuse(given.poisson_ratio == defaults.poisson_ratio,
               "nu",
               format_quantity(given.poisson_ratio, ""));
        refuse(given.density == defaults.density, "rho", format_quantity(given.density, "kg/m^3"));
      }
      ctx.check(soil.dilatancy <= soil.friction_angle,
                "soil.psi",
                fmt::format("{:g}", soil.dilatancy * 180 / 3.14159265358979323846),
                fmt::format("must be <= phi = {:g} (degrees)",
                            soil.friction_angle * 180 / 3.14159265358979323846));
    }
    if (s.materials.concrete.model == FemConcrete::Model::elastic)
    {
      // Bars need the damage law (an elastic concrete stays linear): refused, not ignored.
      const auto scope = ctx.section("materials");
      const auto check = [&](const char *key, const FemReinforcement &r)
      {
        const bool x = r.ratio_x != 0;
        ctx.check(!x && r.ratio_y == 0,
                  std::string("concrete.") + key + (x ? ".ratio_x" : ".ratio_y"),
                  format_quantity(x ? r.ratio_x : r.ratio_y, "%"),
                  "needs materials.concrete.model: damage_plasticity (smeared bars act in the "
                  "concrete damage law only)");
      };
      check("wall_reinforcement", s.materials.concrete.wall_reinforcement);
      check("slab_reinforcement", s.materials.concrete.slab_reinforcement);
      ctx.check(s.materials.concrete.plastic_fraction == 0,
                "concrete.plastic_fraction",
                format_quantity(s.materials.concrete.plastic_fraction, ""),
                "needs materials.concrete.model: damage_plasticity");
    }
    if (s.interface.model == FemInterface::Model::contact)
    {
      ctx.check(s.dynamics.integrator ==
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
      const auto     scope = ctx.section("mesh");
      const FemMesh &m     = s.mesh;
      if (m.h_contact > 0) // else the reader reports its range
      {
        ctx.check(m.h_max >= m.h_contact,
                  "h_max",
                  format_quantity(m.h_max, "cm"),
                  "must be >= h_contact = " + format_quantity(m.h_contact, "cm"));
        ctx.check(m.h_contact <= s.geometry.wall_thickness,
                  "h_contact",
                  format_quantity(m.h_contact, "cm"),
                  "must be <= geometry.wall_thickness = " +
                    format_quantity(s.geometry.wall_thickness, "cm"));
        ctx.check(m.h_contact <= s.geometry.slab_thickness,
                  "h_contact",
                  format_quantity(m.h_contact, "cm"),
                  "must be <= geometry.slab_thickness = " +
                    format_quantity(s.geometry.slab_thickness, "cm"));
      }
    }
    {
      const auto     scope = ctx.section("slab");
      const FemSlab &slab  = s.slab;
      if (slab.mass)
        ctx.check(slab.rigid,
                  "mass",
                  format_quantity(*slab.mass, "kg/m"),
                  "is only for a rigid slab (slab.rigid: true); an elastic slab's mass is "
                  "rho x length x thickness");
    }
    {
      const auto        scope = ctx.section("contact");
      const FemContact &c     = s.contact;
      ctx.check(c.penalty_factor > 0,
                "penalty_factor",
                format_quantity(c.penalty_factor, ""),
                "must be > 0");
      ctx.check(c.contact_damping_ratio >= 0 && c.contact_damping_ratio <= 1,
                "contact_damping_ratio",
                format_quantity(c.contact_damping_ratio, ""),
                "must be in [0, 1]");
      validate_auto_time(c.smoothing_window, "smoothing_window", ctx);
    }
    {
      const auto         scope = ctx.section("dynamics");
      const FemDynamics &d     = s.dynamics;
      validate_auto_time(d.dt, "dt", ctx);
      ctx.check(d.cfl_safety > 0 && d.cfl_safety <= 1,
                "cfl_safety",
                format_quantity(d.cfl_safety, ""),
                "must be in (0, 1]");
      ctx.check(d.implicit_dt_factor > 0,
                "implicit_dt_factor",
                format_quantity(d.implicit_dt_factor, ""),
                "must be > 0");
      ctx.check(d.end_time > 0, "end_time", format_quantity(d.end_time, "ms"), "must be > 0");
      ctx.check(d.separation_hold_time >= 0,
                "separation_hold_time",
                format_quantity(d.separation_hold_time, "ms"),
                "must be >= 0");
      ctx.check(d.output_interval >= 0,
                "output_interval",
                format_quantity(d.output_interval, "ms"),
                "must be >= 0");
    }

    const std::size_t n_failures = ctx.failures().size();
    for (std::size_t i = 0; i < s.wall_heights.size(); ++i)
      validate_height(s, i, ctx);
    if (ctx.failures().size() != n_failures)
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
    if (scene.slab.rigid && scene.slab.mass)
      return *scene.slab.mass;
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

  geometry::SceneGeometry scene_geometry(const FemScene &scene, double wall_height)
  {
    const FemGeometry      &g = scene.geometry;
    geometry::SceneGeometry result;
    result.wall_height     = wall_height;
    result.wall_thickness  = g.wall_thickness;
    result.with_backfill   = g.with_backfill;
    result.backfill_width  = g.backfill_width;
    result.backfill_height = g.backfill_height;
    result.slab_length     = g.slab_length;
    result.slab_thickness  = g.slab_thickness;
    result.slab_top        = g.slab_top;
    result.gap             = g.gap;
    result.mesh_slab       = !scene.slab.rigid;
    result.interface_contact =
      g.with_backfill && scene.interface.model == FemInterface::Model::contact;
    result.h_contact = scene.mesh.h_contact;
    result.h_max     = scene.mesh.h_max;
    result.grading   = scene.mesh.grading;
    return geometry::refined(result, scene.mesh.level);
  }

  fem::SoilParameters soil_parameters(const FemSoil &s)
  {
    constexpr double    deg = 3.14159265358979323846 / 180;
    fem::SoilParameters p;
    if (s.preset != "none")
      p = fem::soil_preset(s.preset);
    else
    {
      p.youngs_modulus = s.youngs_modulus;
      p.poisson_ratio  = s.poisson_ratio;
      p.density        = s.density;
      p.friction_angle = 30 * deg;
    }
    if (s.cohesion)
      p.cohesion = *s.cohesion;
    if (s.friction_angle)
      p.friction_angle = *s.friction_angle * deg;
    if (s.dilatancy)
      p.dilatancy = *s.dilatancy * deg;
    p.tension_cutoff = s.tension_cutoff;
    return p;
  }

  FemSoil without_preset(const FemSoil &soil)
  {
    if (soil.preset == "none")
      return soil;
    constexpr double          deg = 3.14159265358979323846 / 180;
    const fem::SoilParameters p   = soil_parameters(soil);
    FemSoil                   out = soil;
    out.preset                    = "none";
    out.youngs_modulus            = p.youngs_modulus;
    out.poisson_ratio             = p.poisson_ratio;
    out.density                   = p.density;
    out.cohesion                  = p.cohesion;
    out.friction_angle            = p.friction_angle / deg;
    out.dilatancy                 = p.dilatancy / deg;
    return out;
  }

  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>> soil_material(const FemSoil &s)
  {
    const fem::SoilParameters p = soil_parameters(s);
    const fem::Material       m{p.youngs_modulus, p.poisson_ratio, p.density};
    switch (s.model)
    {
      case FemSoil::Model::mohr_coulomb:
        return {m, std::make_shared<const fem::MohrCoulombLaw>(p)};
      case FemSoil::Model::drucker_prager:
        return {m, std::make_shared<const fem::DruckerPragerLaw>(p)};
      case FemSoil::Model::elastic:
        break;
    }
    return {m, nullptr};
  }

  fem::ConcreteParameters concrete_parameters(const FemConcrete &c)
  {
    fem::ConcreteParameters p = fem::ConcreteParameters::from_f_cm(c.f_cm);
    p.poisson_ratio           = c.poisson_ratio;
    if (c.f_ctm)
      p.f_ctm = *c.f_ctm;
    if (c.fracture_energy)
      p.fracture_energy = *c.fracture_energy;
    if (c.strain_rate > 0)
      p.apply_strain_rate(c.strain_rate);
    p.plastic_fraction = c.plastic_fraction;
    return p;
  }

  fem::ReinforcementParameters reinforcement_parameters(const FemReinforcement &r)
  {
    fem::ReinforcementParameters p;
    p.ratio_x        = r.ratio_x;
    p.ratio_y        = r.ratio_y;
    p.yield_stress   = r.f_y;
    p.youngs_modulus = r.E_s;
    p.hardening      = r.hardening;
    return p;
  }

  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>>
  concrete_material(const FemConcrete &c)
  {
    return concrete_material(c, FemReinforcement{});
  }

  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>>
  concrete_material(const FemConcrete &c, const FemReinforcement &reinforcement)
  {
    if (c.model == FemConcrete::Model::elastic)
      return {fem::Material{c.youngs_modulus, c.poisson_ratio, c.density}, nullptr};
    const fem::ConcreteParameters p = concrete_parameters(c);
    return {
      fem::Material{p.youngs_modulus, p.poisson_ratio, c.density},
      std::make_shared<const fem::ConcreteDamageLaw>(p, reinforcement_parameters(reinforcement))};
  }

  fem::ImpactParameters impact_parameters(const FemScene              &scene,
                                          double                       wall_height,
                                          const std::filesystem::path &mesh_file,
                                          const std::filesystem::path &vtu_dir)
  {
    const geometry::SceneGeometry g = scene_geometry(scene, wall_height);

    fem::ImpactParameters p;
    p.mesh_file                          = mesh_file;
    const FemConcrete &c                 = scene.materials.concrete;
    const auto [concrete, concrete_law]  = concrete_material(c, c.wall_reinforcement);
    const auto [soil, soil_law]          = soil_material(scene.materials.soil);
    p.materials[geometry::wall_material] = concrete;
    if (concrete_law)
      p.material_laws[geometry::wall_material] = concrete_law;
    if (!scene.slab.rigid)
    {
      // The slab's own bars: a second law only when they differ from the wall's.
      const FemReinforcement &w = c.wall_reinforcement, &r = c.slab_reinforcement;
      const bool same = w.ratio_x == r.ratio_x && w.ratio_y == r.ratio_y && w.f_y == r.f_y &&
                        w.E_s == r.E_s && w.hardening == r.hardening;
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

    if (scene.boundary.far == FemBoundary::Far::absorbing && scene.geometry.with_backfill)
      p.absorbing_boundaries = {geometry::fixed_base, geometry::soil_far_side};

    p.rigid_slab       = scene.slab.rigid;
    p.slab_mass        = scene.slab.rigid ? slab_mass(scene) : 0.0;
    p.slab_face_y0     = g.slab_bottom();
    p.slab_face_y1     = g.resolved_slab_top();
    p.slab_front_x     = g.slab_front_x();
    p.initial_velocity = scene.slab.velocity;

    p.integrator            = scene.dynamics.integrator;
    p.penalty_factor        = scene.contact.penalty_factor;
    p.contact_damping_ratio = scene.contact.contact_damping_ratio;
    p.smoothing_window      = parse_auto_time(scene.contact.smoothing_window).value_or(0.0);

    p.dt                                     = parse_auto_time(scene.dynamics.dt).value_or(0.0);
    p.explicit_options.cfl_safety            = scene.dynamics.cfl_safety;
    p.implicit_options.dt_factor             = scene.dynamics.implicit_dt_factor;
    p.implicit_options.linear_solver         = scene.dynamics.implicit_solver;
    p.implicit_options.max_halvings          = scene.dynamics.implicit_max_halvings;
    p.implicit_options.newton_max_iterations = scene.dynamics.implicit_newton_max_iterations;
    p.end_time                               = scene.dynamics.end_time;
    p.separation_hold_time                   = scene.dynamics.separation_hold_time;
    p.output_interval                        = scene.dynamics.output_interval;
    p.log_interval                           = scene.dynamics.log_interval;
    if (scene.geometry.with_backfill && scene.interface.model == FemInterface::Model::contact)
    {
      const fem::SoilParameters sp  = soil_parameters(scene.materials.soil);
      p.wall_soil_interface.contact = true;
      p.wall_soil_interface.friction =
        scene.interface.friction.value_or(std::tan(2.0 / 3.0 * sp.friction_angle));
      p.wall_soil_interface.penalty_factor = scene.interface.penalty_factor;
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
