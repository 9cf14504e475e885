// Section `materials` of the FEM scene (docs/physics.md §4 and §6): elastic constants, the soil's
// Mohr-Coulomb / Drucker-Prager strength (or a named preset), the concrete's fib Model Code 2010
// damage law from f_cm and its smeared bars, and their translation to fem/ materials and laws.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fem/impact.h"
#include "fem/inelastic_laws.h"
#include "fem/material_law.h"
#include "io/scene_io.h"

namespace kimp::fem
{
  /// Scene sections `wall_reinforcement` and `slab_reinforcement`: the engine's own struct,
  /// visited in place (in its namespace so that the io readers find it by argument-dependent
  /// lookup).
  template <class Io>
  void visit(Io &io, ReinforcementParameters &s)
  {
    io.quantity("ratio_x",
                s.ratio_x,
                "%",
                "steel area / concrete area of the bars along x, the horizontal of the section "
                "(0: none)",
                io::Range::at_least(0.0).and_at_most(0.1));
    io.quantity("ratio_y",
                s.ratio_y,
                "%",
                "steel area / concrete area of the bars along y, the vertical of the section "
                "(0: none)",
                io::Range::at_least(0.0).and_at_most(0.1));
    io.quantity("f_y", s.yield_stress, "MPa", "steel yield stress (B500)", io::Range::positive());
    io.quantity("E_s", s.youngs_modulus, "GPa", "steel Young's modulus", io::Range::positive());
    io.quantity("hardening",
                s.hardening,
                "",
                "post-yield (linear kinematic hardening) tangent / E_s",
                io::Range::at_least(0.0).and_less(1.0));
    io.quantity("strain_penetration",
                s.strain_penetration,
                "m",
                "L_sp of the vertical bars into the wall's clamped base: the bars of the base "
                "row stretch over the row's height + L_sp (their slip out of the base, "
                "linearised; 0.022 f_y d_b with f_y in MPa, e.g. 0.13 m for 12 mm B500 bars); "
                "0: perfect bond to the base",
                io::Range::at_least(0.0).and_at_most(1.0));
    io.quantity("base_joint_tension",
                s.base_joint_tension,
                "MPa",
                "f_j, the tension of a construction joint at the wall's clamped base (needs "
                "strain_penetration): the base row's concrete carries E k f_j / (E k + f_j) at "
                "the tension measure k, no strength criterion, saturating at f_j and never "
                "softening (of the order of EN 1992-1-1 6.2.5's cohesion c f_ctd of a smooth "
                "joint, 0.2 x 1.35 MPa = 0.27 MPa for C30/37); 0: the base row cracks as the "
                "wall's concrete",
                io::Range::at_least(0.0).and_at_most(10e6));
    io.quantity("crack_spacing",
                s.crack_spacing,
                "m",
                "s_rm, the mean spacing of the cracks the bars impose: the concrete of these "
                "bars' cells softens in tension over s_rm instead of the cell's height, so that "
                "a cracked zone's strain is the same on every mesh (EN 1992-1-1 7.3.4: s_r,max = "
                "3.4 c + 0.17 d_b / rho_eff in bending, the mean about s_r,max / 1.7; e.g. "
                "0.2 m for a 0.25 m wall with 12 mm bars at 40 mm cover, 0.4 % a face); 0: "
                "each cell's own crack band",
                io::Range::at_least(0.0).and_at_most(2.0));
    io.flag("tension_stiffening",
            s.tension_stiffening,
            "the concrete between the cracks keeps an average tension f_t / (1 + sqrt(500 "
            "eps)) (Collins and Mitchell), capped by the bars' reserve at a crack, instead of "
            "softening to nothing over crack_spacing (needs crack_spacing)");
  }
} // namespace kimp::fem

namespace kimp::app
{
  /** Linear elastic isotropic material (plane strain). */
  struct FemMaterial
  {
    double youngs_modulus = 0; ///< E, Pa
    double poisson_ratio  = 0; ///< nu
    double density        = 0; ///< rho, kg/m^3
  };

  template <class Io>
  void visit(Io &io, FemMaterial &s)
  {
    io.quantity("E",
                s.youngs_modulus,
                "GPa",
                "Young's modulus",
                io::Range::plausible(1e5, 1e12, "concrete, steel or soil"));
    io.quantity("nu",
                s.poisson_ratio,
                "",
                "Poisson's ratio",
                io::Range::at_least(0.0).and_less(0.5));
    io.quantity("rho",
                s.density,
                "kg/m^3",
                "density",
                io::Range::plausible(100.0, 20000.0, "concrete, steel or soil"));
  }

