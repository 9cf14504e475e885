// Private to fem/impact/: ImpactProblem, the deal.II problem class behind run_impact() for
// M u_tt + f_int(u) = f_c(u, u_t) (step-18/step-42 layout, one public verb run()). Its phases:
// setup.cc, contact_setup.cc, interface_setup.cc, absorbing_boundary.cc, geostatic.cc, the time
// loops explicit.cc and implicit.cc (Newmark), and recording.cc, which both loops share.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <deal.II/base/index_set.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include "fem/bar_gauge.h"
#include "fem/frictional_interface.h"
#include "fem/impact.h"
#include "fem/material_law.h"
#include "fem/penalty_contact.h"
#include "geometry/scene_ids.h"

namespace kimp::fem::internal
{
  // The deal.II names of this header (each source file of fem/impact/ opens dealii itself).
  using dealii::AffineConstraints;
  using dealii::DoFHandler;
  using dealii::FESystem;
  using dealii::FEValues;
  using dealii::IndexSet;
  using dealii::Point;
  using dealii::SymmetricTensor;
  using dealii::Vector;
  namespace parallel         = dealii::parallel;
  namespace TrilinosWrappers = dealii::TrilinosWrappers;
  namespace types            = dealii::types;
  constexpr int dim          = 2;
  using Vec                  = TrilinosWrappers::MPI::Vector;

  /** x formatted with 6 significant digits (messages). */
  std::string fmt_double(double x);
  /** x with 4 significant digits (log lines). */
  std::string fmt_sig(double x);
  /** global = the entry-wise reduction op (MPI_SUM, MPI_MAX) over the ranks of comm of the n
   *  values at local. */
  void
  reduce_over_ranks(const double *local, double *global, std::size_t n, MPI_Op op, MPI_Comm comm);
  /** The entry-wise sum of local over the ranks of comm. */
  std::vector<double> sum_over_ranks(const std::vector<double> &local, MPI_Comm comm);
  /** Throws ExcMessage(message) unless ok. */
  void require(bool ok, const std::string &message);
  /** Compact vector of the contact evaluation with the rigid DoF appended if missing. */
  std::vector<double> padded_force(const PenaltyContact::Evaluation &ev, std::size_t size);

  /** One boundary face of a locally owned cell, as gathered from all ranks (reference geometry,
   *  global DoFs). */
  struct FaceSegment
  {
    unsigned int                           boundary_id = 0;
    unsigned int                           material_id = 0;
    Point<dim>                             p0, p1, cell_center;
    std::array<types::global_dof_index, 4> dofs{}; // p0 x, p0 y, p1 x, p1 y
  };

  class ImpactProblem
  {
  public:
    ImpactProblem(const ImpactParameters &parameters, MPI_Comm comm, std::ostream *log);
    ImpactProblem(const ImpactProblem &)            = delete;
    ImpactProblem &operator=(const ImpactProblem &) = delete;

    /** Runs the impact as documented at run_impact(). Collective on comm. */
    ImpactResult run();

  private:
    // setup.cc
    void validate_parameters() const;
    void make_grid();
    void setup_system();
    void assemble_system();
    /** The stiffness's sparsity: the cells', and the contact and interface couplings. */
    void make_stiffness_sparsity();
    /** inverse_mass and free_mask of the unconstrained DoFs with mass; slab_total_mass. */
    void mark_free_dofs();
    /** Constitutive law per material id: material_laws, else linear elastic. */
    void make_laws();
    /** f = laws_internal_force(u) + the geostatic offset (initial stress - gravity) - the
     *  wall-soil interface force: the force the time loops balance with the inertia. */
    void internal_force(const Vec &u, Vec &f);
    void compute_time_step();
    /** compute_time_step() with the contact sub-cycled: dt, contact_substeps, the limit. */
    void compute_subcycled_step();
    /** Largest 2 c_p / h over the cells (h: a cell's shortest edge), over all ranks. */
    double cells_omega() const;
    void   log_line(const std::string &s) const;
    /** The slab's mean velocity along the impact: v_r (rigid) or the mass-weighted mean of v. */
    double slab_velocity(const Vec &v, double v_r) const;
    /** The separation test of both time loops: the slab comes in at no more than
     *  separation_velocity_fraction of the impact velocity. */
    bool slab_no_longer_comes_in(double slab_v) const;
    /** The stop of both time loops after the hold time: the slab no longer comes in, and wall
     *  and soil hold at most stored_energy_fraction of E_0 (last sample) or the slab rebounds at
     *  rebound_velocity_fraction of the impact velocity or more. */
    bool system_released_the_slab(double slab_v) const;
    /** Step counts of both time loops at the step dt: output every vtu_every (write_vtu) and
     *  frame_every (0: no frames) steps, at most n_max steps, separation after hold_steps. */
    struct LoopSteps
    {
      bool          write_vtu   = false;
      unsigned long vtu_every   = 0;
      unsigned long frame_every = 0;
      unsigned long n_max       = 0;
      unsigned long hold_steps  = 0;
    };
    LoopSteps loop_steps() const;

