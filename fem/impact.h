// Plane-strain slab-wall impact: rho u_tt = div sigma(u), sigma = C : eps(u), with frictionless
// node-to-segment penalty contact between the slab front face and the wall face (docs/physics.md
// §4). Light public header: plain structs and functions, no deal.II includes.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mpi.h>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/material.h"
#include "fem/numerical_error.h"

namespace kimp::fem
{
  class MaterialLaw; // fem/material_law.h

  /** P-wave speed of a plane-strain continuum, sqrt((lambda + 2 mu) / rho), m/s. */
  double p_wave_speed(const Material &material);

  /**
   * omega_p / omega_mesh at which the damped explicit stable step of mesh and penalty together,
   * 2 / omega (sqrt(1 + xi^2) - xi) with omega^2 = omega_mesh^2 + omega_p^2 and
   * xi = damping_ratio omega_p / omega, is `step_ratio` times the mesh's own 2 / omega_mesh
   * (step_ratio in (0, 1), damping_ratio >= 0; the ratio falls monotonically in omega_p).
   */
  double penalty_omega_ratio_for_step(double step_ratio, double damping_ratio);

  /**
   * Contact sub-cycling (ImpactParameters::contact_subcycles), its stability limit
   * min(subcycle_mesh_fraction 2 / omega_mesh, subcycle_phase_limit / omega_p): the largest
   * phase omega_p dt of the penalty over one mesh step, and the fraction of the cells' own limit,
   * that the impulse scheme keeps stable (docs/physics.md §4: the amplification matrix of two
   * bars in contact, 2-4 sub-steps, contact damping 0 and 0.5, omega_p / omega_mesh 0.3-3).
   */
  inline constexpr double subcycle_phase_limit   = 1.75;
  inline constexpr double subcycle_mesh_fraction = 0.95;
  /** Step of mesh and contact with the contact sub-cycled, its stability limit (s) and the
   *  sub-steps per step. */
  struct SubcycledStep
  {
    double       limit    = 0; ///< as at subcycle_phase_limit
    unsigned int substeps = 1;
  };
  /**
   * The sub-cycled step's limit for the cells' omega_mesh and the penalty's omega_penalty
   * (rad/s), and its sub-steps: `subcycles` if >= 2, else (0, automatic) the fewest whose
   * sub-step of the limit is not above dt_stable, the limit of mesh and damped penalty together
   * (ceil(limit / dt_stable), at least 2).
   */
  SubcycledStep
  subcycled_step(double omega_mesh, double omega_penalty, double dt_stable, unsigned int subcycles);

  /** Options of the explicit central-difference integrator (ImpactParameters::explicit_options). */
  struct ExplicitOptions
  {
    /**
     * Time step as a fraction of the stable limit 2 / omega_max (mesh + penalty) when
     * ImpactParameters::dt == 0, in (0, 1].
     */
    double cfl_safety = 0.8;
    /**
     * For stability studies: if > 0, dt = dt_over_limit * the stable limit, also above it (no
     * refusal); a run that then diverges stops with NumericalError as always. Requires
     * ImpactParameters::dt == 0 (>= 0; 0: off).
     */
    double dt_over_limit = 0;
  };

  /**
   * Options of the implicit Newmark integrator (average acceleration, beta = 1/4, gamma = 1/2,
   * Newton on the contact; ImpactParameters::implicit_options).
   */
  struct ImplicitOptions
  {
    /** Linear solver of the Newton iterations. */
    enum class LinearSolver
    {
      /** Amesos KLU factorization of K + M / (beta dt^2), once per step size; the contact
       *  tangent (rank <= active slave nodes) enters by the Woodbury identity. */
      direct,
      /** CG with an ML algebraic multigrid preconditioner built once per step size on
       *  K + M / (beta dt^2), applied to the matrix with the contact tangent. */
      cg_amg
    };