  /// A soil angle key in degrees: a friction or dilatancy angle (no unit, 0 to 89); `doc` says
  /// which.
  template <class Io>
  void
  visit_soil_angle(Io &io, std::string_view key, std::optional<double> &angle, std::string_view doc)
  {
    io.quantity(key, angle, "", doc, io::Range::at_least(0.0).and_at_most(89.0));
  }

  /// The keys a material begins with: its elastic constants (E, nu, rho), then `model`, its law
  /// among `models`; `doc` says what each model takes.
  template <class Io, class Material>
  void visit_elastic_and_model(
    Io                                                                  &io,
    Material                                                            &s,
    const std::vector<std::pair<std::string, typename Material::Model>> &models,
    std::string_view                                                     doc)
  {
    visit(io, static_cast<FemMaterial &>(s));
    io.choice("model", s.model, models, doc);
  }

  /** Backfill: elasticity plus, for the inelastic models, Mohr-Coulomb strength. */
  struct FemSoil : FemMaterial
  {
    FemSoil()
      : FemMaterial{50e6, 0.3, 1900}
    {
    }
    enum class Model
    {
      elastic,
      mohr_coulomb,
      drucker_prager
    };
    Model       model = Model::elastic;
    std::string preset =
      "none"; ///< "none" or a fem::soil_presets() name (sets E, nu, rho, c, phi, psi)
    std::optional<double> cohesion;           ///< c, Pa; default: the preset's, else 0
    std::optional<double> friction_angle;     ///< phi, degrees; default: the preset's, else 30
    std::optional<double> dilatancy;          ///< psi, degrees; default: the preset's, else 0
    double                tension_cutoff = 0; ///< Pa (clipped to c cot(phi))
    /// At-rest earth pressure coefficient of the geostatic state; default 1 - sin(phi) (Jaky).
    std::optional<double> K0;
  };

  template <class Io>
  void visit(Io &io, FemSoil &s)
  {
    visit_elastic_and_model(io,
                            s,
                            {{"elastic", FemSoil::Model::elastic},
                             {"mohr_coulomb", FemSoil::Model::mohr_coulomb},
                             {"drucker_prager", FemSoil::Model::drucker_prager}},
                            "elastic; mohr_coulomb: perfectly plastic, tension cut-off, "
                            "non-associated; drucker_prager: matched to Mohr-Coulomb in plane "
                            "strain");
    io.choice("preset",
              s.preset,
              {"none", "loose_sand", "medium_dense_sand", "dense_sand", "soft_clay", "stiff_clay"},
              "named soil (docs/physics.md): sets E, nu, rho, c, phi, psi; c, phi, psi given "
              "here override it");
    io.quantity("c", s.cohesion, "kPa", "cohesion", io::Range::non_negative());
    visit_soil_angle(io, "phi", s.friction_angle, "friction angle in degrees");
    visit_soil_angle(io, "psi", s.dilatancy, "dilatancy angle in degrees (<= phi)");
    io.quantity("tension_cutoff",
                s.tension_cutoff,
                "kPa",
                "largest principal stress (at most c cot(phi))",
                io::Range::non_negative());
    io.quantity("K0",
                s.K0,
                "",
                "at-rest earth pressure coefficient sigma_h / sigma_v of the geostatic state "
                "(null: 1 - sin(phi), Jaky)",
                io::Range::at_least(0.0).and_at_most(3.0));
  }

  /** Slab and wall concrete: elasticity, or damage from f_cm by fib Model Code 2010. */
  struct FemConcrete : FemMaterial
  {
    FemConcrete()
      : FemMaterial{30e9, 0.2, 2400}
    {
    }
    enum class Model
    {
      elastic,
      damage_plasticity
    };
    Model                 model = Model::elastic;
    double                f_cm  = 38e6;    ///< mean compressive strength, Pa
    std::optional<double> f_ctm;           ///< Pa; default: MC2010 from f_cm
    std::optional<double> fracture_energy; ///< G_F, N/m; default: MC2010 from f_cm
    double strain_rate = 0; ///< 1/s for the MC2010 dynamic increase factors (0: none)
    /// b_c: plastic fraction of the compressive inelastic strain (0: secant unloading).
    double plastic_fraction = 0;
    /// The crack frame of the damage law (fem::ConcreteParameters::rotating_crack).
    enum class CrackFrame
    {
      rotating, ///< coaxial with the principal directions: no stress locking in a hinge
      fixed     ///< fixed at the first crack, with shear retention and dowels in it
    };
    CrackFrame crack_frame = CrackFrame::rotating;
    /// l_c, m: the crack band in compression (fem::ConcreteParameters::compression_band) of the
    /// impact model and the pushover alike; 0: the local curve.
    double compression_band = 0.3;
    /// Smeared bars of the wall (damage_plasticity only; default none).
    fem::ReinforcementParameters wall_reinforcement;
    /// Smeared bars of the meshed slab (damage_plasticity only; default none).
    fem::ReinforcementParameters slab_reinforcement;
  };

