// Static, displacement-controlled, load-stepped full-Newton solver for plane-strain bodies of
// inelastic material laws (fem/material_law.h) with gravity and an initial (geostatic) stress:
// the verification problems of docs/physics.md §6. Plain-struct header, no deal.II includes.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <vector>

#include "fem/material.h"
#include "fem/material_law.h"
#include "fem/numerical_error.h"
#include "fem/static_step_statistics.h"

namespace kimp::fem
{
  /**
   * A mesh of bilinear quadrilaterals given in memory. Cell vertices in deal.II's lexicographic
   * order: (x0, y0), (x1, y0), (x0, y1), (x1, y1) of the cell's own axes (counter-clockwise
   * orientation, so 0-1-3-2 runs counter-clockwise). Boundary edges not listed get id 0.
   */
  struct PlaneMesh
  {
    struct Cell
    {
      std::array<unsigned int, 4> vertices{};
      unsigned int                material = 0;
    };
    struct Edge
    {
      std::array<unsigned int, 2> vertices{};
      unsigned int                boundary = 0;
    };
    std::vector<std::array<double, 2>> vertices; ///< m
    std::vector<Cell>                  cells;
    std::vector<Edge>                  boundary_edges;
  };

  /**
   * Tensor-product mesh on the grid lines @p xs x @p ys (m, increasing), every cell of material
   * @p material; each boundary edge gets boundary_id(x, y) of its midpoint (m).
   */
  PlaneMesh tensor_product_mesh(const std::vector<double>                         &xs,
                                const std::vector<double>                         &ys,
                                unsigned int                                       material,
                                const std::function<unsigned int(double, double)> &boundary_id);

  /**
   * @p n + 1 grid lines from @p a to @p b (m) whose spacing grows geometrically by @p ratio (> 0)
   * from a to b (ratio < 1: finer towards b; 1: uniform).
   */
  std::vector<double> graded_coordinates(double a, double b, unsigned int n, double ratio);

  /**
   * Prescribed displacement components on the edges of one boundary id, reached in proportion to
   * the load factor (0 at the start, the given value at 1). A rigid smooth wall with normal x:
   * x only; a rough wall: x and y; a roller: one component with 0. Where entries share a DoF,
   * the later entry governs it (and gets its reaction).
   */
  struct PrescribedDisplacement
  {
    unsigned int boundary_id = 0;
    bool         x           = false; ///< prescribe u_x
    bool         y           = false; ///< prescribe u_y
    double       ux          = 0;     ///< m, at load factor 1
    double       uy          = 0;     ///< m, at load factor 1
  };

  /** Initial stress field sigma_0(x, y) (Pa, tension positive) at a point (m). */
  using InitialStressField = std::function<VoigtStress(double x, double y)>;

  /**
   * Geostatic stress below a horizontal surface at y = @p surface_y (m): sigma_yy = -gamma z,
   * sigma_xx = -K0 gamma z, z = surface_y - y, sigma_xy = 0 (@p unit_weight gamma in N/m^3).
   */
  InitialStressField geostatic_stress(double surface_y, double unit_weight, double k0);

  struct StaticStep;

  /**
   * One node pair of a unilateral frictional interface between two bodies of the mesh whose
   * vertices coincide (fem/frictional_interface.h): vertex a on the first body, vertex b on the
   * second, (nx, ny) the unit normal from a's body into b's body.
   */
  struct StaticInterfacePair
  {
    unsigned int vertex_a = 0, vertex_b = 0;
    double       nx = 1, ny = 0;
    double       normal_stiffness     = 0; ///< N/m per metre of depth (> 0)
    double       tangential_stiffness = 0; ///< N/m per metre of depth (> 0)
    double       friction             = 0; ///< Coulomb mu (>= 0)
  };

  /**
   * Displacement control of a distributed load: a uniform traction along x on the edges of one
   * boundary id, whose resultant P (N/m, unknown) makes the load-weighted mean u_x of those
   * edges equal to load factor times `displacement` (a bordered Newton system: two solves with
   * one factorisation). P and that mean are work-conjugate, so P / mean is the stiffness of
   * the uniform band load (fem::timoshenko_band_stiffness()).
   */
  struct ControlledLoad
  {
    unsigned int boundary_id  = 0;
    double       displacement = 0; ///< m, at load factor 1
  };

