// Scene of `kimp mesh` and `kimp fem`: the plane-strain slab-wall-backfill impact of
// docs/physics.md §4 (defaults = the §4 default scene), one case per wall height. The scene holds
// the engines' own parameter structs (geometry::SceneGeometry, fem::ImpactParameters) and visits
// them in place; scene_geometry() and impact_parameters() add what each case derives (its wall
// height, materials and laws, "auto" times, the rigid slab's mass and face, the interface and
// geostatic state).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/fem/fem_materials.h"
#include "app/laws/friction_key.h"
#include "app/step_budget.h"
#include "fem/impact.h"
#include "geometry/scene_geometry.h"
#include "io/scene_io.h"

namespace kimp::geometry
{
  /// Scene section `geometry`: the dimensions of the engine's SceneGeometry, visited in place
  /// (in its namespace so that the io readers find it by argument-dependent lookup). The wall
  /// height is the case parameter `wall_heights`, the element sizes are section `mesh`, mesh_slab
  /// and interface_contact follow from slab.rigid and interface.model.
  template <class Io>
  void visit(Io &io, SceneGeometry &s)
  {
    io.quantity("wall_thickness",
                s.wall_thickness,
                "m",
                "moat wall thickness",
                io::Range::plausible(0.02, 5.0, "a moat wall"));
    io.flag("with_backfill", s.with_backfill, "soil block behind the wall, bonded to it");
    io.quantity("backfill_width",
                s.backfill_width,
                "m",
                "backfill width behind the wall",
                io::Range::plausible(0.1, 100.0, "a backfill block"));
    io.quantity("backfill_height",
                s.backfill_height,
                "m",
                "backfill height (null: the wall height; must be <= the wall height)",
                io::Range::plausible(0.01, 20.0, "a backfill behind a moat wall"));
    io.quantity("slab_length",
                s.slab_length,
                "m",
                "slab length",
                io::Range::plausible(0.1, 500.0, "a building's slab"));
    io.quantity("slab_thickness",
                s.slab_thickness,
                "m",
                "slab thickness",
                io::Range::plausible(0.02, 5.0, "a building's slab"));
    io.quantity("slab_top",
                s.slab_top,
                "m",
                "height of the slab top above the ground (null: the wall top)",
                io::Range::plausible(0.01, 20.0, "a slab beside a moat wall"));
    io.quantity("gap",
                s.gap,
                "mm",
                "initial clear distance between slab and wall",
                io::Range::positive().and_at_most(1.0).because(
                  "the slab must not touch or overlap the wall at t = 0, and a moat gap is not "
                  "wider"));
  }
} // namespace kimp::geometry

namespace kimp::fem
{
  /// The explicit integrator's key of section `dynamics` (fem::ExplicitOptions in place).
  template <class Io>
  void visit(Io &io, ExplicitOptions &s)
  {
    io.quantity("cfl_safety",
                s.cfl_safety,
                "",
                "explicit dt / stable limit",
                io::Range::greater(0.0).and_at_most(1.0));
  }

  /// The implicit integrator's keys of section `dynamics` (fem::ImplicitOptions in place).
  template <class Io>
  void visit(Io &io, ImplicitOptions &s)
  {
    io.quantity("implicit_dt_factor",
                s.dt_factor,
                "",
                "implicit dt / explicit stable limit when dt is auto",
                io::Range::positive());
    io.choice("implicit_solver",
              s.linear_solver,
              {{"direct", ImplicitOptions::LinearSolver::direct},
               {"cg_amg", ImplicitOptions::LinearSolver::cg_amg}},
              "implicit linear solver: direct (Amesos KLU, fastest up to ~1e5 DoFs) or cg_amg "
              "(CG with ML algebraic multigrid, for large meshes)");
    io.integer("implicit_max_halvings",
               s.max_halvings,
               "implicit: how often a step whose Newton iteration fails may be halved before "
               "the run stops with an error",
               0,
               30);
    io.integer("implicit_newton_max_iterations",
               s.newton_max_iterations,
               "implicit: Newton iterations per step before the step is halved",
               1,
               1000);
  }
} // namespace kimp::fem

namespace kimp::app
{
  /// The heights of a moat wall kimp accepts (a height outside is refused as implausible), m.
  inline io::Range moat_wall_height_range()
  {
    return io::Range::plausible(0.1, 20.0, "a moat wall");
  }