    /** dt = dt_factor * the stable explicit limit when ImpactParameters::dt == 0 (> 0). */
    double       dt_factor     = 4.0;
    LinearSolver linear_solver = LinearSolver::direct;
    /**
     * A step whose Newton iteration does not converge is retried with half the step, at most
     * this many times (dt floor = dt / 2^max_halvings); at the floor NumericalError is thrown.
     * The substeps then grow back to dt (>= 0).
     */
    unsigned int max_halvings = 6;
    /** Newton iterations per attempt of a step before it is halved (> 0). */
    unsigned int newton_max_iterations = 30;
  };

  /**
   * Geostatic initial state (ImpactParameters::geostatic): gravity on every body but the slab
   * (which rides on its isolators), an initial stress sigma_v = -gamma z, sigma_h = sigma_zz =
   * K0 sigma_v (tension positive, z depth below the top of the material's cells, gamma = rho g)
   * in the materials of initial_stress_K0, and a static equilibrium step before the impact
   * (docs/physics.md §6 "Geostatic initial state"). The impact starts from that state; reported
   * displacements, indentation and dissipation are relative to it.
   */
  struct GeostaticOptions
  {
    bool   enabled = false;   ///< false: no gravity, stress-free start (the default)
    double gravity = 9.80665; ///< g, m/s^2 (standard gravity), acting in -y (> 0)
    /** K0 = sigma_h / sigma_v per material id carrying an initial stress (>= 0). */
    std::map<unsigned int, double> initial_stress_K0;
    /** Largest out-of-balance force after the static step, as a fraction of the weight of the
     *  materials of initial_stress_K0 (or of all weight without them) (> 0). */
    double tolerance = 1e-8;
    /** Iterations of the static step (modified Newton, then the consistent tangent) before
     *  NumericalError (> 0). */
    unsigned int max_iterations = 200;
  };

  /**
   * Wall-soil interface (ImpactParameters::wall_soil_interface). Bonded: the mesh shares the
   * nodes. Contact: the mesh has separate wall_back and soil_front faces (geometry/scene_ids.h)
   * whose nodes coincide in pairs, joined by a unilateral Coulomb penalty interface
   * (fem/frictional_interface.h): closed by the geostatic earth pressure, free to open. Explicit
   * integrator only.
   */
  struct InterfaceOptions
  {
    bool   contact  = false; ///< false: bonded (shared nodes)
    double friction = 0.5;   ///< Coulomb mu (>= 0)
    /** k_N = penalty_factor * E_soil / h * l_i per pair (h: shortest interface segment, l_i:
     *  tributary length); k_T = k_N (> 0). */
    double penalty_factor = 1.0;
  };

  /**
   * Everything run_impact() needs: the options common to both integrators, and one set of
   * options per integrator (those of the integrator not chosen are ignored). Mesh ids follow
   * geometry/scene_ids.h.
   */
  struct ImpactParameters
  {
    /** Time integrator; each has its own options below. */
    enum class Integrator
    {
      explicit_central_difference, ///< leap-frog with a Gauss-Lobatto lumped mass (default)
      implicit_newmark ///< average acceleration (beta = 1/4, gamma = 1/2), Newton on the contact
    };

    /** ASCII MSH file (4.1 or 2.2) with material ids and boundary ids of scene_ids.h. */
    std::filesystem::path mesh_file;
    /** Material per material id; every id present in the mesh must be given. */
    std::map<unsigned int, Material> materials;
    /**
     * Optional constitutive law per material id replacing the linear elastic law of materials
     * (which still gives the density, the wave speed of the time-step limit and the penalty
     * scale). A law that is not MaterialLaw::is_linear() makes the internal force assembled from
     * its stress at every quadrature point, with the history committed once per accepted step;
     * the implicit Newton matrix then stays the law's tangent at zero strain (modified Newton).
     */
    std::map<unsigned int, std::shared_ptr<const MaterialLaw>> material_laws;
    /**
     * Non-linear laws: evaluate the internal force by a deal.II FEValues loop over the cells at
     * every step instead of the kernel precomputed once (same numbers, slower): the kernel's
     * reference in tests.
     */
    bool reference_internal_force = false;
    /**
     * Mean-dilatation B-bar (Q1/P0, as the static solver's StaticPlasticityParameters::bbar) in
     * the soil cells of a law that is not MaterialLaw::is_linear(): their volumetric strain is
     * the cell mean, so that near-isochoric plastic flow does not lock the Q1 element
     * (docs/physics.md §6). false: the plain Q1 strain everywhere (comparison runs).
     */
    bool mean_dilatation = true;