  template <class Io>
  void visit(Io &io, FemConcrete &s)
  {
    visit_elastic_and_model(io,
                            s,
                            {{"elastic", FemConcrete::Model::elastic},
                             {"damage_plasticity", FemConcrete::Model::damage_plasticity}},
                            "elastic (E, nu); damage_plasticity: tension/compression damage with "
                            "crack band, parameters from f_cm by fib Model Code 2010 (E then = "
                            "E_ci)");
    io.quantity("f_cm",
                s.f_cm,
                "MPa",
                "mean cylinder compressive strength",
                io::Range::greater(8e6));
    io.quantity("f_ctm",
                s.f_ctm,
                "MPa",
                "mean tensile strength (null: MC2010 from f_cm)",
                io::Range::positive());
    io.quantity("G_F",
                s.fracture_energy,
                "N/m",
                "fracture energy (null: MC2010 73 f_cm^0.18)",
                io::Range::positive());
    io.quantity("strain_rate",
                s.strain_rate,
                "1",
                "strain rate (1/s) of the MC2010 dynamic increase factors (0: none)",
                io::Range::non_negative());
    io.quantity("plastic_fraction",
                s.plastic_fraction,
                "",
                "damage_plasticity: fraction b_c of the compressive inelastic strain that stays "
                "as plastic strain on unloading (0: secant unloading; Abaqus CDP calibrations "
                "~0.7)",
                io::Range::at_least(0.0).and_less(1.0));
    io.choice("crack_frame",
              s.crack_frame,
              {{"rotating", FemConcrete::CrackFrame::rotating},
               {"fixed", FemConcrete::CrackFrame::fixed}},
              "damage_plasticity: the cracks' frame; rotating: it turns with the principal "
              "directions (no tension locked across the cracks of a hinge, so the yielding wall "
              "converges with the mesh); fixed: set at the first crack, with shear retention "
              "and dowel action in it");
    io.quantity("compression_band",
                s.compression_band,
                "m",
                "damage_plasticity: length over which crushing past the compressive peak "
                "dissipates its energy, so that every mesh crushes alike, in the impact run and "
                "the pushover (0: each cell follows the local stress-strain curve, which softens "
                "with the mesh)",
                io::Range::at_least(0.0));
    io.section("wall_reinforcement",
               s.wall_reinforcement,
               "damage_plasticity: smeared, perfectly bonded steel bars of the wall (ratio_y: "
               "its vertical bars; ratio_x: ties through its thickness)");
    io.section("slab_reinforcement",
               s.slab_reinforcement,
               "damage_plasticity: smeared, perfectly bonded steel bars of the meshed slab "
               "(ratio_x: its bars along the impact; ratio_y: links through its thickness)");
  }

  /** Concrete (slab and wall) and soil (backfill); docs/physics.md §4 defaults. */
  struct FemMaterials
  {
    FemConcrete concrete;
    FemSoil     soil;
  };

  template <class Io>
  void visit(Io &io, FemMaterials &s)
  {
    io.section("concrete", s.concrete, "slab and wall");
    io.section("soil", s.soil, "backfill");
  }

  /** The materials' rules that link several keys (preset against E, nu, rho; psi <= phi; bars
   *  and plastic_fraction need the damage law); key paths relative to `materials`. */
  void validate(const FemMaterials &materials, io::ValidationContext &ctx);

  /** Soil strength and elasticity of @p soil: its preset (if any) with c, phi, psi given in
   *  the scene overriding the preset's. */
  fem::SoilParameters soil_parameters(const FemSoil &soil);
  /** @p soil with its preset written out as E, nu, rho, c, phi, psi (preset "none"), so that
   *  those values can be changed (the same soil_parameters()). */
  FemSoil without_preset(const FemSoil &soil);
  /** Concrete parameters by fib Model Code 2010 from f_cm, with the scene's overrides. */
  fem::ConcreteParameters concrete_parameters(const FemConcrete &concrete);
  /** The elastic constants the solver uses (dt, penalty, mass) and the law (null: linear). */
  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>>
  soil_material(const FemSoil &soil);
  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>>
  concrete_material(const FemConcrete &concrete);
  /** As concrete_material(), the damage law with the smeared bars @p reinforcement. */
  std::pair<fem::Material, std::shared_ptr<const fem::MaterialLaw>>
  concrete_material(const FemConcrete &concrete, const fem::ReinforcementParameters &reinforcement);
} // namespace kimp::app