  /// An output interval key: the time between two samples or snapshots a run writes (shown in ms,
  /// >= 0); `doc` says of what and what 0 means.
  template <class Io>
  void visit_output_interval(Io &io, std::string_view key, double &interval, std::string_view doc)
  {
    io.quantity(key, interval, "ms", doc, io::Range::non_negative());
  }

  /// The sizes a contact element may have (mesh.h_contact and the studies' mesh levels), m.
  inline io::Range contact_element_range()
  {
    return io::Range::plausible(1e-6, 1.0, "a contact element");
  }

  /** Field output of `kimp fem` (the study records neither). */
  struct FemOutput
  {
    double vtu_interval = 0; ///< s between VTU snapshots under DIR/vtu/<case>/ (0: none)
    /// s between the deformed-mesh frames of fem.h5 (`frames`, the report's animation; 0: none)
    double frame_interval = 1e-3;
  };

  template <class Io>
  void visit(Io &io, FemOutput &s)
  {
    visit_output_interval(io,
                          "vtu_interval",
                          s.vtu_interval,
                          "interval of VTU field snapshots under DIR/vtu/<case>/ (0: none)");
    visit_output_interval(io,
                          "frame_interval",
                          s.frame_interval,
                          "interval of the deformed-mesh frames in fem.h5 (`frames`: mesh, "
                          "displacements, von Mises and mean stress, damage and plastic strain), "
                          "drawn as an animation by `kimp report` (0: none)");
  }

  /** Boundary conditions of the backfill block (docs/physics.md §6). */
  struct FemBoundary
  {
    /** What ends the model's soil at its far side and base. */
    enum class Far
    {
      rollers,       ///< far side u_x = 0, base u = 0 (the thesis' finite block)
      absorbing,     ///< Lysmer-Kuhlemeyer dashpots rho c_p (normal), rho c_s (tangential)
      viscous_spring ///< the dashpots with springs alpha G / R beside them
    };
    Far far = Far::rollers;
    /// viscous_spring: alpha_n and alpha_t of the springs alpha G / R (null: 1.0 and 0.5).
    std::optional<double> spring_normal, spring_tangential;
  };

  /// alpha_n and alpha_t of the viscous-spring boundary when the scene does not give them (the
  /// two-dimensional values of docs/physics.md §6 "Viscous-spring boundary").
  inline constexpr double default_spring_normal = 1.0, default_spring_tangential = 0.5;

  /// The scene's word for a far side (`boundary.far`), as logs, labels and errors print it.
  inline const char *far_boundary_name(const FemBoundary::Far far)
  {
    switch (far)
    {
      case FemBoundary::Far::rollers:
        return "rollers";
      case FemBoundary::Far::absorbing:
        return "absorbing";
      case FemBoundary::Far::viscous_spring:
        return "viscous_spring";
    }
    return "?";
  }

  template <class Io>
  void visit(Io &io, FemBoundary &s)
  {
    io.choice("far",
              s.far,
              {{far_boundary_name(FemBoundary::Far::rollers), FemBoundary::Far::rollers},
               {far_boundary_name(FemBoundary::Far::absorbing), FemBoundary::Far::absorbing},
               {far_boundary_name(FemBoundary::Far::viscous_spring),
                FemBoundary::Far::viscous_spring}},
              "soil far side and base: rollers (far side u_x = 0, base fixed: a finite block "
              "that reflects the waves), absorbing (Lysmer-Kuhlemeyer dashpots rho c_p normal, "
              "rho c_s tangential on the soil's far side and base, for an unbounded backfill; "
              "the wall base stays fixed) or viscous_spring (those dashpots with springs "
              "alpha G / R beside them, R the distance to the contact band's centre: an "
              "unbounded backfill that also holds a permanent displacement)");
    io.quantity("spring_normal",
                s.spring_normal,
                "",
                "viscous_spring: alpha_n of the normal springs alpha_n G / R (null: 1.0)",
                io::Range::positive().and_at_most(4.0));
    io.quantity("spring_tangential",
                s.spring_tangential,
                "",
                "viscous_spring: alpha_t of the tangential springs alpha_t G / R (null: 0.5)",
                io::Range::positive().and_at_most(4.0));
  }

