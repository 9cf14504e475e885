// Internal to the central difference integrator: the run state (CentralDifferenceStepper::Session)
// and what its two kernels share: the effective-matrix inverse, the law velocity and the explicit
// isolator and contact force evaluation. Not part of the public API.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/response_recorder.h"
#include "lumped/isolators/isolator.h"
#include "lumped/structure/tridiagonal_matrix.h"

namespace kimp::lumped
{
  namespace cdm
  {
    /**
     * Inverse of the constant effective matrix A = M/Δt² + C/(2Δt). A is block-tridiagonal with
     * one block per building (zero coupling between blocks, and between DOFs without damping
     * coupling). Small blocks keep their dense inverse: a matrix-vector product has a much shorter
     * dependency chain than the sequential Thomas sweeps, which matters because every step waits
     * for the previous one; blocks above `max_dense` DOFs use the pre-factorised Thomas algorithm.
     */
    class EffectiveMatrixInverse
    {
    public:
      static constexpr std::size_t max_dense = 16;

      explicit EffectiveMatrixInverse(const TridiagonalMatrix &a);

      /// y = A⁻¹·x (x and y distinct).
      void apply(const double *x, double *y) const;

    private:
      struct Block
      {
        std::size_t         first = 0;
        std::size_t         size  = 0;
        std::vector<double> inverse;
        TridiagonalSolver   thomas;
      };
      std::vector<Block> blocks_;
    };

    /// Steps per bookkeeping block: the dynamics runs a block, then velocities, accelerations,
    /// energies and peaks are evaluated for the whole block in loops over the steps (vectorised).
    constexpr long block_steps = 64;
  } // namespace cdm

  /**
   * Everything one integration touches, allocated at init(). Displacements live in a block
   * buffer, one row per DOF plus a zero row for the ground, column c holding u at step
   * s0 − 2 + c for the block starting at step s0 (so step s0 + k reads u_{n−2}, u_{n−1}, u_n in
   * columns k, k + 1, k + 2 and writes u_{n+1} to column k + 3).
   */
  struct CentralDifferenceStepper::Session
  {
    const PoundingModel            *model  = nullptr;
    const CentralDifferenceOptions *opt    = nullptr;
    const GroundMotion             *motion = nullptr;

    std::size_t n       = 0;
    double      dt      = 0.0;
    long        n_steps = 0; ///< last step index N (t_N = end)
    long        step    = 0; ///< next step to evaluate
    LawVelocity scheme  = LawVelocity::backward;

    // matrices
    std::vector<double>                          mass;
    std::vector<double>                          b_diag, b_upper; ///< 2M/Δt² − K
    std::vector<double>                          d_diag, d_upper; ///< −M/Δt² + C/(2Δt)
    std::unique_ptr<cdm::EffectiveMatrixInverse> a_inverse;       ///< (M/Δt² + C/(2Δt))⁻¹
    /// Fused kernel (up to 8 DOFs): dense column-major matrices with leading dimension padded_n
    /// (padding rows zero): A⁻¹, A⁻¹(C/Δt + K), A⁻¹K, and the vector A⁻¹M·1.
    bool                fused = false;
    std::vector<double> dense_inverse, dense_f, dense_g, dense_am;
    /// Fused kernel state carried between blocks (padded_n each): u_n, Δu_n = u_n − u_{n−1},
    /// z_{n−1} = A⁻¹K·u_{n−1}, and v and a of the last step taken (checks, history sample).
    std::vector<double> fused_u, fused_d, fused_z, fused_v, last_accel;
    /// delta_prev/delta_prev2 hold δ_{n−1}, δ_{n−2} (false after steps that skipped the laws).
    bool deltas_current = true;
    /// Fused kernel, per DOF lane (3 × padded_n each): the running peaks of |u_i|, |a_i| and
    /// |u_i − u_{i−1}| (u_{−1} = 0; the storeys' drifts, storeys being between consecutive
    /// DOFs), and the sums over the steps so far of ü_g·v_i, v_i² and v_i·v_{i+1}.
    std::vector<double> fused_peaks, fused_sums;
    int                 lanes    = 2; ///< doubles per vector register of the fused kernel
    std::size_t         padded_n = 0; ///< n rounded up to a multiple of lanes
    double              p_in_0 = 0.0, p_visc_0 = 0.0; ///< input and viscous power at t_0, W
    /// Fused kernel, per DOF lane: 1 where the storey below DOF i joins DOF i − 1, 0 where it
    /// joins the ground (or there is none).
    std::vector<double> drift_mask;
    /// Fused kernel contact pre-check: a law is skipped while u_L − u_R <= gap_skip (the gap, or
    /// −∞ while the law is in contact, was called last step or holds a force).
    std::vector<double> gap_skip;
    /// Any-size kernel (more than 8 DOFs): per vector of rows r = i·lanes..(i + 1)·lanes − 1,
    /// the columns [any_lo[i], any_hi[i]) (multiples of 4) outside which A⁻¹, A⁻¹(C/Δt + K)
    /// and A⁻¹K are zero in those rows (one block per building), and its scratch vectors.
    std::vector<int>         any_lo, any_hi;
    std::vector<double>      any_work;
    const TridiagonalMatrix *k = nullptr;
    const TridiagonalMatrix *c = nullptr;

