// Central difference method for the pounding system (thesis eq. 3.9-3.11):
//   (M/Δt² + C/(2Δt))·u_{n+1} = p_n − K·u_n − f_nl,n + (2M/Δt²)·u_n − (M/Δt² − C/(2Δt))·u_{n−1},
// stable for Δt < 2/ω_max (3.12) with ω_max including every contact's ω_imp = √(k_t/m_eff) (3.13).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lumped/excitation/ground_motion.h"
#include "lumped/integrators/response.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::lumped
{
  /**
   * Velocity handed to the impact laws and the isolator at step n. The central difference
   * velocity (u_{n+1} − u_{n−1})/(2Δt) needs u_{n+1}, which depends on the force being evaluated,
   * so an explicit scheme must use past displacements (docs/physics.md §5):
   *  - backward: (u_n − u_{n−1})/Δt, first order, lags by Δt/2 (the thesis' choice);
   *  - backward_second_order: (3u_n − 4u_{n−1} + u_{n−2})/(2Δt), second order, no lag.
   * The viscous matrix C is integrated implicitly (central) in either case.
   */
  enum class LawVelocity
  {
    backward,
    backward_second_order
  };

  /// The rate of a quantity x handed to a law at step n, from x_n, x_{n−1} and x_{n−2}
  /// (LawVelocity; inv_dt = 1/Δt).
  inline double law_rate(const LawVelocity scheme,
                         const double      x_n,
                         const double      x_nm1,
                         const double      x_nm2,
                         const double      inv_dt)
  {
    return scheme == LawVelocity::backward ? (x_n - x_nm1) * inv_dt :
                                             (3.0 * x_n - 4.0 * x_nm1 + x_nm2) * (0.5 * inv_dt);
  }

  /**
   * Time-loop kernel of the central difference method.
   *  - automatic: when every storey joins DOF i − 1 and DOF i or the ground and DOF i (true for
   *    every PoundingScene), the fused dense kernel for models of at most 8 DOFs (the isolated
   *    4-storey building with walls, bumpers or a basement; fixed-base buildings of up to 8
   *    storeys; an isolated building with one small neighbour) and the any-size fused kernel
   *    beyond while every building has at most 16 DOFs (neighbours on both sides, basements,
   *    bumpers); the block-tridiagonal reference kernel otherwise (taller buildings, where its
   *    O(n) Thomas sweeps beat dense products);
   *  - reference: always the block-tridiagonal kernel (Thomas or a dense inverse per block, the
   *    step-lane bookkeeping); slower, kept as the reference (oracle) for the fused kernels;
   *  - any_size: the any-size fused kernel for every model size (tests and benchmarks compare
   *    it with the fused kernel at <= 8 DOFs).
   */
  enum class CdmKernel
  {
    automatic,
    reference,
    any_size
  };

  /**
   * The stepping options of every central difference integrator (CentralDifferenceOptions, the
   * plan engine's lumped::plan::PlanOptions):
   *
   * | option                   | unit | default | meaning                                     |
   * |--------------------------|------|---------|---------------------------------------------|
   * | dt                       | s    | 0       | time step; 0 = auto: safety·Δt_cr, reduced  |
   * |                          |      |         | so that it divides the record's dt exactly  |
   * | safety                   | -    | 0.5     | (0, 1]; margin for contact damping and      |
   * |                          |      |         | stiffening beyond the expected penetration  |
   * | expected_max_penetration | m    | 0.05    | δ at which k_t = law.stability_stiffness(δ) |
   * | duration                 | s    | 0       | analysis length; 0 = the record's length    |
   * | output_interval          | s    | 0.01    | history sampling; 0 = no histories          |
   * | law_velocity             | -    | backward| see LawVelocity                             |
   * | initial_displacement     | m    | zeros   | u(0), empty or one per DOF                  |
   * | initial_velocity         | m/s  | zeros   | u̇(0), empty or one per DOF                  |
   * | divergence_energy_factor | -    | 10      | stop when E_kin + E_strain exceeds this     |
   * |                          |      |         | times max(E_0 + W_in)                       |
   */
  struct SteppingOptions
  {
    double              dt                       = 0.0;
    double              safety                   = 0.5;
    double              expected_max_penetration = 0.05;
    double              duration                 = 0.0;
    double              output_interval          = 0.01;
    LawVelocity         law_velocity             = LawVelocity::backward;
    std::vector<double> initial_displacement;
    std::vector<double> initial_velocity;
    double              divergence_energy_factor = 10.0;
  };

  /**
   * The checks of SteppingOptions for a model of n_dofs DOFs.
   * @throws std::invalid_argument naming the option ("central_difference.<key> = ...").
   */
  void check_stepping(const SteppingOptions &options, std::size_t n_dofs);

  /**
   * SteppingOptions and the kernel of the planar integrator:
   *
   * | option                   | unit | default | meaning                                     |
   * |--------------------------|------|---------|---------------------------------------------|
   * | kernel                   | -    | auto    | see CdmKernel                               |
   * | vector_lanes             | -    | 0       | cap on the fused kernel's vector width in   |
   * |                          |      |         | doubles: 0 = widest available (AVX-512: 8,  |
   * |                          |      |         | AVX2: 4, SSE2: 2), or 4 or 2; bitwise equal |
   * |                          |      |         | results for every width                     |
   */
  struct CentralDifferenceOptions : SteppingOptions
  {
    CdmKernel kernel       = CdmKernel::automatic;
    int       vector_lanes = 0;
  };

  /// Stability limit of the central difference method for a model.
  struct StabilityLimit
  {
    double      omega_structure = 0.0; ///< ω_max of (K + K1·e0e0ᵀ, M), contacts open, rad/s
    double      omega_closed    = 0.0; ///< ω_max with every contact at its tangent k_t, rad/s
    double      omega_impact    = 0.0; ///< max_c √(k_t,c/m_eff,c), rad/s
    double      dt_critical     = 0.0; ///< 2/max(the three), s
    std::string governing;             ///< which bound governs (for messages)
  };

  /**
   * Δt_cr from the structure and every contact, with k_t = law.stability_stiffness(δ_max).
   * @param[in] expected_max_penetration δ_max, m (> 0)
   */
  StabilityLimit stability_limit(const PoundingModel &model, double expected_max_penetration);

  /**
   * The step of the central difference method for a record sampled every `record_dt` s:
   * options.dt when given (> 0), else (auto) record_dt divided into the fewest equal steps of at
   * most options.safety·Δt_cr.
   * @throws std::invalid_argument for record_dt <= 0, or auto without a stability limit (no
   * stiffness); TimeStepError when options.dt >= Δt_cr (both numbers named).
   */
  double central_difference_step(double                 record_dt,
                                 const SteppingOptions &options,
                                 const StabilityLimit  &stability);

  /**
   * What every fixed-step central difference integrator holds (CentralDifference, the plan
   * engine's lumped::plan::PlanCentralDifference): its model, its options (SteppingOptions or
   * derived) and their stability limit, and the step it takes for a record. The derived
   * constructor checks the options and sets stability_.
   */
  template <class Model, class Options>
  class CentralDifferenceMethod
  {
  public:
    /// ω_max of the structure, with the contacts closed, of the impacts, and Δt_cr = 2/ω_max.
    const StabilityLimit &stability() const { return stability_; }

    /**
     * The step used for a record sampled every `record_dt` seconds (central_difference_step()).
     * @throws TimeStepError when options.dt exceeds stability().dt_critical (both numbers named).
     */
    double time_step(double record_dt) const
    {
      return central_difference_step(record_dt, options_, stability_);
    }

    const Model   &model() const { return model_; }
    const Options &options() const { return options_; }

  protected:
    CentralDifferenceMethod(Model model, Options options)
      : model_(std::move(model))
      , options_(std::move(options))
    {
    }

    Model          model_;
    Options        options_;
    StabilityLimit stability_;
  };

  /**
   * Fixed-step central difference integrator with an allocation-free time loop. The effective
   * matrix A = M/Δt² + C/(2Δt) is block-tridiagonal (one block per building, no coupling between
   * blocks) and is inverted once. Contacts and the isolator are evaluated explicitly at u_n
   * (trial + commit every step); a law whose gap is open and which is not in contact is not
   * called, and is brought up to date with the last open state just before it closes (so its
   * first contact step starts from the true previous, open, deformation).
   *
   * Two kernels (CdmKernel), chosen at init():
   *  - fused (automatic, n <= 8 DOFs, see CdmKernel): the increment form
   *      Δu_{n+1} = Δu_n − z_{n−1} − A⁻¹M·1·ü_g,n − A⁻¹(C/Δt + K)·Δu_n − A⁻¹·f_nl,n,
   *      u_{n+1} = u_n + Δu_{n+1},  z_n = z_{n−1} + A⁻¹K·Δu_n  (z_n = A⁻¹K·u_n),
   *    algebraically the central difference step. u_n, Δu_n and z_n stay in vector registers
   *    from step to step; Δu is carried exactly (never re-formed from u: no cancellation in
   *    u_{n+1} − u_n at small Δt). Only one dense product (summed as a tree) and the force term
   *    lie on the step-to-step dependency chain; z, the bookkeeping of the step (v_n =
   *    (Δu_n + Δu_{n+1})/(2Δt), a_n = (Δu_{n+1} − Δu_n)/Δt² + ü_g, peaks, per-DOF running sums
   *    for the input and viscous work, reduced at the check points, so that max(E_0 + W_in)
   *    is taken over the check points) overlap with it. A contact law is called only when a
   *    cheap pre-check (u_L − u_R > gap, or the law in contact or just released) fails, outside
   *    the fast loop. The vector width (SSE2, AVX2 or AVX-512F; see
   *    CentralDifferenceOptions::vector_lanes) is picked at run time; every operation is per
   *    DOF lane without FMA contraction, so all widths give bitwise equal results;
   *  - any-size fused (automatic, more than 8 DOFs, buildings of <= 16 DOFs): the same step; A is
   * block-diagonal (one block per building), so each vector of rows multiplies only its buildings'
   * columns, in four partial sums by column index mod 4 (the order depends on the column only, and
   * the columns a wider vector adds are exact zeros: bitwise equal results for every width). The
   *    state lives in L1 scratch rather than registers;
   *  - reference (on request, or a model whose storeys do not join consecutive DOFs): right-hand
   *    side with the
   *    tridiagonal B = 2M/Δt² − K and D = −M/Δt² + C/(2Δt), A⁻¹ block-wise (dense for blocks
   *    of up to 16 DOFs, else the pre-factorised Thomas algorithm), and the bookkeeping of each
   *    block of up to 64 steps vectorised over the steps afterwards.
   * Both kernels run in blocks of up to 64 steps that end at every check point (history sample,
   * every ≤ 512 steps aligned with the history interval, the last step), and every quantity is
   * computed with the same operations in the same order whatever the blocking, so advance(k) and
   * step() give bitwise equal results. The two kernels agree to round-off
   * (tests/lumped/integrator_test.cc states the tolerances).
   *
   * Recorded at every t_n (n = 0..N): u_n, the step's acceleration (u_{n+1} − 2u_n + u_{n−1})/Δt²
   * + ü_g(t_n) (docs/physics.md §5), the contact forces F_n, and the energy terms (E_kin and
   * E_strain only at the check points, where they are used).
   */
  class CentralDifference : public CentralDifferenceMethod<PoundingModel, CentralDifferenceOptions>
  {
  public:
    /// @throws std::invalid_argument for invalid options.
    explicit CentralDifference(PoundingModel model, CentralDifferenceOptions options = {});

    /**
     * Integrate from rest (or the initial conditions) under ü_g (zero past the record's end):
     * a CentralDifferenceStepper advanced from init() to the end.
     * @throws TimeStepError, DivergenceError (time, step and DoF named).
     */
    Response run(const GroundMotion &motion) const;
  };

  /**
   * Step-by-step integration with a CentralDifference (MFEM ODESolver Init/Step;
   * docs/architecture.md "Time integration"). Time is counted in integer steps, t_n = n·Δt (never
   * accumulated); Δt = time_step(motion.dt) is fixed at init(); the run has steps n = 0..N, N =
   * last_step() = round(duration/Δt).
   *
   * Contract:
   *  - init(motion) [in: motion, which must outlive the stepper or the next init()]: (re)starts
   *    at n = 0 from the options' initial conditions (u_0, u̇_0, with u_{−1}, u_{−2} from a Taylor
   *    expansion), with fresh clones of every contact law and of the isolator in their virgin
   *    state, and an empty Response. Whatever a previous run left behind is discarded, so a run
   *    after init() is identical to a run on a new stepper.
   *  - step() [in: n, u_{n−1}, u_n (and u_{n−2}), the laws' and the isolator's state committed at
   *    t_{n−1}; out: their state committed at t_n, u_{n+1}, the response at t_n recorded (peaks,
   *    energies, history sample), n ← n + 1]. The forces are evaluated explicitly at u_n and
   *    committed every step; nothing is ever reverted.
   *  - advance(k): min(k, N + 1 − n) steps, identical to as many step() calls (faster: the
   *    bookkeeping runs vectorised over blocks of steps).
   *  - Integrators do no I/O; numerical failure throws DivergenceError (time, step, DoF), after
   *    which the stepper must be init()-ed again.
   */
  class CentralDifferenceStepper
  {
  public:
    /// @param integrator model, options and stability limit; must outlive the stepper.
    explicit CentralDifferenceStepper(const CentralDifference &integrator);
    ~CentralDifferenceStepper();
    CentralDifferenceStepper(CentralDifferenceStepper &&) noexcept;
    CentralDifferenceStepper &operator=(CentralDifferenceStepper &&) noexcept;

    /// Start or restart under `motion`. @throws TimeStepError, std::invalid_argument.
    void init(const GroundMotion &motion);
    /// One step (see the contract). @throws std::logic_error before init() or after the end.
    void step();
    /// Up to `count` steps; returns how many were taken (0 at the end).
    long advance(long count);

    /// Index n of the next step to evaluate (0 after init(), N + 1 at the end).
    long step_index() const;
    /// t_n = n·Δt, s.
    double time() const;
    /// Δt, s.
    double dt() const;
    /// N, the index of the last step (t_N = duration).
    long last_step() const;
    /// True once step N has been evaluated.
    bool finished() const;
    /// True when init() chose the fused dense kernel (see CentralDifference and CdmKernel).
    bool uses_fused_kernel() const;
    /// u_{n+level} for level 0, −1, −2 (m, relative to the ground).
    std::vector<double> displacement(int level = 0) const;
    /// The response recorded at t_0..t_{n−1} (energy fields as of the last check: every history
    /// sample, every ≤ 512 steps and the last step).
    Response response() const;

    struct Session; ///< run state (central_difference_session.h)

  private:
    friend class FreeRunPrefix; // restarts a run from a contact-free run's check point

    void require_init(const char *what) const;

    const CentralDifference *integrator_;
    std::unique_ptr<Session> session_;
    bool                     initialised_ = false;
  };
} // namespace kimp::lumped