  /** Wall-soil interface (docs/physics.md §6 "Wall-soil interface"); its penalty factor is
   *  fem::InterfaceOptions::penalty_factor (FemScene::solver). */
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
  };

  /** Section `pushover`: the static pushover of `kimp fem --pushover` (docs/guide/fem.md). */
  struct FemPushover
  {
    std::optional<double> displacement;     ///< m; default 5 % of the wall height
    std::vector<double>   unload_at;        ///< m: push to each, unload to zero force, go on
    double                increment = 1e-3; ///< largest band displacement step, m
    double                cover     = 0.05; ///< bar centre to the wall face, m
    std::optional<double> hinge_length;     ///< L_p, m; default none (per-cell hardening)
  };

  template <class Io>
  void visit(Io &io, FemPushover &s)
  {
    io.quantity("displacement",
                s.displacement,
                "mm",
                "largest band displacement of the push (null: 5 % of the wall height)",
                io::Range::positive());
    io.quantity_list("unload_at",
                     s.unload_at,
                     "mm",
                     "cyclic push: band displacements at which the push unloads to zero force "
                     "and reloads (increasing, below displacement; empty: monotonic)",
                     io::Range::positive());
    io.quantity("increment",
                s.increment,
                "mm",
                "largest band displacement step",
                io::Range::positive());
    io.quantity("cover",
                s.cover,
                "mm",
                "damage_plasticity: distance of the wall's vertical bars from each face; ratio_y "
                "of wall_reinforcement is the whole section's, half at each face",
                io::Range::positive());
    io.quantity("hinge_length",
                s.hinge_length,
                "m",
                "plastic hinge length L_p over which a yielding bar's hardening is spread "
                "(null: none, each cell hardens by its own strain, which converges where the "
                "moment gradient spreads the yielding over several rows)",
                io::Range::positive());
  }

  /** Geostatic initial state before the impact (docs/physics.md §6). */
  enum class FemGeostatic
  {
    auto_, ///< on when the backfill's law is inelastic
    on,
    off
  };

  /** The solver options of the FEM scene: fem::ImpactParameters' defaults, with a log line every
   *  100 history samples. */
  fem::ImpactParameters default_fem_solver();

  /**
   * The FEM scene: one impact per entry of wall_heights (case name fem_case_name(H), "H1.25").
   * Load with read_scene<FemScene>(file), which validates.
   */
  struct FemScene
  {
    std::vector<double> wall_heights{geometry::SceneGeometry().wall_height}; ///< m
    /// Sections `geometry` (dimensions) and `mesh` (h_contact, h_max, grading); its wall_height,
    /// mesh_slab and interface_contact are set per case by scene_geometry().
    geometry::SceneGeometry geometry;
    int                     mesh_level = 0; ///< mesh.level: element sizes divided by 2^level
    FemMaterials            materials;
    /// slab.mass: rigid slab only, kg per metre of wall; default rho_concrete * slab_length *
    /// slab_thickness.
    std::optional<double> rigid_slab_mass;
    /// The solver options written in sections `slab` (rigid, velocity), `contact`, `dynamics`
    /// and `interface` (penalty_factor); impact_parameters() sets the rest per case.
    fem::ImpactParameters solver = default_fem_solver();
    /// contact.smoothing_window: "auto" (p-wave transit time across the contact) or a time.
    std::string smoothing_window = "auto";
    /// dynamics.dt: "auto" (cfl_safety x stable limit; implicit: implicit_dt_factor x limit)
    /// or a time.
    std::string dt = "auto";
    /// dynamics.max_steps: a case whose estimated steps (end_time / dt) exceed it is refused
    /// before it is meshed (app/fem/fem_estimate.h).
    double       max_steps = 1e6;
    FemOutput    output;
    FemBoundary  boundary;
    FemGeostatic geostatic = FemGeostatic::auto_;
    FemInterface interface;
    FemPushover  pushover;
  };

  /// Section `mesh`: the element sizes of FemScene::geometry and the refinement level.
  inline constexpr auto visit_fem_mesh = [](auto &io, FemScene &s)
  {
    io.quantity("h_contact",
                s.geometry.h_contact,
                "cm",
                "element size at the contact",
                contact_element_range());
    io.quantity("h_max",
                s.geometry.h_max,
                "cm",
                "largest element size (>= h_contact)",
                io::Range::plausible(1e-6, 10.0, "an element of a moat wall model"));
    io.quantity("grading",
                s.geometry.grading,
                "",
                "largest size ratio of neighbouring elements",
                io::Range::at_least(1.0));
    io.quantity("wall_aspect_max",
                s.geometry.wall_aspect_max,
                "",
                "largest height/width of the wall's cells (and the backfill rows beside them); "
                "null: 1 with inelastic concrete (plain Q1 cells taller than wide lock in "
                "bending once the wall cracks), else the rows grow to h_max",
                io::Range::at_least(1.0).and_at_most(20.0));
    io.integer("level",
               s.mesh_level,
               "refinement level: every element size divided by 2^level",
               0,
               6);
  };

  /// Section `slab`: fem::ImpactParameters' rigid_slab and initial_velocity, and the rigid mass.
  inline constexpr auto visit_fem_slab = [](auto &io, FemScene &s)
  {
    io.flag("rigid",
            s.solver.rigid_slab,
            "true: rigid slab (one translational DoF); false: meshed elastic concrete slab");
    io.quantity("mass",
                s.rigid_slab_mass,
                "kg/m",
                "rigid slab mass per metre of wall (null: rho_concrete x slab length x "
                "thickness)",
                io::Range::positive());
    io.quantity("damping_ratio",
                s.solver.slab_damping_ratio,
                "",
                "elastic slab: damping of its axial vibration as a fraction of critical at its "
                "first free-free axial mode (mass-proportional, relative to the plane sections' "
                "motion; 0: undamped)",
                io::Range::at_least(0.0).and_at_most(1.0));
    io.quantity("velocity",
                s.solver.initial_velocity,
                "m/s",
                "initial slab velocity toward the wall",
                io::Range::positive().because("toward the wall"));
  };

  /// Section `contact`: fem::ImpactParameters' penalty contact and the force smoothing.
  inline constexpr auto visit_fem_contact = [](auto &io, FemScene &s)
  {
    io.quantity("penalty_factor",
                s.solver.penalty_factor,
                "",
                "penalty stiffness per slave node / (E_master / h_contact x tributary length)",
                io::Range::positive());
    io.quantity("penalty_step_ratio",
                s.solver.penalty_step_ratio,
                "",
                "0: off; in (0, 1): penalty_factor replaced by the penalty whose springs (with "
                "their damping) leave the explicit stable step at this fraction of the mesh's own",
                io::Range::at_least(0.0).and_less(1.0));
    io.integer("subcycles",
               s.solver.contact_subcycles,
               "contact sub-cycling (explicit only): 1 off; N >= 2 penalty sub-steps per mesh "
               "step, whose step is then the mesh's own; 0 automatic (the fewest sub-steps not "
               "longer than the step without sub-cycling)",
               0,
               64);
    io.quantity("contact_damping_ratio",
                s.solver.contact_damping_ratio,
                "",
                "damping of each penalty spring as a fraction of critical",
                io::Range::at_least(0.0).and_at_most(1.0));
    io.quantity_text("smoothing_window",
                     s.smoothing_window,
                     "ms",
                     "width of the impulse-preserving moving average of the force: 'auto' (p-wave "
                     "transit time across the contact) or a time, e.g. '0.05 ms'",
                     io::Range::plausible(1e-9, 1.0, "a force smoothing window"));
  };

  /// Section `dynamics`: fem::ImpactParameters' integrator, times and log, its explicit and
  /// implicit options, and the time step.
  inline constexpr auto visit_fem_dynamics = [](auto &io, FemScene &s)
  {
    io.choice("integrator",
              s.solver.integrator,
              {{"explicit", fem::ImpactParameters::Integrator::explicit_central_difference},
               {"implicit", fem::ImpactParameters::Integrator::implicit_newmark}},
              "explicit: central difference, lumped mass; implicit: Newmark average "
              "acceleration with Newton on the contact");
    io.quantity_text("dt",
                     s.dt,
                     "s",
                     "time step: 'auto' (explicit: cfl_safety x stable limit; implicit: "
                     "implicit_dt_factor x explicit limit) or a time, e.g. '2e-6 s'; a dt above "
                     "the explicit stability limit is refused",
                     io::Range::plausible(1e-10, 0.01, "an FEM impact time step"));
    visit(io, s.solver.explicit_options);
    visit(io, s.solver.implicit_options);
    io.quantity("end_time",
                s.solver.end_time,
                "ms",
                "largest simulated time",
                io::Range::positive());
    io.quantity("separation_hold_time",
                s.solver.separation_hold_time,
                "ms",
                "stop once the slab has separated and the force stayed zero this long",
                io::Range::non_negative());
    visit_output_interval(io,
                          "output_interval",
                          s.solver.output_interval,
                          "history sampling interval (0: every step)");
    io.quantity("bar_gauge_length",
                s.solver.bar_gauge_length,
                "cm",
                "reinforced wall: the gauge length over which the vertical bars' strain is "
                "averaged for max_bar_gauge_strain_ratio (0: half the wall's thickness, Park and "
                "Paulay's plastic hinge length)",
                io::Range::non_negative());
    io.integer("log_interval",
               s.solver.log_interval,
               "history samples between log lines (shown with -v; 0: none)",
               0,
               1000000000);
    visit_max_steps(io,
                    s.max_steps,
                    "step budget: a case of more estimated time steps (end_time / dt) is refused "
                    "before it is meshed, with the estimate (DoFs, steps, time)");
  };

  /// Section `interface`: the model, its friction and fem::InterfaceOptions::penalty_factor.
  inline constexpr auto visit_fem_interface = [](auto &io, FemScene &s)
  {
    io.choice("model",
              s.interface.model,
              {{"bonded", FemInterface::Model::bonded}, {"contact", FemInterface::Model::contact}},
              "bonded: wall and backfill share their nodes; contact: unilateral frictional "
              "penalty contact between wall back and backfill (explicit integrator), closed by "
              "the geostatic earth pressure, free to open");
    visit_friction(io,
                   s.interface.friction,
                   "contact: Coulomb friction coefficient mu (null: tan(2 phi / 3))");
    io.quantity("penalty_factor",
                s.solver.wall_soil_interface.penalty_factor,
                "",
                "contact: normal and tangential penalty per node pair / (E_soil / h x tributary "
                "length)",
                io::Range::positive());
  };

  template <class Io>
  void visit(Io &io, FemScene &s)
  {
    io.quantity_list("wall_heights",
                     s.wall_heights,
                     "m",
                     "moat wall heights H, one impact case each, named H<height in m>",
                     moat_wall_height_range());
    io.section("geometry", s.geometry, "scene dimensions (docs/physics.md §4)");
    io.section("mesh", s, "bilinear quadrilateral mesh", visit_fem_mesh);
    io.section("materials", s.materials, "materials (linear elastic unless a model is chosen)");
    io.section("slab", s, "the striking slab", visit_fem_slab);
    io.section("contact",
               s,
               "frictionless penalty contact slab front - wall face",
               visit_fem_contact);
    io.section("dynamics", s, "time integration", visit_fem_dynamics);
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
    io.section("interface", s, "wall-soil interface", visit_fem_interface);
    io.section("pushover",
               s.pushover,
               "static pushover of wall and backfill (kimp fem --pushover)");
  }

  /** Whether the case runs the geostatic step (FemScene::geostatic resolved). */
  bool geostatic_enabled(const FemScene &scene);

  /** True if the scene's concrete model, or its soil model with a backfill, is inelastic. */
  bool has_inelastic_materials(const FemScene &scene);

  /** Rules that link several keys, for every wall height (single-key ranges are declared in
   *  visit()). */
  void validate(const FemScene &scene, io::ValidationContext &context);

  /**
   * A time that may be "auto": std::nullopt for "auto", else the time in s.
   * @throws UnitError if @p text is neither "auto" nor a time with unit.
   */
  std::optional<double> parse_auto_time(const std::string &text);

  /** Case name of a wall height: "H1.25", "H2.00" (more digits only when needed). */
  std::string fem_case_name(double wall_height);

  /** Rigid slab: slab.mass, else rho_concrete * slab_length * slab_thickness (kg/m).
   *  Elastic slab: the meshed slab's mass, rho_concrete * slab_length * slab_thickness. */
  double slab_mass(const FemScene &scene);

  /**
   * mesh.wall_aspect_max where the scene leaves it null and its concrete is inelastic: square
   * wall cells. Plain Q1 cells several times taller than wide lock in bending once the wall
   * cracks (the graded 5 -> 25 cm mesh doubled the reinforced wall's resistance,
   * docs/validation.md "What the dynamic FEM's wall resists"); elastic concrete keeps the graded
   * rows, so linear results do not change.
   */
  inline constexpr double inelastic_wall_aspect_max = 1.0;

  /** The meshing parameters of the case with wall height @p wall_height (mesh level applied;
   *  wall_aspect_max = inelastic_wall_aspect_max where the scene leaves it null and its concrete
   *  is inelastic). */
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