  /** Everything run_static_plasticity() needs. */
  struct StaticPlasticityParameters
  {
    PlaneMesh mesh;
    /** Material law per material id; every id of the mesh must have one. */
    std::map<unsigned int, std::shared_ptr<const MaterialLaw>> laws;
    /** Density per material id (kg/m^3); a missing id is weightless. */
    std::map<unsigned int, double> densities;
    /** Gravitational acceleration along -y (m/s^2, >= 0), applied in full from the start. */
    double gravity = 0;
    /**
     * Initial stress (empty: stress-free). Imposed as an eigenstrain: each law is evaluated at
     * eps(u) + eps_0 with eps_0 = D^-1 sigma_0 (D: the law's tangent in its virgin state), so
     * sigma_0 must lie inside the elastic domain; the out-of-plane stress that results is
     * sigma_zz,0 = nu (sigma_xx,0 + sigma_yy,0) of the plane-strain elasticity (equal to
     * K0 gamma z of a geostatic state when K0 = nu / (1 - nu)).
     */
    InitialStressField                  initial_stress;
    std::vector<PrescribedDisplacement> prescribed;
    /** A displacement-controlled uniform band load (none if not set); its edges' DoFs must not
     *  be prescribed. */
    std::optional<ControlledLoad> controlled_load;
    /**
     * Material ids whose tangent is taken as a central difference of the law's stress (the
     * algorithmic tangent) instead of MaterialLaw::tangent(): for laws whose tangent() is only a
     * secant (ConcreteDamageLaw), with which Newton converges linearly and stalls in softening.
     */
    std::set<unsigned int> numerical_tangent;
    /** Boundary ids of a clamped base that anchors bars: the points of the cells with an edge
     *  on one are initialised by MaterialLaw::initialize_anchored_point(). */
    std::set<unsigned int> anchoring_boundaries;
    /** Load steps per unit change of the load factor (> 0), after the equilibrium step 0 (each
     *  segment of load_path gets at least one). */
    unsigned int n_steps = 20;
    /**
     * The load factor at the end of each segment, walked from 0 in order (empty: one segment
     * to 1). A segment that goes back (unloading) or past 1 is allowed: the prescribed
     * displacements are load factor times their values.
     */
    std::vector<double> load_path;
    /**
     * Called after each converged step with the steps so far (the last one just converged) and
     * the segment's index; true ends that segment at this step (the next segment starts from
     * here), e.g. an unloading that reached zero force.
     */
    std::function<bool(const std::vector<StaticStep> &steps, std::size_t segment)> end_segment;
    /** Frictional interface pairs (empty: none); their history is committed per step. */
    std::vector<StaticInterfacePair> interface;
    /**
     * Mean-dilatation B-bar: the volumetric strain of each cell is its mean (Q1/P0), so that
     * isochoric or dilatant plastic flow does not lock the Q1 element (Nagtegaal, Parks & Rice
     * 1974); false: the plain Q1 strain.
     */
    bool bbar = true;
    /** Newton converged when |R_free| <= tolerance * max(|f_ext|, |reactions|) (> 0). */
    double newton_tolerance = 1e-10;
    /** Newton iterations per (sub)step before it is cut (> 0). */
    unsigned int max_iterations = 25;
    /**
     * A step whose Newton iteration has not reached newton_tolerance after max_iterations, and
     * cannot be halved any more, is still accepted at its best iterate if that iterate's relative
     * residual is at most this (0: never; counted in StaticPlasticityResult::n_loose_steps).
     * For damage laws whose cracking points make Newton cycle just above the tolerance.
     */
    double loose_tolerance = 0;
    /**
     * Levenberg-Marquardt damping: an update that does not lower the residual (after the line
     * search) is rejected and the next one solved with the tangent's free diagonal times
     * (1 + lambda), lambda growing 4 times per rejection from 1e-2 and shrinking 4 times per
     * success. For cracking concrete, whose points switch between loading and unloading from
     * one iteration to the next and make plain Newton cycle.
     */
    bool damped_newton = false;
    /**
     * Newton matrix only (the residual, hence the converged state, is unchanged): this
     * fraction (>= 0, < 1) of each point's virgin tangent and of each interface pair's normal
     * and tangential springs is added to the assembled tangent. A perfectly plastic point at
     * the apex of its yield surface has no stiffness, an open pair none either, so a soil node
     * next to an unloading wall can have a singular tangent (Newton's update then runs to
     * 1e12 m); the floor bounds it. 0: the consistent tangent alone.
     */
    double tangent_floor = 0;
    /**
     * The floor of each Newton solve follows the out-of-balance force: min(tangent_floor, the
     * iterate's relative residual) instead of tangent_floor throughout (a Levenberg-Marquardt
     * parameter proportional to the residual, Yamashita & Fukushima 2001). It still bounds the
     * update where the tangent is singular, but vanishes as Newton converges, so the rate near
     * the solution is that of the consistent tangent (quadratic) instead of linear; a fixed
     * floor leaves an error of about floor x virgin / tangent stiffness per iteration in the
     * soft modes of a plastic zone.
     */
    bool floor_follows_residual = false;
    /**
     * With damped_newton: the first iterate of a step may also be the converged state moved on
     * by the last step's increment (free displacements and controlled load) scaled to this
     * step's, kept when its out-of-balance force is lower than that of the state with only the
     * prescribed increment applied (none at the first step and at a reversal of the path). The
     * same tolerance ends the iteration, so the converged state is the same within it; a
     * plastic mechanism that continues from one step to the next then starts near its end.
     */
    bool extrapolated_predictor = false;
    /**
     * Backtracking line search: a Newton update is halved at most this many times until the
     * residual falls (0: plain Newton). Full updates are taken once Newton converges.
     */
    unsigned int max_line_search = 4;
    /** A step that does not converge is halved at most this many times (at most 30); then
     *  NumericalError. The smallest step is 1 / (n_steps 2^max_cuts). */
    unsigned int max_cuts = 4;
    /**
     * Growing a halved step back. 0: a halved step's halves are walked and the next step is
     * full size again as soon as the walk is back on the grid of full steps (bisection). n > 0
     * (automatic step control): the step size is kept after a halving and doubled after n
     * consecutive easy steps, each converged within max_iterations / 4 Newton iterations at
     * the tolerance (not loose, not halved for the IMPL-EX error), once the load factor lies
     * on the grid of the doubled step; never above 1 / n_steps. A push through a hard range
     * then goes on at the step that converged there instead of failing the full step again.
     */
    unsigned int grow_after = 0;
    /**
     * IMPL-EX step control (0: off): a converged step whose largest MaterialLaw::step_error()
     * exceeds this is halved (while the step has been halved fewer than max_error_cuts times;
     * past that it is accepted and counted in StaticPlasticityResult::n_large_error_steps).
     */
    double step_error_tolerance = 0;
    /** Halvings for the IMPL-EX error at most (and at most max_cuts). */
    unsigned int max_error_cuts = 4;
  };

