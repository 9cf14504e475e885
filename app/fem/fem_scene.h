// Scene of `kimp mesh` and `kimp fem`: the plane-strain slab-wall-backfill impact of
// docs/physics.md §4 as a plain struct with SI members (defaults = the §4 default scene), one case
// per wall height.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fem/impact.h"
#include "fem/inelastic_laws.h"
#include "geometry/scene_geometry.h"
#include "io/scene_io.h"

namespace kimp::app
{
  /** Linear elastic isotropic material (plane strain). */
  struct FemMaterial
  {
    double youngs_modulus = 0; ///< E, Pa (> 0)
    double poisson_ratio  = 0; ///< nu (in [0, 0.5))
    double density        = 0; ///< rho, kg/m^3 (> 0)
  };

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

  /** Smeared reinforcement of one concrete body (fem::ReinforcementParameters). */
  struct FemReinforcement
  {
    double ratio_x   = 0;     ///< steel / concrete area of the bars along x (horizontal), -
    double ratio_y   = 0;     ///< steel / concrete area of the bars along y (vertical), -
    double f_y       = 500e6; ///< yield stress, Pa
    double E_s       = 200e9; ///< Pa
    double hardening = 0.01;  ///< post-yield modulus / E_s, -
  };

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
    /// Smeared bars of the wall (damage_plasticity only; default none).
    FemReinforcement wall_reinforcement;
    /// Smeared bars of the meshed slab (damage_plasticity only; default none).
    FemReinforcement slab_reinforcement;
  };

  /** Concrete (slab and wall) and soil (backfill); docs/physics.md §4 defaults. */
  struct FemMaterials
  {
    FemConcrete concrete;
    FemSoil     soil;
  };

  /**
   * Scene dimensions other than the wall height (which is the case parameter `wall_heights`).
   * Defaults from geometry::SceneGeometry.
   */
  struct FemGeometry
  {
    double                wall_thickness = geometry::SceneGeometry().wall_thickness; ///< m
    bool                  with_backfill  = geometry::SceneGeometry().with_backfill;
    double                backfill_width = geometry::SceneGeometry().backfill_width; ///< m
    std::optional<double> backfill_height; ///< m; default: the wall height of the case
    double                slab_length    = geometry::SceneGeometry().slab_length;    ///< m
    double                slab_thickness = geometry::SceneGeometry().slab_thickness; ///< m
    std::optional<double> slab_top; ///< y of the slab top, m; default: the wall top
    double                gap = geometry::SceneGeometry().gap; ///< initial clear distance, m
  };

  /** Element sizes (defaults from geometry::SceneGeometry) and the refinement level. */
  struct FemMesh
  {
    double h_contact = geometry::SceneGeometry().h_contact; ///< m, element size at the contact
    double h_max     = geometry::SceneGeometry().h_max;     ///< m, largest element size
    double grading   = geometry::SceneGeometry().grading;   ///< largest neighbour size ratio
    int    level     = 0; ///< every size divided by 2^level (geometry::refined)
  };

  /** The striking slab. */
  struct FemSlab
  {
    bool rigid = false; ///< true: one translational DoF; false: meshed elastic concrete slab
    /// Rigid slab only: kg per metre of wall; default rho_concrete * slab_length * slab_thickness.
    std::optional<double> mass;
    double                velocity = fem::ImpactParameters().initial_velocity; ///< m/s, +x
  };

  /** Penalty contact (see fem::ImpactParameters for the scalings). */
  struct FemContact
  {
    double penalty_factor        = fem::ImpactParameters().penalty_factor;        ///< x E/h_contact
    double contact_damping_ratio = fem::ImpactParameters().contact_damping_ratio; ///< in [0, 1]
    /// Moving-average width of the reported force: "auto" (p-wave transit time across the
    /// contact) or a time with unit, e.g. "0.05 ms".
    std::string smoothing_window = "auto";
  };

  /** Time integration. */
  struct FemDynamics
  {
    fem::ImpactParameters::Integrator integrator = fem::ImpactParameters().integrator;
    /// "auto" (cfl_safety x stable limit; implicit: implicit_dt_factor x limit) or a time.
    std::string dt                 = "auto";
    double      cfl_safety         = fem::ExplicitOptions().cfl_safety; ///< (0, 1]
    double      implicit_dt_factor = fem::ImplicitOptions().dt_factor;  ///< > 0
    fem::ImplicitOptions::LinearSolver implicit_solver       = fem::ImplicitOptions().linear_solver;
    unsigned int                       implicit_max_halvings = fem::ImplicitOptions().max_halvings;
    unsigned int implicit_newton_max_iterations = fem::ImplicitOptions().newton_max_iterations;
    double       end_time                       = fem::ImpactParameters().end_time;   ///< s
    double       separation_hold_time = fem::ImpactParameters().separation_hold_time; ///< s
    double       output_interval      = fem::ImpactParameters().output_interval;      ///< s
    unsigned int log_interval         = 100; ///< history samples between log lines (0: none)
    /// Step budget: a case whose estimated steps (end_time / dt) exceed it is refused before it
    /// is meshed (app/fem/fem_estimate.h).
    double max_steps = 1e6;
  };

  /** Boundary conditions of the backfill block (docs/physics.md §6). */
  struct FemBoundary
  {
    /** What ends the model's soil at its far side and base. */
    enum class Far
    {
      rollers,  ///< far side u_x = 0, base u = 0 (the thesis' finite block)
      absorbing ///< Lysmer-Kuhlemeyer dashpots rho c_p (normal), rho c_s (tangential)
    };
    Far far = Far::rollers;
  };

  /** Field output. */
  struct FemOutput
  {
    double vtu_interval = 0; ///< s between VTU snapshots under DIR/vtu/<case>/ (0: none)
    /// s between the deformed-mesh frames of fem.h5 (`frames`, the report's animation; 0: none)
    double frame_interval = 1e-3;
  };

  /** Wall-soil interface (docs/physics.md §6 "Wall-soil interface"). */
  struct FemInterface
  {
    enum class Model
    {
      bonded, ///< wall and backfill share their interface nodes
      contact ///< unilateral Coulomb penalty contact, free to open
    };
    Model model = Model::bonded;
    /// Coulomb friction coefficient; default tan(2 phi / 3) of the soil.
    std::optional<double> friction;
    double                penalty_factor = fem::InterfaceOptions().penalty_factor; ///< x E_soil / h
  };

  template <class Io>
  void visit(Io &io, FemInterface &s)
  {
    io.choice("model",
              s.model,
              {{"bonded", FemInterface::Model::bonded}, {"contact", FemInterface::Model::contact}},
              "bonded: wall and backfill share their nodes; contact: unilateral frictional "
              "penalty contact between wall back and backfill (explicit integrator), closed by "
              "the geostatic earth pressure, free to open");
    io.quantity("friction",
                s.friction,
                "",
                "contact: Coulomb friction coefficient mu (>= 0; null: tan(2 phi / 3))",
                io::Range::non_negative());
    io.quantity("penalty_factor",
                s.penalty_factor,
                "",
                "contact: normal and tangential penalty per node pair / (E_soil / h x tributary "
                "length) (> 0)",
                io::Range::positive());
  }

  /** Geostatic initial state before the impact (docs/physics.md §6). */
  enum class FemGeostatic
  {
    auto_, ///< on when the backfill's law is inelastic
    on,
    off
  };

  /**
   * The FEM scene: one impact per entry of wall_heights (case name fem_case_name(H), "H1.25").
   * Load with read_scene<FemScene>(file), which validates.
   */
  struct FemScene
  {
    std::vector<double> wall_heights{geometry::SceneGeometry().wall_height}; ///< m
    FemGeometry         geometry;
    FemMesh             mesh;
    FemMaterials        materials;
    FemSlab             slab;
    FemContact          contact;
    FemDynamics         dynamics;
    FemOutput           output;
    FemBoundary         boundary;
    FemGeostatic        geostatic = FemGeostatic::auto_;
    FemInterface        interface;
  };

  template <class Io>
  void visit(Io &io, FemMaterial &s)
  {
    io.quantity("E", s.youngs_modulus, "GPa", "Young's modulus (> 0)", io::Range::positive());
    io.quantity("nu",
                s.poisson_ratio,
                "",
                "Poisson's ratio (in [0, 0.5))",
                io::Range::at_least(0.0).and_less(0.5));
    io.quantity("rho", s.density, "kg/m^3", "density (> 0)", io::Range::positive());
  }

  template <class Io>
  void visit(Io &io, FemSoil &s)
  {
    visit(io, static_cast<FemMaterial &>(s));
    io.choice("model",
              s.model,
              {{"elastic", FemSoil::Model::elastic},
               {"mohr_coulomb", FemSoil::Model::mohr_coulomb},
               {"drucker_prager", FemSoil::Model::drucker_prager}},
              "elastic; mohr_coulomb: perfectly plastic, tension cut-off, non-associated; "
              "drucker_prager: matched to Mohr-Coulomb in plane strain");
    io.choice("preset",
              s.preset,
              {"none", "loose_sand", "medium_dense_sand", "dense_sand", "soft_clay", "stiff_clay"},
              "named soil (docs/physics.md): sets E, nu, rho, c, phi, psi; c, phi, psi given "
              "here override it");
    io.quantity("c", s.cohesion, "kPa", "cohesion (>= 0)", io::Range::non_negative());
    io.quantity("phi",
                s.friction_angle,
                "",
                "friction angle in degrees (in [0, 89])",
                io::Range::at_least(0.0).and_at_most(89.0));
    io.quantity("psi",
                s.dilatancy,
                "",
                "dilatancy angle in degrees (in [0, phi])",
                io::Range::at_least(0.0).and_at_most(89.0));
    io.quantity("tension_cutoff",
                s.tension_cutoff,
                "kPa",
                "largest principal stress (>= 0; at most c cot(phi))",
                io::Range::non_negative());
    io.quantity("K0",
                s.K0,
                "",
                "at-rest earth pressure coefficient sigma_h / sigma_v of the geostatic state "
                "(in [0, 3]; null: 1 - sin(phi), Jaky)",
                io::Range::at_least(0.0).and_at_most(3.0));
  }

  template <class Io>
  void visit(Io &io, FemReinforcement &s)
  {
    io.quantity("ratio_x",
                s.ratio_x,
                "%",
                "steel area / concrete area of the bars along x, the horizontal of the section "
                "(in [0, 10 %]; 0: none)",
                io::Range::at_least(0.0).and_at_most(0.1));
    io.quantity("ratio_y",
                s.ratio_y,
                "%",
                "steel area / concrete area of the bars along y, the vertical of the section "
                "(in [0, 10 %]; 0: none)",
                io::Range::at_least(0.0).and_at_most(0.1));
    io.quantity("f_y", s.f_y, "MPa", "steel yield stress (> 0; B500)", io::Range::positive());
    io.quantity("E_s", s.E_s, "GPa", "steel Young's modulus (> 0)", io::Range::positive());
    io.quantity("hardening",
                s.hardening,
                "",
                "post-yield (linear kinematic hardening) tangent / E_s (in [0, 1))",
                io::Range::at_least(0.0).and_less(1.0));
  }

  template <class Io>
  void visit(Io &io, FemConcrete &s)
  {
    visit(io, static_cast<FemMaterial &>(s));
    io.choice("model",
              s.model,
              {{"elastic", FemConcrete::Model::elastic},
               {"damage_plasticity", FemConcrete::Model::damage_plasticity}},
              "elastic (E, nu); damage_plasticity: tension/compression damage with crack band, "
              "parameters from f_cm by fib Model Code 2010 (E then = E_ci)");
    io.quantity("f_cm",
                s.f_cm,
                "MPa",
                "mean cylinder compressive strength (> 8 MPa)",
                io::Range::greater(8e6));
    io.quantity("f_ctm",
                s.f_ctm,
                "MPa",
                "mean tensile strength (> 0; null: MC2010 from f_cm)",
                io::Range::positive());
    io.quantity("G_F",
                s.fracture_energy,
                "N/m",
                "fracture energy (> 0; null: MC2010 73 f_cm^0.18)",
                io::Range::positive());
    io.quantity("strain_rate",
                s.strain_rate,
                "1",
                "strain rate (1/s) of the MC2010 dynamic increase factors (>= 0; 0: none)",
                io::Range::non_negative());
    io.quantity("plastic_fraction",
                s.plastic_fraction,
                "",
                "damage_plasticity: fraction b_c of the compressive inelastic strain that stays "
                "as plastic strain on unloading (in [0, 1); 0: secant unloading; Abaqus CDP "
                "calibrations ~0.7)",
                io::Range::at_least(0.0).and_less(1.0));
    io.section("wall_reinforcement",
               s.wall_reinforcement,
               "damage_plasticity: smeared, perfectly bonded steel bars of the wall (ratio_y: "
               "its vertical bars; ratio_x: ties through its thickness)");
    io.section("slab_reinforcement",
               s.slab_reinforcement,
               "damage_plasticity: smeared, perfectly bonded steel bars of the meshed slab "
               "(ratio_x: its bars along the impact; ratio_y: links through its thickness)");
  }

  template <class Io>
  void visit(Io &io, FemMaterials &s)
  {
    io.section("concrete", s.concrete, "slab and wall");
    io.section("soil", s.soil, "backfill");
  }

  template <class Io>
  void visit(Io &io, FemGeometry &s)
  {
    io.quantity("wall_thickness",
                s.wall_thickness,
                "m",
                "moat wall thickness (> 0)",
                io::Range::positive());
    io.flag("with_backfill", s.with_backfill, "soil block behind the wall, bonded to it");
    io.quantity("backfill_width", s.backfill_width, "m", "backfill width behind the wall (> 0)");
    io.quantity("backfill_height",
                s.backfill_height,
                "m",
                "backfill height (null: the wall height; must be <= the wall height)");
    io.quantity("slab_length", s.slab_length, "m", "slab length (> 0)", io::Range::positive());
    io.quantity("slab_thickness",
                s.slab_thickness,
                "m",
                "slab thickness (> 0)",
                io::Range::positive());
    io.quantity("slab_top",
                s.slab_top,
                "m",
                "height of the slab top above the ground (null: the wall top)");
    io.quantity("gap",
                s.gap,
                "mm",
                "initial clear distance between slab and wall (> 0)",
                io::Range::positive().because(
                  "the slab must not touch or overlap the wall at t = 0"));
  }

  template <class Io>
  void visit(Io &io, FemMesh &s)
  {
    io.quantity("h_contact",
                s.h_contact,
                "cm",
                "element size at the contact (> 0)",
                io::Range::positive());
    io.quantity("h_max", s.h_max, "cm", "largest element size (>= h_contact)");
    io.quantity("grading",
                s.grading,
                "",
                "largest size ratio of neighbouring elements (>= 1)",
                io::Range::at_least(1.0));
    io.integer("level", s.level, "refinement level: every element size divided by 2^level", 0, 6);
  }

  template <class Io>
  void visit(Io &io, FemSlab &s)
  {
    io.flag("rigid",
            s.rigid,
            "true: rigid slab (one translational DoF); false: meshed elastic concrete slab");
    io.quantity("mass",
                s.mass,
                "kg/m",
                "rigid slab mass per metre of wall (null: rho_concrete x slab length x "
                "thickness)",
                io::Range::positive());
    io.quantity("velocity",
                s.velocity,
                "m/s",
                "initial slab velocity toward the wall (> 0)",
                io::Range::positive().because("toward the wall"));
  }

  template <class Io>
  void visit(Io &io, FemContact &s)
  {
    io.quantity("penalty_factor",
                s.penalty_factor,
                "",
                "penalty stiffness per slave node / (E_master / h_contact x tributary length) "
                "(> 0)");
    io.quantity("contact_damping_ratio",
                s.contact_damping_ratio,
                "",
                "damping of each penalty spring as a fraction of critical (in [0, 1])");
    io.text("smoothing_window",
            s.smoothing_window,
            "width of the impulse-preserving moving average of the force: 'auto' (p-wave "
            "transit time across the contact) or a time, e.g. '0.05 ms' [s]");
  }

  template <class Io>
  void visit(Io &io, FemDynamics &s)
  {
    io.choice("integrator",
              s.integrator,
              {{"explicit", fem::ImpactParameters::Integrator::explicit_central_difference},
               {"implicit", fem::ImpactParameters::Integrator::implicit_newmark}},
              "explicit: central difference, lumped mass; implicit: Newmark average "
              "acceleration with Newton on the contact");
    io.text("dt",
            s.dt,
            "time step: 'auto' (explicit: cfl_safety x stable limit; implicit: "
            "implicit_dt_factor x explicit limit) or a time, e.g. '2e-6 s'; a dt above the "
            "explicit stability limit is refused [s]");
    io.quantity("cfl_safety", s.cfl_safety, "", "explicit dt / stable limit (in (0, 1])");
    io.quantity("implicit_dt_factor",
                s.implicit_dt_factor,
                "",
                "implicit dt / explicit stable limit when dt is auto (> 0)");
    io.choice("implicit_solver",
              s.implicit_solver,
              {{"direct", fem::ImplicitOptions::LinearSolver::direct},
               {"cg_amg", fem::ImplicitOptions::LinearSolver::cg_amg}},
              "implicit linear solver: direct (Amesos KLU, fastest up to ~1e5 DoFs) or cg_amg "
              "(CG with ML algebraic multigrid, for large meshes)");
    io.integer("implicit_max_halvings",
               s.implicit_max_halvings,
               "implicit: how often a step whose Newton iteration fails may be halved before "
               "the run stops with an error",
               0,
               30);
    io.integer("implicit_newton_max_iterations",
               s.implicit_newton_max_iterations,
               "implicit: Newton iterations per step before the step is halved",
               1,
               1000);
    io.quantity("end_time", s.end_time, "ms", "largest simulated time (> 0)");
    io.quantity("separation_hold_time",
                s.separation_hold_time,
                "ms",
                "stop once the slab has separated and the force stayed zero this long (>= 0)");
    io.quantity("output_interval",
                s.output_interval,
                "ms",
                "history sampling interval (>= 0; 0: every step)");
    io.integer("log_interval",
               s.log_interval,
               "history samples between log lines (shown with -v; 0: none)",
               0,
               1000000000);
    io.quantity("max_steps",
                s.max_steps,
                "",
                "step budget: a case of more estimated time steps (end_time / dt) is refused "
                "before it is meshed, with the estimate (DoFs, steps, time)",
                io::Range::at_least(1.0));
  }

  template <class Io>
  void visit(Io &io, FemOutput &s)
  {
    io.quantity("vtu_interval",
                s.vtu_interval,
                "ms",
                "interval of VTU field snapshots under DIR/vtu/<case>/ (>= 0; 0: none)",
                io::Range::non_negative());
    io.quantity("frame_interval",
                s.frame_interval,
                "ms",
                "interval of the deformed-mesh frames in fem.h5 (`frames`: mesh, displacements, "
                "von Mises and mean stress, damage and plastic strain), drawn as an animation by "
                "`kimp report` (>= 0; 0: none)",
                io::Range::non_negative());
  }

  template <class Io>
  void visit(Io &io, FemBoundary &s)
  {
    io.choice("far",
              s.far,
              {{"rollers", FemBoundary::Far::rollers}, {"absorbing", FemBoundary::Far::absorbing}},
              "soil far side and base: rollers (far side u_x = 0, base fixed: a finite block "
              "that reflects the waves) or absorbing (Lysmer-Kuhlemeyer dashpots rho c_p normal, "
              "rho c_s tangential on the soil's far side and base, for an unbounded backfill; "
              "the wall base stays fixed)");
  }

  template <class Io>
  void visit(Io &io, FemScene &s)
  {
    io.quantity_list("wall_heights",
                     s.wall_heights,
                     "m",
                     "moat wall heights H, one impact case each, named H<height in m>");
    io.section("geometry", s.geometry, "scene dimensions (docs/physics.md §4)");
    io.section("mesh", s.mesh, "bilinear quadrilateral mesh");
    io.section("materials", s.materials, "materials (linear elastic unless a model is chosen)");
    io.section("slab", s.slab, "the striking slab");
    io.section("contact", s.contact, "frictionless penalty contact slab front - wall face");
    io.section("dynamics", s.dynamics, "time integration");
    io.section("output", s.output, "field output");
    io.section("boundary", s.boundary, "boundary conditions of the backfill block");
    io.choice("geostatic",
              s.geostatic,
              {{"auto", FemGeostatic::auto_}, {"on", FemGeostatic::on}, {"off", FemGeostatic::off}},
              "gravity (not on the slab) and the at-rest stress sigma_v = gamma z, sigma_h = K0 "
              "sigma_v in the backfill, brought to static equilibrium before the impact; "
              "results are relative to that state. auto: on when the soil model is inelastic "
              "(a linear body's impact does not depend on the preload) or the wall-soil "
              "interface is a contact");
    io.section("interface", s.interface, "wall-soil interface");
  }

  /** Whether the case runs the geostatic step (FemScene::geostatic resolved). */
  bool geostatic_enabled(const FemScene &scene);

  /** True if the scene's concrete model, or its soil model with a backfill, is inelastic. */
  bool has_inelastic_materials(const FemScene &scene);

  /** Checks ranges and cross-field rules of every section, for every wall height. */
  void validate(const FemScene &scene, io::ValidationContext &context);

  /**
   * A time that may be "auto": std::nullopt for "auto", else the time in s.
   * @throws UnitError if @p text is neither "auto" nor a time with unit.
   */
  std::optional<double> parse_auto_time(const std::string &text);

  /** Case name of a wall height: "H1.25", "H2.00" (more digits only when needed). */
  std::string fem_case_name(double wall_height);

  /** Rigid slab: scene.slab.mass, else rho_concrete * slab_length * slab_thickness (kg/m).
   *  Elastic slab: the meshed slab's mass, rho_concrete * slab_length * slab_thickness. */
  double slab_mass(const FemScene &scene);

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
  concrete_material(const FemConcrete &concrete, const FemReinforcement &reinforcement);
  /** The law's steel parameters of a scene's reinforcement section. */
  fem::ReinforcementParameters reinforcement_parameters(const FemReinforcement &reinforcement);

  /** The meshing parameters of the case with wall height @p wall_height (mesh level applied). */
  geometry::SceneGeometry scene_geometry(const FemScene &scene, double wall_height);

  /**
   * The solver parameters of the case with wall height @p wall_height run on @p mesh_file
   * (written by geometry::build_scene_mesh(scene_geometry(scene, wall_height), ...)).
   * @param[in] vtu_dir field output directory, used only if scene.output.vtu_interval > 0
   */
  fem::ImpactParameters impact_parameters(const FemScene              &scene,
                                          double                       wall_height,
                                          const std::filesystem::path &mesh_file,
                                          const std::filesystem::path &vtu_dir = {});
} // namespace kimp::app