    /**
     * Rigid slab: the slab is one translational DoF of mass slab_mass (kg per metre of depth)
     * whose front face is the line x = slab_front_x + u, y in [slab_face_y0, slab_face_y1]; slab
     * cells in the mesh (material id slab_material), if any, are ignored. The wall-face nodes are
     * then the slave points and the rigid face is the master. Elastic slab: the slab is meshed,
     * its front-face nodes are the slave points, the wall-face segments the master.
     */
    bool   rigid_slab   = false;
    double slab_mass    = 0; ///< kg/m, rigid slab only (> 0)
    double slab_face_y0 = 0; ///< m, rigid slab only
    double slab_face_y1 = 0; ///< m, rigid slab only (> slab_face_y0)
    double slab_front_x = 0; ///< m, rigid slab only: x of the front face at t = 0

    /**
     * Elastic slab, explicit integrator only: damping of the slab's axial vibration, as a
     * fraction of critical at its first free-free axial mode omega_1 = pi c / L (c = sqrt(E /
     * (rho (1 - nu^2))) of the slab's Material, L the slab's length in x). Each slab node's x
     * velocity is damped by alpha m_i (v_i - v_plane(y_i)), alpha = 2 ratio omega_1, where
     * v_plane(y) = V + w (y - y_c) is the mass-weighted least-squares fit of the slab's x
     * velocities (the plane sections' motion): the slab's momentum and angular momentum and its
     * bending's transverse motion are not damped, and axial mode n keeps ratio omega_1 /
     * omega_n of it (mass-proportional). It stands for the damping of a concrete slab that an
     * undamped elastic slab lacks: without it the slab rings after the first pulse and makes
     * and breaks the contact in the rebound (docs/physics.md §4). Its work is
     * ImpactHistory::slab_damping. 0 (the default): undamped. In [0, 1].
     */
    double slab_damping_ratio = 0;

    double initial_velocity = 1.0; ///< m/s, slab, +x (> 0)
    /**
     * Wave-propagation checks only: the elastic slab starts moving in +y instead of +x (a
     * velocity pulse in a column of which the slab cells are a bonded part). No contact then
     * occurs unless the mesh places one; the slab histories (x means) stay zero.
     */
    bool initial_velocity_along_y = false;

    /**
     * Lysmer-Kuhlemeyer absorbing boundary (docs/physics.md §6): boundary ids whose faces on
     * soil cells (material id geometry::soil_material) carry viscous dashpots instead of their
     * constraint; faces of other cells keep it (the wall base stays clamped). Per unit area the
     * dashpots are rho c_p normal and rho c_s tangential to the face (c_p, c_s of the soil's
     * Material), lumped to the face's two nodes by the trapezoidal rule, so C is diagonal; faces
     * must be axis-parallel. Allowed ids: geometry::fixed_base and geometry::soil_far_side.
     * Empty (default): fixed base and rollers. The dashpots leave the explicit stability limit
     * unchanged (they enter at the full step, implicitly in the velocity); their work is the
     * radiated energy of the energy balance. With a geostatic state the static step holds
     * these faces as the rollers do and their reactions are applied as constant forces after it,
     * so the dynamic step starts in equilibrium.
     */
    std::vector<unsigned int> absorbing_boundaries;

    /**
     * Viscous-spring boundary (docs/physics.md §6 "Viscous-spring boundary"; Deeks & Randolph,
     * J. Eng. Mech. 120, 1994; Liu et al., Earthq. Eng. Eng. Vib. 5, 2006): springs beside the
     * dashpots of absorbing_boundaries, per unit area alpha_n G / R normal and alpha_t G / R
     * tangential to the face, G the soil's shear modulus and R the distance from the face's
     * midpoint to the contact band's centre (the waves' source). Lumped to the face's nodes as
     * the dashpots are, they hold the displacement the time loop starts from (the geostatic
     * state): a residual thrust then settles the far field at a finite displacement instead of
     * drifting through the dashpots. Their energy is stored (ImpactHistory::boundary_springs).
     * 0 and 0 (default): the dashpots alone. Both >= 0; either > 0 needs absorbing_boundaries.
     */
    double boundary_spring_normal = 0, boundary_spring_tangential = 0;

