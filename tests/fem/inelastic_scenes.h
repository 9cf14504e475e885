// The inelastic test scenes shared by the kimp::fem impact tests: the docs/physics.md §4 scene
// (H = 1.25 m, 5 cm at the contact) with Mohr-Coulomb backfill and damaged concrete, plain or
// with smeared bars; and with a cohesionless backfill in its geostatic state.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "fem/inelastic_laws.h"
#include "tests/fem/impact_test_support.h"

namespace kimp::fem::testing
{
  /** Mohr-Coulomb soil (c = 10 kPa, phi = 30 deg, psi = 0, no tension) and concrete damage from
   *  f_cm = 38 MPa in slab and wall, slab (elastic or rigid) at 2 m/s. */
  inline ImpactParameters inelastic_scene(const std::string &name, bool rigid = false)
  {
    auto           p = scene_parameters(0.05, rigid, name);
    SoilParameters sp;
    sp.youngs_modulus         = soil.youngs_modulus;
    sp.poisson_ratio          = soil.poisson_ratio;
    sp.density                = soil.density;
    sp.cohesion               = 10e3;
    sp.friction_angle         = 30 * 3.14159265358979323846 / 180;
    const auto     cp         = ConcreteParameters::from_f_cm(38e6);
    const auto     concrete_l = std::make_shared<const ConcreteDamageLaw>(cp);
    const Material concrete_m{cp.youngs_modulus, cp.poisson_ratio, concrete.density};
    p.materials[ids::slab_material]     = concrete_m;
    p.materials[ids::wall_material]     = concrete_m;
    p.material_laws[ids::slab_material] = concrete_l;
    p.material_laws[ids::wall_material] = concrete_l;
    p.material_laws[ids::soil_material] = std::make_shared<const MohrCoulombLaw>(sp);
    p.initial_velocity                  = 2.0;
    return p;
  }

  /** inelastic_scene() with smeared B500 bars (docs/physics.md §6): the wall's vertical
   *  ratio_y = 0.8 % and ties ratio_x = 0.2 %, the slab's ratio_x = 0.5 % along the impact. */
  inline ImpactParameters reinforced_scene(const std::string &name, bool rigid = false)
  {
    auto                    p  = inelastic_scene(name, rigid);
    const auto              cp = ConcreteParameters::from_f_cm(38e6);
    ReinforcementParameters wall, slab;
    wall.ratio_x                        = 0.002;
    wall.ratio_y                        = 0.008;
    slab.ratio_x                        = 0.005;
    p.material_laws[ids::wall_material] = std::make_shared<const ConcreteDamageLaw>(cp, wall);
    p.material_laws[ids::slab_material] = std::make_shared<const ConcreteDamageLaw>(cp, slab);
    return p;
  }

  /** The §4 scene (H = 1.25 m, backfill 2 m) at contact size h with the medium_dense_sand
   *  Mohr-Coulomb backfill and the geostatic state, K0 = 1 - sin(phi). With
   *  `interface_contact`, wall and soil have separate nodes along the wall's back, joined by the
   *  frictional contact interface with mu = tan(2 phi / 3); else they are bonded. */
  inline ImpactParameters geostatic_scene(const std::string &name,
                                          bool               rigid,
                                          double             h                 = 0.05,
                                          bool               interface_contact = false)
  {
    auto                 p              = scene_parameters(h, rigid, name, 0.2, interface_contact);
    const SoilParameters sp             = soil_preset("medium_dense_sand");
    p.materials[ids::soil_material]     = Material{sp.youngs_modulus, sp.poisson_ratio, sp.density};
    p.material_laws[ids::soil_material] = std::make_shared<const MohrCoulombLaw>(sp);
    p.geostatic.enabled                 = true;
    p.geostatic.initial_stress_K0[ids::soil_material] = 1 - std::sin(sp.friction_angle);
    p.wall_soil_interface.contact                     = interface_contact;
    p.wall_soil_interface.friction                    = std::tan(2.0 / 3.0 * sp.friction_angle);
    return p;
  }
} // namespace kimp::fem::testing