    // residual.cc
    /** After the run, u (and u_r) at its end: the wall face's displacement then and its
     *  permanent indentation (elastic unloading from the committed end state). */
    void compute_residual_state(const Vec &u, double u_r);

    // internal_force.cc
    /** Precomputes the kernel of internal_force() (non-linear laws; after make_laws()). */
    void setup_internal_force();
    /** f = internal force of the laws at u: K u for linear laws, else assembled from the
     *  laws' stress with the committed history (trial history written). */
    void laws_internal_force(const Vec &u, Vec &f);
    /** f from force_local: the ghost entries added on their owner, then the owned sums;
     *  constrained DoFs get none. */
    void add_force_to_owners(Vec &f);
    /** The same by an FEValues loop over the cells at every call: the kernel's reference. */
    void internal_force_reference(const Vec &u, Vec &f);
    /** Cells of this material id get the mean-dilatation B-bar: soil cells of a non-linear law
     *  (ImpactParameters::mean_dilatation). */
    bool mean_dilatation(types::material_id id) const;
    /** b[q n + i]: the Voigt strain of DoF i's shape function at Gauss point q (n DoFs per
     *  cell) of the cell fv was reinit()ed on, with the mean dilatation where
     *  mean_dilatation(id): the rows of the cell's B (B-bar) operator. fv: 2 x 2 Gauss points,
     *  gradients and JxW. */
    void strain_columns(types::material_id                  id,
                        const FEValues<dim>                &fv,
                        std::vector<std::array<double, 3>> &b) const;
    /** The Gauss-point strains eps (from FEValues symmetric gradients) of a cell of material
     *  id as Voigt vectors, with the mean dilatation where mean_dilatation(id) (weights jxw). */
    std::array<VoigtStrain, 4> cell_strains(types::material_id                          id,
                                            const std::vector<SymmetricTensor<2, dim>> &eps,
                                            const std::array<double, 4>                &jxw) const;
    /** The same for `cell` at the (ghosted) displacement u: fv (2 x 2 Gauss points, gradients
     *  and JxW) reinit()ed on the cell, the symmetric gradients at its points in eps and their
     *  weights in jxw. */
    std::array<VoigtStrain, 4> cell_strains(const DoFHandler<dim>::active_cell_iterator &cell,
                                            const Vec                                   &u,
                                            FEValues<dim>                               &fv,
                                            std::vector<SymmetricTensor<2, dim>>        &eps,
                                            std::array<double, 4>                       &jxw) const;