    /**
     * Penalty stiffness per slave node: k_i = penalty_factor * E_master / h_contact * l_i (N/m per
     * metre of depth), with l_i the node's tributary face length and h_contact the smallest
     * contact-face segment length. Factor 1 makes the contact spring as stiff as one element;
     * integral results and the plateau force are converged to < 1 % there (tests/fem).
     */
    double penalty_factor = 1.0;
    /**
     * If > 0: the penalty scaled to the mesh's stable step. penalty_factor is replaced by the
     * factor whose springs (with their contact damping) leave the explicit stable step at this
     * fraction of the cells' own limit 2 / omega_mesh (the wall-soil interface springs not
     * counted), so the stiffest penalty the mesh's step affords; the factor used is
     * ImpactSummary::penalty_factor. 0 (the default): off. In [0, 1).
     */
    double penalty_step_ratio = 0;
    /**
     * Contact sub-cycling (explicit only; docs/physics.md §4): 1 (the default) off; N >= 2 the
     * contact nodes (slave and master face nodes, and the rigid slab) advance their penalty
     * interaction in N sub-steps dt / N per mesh step, their internal force applied as the mesh
     * step's impulse (a multiple-time-step "impulse" scheme), so that dt is the mesh's own step
     * min(2 / omega_mesh, subcycle_phase_limit / omega_p) times the safety; 0: automatic, the
     * fewest sub-steps whose step is not above the step without sub-cycling. In [0, 64].
     */
    unsigned int contact_subcycles = 1;
    /**
     * Contact damping as a fraction of the critical damping of each penalty spring with its
     * reduced node mass, c_i = 2 xi sqrt(k_i m_i). It removes the penalty-spring chatter; its
     * dissipation vanishes as 1/sqrt(k) when the penalty grows and is reported in the history.
     * Explicit only: the implicit path uses no contact damping (Newton needs a residual without
     * the dashpot's jump at first touch), but its automatic dt scales the explicit stability
     * limit, which this damping lowers.
     */
    double contact_damping_ratio = 0.5;
    /**
     * Width (s) of the impulse-preserving centred moving average of the reported force; 0 (the
     * default): the p-wave transit time across the contact width, w / c_p (w = slave face length,
     * c_p of the wall material; 54 us for the default scene). Force features shorter than that
     * are contact chatter, not resolved physics; the time scale does not depend on the mesh or
     * the penalty, so the smoothed peak converges in both (>= 0).
     */
    double smoothing_window = 0;

    /**
     * s; 0: automatic (explicit: ExplicitOptions::cfl_safety or dt_over_limit times the stable
     * limit; implicit: ImplicitOptions::dt_factor times the explicit limit). An explicit dt above
     * the limit is refused (>= 0).
     */
    double dt = 0;