    // block buffers
    std::size_t         width = 0; ///< columns of the displacement block, block_steps + 3
    std::vector<double> u_block;   ///< (n + 1) × width
    std::vector<double> ag_block, velocity, mv, cvv;
    std::vector<double> lane_peak_u, lane_peak_a, lane_peak_d; ///< per DOF/storey and lane
    std::vector<double> force, rhs, solution;
    std::vector<int>    force_dofs; ///< DOFs that can receive a non-linear force, ascending

    // ground motion
    bool        integer_substeps = false; ///< Δt divides the record's dt exactly
    long        sub              = 1;     ///< steps per record interval (record dt / Δt)
    double      inv_sub          = 1.0;   ///< 1/sub
    std::size_t rec_j            = 0;     ///< record interval of the next step
    long        rec_s            = 0;     ///< sub-step of the next step within rec_j
    long        every            = 0;     ///< steps between history samples (0: none)
    /// Steps between check points (energy checks): at most 512, and a divisor of `every` when
    /// histories are recorded, so that check points and samples coincide (fewer, longer blocks).
    long check_every = 512;

    // laws
    std::unique_ptr<Isolator>              iso;
    std::vector<std::unique_ptr<ForceLaw>> laws;
    std::vector<int>                       left, right;
    std::vector<std::size_t>               left_row, right_row; ///< offsets in u_block + 2
    std::vector<double>                    gap, cf, delta_prev, delta_prev2;
    std::vector<int>                       active, called_prev;
    std::vector<int>                       storey_low, storey_up;

    // energy sums (t_n of the last recorded step)
    double w_in = 0.0, w_visc = 0.0, w_contact = 0.0, p_in_prev = 0.0, p_visc_prev = 0.0;
    double e0 = 0.0, e_kin = 0.0, e_strain = 0.0;

    /// Impacts, peak contact forces, energy checks, histories (peaks of u, a and drifts: above).
    ResponseRecorder rec;

    using Kernel    = void (*)(Session &, long len);
    Kernel dynamics = nullptr;

    /// Displacement buffer strides: the reference kernel stores a row per DOF (row_stride =
    /// width, col_stride = 1: the bookkeeping vectorises over steps), the fused kernel a column
    /// per step (row_stride = 1, col_stride = the padded DOF count: one vector store per step).
    std::size_t row_stride = 0, col_stride = 1;

    double *column(const std::size_t row, const long c)
    {
      return u_block.data() + row * row_stride + static_cast<std::size_t>(c) * col_stride;
    }

    /// Set up for a run under `g` (central_difference_session.cc), in the steps below.
    void init(const CentralDifference &cdm, const GroundMotion &g);
    /// Reference kernel: b, d and the effective matrix A = M/Δt² + C/(2Δt); returns A.
    TridiagonalMatrix prepare_reference_matrices();
    /// Which kernel runs (fused: DOFs in storey order and, automatic, blocks the dense products
    /// pay for), its lanes and the fused state vectors.
    void choose_kernel();
    /// Fused kernels: A⁻¹, A⁻¹(C/Δt + K), A⁻¹K, A⁻¹M padded to the lanes, and each row vector's
    /// columns.
    void prepare_fused_matrices(const TridiagonalMatrix &a);
    /// The displacement block and the per-step buffers of the chosen kernel.
    void prepare_buffers();
    /// Fresh clones of the contact laws, their DOFs and gaps, the storeys' DOFs and the peaks.
    void prepare_contacts();
    /// u_{−1}, u_{−2} (and the fused z_{−1}) from u_0, v_0 and a_0 of the first ground step.
    void initial_conditions(const GroundMotion &g);
    /// Substeps of the record, the output and check intervals, the recorder and the works.
    void prepare_recording(const GroundMotion &g);
    /// Up to `count` steps in blocks ending at the check points (central_difference.cc).
    void advance(long count);
    /// Reference kernel: velocities, accelerations, peaks and powers of a block, vectorised over
    /// its steps (central_difference_reference.cc).
    void bookkeeping(long len);
    /// E_kin, E_strain (and the fused kernel's works) at a check point.
    void checkpoint_energies(long len);
    /// Energy balance, divergence checks and the history sample at a check point.
    void checkpoint(long k);
    /// The Response so far (peaks reduced over lanes, laws' results).
    Response response() const;
  };

