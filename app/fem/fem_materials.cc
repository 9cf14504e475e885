// FEM scene materials: their cross-key rules and their fem/ parameters and laws; see
// fem_materials.h.
#include "app/fem/fem_materials.h"

#include <fmt/format.h>

#include "fem/inelastic_laws.h"
#include "fem/material_law.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::io;

  void validate(const FemMaterials &materials, ValidationContext &ctx)
  {
    {
      const fem::SoilParameters soil = soil_parameters(materials.soil);
      // A preset sets E, nu and rho: a value given beside it would be ignored, so it is refused.
      const FemSoil &given = materials.soil;
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
    if (materials.concrete.model == FemConcrete::Model::elastic)
    {
      // Bars need the damage law (an elastic concrete stays linear): refused, not ignored.
      const auto check = [&](const char *key, const fem::ReinforcementParameters &r)
      {
        const bool x = r.ratio_x != 0;
        ctx.check(!x && r.ratio_y == 0,
                  std::string("concrete.") + key + (x ? ".ratio_x" : ".ratio_y"),
                  format_quantity(x ? r.ratio_x : r.ratio_y, "%"),
                  "needs materials.concrete.model: damage_plasticity (smeared bars act in the "
                  "concrete damage law only)");
      };
      check("wall_reinforcement", materials.concrete.wall_reinforcement);
      check("slab_reinforcement", materials.concrete.slab_reinforcement);
      ctx.check(materials.concrete.plastic_fraction == 0,
                "concrete.plastic_fraction",
                format_quantity(materials.concrete.plastic_fraction, ""),
                "needs materials.concrete.model: damage_plasticity");
      const FemConcrete defaults;
      ctx.check(materials.concrete.compression_band == defaults.compression_band,
                "concrete.compression_band",
                format_quantity(materials.concrete.compression_band, "m"),
                "needs materials.concrete.model: damage_plasticity");
      ctx.check(materials.concrete.crack_frame == defaults.crack_frame,
                "concrete.crack_frame",
                "fixed",
                "needs materials.concrete.model: damage_plasticity");
    }
    // Strain penetration acts on the wall's vertical bars at its clamped base, nowhere else.
    const fem::ReinforcementParameters &wall = materials.concrete.wall_reinforcement;
    ctx.check(wall.strain_penetration == 0 ||
                (materials.concrete.model != FemConcrete::Model::elastic && wall.ratio_y > 0),
              "concrete.wall_reinforcement.strain_penetration",
              format_quantity(wall.strain_penetration, "m"),
              "needs vertical bars (wall_reinforcement.ratio_y > 0) in a damage_plasticity "
              "concrete");
    // The base joint is the base row's concrete: the cells strain penetration marks.
    ctx.check(wall.base_joint_tension == 0 || wall.strain_penetration > 0,
              "concrete.wall_reinforcement.base_joint_tension",
              format_quantity(wall.base_joint_tension, "MPa"),
              "needs wall_reinforcement.strain_penetration > 0 (the joint is the base row's "
              "crack, where the vertical bars slip out of the base)");
    ctx.check(materials.concrete.slab_reinforcement.base_joint_tension == 0,
              "concrete.slab_reinforcement.base_joint_tension",
              format_quantity(materials.concrete.slab_reinforcement.base_joint_tension, "MPa"),
              "must be 0: the slab has no clamped base (wall_reinforcement.base_joint_tension)");
    ctx.check(materials.concrete.slab_reinforcement.strain_penetration == 0,
              "concrete.slab_reinforcement.strain_penetration",
              format_quantity(materials.concrete.slab_reinforcement.strain_penetration, "m"),
              "must be 0: the slab has no clamped base to anchor its bars in (the wall's "
              "vertical bars take it, wall_reinforcement.strain_penetration)");
    // A crack spacing is what bars impose: without them the cell's crack band keeps G_F. Tension
    // stiffening is the tension between those cracks.
    for (const auto &[key, r] :
         {std::pair{"wall_reinforcement", &materials.concrete.wall_reinforcement},
          std::pair{"slab_reinforcement", &materials.concrete.slab_reinforcement}})
    {
      const std::string path = std::string("concrete.") + key;
      ctx.check(r->crack_spacing == 0 ||
                  (materials.concrete.model != FemConcrete::Model::elastic && r->any()),
                path + ".crack_spacing",
                format_quantity(r->crack_spacing, "m"),
                "needs bars (ratio_x or ratio_y > 0) in a damage_plasticity concrete");
      ctx.check(!r->tension_stiffening || r->crack_spacing > 0,
                path + ".tension_stiffening",
                "true",
                "needs the bars' crack_spacing (> 0): the tension between the cracks is that of "
                "a member cracked every s_rm");
    }
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
    p.rotating_crack   = c.crack_frame == FemConcrete::CrackFrame::rotating;
    p.compression_band = c.compression_band;
    return p;
  }

  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>>
  concrete_material(const FemConcrete &c)
  {
    return concrete_material(c, fem::ReinforcementParameters{});
  }

  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>>
  concrete_material(const FemConcrete &c, const fem::ReinforcementParameters &reinforcement)
  {
    if (c.model == FemConcrete::Model::elastic)
      return {fem::Material{c.youngs_modulus, c.poisson_ratio, c.density}, nullptr};
    const fem::ConcreteParameters p = concrete_parameters(c);
    return {fem::Material{p.youngs_modulus, p.poisson_ratio, c.density},
            std::make_shared<const fem::ConcreteDamageLaw>(p, reinforcement)};
  }
} // namespace kimp::app