    double end_time = 0.05; ///< s (> 0)
    /**
     * s: the run stops once the force stayed zero this long and the slab moves in at no more than
     * separation_velocity_fraction of the impact velocity (>= 0).
     */
    double separation_hold_time = 1.0e-3;
    /**
     * A slab still moving in faster than this fraction of the impact velocity has not separated:
     * a yielding wall, or a wall face springing ahead of a rigid slab, opens gaps while the slab
     * still comes. Above zero so that a slab that hands on all its momentum (equal bars) and
     * rests at round-off speed counts as separated. In [0, 1).
     */
    double separation_velocity_fraction = 0.05;
    /**
     * The stop sees the whole system: a run ends on separation only once the energy still
     * stored in wall and soil (their recoverable strain energy and kinetic energy, less the
     * kinetic energy of their mean translation, relative to the geostatic state) has come back
     * to at most this fraction of E_0, or the slab rebounds (rebound_velocity_fraction);
     * otherwise it goes on, and a run that reaches end_time is reported truncated with the share
     * still stored (ImpactSummary::stored_energy_share). In (0, 1]; 1: the slab's rule alone.
     */
    double stored_energy_fraction = 0.05;
    /**
     * A slab that moves away at this fraction of the impact velocity or more has rebounded: the
     * energy left in wall and soil is then their free vibration, which an undamped elastic wall
     * on rollers keeps for ever, and the run ends on separation whatever it is. In (0, 1].
     */
    double rebound_velocity_fraction = 0.5;
    double output_interval           = 1.0e-5; ///< s: history sampling interval (0: every step)
    double vtu_interval              = 0;      ///< s: field output interval (0: none)
    /** s: interval of the deformed-mesh frames of ImpactResult::frames (0: none; >= 0). */
    double frame_interval = 0;
    /**
     * m: the gauge length over which the vertical bars' strain is averaged for
     * ImpactSummary::max_bar_gauge_strain_ratio (reinforced walls only; >= 0). 0: half the
     * wall's thickness, the plastic hinge length Park and Paulay estimate (about half the
     * section depth; docs/physics.md "Engineer's quantities").
     */
    double                bar_gauge_length = 0;
    std::filesystem::path vtu_dir;          ///< field output directory (empty: none)
    unsigned int          log_interval = 0; ///< steps between log lines (0: none)
    /**
     * Progress report: called on rank 0 as progress(t, end_time) (s) every progress_interval
     * steps and once at the end (empty: none). It must not throw or call MPI.
     */
    std::function<void(double t, double t_end)> progress;
    unsigned int progress_interval = 1000; ///< steps between progress calls (> 0)


    Integrator       integrator = Integrator::explicit_central_difference;
    ExplicitOptions  explicit_options;    ///< used when integrator is explicit_central_difference
    ImplicitOptions  implicit_options;    ///< used when integrator is implicit_newmark
    GeostaticOptions geostatic;           ///< gravity and initial stress before the impact
    InterfaceOptions wall_soil_interface; ///< bonded or frictional contact
  };

  /** Histories sampled every output_interval. Forces and energies per metre of depth. */
  struct ImpactHistory
  {
    std::vector<double> time;                   ///< s
    std::vector<double> contact_force;          ///< N/m, raw penalty + damping force
    std::vector<double> smoothed_contact_force; ///< N/m, moving average (see ImpactSummary)
    std::vector<double> n_active;               ///< active slave nodes
    std::vector<double> slab_displacement;      ///< m, mass-weighted mean x of the slab
    std::vector<double> slab_velocity;          ///< m/s, mass-weighted mean x of the slab
    std::vector<double> wall_displacement;      ///< m, mean x of the wall face in contact range
    std::vector<double> indentation;     ///< m, slab front - wall face displacement - initial gap
    std::vector<double> max_penetration; ///< m
    std::vector<double> kinetic;         ///< J/m
    std::vector<double> strain;          ///< J/m
    std::vector<double> penalty;         ///< J/m, energy stored in the penalty springs
    std::vector<double> contact_dissipation; ///< J/m, work of the contact damping
    /// (E_kin + E_strain - W_contact + E_radiated + E_slab_damping + E_springs) / E_0 - 1
    std::vector<double> energy_error;
    /// Non-linear laws only (empty otherwise), J/m: accumulated plastic and damage
    /// dissipation, and the internal work (integrated stress power) that replaces E_strain in
    /// energy_error; `strain` is then the recoverable part.
    std::vector<double> plastic_dissipation, damage_dissipation, internal_work;
    /// Absorbing boundaries only (empty otherwise), J/m: energy radiated through the dashpots,
    /// the time integral of v . C v.
    std::vector<double> radiation;
    /// ImpactParameters::slab_damping_ratio > 0 only (empty otherwise), J/m: energy the slab's
    /// damping took from its vibration.
    std::vector<double> slab_damping;
    /// Viscous-spring boundary only (empty otherwise), J/m: energy stored in the boundary's
    /// springs, 1/2 k (u - u_0)^2 summed over their DoFs.
    std::vector<double> boundary_springs;
    /// Wall-soil contact interface only (empty otherwise): total normal force (N/m), closed
    /// pairs, friction dissipation since the start of the impact (J/m).
    std::vector<double> interface_normal_force, interface_closed, friction_dissipation;
  };