  namespace cdm
  {
    using Session = CentralDifferenceStepper::Session;

    /**
     * Isolator and contact forces at t_n = (s0 + k)·Δt from the displacements in the block
     * columns (explicit, trial + commit). A law whose gap is open and which is not in contact is
     * not called: every law returns zero force there and its history only matters from the next
     * contact on (modified Kelvin-Voigt's permanent indentation is read by the law itself when it
     * is called again; laws 5-7 take v_imp from the rate of the first contact step). Before a law
     * is called again it is brought to the last open state it skipped, so its first contact step
     * starts from δ_{n−1} <= 0 (not from an older open state).
     */
    template <class IsolatorType>
    class ForceEvaluator
    {
    public:
      explicit ForceEvaluator(Session &s)
        : s_(s)
        , iso_(static_cast<IsolatorType *>(s.iso.get()))
        , ub_(s.u_block.data())
        , cs_(s.col_stride)
        , f_(s.force.data())
        , fd_(s.force_dofs.data())
        , n_fd_(s.force_dofs.size())
        , ground_(s.n)
        , inv_dt_(1.0 / s.dt)
        , scheme_(s.scheme)
        , nc_(s.laws.size())
        , row_l_(s.left_row.data())
        , row_r_(s.right_row.data())
        , gap_(s.gap.data())
        , active_(s.active.data())
        , called_(s.called_prev.data())
        , cf_(s.cf.data())
        , dp_(s.delta_prev.data())
        , dpp_(s.delta_prev2.data())
      {
      }

      /// Forces at step s0 + k (time t) into Session::force.
      inline __attribute__((always_inline)) void operator()(const long k, const double t)
      {
        const double *const ub = ub_ + static_cast<std::size_t>(k) * cs_;
        double *const       f  = f_;
        for (std::size_t q = 0; q < n_fd_; ++q)
          f[fd_[q]] = 0.0;
        f[ground_] = 0.0;
        if (iso_)
          f[0] = isolator(k, ub[2 * cs_]);
        contacts(k, t);
      }

      /// Isolator force at step s0 + k for u_0 = `u0` (equal to the block's value; passed in so
      /// that the step-to-step chain does not go through memory), committed.
      inline __attribute__((always_inline)) double isolator(const long k, const double u0)
      {
        const double *const ub = ub_ + static_cast<std::size_t>(k) * cs_;
        const double f = iso_->set_trial(u0, law_rate(scheme_, u0, ub[cs_], ub[0], inv_dt_)).force;
        iso_->commit();
        s_.rec.isolator_force(f);
        return f;
      }

      bool has_isolator() const { return iso_ != nullptr; }

      /// Contact forces at step s0 + k, added to Session::force; true if any law was called (the
      /// force entries may then be non-zero).
      inline __attribute__((always_inline)) bool contacts(const long k, const double t)
      {
        const double *const ub      = ub_ + static_cast<std::size_t>(k) * cs_;
        bool                touched = false;
        for (std::size_t c = 0; c < nc_; ++c)
        {
          const double delta = ub[row_l_[c]] - ub[row_r_[c]] - gap_[c];
          if (delta > 0.0 || active_[c])
          {
            contact(c, delta, t);
            touched = true;
          }
          else
          {
            called_[c] = 0;
            // Zero force now; the work term survives only if the last step's force was not
            // zero.
            if (cf_[c] != 0.0)
            {
              s_.w_contact += 0.5 * cf_[c] * (delta - dp_[c]);
              cf_[c] = 0.0;
            }
          }
          dpp_[c] = dp_[c];
          dp_[c]  = delta;
        }
        return touched;
      }