    // contact_setup.cc
    void setup_contact();
    /** The contact faces, nodes, slaves and masters while setup_contact() builds them;
     *  complete only in contact_setup.cc. */
    struct ContactLayout;
    /** The contact nodes of the sorted faces, numbered by their coordinates, and contact_dofs. */
    void number_contact_nodes(ContactLayout &c);
    /** The slave nodes' tributary lengths, the master segments and the master's stiffness. */
    void measure_contact_faces(ContactLayout &c);
    /** The slave springs and dashpots (penalty, reduced mass), their lengths and the penalty
     *  frequency. */
    void make_contact_slaves(ContactLayout &c);
    /** ImpactParameters::penalty_factor, or with penalty_step_ratio > 0 the factor that leaves
     *  the damped stable step of cells and penalty at that fraction of the cells' own; slave_mass
     *  holds each slave node and its reduced mass. */
    double
    contact_penalty_factor(const ContactLayout                                &c,
                           const std::vector<std::pair<unsigned int, double>> &slave_mass) const;
    /** initial_gap: the smallest reference gap; an overlap is refused. */
    void check_initial_gaps(const ContactLayout &c);
    /** The weights of the mean wall-face and slab-front displacements. */
    void set_face_weights(const ContactLayout &c);
    /** The faces with boundary id a or b of every rank's locally owned cells, in rank order (the
     *  same list on all ranks). Collective. */
    std::vector<FaceSegment> gather_boundary_faces(types::boundary_id a,
                                                   types::boundary_id b) const;
    /** v at each of dofs, from the rank that owns it (the others add zeros: the sum is exact);
     *  the same on all ranks. Collective. */
    std::vector<double> gather_owned(const std::vector<types::global_dof_index> &dofs,
                                     const Vec                                  &v) const;
    /** Compact contact values (all ranks) of a distributed vector, plus the rigid DoF. */
    std::vector<double> gather_compact(const Vec &v, double rigid_value) const;
    /** Two compact gathers in one reduction: (a, rigid a), (b, rigid b). */
    std::pair<std::vector<double>, std::vector<double>>
    gather_compact(const Vec &a, double rigid_a, const Vec &b, double rigid_b) const;
    /** Adds compact contact forces to the owned entries of a distributed vector. */
    void scatter_add(const std::vector<double> &compact, Vec &f) const;

    // implicit.cc
    void run_implicit();
    /** The implicit loop's state; complete only in implicit.cc. */
    struct ImplicitState;
    /** compact_free: the contact DoFs that no constraint holds, the same on all ranks. */
    void mark_free_contact_dofs();
    /** One Newmark step of size dt / 2^level from the state's step into its iterate; false if
     *  Newton fails (the caller halves the step). */
    bool implicit_newton_step(ImplicitState &s, unsigned int level);
    /** Accelerations, velocities, contact and residual of the state's iterate, for a step of
     *  size @p h with Newmark's c1. */
    void evaluate_implicit_iterate(ImplicitState &s, double h, double c1);
    /** Implicit: K + c1 M of one step size dt / 2^level and its solver. Complete only in
     *  implicit.cc, which alone needs the Trilinos solver headers. */
    struct StepOperator;
    StepOperator &step_operator(unsigned int level);
    /** x = base^{-1} b (direct solver only). */
    void                       base_solve(StepOperator &op, Vec &x, const Vec &b);
    const std::vector<double> &flexibility_column(StepOperator &op, unsigned int k);
    /** Newton increment (du, du_r) of J (du, du_r) = -(residual, r_rigid). */
    void solve_newton_system(StepOperator                     &op,
                             const PenaltyContact::Evaluation &ev,
                             const Vec                        &residual,
                             double                            r_rigid,
                             Vec                              &du,
                             double                           &du_r);