  /** Scalar results of one run. */
  struct ImpactSummary
  {
    double peak_force       = 0; ///< N/m, of the smoothed force
    double peak_force_raw   = 0; ///< N/m, of the raw force (every step)
    double contact_start    = 0; ///< s
    double contact_duration = 0; ///< s, first to last step with a non-zero force
    double impulse          = 0; ///< N s/m, integral of the raw force
    double rebound_velocity = 0; ///< m/s, slab mean velocity at the end (negative: rebound)
    double apparent_cor     = 0; ///< -rebound_velocity / initial_velocity
    double energy_error     = 0; ///< max |energy_error| over the run
    double smoothing_window = 0; ///< s, moving-average window actually used
    double max_penetration  = 0; ///< m, largest slave penetration (dynamic node impacts)
    /** m: stiffness-weighted mean slave penetration averaged over the contact duration. Since
     *  k p = lambda - c dp/dt, it equals impulse / (T sum k_i): it falls as 1 / penalty. */
    double mean_penetration  = 0;
    double initial_gap       = 0; ///< m
    double penalty_stiffness = 0; ///< N/m per metre, largest slave-node penalty k_i
    double penalty_factor    = 0; ///< used: penalty_factor or penalty_step_ratio's
    /** Contact sub-steps per step (1: no sub-cycling); the contact's step is dt / this. */
    unsigned int  contact_subcycles = 1;
    unsigned long n_dofs            = 0;
    unsigned long n_cells           = 0;
    unsigned long n_steps           = 0;
    unsigned long n_newton          = 0; ///< implicit: total Newton iterations
    unsigned long n_step_halvings   = 0; ///< implicit: steps retried with half the step
    unsigned long n_linear_solves   = 0; ///< implicit: Newton linear solves
    /** s, implicit: wall time of the linear solver (setup, factorizations and solves). */
    double linear_solver_seconds = 0;
    /** s, implicit: wall time of the setups (factorization or AMG hierarchy), included above. */
    double       linear_setup_seconds = 0;
    double       dt                   = 0; ///< s
    double       dt_stable            = 0; ///< s, explicit stability limit 2 / omega_max
    double       wall_seconds         = 0;
    unsigned int n_ranks              = 1;
    bool         separated            = false; ///< stopped on separation (else end_time)
    /** Ended at end_time without the stop rule met (the slab still in contact or coming in, or
     *  more than stored_energy_fraction of E_0 still in wall and soil): a cut record. */
    bool truncated = false;
    /** Energy stored in wall and soil at the end over E_0 (the stop rule's measure,
     *  ImpactParameters::stored_energy_fraction). */
    double stored_energy_share = 0;
    double plastic_dissipation = 0; ///< J/m at the end (non-linear laws)
    double damage_dissipation  = 0; ///< J/m at the end (non-linear laws)
    /// The same split by body: slab, wall, soil (J/m; a material of another id is in neither).
    std::array<double, 3> plastic_dissipation_by_body{}, damage_dissipation_by_body{};
    /** Non-linear laws: max |W_int - (E_stored + D_plastic + D_damage)| / E_0 over the run,
     *  the consistency of the point-wise bookkeeping with the integrated stress power. */
    double dissipation_gap          = 0;
    double radiated_energy          = 0; ///< J/m at the end (absorbing boundaries)
    double slab_damping_dissipation = 0; ///< J/m at the end (ImpactParameters::slab_damping_ratio)
    double boundary_spring_energy   = 0; ///< J/m stored at the end (viscous-spring boundary)
    /**
     * m: permanent indentation of the wall, the x displacement (+x: pushed back, away from the
     * slab) of the wall face in the contact range that stays once the vibrations have died out:
     * the static displacement after elastic unloading (virgin stiffness of wall and soil) from
     * the committed end state, K u = -f_int(0; h). Zero for history-free laws and for damage
     * (secant unloading); plastic strain leaves it. The next impact meets a gap wider by this.
     */
    double permanent_indentation = 0;
    /** m: x displacement of the wall face in the contact range at the end of the run (the
     *  permanent part plus the free vibration at that instant). */
    double wall_residual_displacement = 0;
    /**
     * Reinforced wall (bars in the wall's concrete law): the largest bar strain of the run over
     * the yield strain, max |eps| / eps_y (eps_y = f_y / E_s; the x bars' eps_xx and the y bars'
     * eps_yy at the wall's Gauss points, perfect bond, sampled at the history's steps), the
     * height y (m, ground at y = 0) of that point and the time (s). >= 1: the bars yield there.
     * NaN without bars in the wall.
     */
    double max_bar_strain_ratio  = std::numeric_limits<double>::quiet_NaN();
    double max_bar_strain_height = std::numeric_limits<double>::quiet_NaN();
    double max_bar_strain_time   = std::numeric_limits<double>::quiet_NaN();
    /**
     * Reinforced wall with vertical bars: the largest mean of their strain eps_yy over a gauge
     * of ImpactParameters::bar_gauge_length (the elongation between the gauge's ends over its
     * length, along a vertical line of Gauss points, any position within the wall, sampled at
     * the history's steps) over eps_y, and the height (m) of that gauge's centre. Unlike the
     * point strain it does not grow as the cells shrink around a localised crack. NaN without
     * vertical bars.
     */
    double max_bar_gauge_strain_ratio  = std::numeric_limits<double>::quiet_NaN();
    double max_bar_gauge_strain_height = std::numeric_limits<double>::quiet_NaN();
    double bar_gauge_length            = std::numeric_limits<double>::quiet_NaN(); ///< m used
    /** J/m: work of the contact damping at the end. */
    double contact_dissipation = 0;
    /**
     * J/m: energy left in the bodies at the end besides the slab's mean motion: kinetic energy
     * of wall, soil and the slab's vibration plus the recoverable strain energy. With the
     * dissipation it closes E_0 (1 - COR^2) = plastic + damage + contact + residual (+ the
     * radiated energy with absorbing boundaries, + the energy error).
     */
    double residual_energy = 0;
    /** sqrt(1 - (plastic + damage dissipation) / E_0): the COR the material dissipation alone
     *  implies (1 for elastic laws), beside apparent_cor from the rebound velocity. */
    double dissipation_cor = 1;