      /// Evaluate and commit law `c` at δ (it is in contact or its gap is closed).
      void contact(const std::size_t c, const double delta, const double t)
      {
        const int    L    = s_.left[c];
        const int    R    = s_.right[c];
        ForceLaw    &law  = *s_.laws[c];
        const double dp   = dp_[c];
        const double rate = law_rate(scheme_, delta, dp, dpp_[c], inv_dt_);
        if (!called_[c])
        {
          law.set_trial(dp, (dp - dpp_[c]) * inv_dt_);
          law.commit();
        }
        const double force = law.set_trial(delta, rate).force;
        law.commit();
        const int now_active = law.in_contact() ? 1 : 0;
        if (now_active && !active_[c])
          s_.rec.impact(c, t, rate);
        active_[c] = now_active;
        called_[c] = 1;
        // Contact work ∫F dδ, trapezoid between t_{n−1} and t_n.
        s_.w_contact += 0.5 * (cf_[c] + force) * (delta - dp);
        cf_[c] = force;
        f_[L] += force;
        f_[R] -= force;
        s_.rec.contact_force(c, force, delta, t);
      }

    private:
      Session            &s_;
      IsolatorType *const iso_;
      double *const       ub_;
      const std::size_t   cs_;
      double *const       f_;
      const int *const    fd_;
      const std::size_t   n_fd_;
      const std::size_t   ground_;
      const double        inv_dt_;
      const LawVelocity   scheme_;
      const std::size_t   nc_;
      const std::size_t  *row_l_;
      const std::size_t  *row_r_;
      const double       *gap_;
      int *const          active_;
      int *const          called_;
      double *const       cf_;
      double *const       dp_;
      double *const       dpp_;
    };

    /// A contact pre-check failed at step s0 + k (or the run is in its first two steps): the
    /// reference kernel's contact evaluation for every law, with δ_{n−1} and δ_{n−2} re-formed
    /// from the displacement columns if the previous step skipped the laws, then the pre-check
    /// re-armed. Returns true if a law was called (forces in Session::force).
    template <class IsolatorType>
    __attribute__((noinline)) inline bool
    fused_contacts(Session &s, ForceEvaluator<IsolatorType> &forces, const long k)
    {
      const std::size_t nc = s.laws.size();
      if (!s.deltas_current)
      {
        const double     *col = s.u_block.data() + static_cast<std::size_t>(k) * s.col_stride;
        const std::size_t cs  = s.col_stride; // left_row points at column 2 (u_n)
        for (std::size_t c = 0; c < nc; ++c)
        {
          s.delta_prev[c]  = col[s.left_row[c] - cs] - col[s.right_row[c] - cs] - s.gap[c];
          s.delta_prev2[c] = col[s.left_row[c] - 2 * cs] - col[s.right_row[c] - 2 * cs] - s.gap[c];
        }
      }
      const bool touched = forces.contacts(k, static_cast<double>(s.step + k) * s.dt);
      for (std::size_t c = 0; c < nc; ++c)
      {
        const bool armed = !s.active[c] && !s.called_prev[c] && s.cf[c] == 0.0;
        s.gap_skip[c]    = armed ? s.gap[c] : -std::numeric_limits<double>::infinity();
      }
      s.deltas_current = true;
      return touched;
    }

    /// The reference (block-tridiagonal) kernel for the model's isolator type
    /// (central_difference_reference.cc).
    Session::Kernel reference_kernel(const Isolator *isolator);

    /// Widest vector (doubles per register) of the fused kernel on this processor, capped at
    /// `cap` (0: no cap) (central_difference_fused.cc).
    int fused_lanes(int cap);

    /// The any-size fused kernel (any n; the fused kernel's step, products restricted to each
    /// row vector's columns, `lanes` doubles per vector) (central_difference_anysize.cc).
    Session::Kernel anysize_kernel(int lanes, const Isolator *isolator);

    /// The fused kernel for n <= 8 DOFs, `lanes` doubles per vector and the model's isolator type
    /// (nullptr for n > 8) (central_difference_fused.cc).
    Session::Kernel fused_kernel(std::size_t n, int lanes, const Isolator *isolator);
  } // namespace cdm
} // namespace kimp::lumped