    // absorbing_boundary.cc
    /** prm.absorbing_boundaries holds this boundary id. */
    bool is_absorbing(unsigned int boundary_id) const;
    /** Constrains the faces of absorbing ids that are not on soil cells (fixed base: u = 0;
     *  far side: u_x = 0), as the constraint they replace. Before constraints.close(). */
    void constrain_non_absorbing_faces();
    /** f(i, c) for every vertex DoF i (component c) that the faces of absorbing ids of the
     *  non-artificial cells on soil (on_soil) or not on soil would hold fixed without dashpots:
     *  both components on the fixed base, x on the soil's far side. */
    template <class F>
    void for_each_absorbing_dof(bool on_soil, const F &f) const
    {
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial() && (cell->material_id() == geometry::soil_material) == on_soil)
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && is_absorbing(face->boundary_id()))
            {
              const unsigned int n_components = face->boundary_id() == geometry::fixed_base ? 2 : 1;
              for (unsigned int v = 0; v < face->n_vertices(); ++v)
                for (unsigned int c = 0; c < n_components; ++c)
                  f(face->vertex_dof_index(v, c), c);
            }
    }
    /** Lumped Lysmer-Kuhlemeyer dashpots into `damping` and the list of damped free DoFs, with
     *  the viscous-spring boundary's springs beside them (damped_k). */
    void assemble_dashpots();
    /** The springs' stiffness per unit area, normal and tangential, of a soil face of
     *  `material` whose midpoint is `mid` (alpha G / R, R from contact_centre). */
    std::pair<double, double> boundary_spring_stiffness(const Material   &material,
                                                        const Point<dim> &mid) const;
    /** The displacement the boundary springs hold at owned local index j: the time loop's
     *  start, the geostatic state (else 0). */
    double spring_rest(unsigned int j) const;
    /** Explicit: a = M^{-1} (f - K u) on entry; on the damped DoFs it becomes the acceleration
     *  with the springs' force -k (u - u_0) and the dashpot force -C v_n at
     *  v_n = (M v_{n-1/2} + dt/2 (f - K u - k (u - u_0))) / (M + dt/2 C) (v_0 itself at the
     *  first step), so the usual v updates stay. */
    void apply_dashpots_explicit(bool first_step, const Vec &u, const Vec &v_half, Vec &a) const;
    /** Implicit: r += C v + k (u - u_0) (owned entries). */
    void add_dashpot_force(const Vec &u, const Vec &v, Vec &r) const;
    /** Implicit: matrix += factor C + k on the diagonal (before compress). */
    void add_dashpot_matrix(TrilinosWrappers::SparseMatrix &matrix, double factor) const;
    /** Trapezoidal dashpot work since the last call, added to radiation_local. */
    void accumulate_radiation(const Vec &u, const Vec &v);
    /** This rank's energy in the boundary springs, 1/2 k (u - u_0)^2, J/m. */
    double boundary_spring_energy_local(const Vec &u) const;

    // slab_damping.cc
    /** The slab's damped x DoFs (owned, free), their masses and heights about the slab's
     *  centre, and alpha = 2 ratio omega_1 (ImpactParameters::slab_damping_ratio). */
    void setup_slab_damping();
    /** Explicit: a = M^{-1} (f - K u) on entry; on the slab's x DoFs it gains
     *  -alpha (v - v_plane) at v_{n-1/2} (the damping lags half a step, as the contact's), and the
     *  step's dissipation is added to slab_damping_local. */
    void apply_slab_damping(bool first_step, const Vec &v_half, Vec &a);
    /** Slab velocity at t = 0: +x, or +y with initial_velocity_along_y (then E_0 is set to
     *  the initial kinetic energy). */
    void set_initial_slab_velocity(Vec &v);

    // geostatic.cc
    /** Gravity, initial stress and the static equilibrium the impact starts from. */
    void run_geostatic_step();
    /** DoFs the geostatic step holds: the free slab's (by their diagonal) and the owned, free
     *  DoFs of the absorbing faces (`supported`, with their component), masked out of the
     *  residual by `static_mask`. */
    struct GeostaticHold
    {
      std::set<types::global_dof_index>    slab_dofs;
      Vec                                  static_mask;
      std::vector<types::global_dof_index> supported;
      std::vector<unsigned int>            supported_component;
    };
    /** The Newton iteration's outcome: out-of-balance force (N/m), iterations, of them on the
     *  consistent tangent, wall-clock seconds. */
    struct GeostaticIterations
    {
      double        residual  = 0;
      unsigned long k         = 0;
      unsigned long n_tangent = 0;
      double        seconds   = 0;
    };
    /** Gravity load and the initial-stress force into geostatic_offset (the initial stress
     *  of the laws that hold it committed to their history); the slab's DoFs into @p hold;
     *  returns the weight (N/m) of the bodies under gravity. */
    double geostatic_gravity_load(GeostaticHold &hold);
    /** The absorbing faces' DoFs held as by rollers during the static step, into @p hold. */
    void hold_geostatic_supports(GeostaticHold &hold) const;
    /** Turns an assembled stiffness into the static operator: the slab's diagonal, the
     *  interface (its springs; with @p u its regularised consistent tangent at u), the supported
     *  rows replaced by their diagonal. */
    void finish_static_operator(TrilinosWrappers::SparseMatrix &matrix,
                                const GeostaticHold            &hold,
                                const Vec                      *u = nullptr) const;
    /** The consistent tangent at @p u from the committed state, regularised, as an operator. */
    void assemble_geostatic_tangent(const Vec                      &u,
                                    const GeostaticHold            &hold,
                                    TrilinosWrappers::SparseMatrix &tangent);
    /** Modified Newton on the virgin stiffness, then full Newton on the consistent tangent
     *  with a virgin-stiffness fallback, to g.tolerance x @p weight; @p u is the result. */
    GeostaticIterations
    solve_geostatic_equilibrium(const GeostaticHold &hold, double weight, Vec &u);
    /** The supports' reactions at @p u, applied as constant forces during the impact. */
    void apply_support_reactions(const Vec &u, const GeostaticHold &hold);
    /** Commits the geostatic state @p u: histories, interface, energies. */
    void commit_geostatic_state(const Vec &u);
    /** The slab-wall gap at the geostatic state @p u (the earth pressure moves the wall face). */
    void gap_after_geostatic(const Vec &u);
    /** Gauss-point stresses of the geostatic state, gathered to all ranks. */
    std::vector<PointStress> gather_point_stresses(const Vec &u);

    // interface_setup.cc
    /** The wall-soil contact interface's node pairs (wall_soil_interface.contact only). */
    void setup_interface();
    /** f -= the interface forces at u (trial history of the interface written). */
    void subtract_interface_force(const Vec &u, Vec &f);
    /** Adds the interface's penalty springs to a matrix whose sparsity has their couplings;
     *  with @p u the pairs' consistent tangent at u (open, stick or slip from the committed
     *  history) plus @p floor x the springs. */
    void add_interface_stiffness(TrilinosWrappers::SparseMatrix &matrix,
                                 const Vec                      *u     = nullptr,
                                 double                          floor = 0) const;

    // explicit.cc
    void run_explicit();
    /** Contact sub-cycling, the contact nodes' compact state over one step from t_n: u_c, v_c
     *  (v at t_n - dt_contact / 2) and the step's held acceleration a_c = M^-1 (f - f_int)(u_n)
     *  on them. */
    struct SubcycleState
    {
      std::vector<double> u, v, a;
    };
    /** The contact nodes' compact velocity at t_n of step n (fc: the penalty force at u_n). */
    std::vector<double> subcycled_velocity_at_step(unsigned long              n,
                                                   const std::vector<double> &fc,
                                                   const SubcycleState       &s) const;
    /**
     * Advances s over the step n in contact_substeps sub-steps (leap-frog at dt_contact with the
     * penalty force at every sub-step, a_c's impulse dt a_c at the first; the first step starts
     * with half kicks). The first sub-step's evaluation is ev0 (at u_n). Accumulates the contact
     * work, raw force (the step's mean) and penetration of every sub-step.
     */
    void advance_subcycled_contact(unsigned long                     n,
                                   const PenaltyContact::Evaluation &ev0,
                                   SubcycleState                    &s);
    /** Writes the owned entries of compact values into a distributed vector (and the rigid
     *  DoF into rigid). Collective. */
    void write_compact(const std::vector<double> &compact, Vec &v, double &rigid) const;
    /** The contact work of the trapezoid rule from the last call to compact forces fc at
     *  compact displacements cu (explicit: per step, or per sub-step when sub-cycled). */
    void accumulate_contact_work(const std::vector<double> &fc, const std::vector<double> &cu);

    // recording.cc
    /** What record() reads of step n (time t): the state and its contact evaluation. */
    struct RecordedStep
    {
      unsigned long                     n;
      double                            t;
      const Vec                        &u;
      const Vec                        &v_n;
      const Vec                        &Ku;
      double                            u_r;
      double                            v_r;
      const PenaltyContact::Evaluation &ev;
      const std::vector<double>        &cu; ///< the contact points' compact displacements
      /// The contact's work, raw force and penetration were accumulated by the sub-steps.
      bool contact_subcycled = false;
    };
    /** Records histories and energies of one step. */
    void record(const RecordedStep &step);
    /** Every step: the contact work, force and penetration, the internal work of non-linear
     *  laws and the dashpots' radiation. */
    void accumulate_step_work(const Vec                        &u,
                              const Vec                        &v_n,
                              const Vec                        &Ku,
                              const PenaltyContact::Evaluation &ev,
                              const std::vector<double>        &cu,
                              bool                              contact_subcycled);
    /** The energy and momentum sums of a sampled step, over the ranks (the layout is listed
     *  in recording.cc). */
    static constexpr unsigned int       n_energy_values = 9 + 8 + 5;
    std::array<double, n_energy_values> sum_energies(const Vec &u, const Vec &v_n, const Vec &Ku);
    [[noreturn]] void throw_divergence(unsigned long n, double t, const Vec &u) const;
    void
    output_results(double t, const Vec &u, const Vec &v, const std::vector<double> &contact_force);
    /** Cell means over the Gauss points of the stress measures of u_g (ghosted), by active cell
     *  index; locally owned cells only (the others stay 0). */
    struct CellMeans
    {
      Vector<float> sxx, syy, sxy, mean_stress, von_mises, damage, eq_plastic;
    };
    CellMeans cell_means(const Vec &u_g) const;
    /** Appends a frame of ImpactResult::frames at time t with the contact evaluation ev of
     *  that state (collective). */
    void         record_frame(double t, const Vec &u, const PenaltyContact::Evaluation &ev);
    ImpactFrames frames;
    /** Appends the contact pressure of ev to frames (and, at the first frame, the contact
     *  nodes' vertices and tributary lengths). ev is the same on every rank. */
    void record_contact_pressure(const PenaltyContact::Evaluation &ev);
    /** Sampled steps: the largest bar strain of a reinforced wall so far (|eps_xx| of the x
     *  bars, |eps_yy| of the y bars over eps_y = f_y / E_s at the wall's Gauss points; this
     *  rank's cells; collective). Does nothing without bars in the wall's law. */
    void track_bar_strain(double t, const Vec &u);
    /** The largest bar strain over the ranks into @p s (collective). */
    void summarise_bar_strain(ImpactSummary &s) const;
    /** Gauss points of this rank's wall cells for track_bar_strain(): the 8 DoFs of the cell,
     *  the 4 shape gradients (d/dx then d/dy) and y of each point. */
    struct BarPoint
    {
      std::array<types::global_dof_index, 8> dofs{};
      std::array<double, 8>                  gradients{}; // d/dx of an x DoF, d/dy of a y DoF
      std::array<unsigned char, 8>           component{};
      double                                 y = 0;
    };
    std::vector<BarPoint> bar_points;
    /** The vertical bars' gauge (ImpactParameters::bar_gauge_length) over the Gauss points of
     *  every rank's wall cells (rank by rank; this rank's from bar_gauge_offset), their strains
     *  for one sample, and its largest reading so far. */
    std::unique_ptr<BarGauge> bar_gauge;
    std::size_t               bar_gauge_offset = 0;
    std::vector<double>       bar_gauge_strain;
    GaugeStrain               bar_gauge_max;
    /** Sets up bar_gauge from this rank's wall cells (collective). */
    void
    setup_bar_gauge(const std::vector<GaugeSegment> &local, double wall_x_min, double wall_x_max);
    Vec    bar_u_ghosted; // several ranks: u with the wall cells' ghost DoFs
    bool   bar_points_ready = false;
    double bar_ratio_x = 0, bar_ratio_y = 0, bar_yield_strain = 0;
    double bar_max_ratio = -1, bar_max_y = 0, bar_max_time = 0; // this rank
    void   finish(ImpactResult &result, double wall_seconds);

    const ImpactParameters                    prm;
    MPI_Comm                                  comm;
    std::ostream                             *log;
    parallel::distributed::Triangulation<dim> triangulation;
    FESystem<dim>                             fe;
    DoFHandler<dim>                           dof_handler;
    IndexSet                                  locally_owned, locally_relevant;
    AffineConstraints<double>                 constraints;
    TrilinosWrappers::SparseMatrix            stiffness;
    Vec                                       mass, inverse_mass, slab_mass_x, free_mask;
    double                                    slab_total_mass = 0;
    // Lumped mass of every body but the slab on the x and y DoFs, and its sums (kg/m) along the
    // components no support holds (else 0): the energy stored in wall and soil without the
    // kinetic energy of a free translation (the stop rule).
    Vec                   body_mass_x, body_mass_y;
    std::array<double, 2> body_free_mass{{0, 0}};
    /// Energy stored in wall and soil over E_0 at the last sampled step.
    double stored_share = 0;
    /// Stored energy of the slab's points (non-linear laws, this rank), J/m, beside
    /// point_energy_local.
    double slab_stored_local = 0;

    std::unique_ptr<PenaltyContact>      contact;
    std::vector<types::global_dof_index> contact_dofs; // compact node component -> global DoF
    std::vector<double>                  wall_weight, front_weight; // compact node weights
    std::vector<double>                  slave_length; // tributary length per slave (m)
    double                               initial_gap = 0;
    double contact_width = 0, contact_wave_speed = 0; // slave face length (m), wall c_p (m/s)
    double omega_penalty = 0, omega_mesh = 0;
    /** The contact's penalty factor (ImpactParameters::penalty_factor or the step ratio's). */
    double penalty_factor_used = 0;
    double dt = 0, dt_stable = 0;
    /** Contact sub-cycling: sub-steps per step (1: off), their step dt / contact_substeps and
     *  the contact nodes' compact inverse masses (the rigid slab's last). */
    unsigned int        contact_substeps = 1;
    double              dt_contact       = 0;
    std::vector<double> contact_inverse_mass;

    // Bookkeeping of the run.
    double                                      e0 = 0, contact_work = 0, damping_work = 0;
    std::vector<double>                         cu_prev, fc_prev;
    std::vector<double>                         raw_force; // every step
    unsigned long                               sample_every = 1;
    ImpactHistory                               history;
    double                                      max_energy_error = 0, max_penetration = 0;
    std::vector<std::pair<double, std::string>> pvd_records;
    unsigned long                               n_newton = 0, n_steps_done = 0;
    double                                      slab_v_end           = 0;
    bool                                        separated_flag       = false;
    double                                      penetration_integral = 0;
    std::map<unsigned int, std::shared_ptr<StepOperator>>      step_operators; // by level
    std::vector<bool>                                          compact_free;
    std::map<unsigned int, std::shared_ptr<const MaterialLaw>> laws;
    bool                                                       linear_laws = true;
    QuadraturePointHistory                                     qp_history;
    // Energy bookkeeping of non-linear laws (this rank's share): stored, plastic and damage
    // energy of the last internal_force() (trial history), and the internal work
    // sum 1/2 (f_n + f_n+1) . (u_n+1 - u_n), the integrated stress power.
    std::array<double, 3> point_energy_local{{0, 0, 0}};
    /// Plastic and damage energy of the points per body (slab, wall, soil, any other material),
    /// J/m, accumulated beside point_energy_local.
    std::array<std::array<double, 2>, 4> body_dissipation_local{};
    /// The same, summed over the ranks, at the last sampled step (less the geostatic step's).
    std::array<std::array<double, 2>, 4> body_dissipation{};
    std::array<std::array<double, 2>, 4> geostatic_body_dissipation{};
    /// Index of a material id in body_dissipation: slab, wall, soil, other.
    static unsigned int body_of(types::material_id id)
    {
      return id == geometry::slab_material ? 0 :
             id == geometry::wall_material ? 1 :
             id == geometry::soil_material ? 2 :
                                             3;
    }
    /// False while the explicit loop computes a step whose energies are not sampled: the
    /// kernel then skips the points' energies (point_energy_local is not updated).
    bool                point_energy_needed = true;
    double              internal_work_local = 0, max_dissipation_gap = 0;
    std::vector<double> u_prev_local, f_prev_local;
    Vec                 u_ghosted, force_writable; // internal_force() of non-linear laws
    // Absorbing boundary: diagonal dashpot matrix C, its free owned DoFs (local index into the
    // owned range, c_i, m_i), their last u and C v, and this rank's radiated energy.
    // Viscous-spring boundary: whether the springs are on (every rank), their stiffness per
    // damped DoF (damped_k, beside damped_c) and the contact band's centre, their source.
    bool                      absorbing = false, boundary_springs = false;
    Vec                       damping;
    std::vector<unsigned int> damped_index;
    std::vector<double>       damped_c, damped_k, damped_m, damped_u_prev, damped_f_prev;
    double                    radiation_local = 0;
    Point<dim>                contact_centre;
    // Slab damping: alpha (1/s), the owned free slab x DoFs (local index), m_i, y_i - y_c, the
    // slab's sum of m and of m (y - y_c)^2, and this rank's dissipated energy.
    double                    slab_alpha = 0, slab_damped_mass = 0, slab_damped_inertia = 0;
    std::vector<unsigned int> slab_damped_index;
    std::vector<double>       slab_damped_m, slab_damped_y;
    double                    slab_damping_local = 0;
    // Kernel of internal_force(): Q1 cells with 4 Gauss points; per point the 4 vertex shape
    // gradients d/dx, then d/dy, then JxW (gradient_width values).
    static constexpr unsigned int dofs_per_cell = 8, vertices_per_cell = 4, points_per_cell = 4;
    static constexpr unsigned int gradient_width = 2 * vertices_per_cell + 1;
    struct ForceCell
    {
      const MaterialLaw *law    = nullptr;
      unsigned int       cell   = 0;     // active cell index (history)
      unsigned int       body   = 3;     // body_of(material id)
      bool               bbar   = false; // mean_dilatation(material id)
      int                lid[8] = {};    // positions in u_ghosted's local (owned + ghost) array
    };
    double                      wall_end_displacement = 0, permanent_wall_indentation = 0; // m
    unsigned long               unloading_iterations = 0;
    bool                        fast_internal_force  = false;
    std::vector<ForceCell>      force_cells;
    std::vector<double>         force_gradients; // per cell points_per_cell * width
    std::vector<double>         force_local;     // by u_ghosted position
    std::vector<int>            force_owned_lid; // position in an owned vector, or -1
    std::vector<char>           force_constrained;
    std::vector<std::size_t>    force_ghost_lid;
    std::vector<Vec::size_type> force_ghost_gid;
    std::vector<double>         force_ghost_values;
    unsigned long               n_linear_solves = 0, n_step_halvings = 0;
    double                      linear_solver_seconds = 0, linear_setup_seconds = 0;


    // Geostatic state (geostatic.cc). internal_force() then returns f_int(u) + f_0 - f_g, with
    // f_g the gravity load and f_0 the initial stress of points whose law cannot hold it:
    // geostatic_offset = f_0 - f_g (- R, the static reactions of faces released to absorbing
    // dashpots, so that they keep holding). The time loops start from u = geostatic_u; recording
    // subtracts it and the point energies of that state.
    bool                     geostatic_on = false;
    Vec                      geostatic_offset, geostatic_u;
    std::array<double, 3>    geostatic_point_energy{{0, 0, 0}}; // stored, plastic, damage (J/m)
    double                   geostatic_wall = 0, geostatic_front = 0; // compact means (m)
    ImpactSummary            geostatic_summary;                       // geostatic_* fields
    std::vector<PointStress> geostatic_stress;

    // Wall-soil contact interface (interface_setup.cc): pairs over compact interface nodes,
    // their global DoFs, the last evaluation (same on all ranks) and its stored energy plus
    // dissipation at the start of the impact (J/m).
    std::unique_ptr<FrictionalInterface> interface;
    std::vector<types::global_dof_index> interface_dofs;
    FrictionalInterface::Evaluation      interface_ev;
    double                               interface_energy0 = 0, interface_dissipation0 = 0;
    double                               omega_interface = 0;
  };
} // namespace kimp::fem::internal