    /** Geostatic step (GeostaticOptions::enabled only): the weight it balances (N/m), the
     *  out-of-balance force left as a fraction of it, its modified-Newton iterations, the
     *  plastic dissipation and largest equivalent plastic strain it caused (J/m, -), and the
     *  mean x displacement of the wall face in the contact range it caused (m). */
    double        geostatic_weight              = 0;
    double        geostatic_residual            = 0;
    unsigned long geostatic_iterations          = 0;
    double        geostatic_plastic_dissipation = 0;
    double        geostatic_max_plastic_strain  = 0;
    double        geostatic_wall_displacement   = 0;
    /** Wall-soil contact interface: its normal force at the start of the impact (N/m), its
     *  pairs, and the friction dissipation during the impact (J/m). */
    double        interface_normal_force = 0;
    unsigned long interface_pairs        = 0;
    double        friction_dissipation   = 0;
  };

  /**
   * Deformed-mesh frames for an animation (ImpactParameters::frame_interval > 0), complete on
   * rank 0 of the run's communicator (empty on the others): the mesh once, then per frame the
   * displacement of every vertex and cell means of stress measures over the Gauss points. With a
   * rigid slab the slab is not meshed and so not in the frames.
   */
  struct ImpactFrames
  {
    std::vector<double> vertices;         ///< m, undeformed x, y per vertex, [vertex][2]
    std::vector<double> cells;            ///< vertex indices of each quadrilateral, [cell][4]
    std::vector<double> material;         ///< material id per cell (geometry/scene_ids.h), [cell]
    std::vector<double> time;             ///< s, [frame]
    std::vector<double> displacement;     ///< m, [frame][vertex][2]
    std::vector<double> von_mises_stress; ///< Pa, [frame][cell] (with sigma_zz)
    std::vector<double> mean_stress;      ///< Pa, [frame][cell], tension positive
    /// -, [frame][cell]; non-linear laws only (empty otherwise).
    std::vector<double> damage, equivalent_plastic_strain;
    /// Vertex indices of the contact nodes (the penalty contact's slaves: the wall face with a
    /// rigid slab, the slab front otherwise), ordered along the face by y, [node].
    std::vector<double> contact_vertices;
    /// m, tributary length of each contact node on the face (reference geometry), [node].
    std::vector<double> contact_length;
    /// Pa, [frame][node]: slab-wall contact pressure, the node's penalty force (normal contact
    /// traction, positive in compression) over its tributary length; sum(pressure * length)
    /// is the contact force per metre at the frame's time.
    std::vector<double> contact_pressure;
  };