  /** One converged load (sub)step. */
  struct StaticStep
  {
    double load_factor = 0; ///< -
    /** Reaction (N/m per metre of depth, {x, y}) of each prescribed entry: the force the
     *  support exerts on the body, sum of f_int - f_ext over the DoFs the entry governs. */
    std::vector<std::array<double, 2>> reactions;
    /** |R_free| / reference force after each Newton solve (the last one <= tolerance). */
    std::vector<double> residuals;
    std::size_t         segment          = 0; ///< index in load_path of the segment of this step
    double              controlled_force = 0; ///< resultant P of the controlled load, N/m (0: none)
  };

  struct StaticPlasticityResult
  {
    std::vector<StaticStep> steps; ///< steps[0]: equilibrium at load factor 0
    /** Out-of-balance force of the initial state (gravity + initial stress) at the free DoFs
     *  before step 0, relative to the body's weight (0 if weightless). */
    double               initial_out_of_balance = 0;
    double               weight                 = 0; ///< total body weight, N/m
    unsigned int         n_dofs                 = 0;
    StaticStepStatistics step_control;
    double               plastic_dissipation = 0; ///< total at the end, J/m
    double               damage_dissipation  = 0; ///< total at the end, J/m
    /** Final displacement at each mesh vertex (m), in mesh.vertices order. */
    std::vector<std::array<double, 2>> vertex_displacements;
    /** The final state of one cell: where it is, its damage, plastic strain and stress (means
     *  weighted by the points' JxW, so that mean times size[0] size[1] is the integral). */
    struct CellState
    {
      std::array<double, 2> centre{};   ///< m
      std::array<double, 2> size{};     ///< extent in x and y, m
      double                damage = 0; ///< mean over the cell's quadrature points, -
      double plastic_strain        = 0; ///< largest equivalent plastic strain of its points, -
      /** Mean {sigma_xx, sigma_yy, sigma_xy}, Pa: the stress of the converged state. */
      std::array<double, 3> stress{};
      /** Mean PointOutput::reinforcement_stress_xx/yy (the smeared bars' share), Pa. */
      std::array<double, 2> reinforcement_stress{};
      /**
       * First moments in the cell, Pa m: the means of (x - centre[0]) times sigma_xx, sigma_yy
       * and the bars' share of sigma_yy, and of (y - centre[1]) times sigma_xy. The moment about
       * the line x = x_0 that a row of cells passes across its mid-height, in equilibrium with
       * the loads above it to round-off, is the sum over the row of (sigma_yy (x - x_0) +
       * (stress_moment[1] - stress_moment[0]) / 2 + stress_moment[3]) size[0]: the solver's
       * mean-dilatation strain (B-bar) passes half the deviator of a cell's own moments, and
       * the bilinear cells carry part of the bending as a couple of their shear stress (sigma_xy
       * linear in y; 1.6 % of the moment of an elastic wall on 5 cm cells, 4 % at a hinge).
       */
      std::array<double, 4> stress_moment{};
      double                tension_damage = 0; ///< mean PointOutput::tension_damage, -
      /** Mean PointOutput::crack_normal_yy over the points with d_t > 0 (0: none), -. */
      double crack_normal_yy = 0;
    };
    std::vector<CellState> cell_states; ///< one per cell (mesh.cells order)
  };

  /**
   * Solves the static problem step by step: step 0 brings gravity and the initial stress into
   * equilibrium with the prescribed parts held at zero displacement; step n prescribes n /
   * n_steps of the prescribed displacements and iterates full Newton with the laws' consistent
   * tangents (a direct sparse solve per iteration). History is committed per converged step.
   * Serial. Log lines (one per step) go to *log if not nullptr. Bad input throws
   * std::invalid_argument; a step that does not converge after max_cuts halvings throws
   * NumericalError (time = load factor, step = index the step would have had in steps).
   */
  StaticPlasticityResult run_static_plasticity(const StaticPlasticityParameters &parameters,
                                               std::ostream                     *log = nullptr);
} // namespace kimp::fem
