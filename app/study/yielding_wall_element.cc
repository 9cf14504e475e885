// The yielding wall element of an inelastic study: derivation from its inputs, and the inputs of a
// FEM scene.
#include "app/study/yielding_wall_element.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "app/fem/fem_materials.h"
#include "app/study/wall_capacity.h"

namespace kimp::app
{
  namespace
  {
    void require_positive(const double value, const char *name)
    {
      if (!(value > 0.0) || !std::isfinite(value))
        throw std::invalid_argument(std::string("yielding wall element: ") + name +
                                    " must be positive and finite, got " + std::to_string(value));
    }
  } // namespace

  YieldingWallElement derive_yielding_wall(const YieldingWallInputs &in, const double width)
  {
    require_positive(in.capacity, "capacity");
    require_positive(in.stiffness, "stiffness");
    require_positive(in.unloading_stiffness, "unloading_stiffness");
    require_positive(in.soil_density, "soil_density");
    require_positive(in.soil_wave_speed, "soil_wave_speed");
    require_positive(in.loaded_height, "loaded_height");
    if (!(in.slab_impedance > 0.0)) // +infinity: a rigid slab
      throw std::invalid_argument("yielding wall element: slab_impedance must be positive");
    require_positive(in.wall_impedance, "wall_impedance");
    require_positive(in.wall_mass, "wall_mass");
    require_positive(in.striker_mass, "striker_mass");
    require_positive(in.wall_height, "wall_height");
    require_positive(width, "width");
    if (!(in.ultimate_capacity >= in.capacity))
      throw std::invalid_argument(
        "yielding wall element: ultimate_capacity must be at least capacity");
    if (!(in.hardening_ratio >= 0.0 && in.hardening_ratio < 1.0))
      throw std::invalid_argument("yielding wall element: hardening_ratio must be in [0, 1)");

    YieldingWallElement e;
    e.width             = width;
    e.wall_mass         = in.wall_mass;
    e.radiation_damping = in.soil_density * in.soil_wave_speed * in.loaded_height;
    e.contact_impedance = 1.0 / (1.0 / in.slab_impedance + 1.0 / in.wall_impedance);
    e.reduced_mass      = in.wall_mass * in.striker_mass / (in.wall_mass + in.striker_mass);
    e.contact_stiffness = e.contact_impedance * e.contact_impedance / e.reduced_mass;

    YieldingWallScene &b = e.backfill;
    b.width              = width;
    b.height             = in.wall_height; // failure limit: 10 % of it (the scene's default)
    b.envelope           = lumped::WallEnvelope::bilinear;
    b.stiffness          = in.stiffness;
    b.capacity           = in.capacity;
    b.hardening_ratio    = in.hardening_ratio;
    if (std::isfinite(in.ultimate_capacity))
      b.ultimate_capacity = in.ultimate_capacity;
    b.unloading_stiffness = in.unloading_stiffness;
    b.tension_capacity    = in.capacity;
    if (!in.envelope_displacements.empty())
    {
      if (in.envelope_displacements.size() != in.envelope_forces.size())
        throw std::invalid_argument(
          "yielding wall element: the envelope's displacements and forces differ in count");
      b.envelope = lumped::WallEnvelope::curve;
      b.stiffness.reset();
      b.capacity.reset();
      b.hardening_ratio = 0.0;
      b.ultimate_capacity.reset();
      for (std::size_t i = 0; i < in.envelope_displacements.size(); ++i)
        b.curve.push_back({in.envelope_displacements[i], in.envelope_forces[i]});
    }
    b.soil_density      = in.soil_density;
    b.soil_wave_speed   = in.soil_wave_speed;
    b.radiation_damping = e.radiation_damping;
    return e;
  }

  YieldingWallInputs
  yielding_wall_inputs(const FemScene &scene, const double wall_height, const double striker_mass)
  {
    const geometry::SceneGeometry g        = scene_geometry(scene, wall_height);
    const WallCapacityEstimate    estimate = wall_capacity_estimate(scene, wall_height);
    const fem::Material           concrete = concrete_material(scene.materials.concrete).first;
    const fem::Material           soil     = soil_material(scene.materials.soil).first;
    const double                  t        = g.wall_thickness;
    const double                  h_c      = estimate.contact_height;
    const double                  nu_s     = soil.poisson_ratio;
    const double                  m_s =
      soil.youngs_modulus * (1.0 - nu_s) / ((1.0 + nu_s) * (1.0 - 2.0 * nu_s)); // P-wave modulus
    const double nu_c = concrete.poisson_ratio;
    const double c_ps =
      std::sqrt(concrete.youngs_modulus / (concrete.density * (1.0 - nu_c * nu_c))); // bar
    const double c_pc = std::sqrt(concrete.youngs_modulus * (1.0 - nu_c) /
                                  ((1.0 + nu_c) * (1.0 - 2.0 * nu_c) * concrete.density)); // P

    YieldingWallInputs in;
    in.capacity  = estimate.per_metre;
    in.stiffness = 3.0 * 0.5 * concrete.youngs_modulus * (t * t * t / 12.0) / (h_c * h_c * h_c);
    in.unloading_stiffness = in.stiffness;
    in.hardening_ratio     = 0.0;
    in.soil_density        = soil.density;
    in.soil_wave_speed     = std::sqrt(m_s / soil.density);
    in.loaded_height       = g.resolved_backfill_height();
    in.slab_impedance      = concrete.density * c_ps * g.slab_thickness;
    in.wall_impedance      = concrete.density * c_pc * t;
    in.wall_mass           = concrete.density * t * wall_height;
    in.striker_mass        = striker_mass;
    in.wall_height         = wall_height;
    return in;
  }

  LumpedScene
  yielding_walled_scene(const LumpedScene &base, const double gap, const YieldingWallElement &e)
  {
    LumpedScene s = base;
    for (WallScene *wall : {&s.walls.left, &s.walls.right})
    {
      wall->present   = true;
      wall->gap       = gap;
      wall->flexible  = false;
      wall->sdof_mass = e.wall_mass * e.width;
      wall->yielding  = e.backfill;
    }
    s.impact.law = "linear";
    s.impact.k.clear();
    s.impact.k_si     = e.contact_stiffness * e.width;
    s.impact.exponent = std::nullopt;
    return s;
  }
} // namespace kimp::app