  /** Stress at one Gauss point of the geostatic state (tension positive). */
  struct PointStress
  {
    double       x = 0, y = 0; ///< m
    unsigned int material_id = 0;
    double       xx = 0, yy = 0, zz = 0, xy = 0; ///< Pa
  };

  struct ImpactResult
  {
    ImpactHistory history;
    ImpactSummary summary;
    ImpactFrames  frames; ///< empty unless ImpactParameters::frame_interval > 0
    /** Geostatic step only: the stress of every Gauss point after it, all ranks, sorted by
     *  (material, x, y). */
    std::vector<PointStress> geostatic_stress;
  };

  /**
   * Runs the impact until the slab has separated, the contact force stayed zero for
   * separation_hold_time and wall and soil hold at most stored_energy_fraction of E_0 (or the slab
   * rebounds), or end_time (then truncated). Collective on comm. Log lines go to *log on rank 0
   * (nullptr: silent). Bad input throws (message names the parameter and the bad value);
   * numerical failure throws NumericalError.
   */
  ImpactResult run_impact(const ImpactParameters &parameters,
                          MPI_Comm                comm = MPI_COMM_WORLD,
                          std::ostream           *log  = nullptr);

  /**
   * Static horizontal stiffness (N/m per metre of depth) of a plane-strain cantilever of the
   * given height and thickness, base clamped, loaded by a uniform shear traction on its top
   * edge; stiffness = load / mean top-edge x displacement. Mesh: n_thickness square-ish Q1 cells
   * across, n_thickness * height / thickness along. Serial.
   */
  double cantilever_tip_stiffness(double          height,
                                  double          thickness,
                                  const Material &material,
                                  unsigned int    n_thickness);

  /// A cantilever wall with a bonded backfill block on its back (+x) side (SI).
  struct BackfilledWall
  {
    double       height    = 0.0;
    double       thickness = 0.0;
    Material     wall;
    double       backfill_width  = 0.0; ///< 0: the bare cantilever (soil ignored)
    double       backfill_height = 0.0; ///< <= height
    Material     soil;
    unsigned int n_thickness = 4; ///< cells across the wall; soil cells have the wall's size
  };

  /**
   * Static horizontal stiffness (N/m per metre of depth) of the cantilever wall `w` with its
   * backfill, base of wall and soil clamped, far soil side u_x = 0 (the scene's boundary
   * conditions), loaded and measured as in cantilever_tip_stiffness(). Serial.
   */
  double backfilled_wall_tip_stiffness(const BackfilledWall &w);

  /**
   * Timoshenko plane-strain tip stiffness of the same cantilever: 1 / (H^3 / (3 E' I) +
   * H / (kappa G A)), E' = E / (1 - nu^2), I = t^3 / 12, A = t, kappa = 5/6.
   */
  double timoshenko_tip_stiffness(double height, double thickness, const Material &material);

  /** Mesh statistics and a VTU preview (material id per cell) of an MSH file. Serial. */
  struct MeshInfo
  {
    unsigned long              n_cells    = 0;
    unsigned long              n_vertices = 0;
    std::map<unsigned, double> area_by_material;   ///< m^2 per metre
    std::map<unsigned, double> length_by_boundary; ///< m
    double                     min_cell_diameter = 0;
  };
  MeshInfo read_mesh_info(const std::filesystem::path &mesh_file,
                          const std::filesystem::path &vtu_file = {});
} // namespace kimp::fem
