// Central difference method for pounding (thesis eq. 3.9-3.13): stability limit, time-step choice
// and the allocation-free time loop (fused dense kernel for <= 8 DOFs, block-tridiagonal
// otherwise).
#include "lumped/integrators/central_difference.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#if defined(__SSE2__)
#  include <emmintrin.h>
#endif

#include "lumped/integrators/integration_errors.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/linear_isolator.h"

namespace kimp::lumped
{
  namespace
  {
    double largest_omega(const std::vector<double> &masses, const Eigen::MatrixXd &k)
    {
      const auto      n = static_cast<Eigen::Index>(masses.size());
      Eigen::VectorXd inv_sqrt_m(n);
      for (Eigen::Index i = 0; i < n; ++i)
        inv_sqrt_m(i) = 1.0 / std::sqrt(masses[static_cast<std::size_t>(i)]);
      const Eigen::MatrixXd a = inv_sqrt_m.asDiagonal() * k * inv_sqrt_m.asDiagonal();
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a, Eigen::EigenvaluesOnly);
      return std::sqrt(std::max(solver.eigenvalues().maxCoeff(), 0.0));
    }
  } // namespace

  StabilityLimit stability_limit(const PoundingModel &model, const double expected_max_penetration)
  {
    if (!(expected_max_penetration > 0.0))
    {
      std::ostringstream msg;
      msg << "expected_max_penetration = " << expected_max_penetration << " m (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
    StabilityLimit  s;
    Eigen::MatrixXd k = model.initial_stiffness_matrix();
    s.omega_structure = largest_omega(model.masses(), k);
    std::string impact_name;
    for (const ContactPair &c : model.contacts())
    {
      const double kt = c.law->stability_stiffness(expected_max_penetration);
      const double w  = std::sqrt(kt / c.effective_mass);
      if (w > s.omega_impact)
      {
        s.omega_impact = w;
        impact_name    = c.name;
      }
      if (c.left_dof >= 0)
        k(c.left_dof, c.left_dof) += kt;
      if (c.right_dof >= 0)
        k(c.right_dof, c.right_dof) += kt;
      if (c.left_dof >= 0 && c.right_dof >= 0)
      {
        k(c.left_dof, c.right_dof) -= kt;
        k(c.right_dof, c.left_dof) -= kt;
      }
    }
    s.omega_closed =
      model.contacts().empty() ? s.omega_structure : largest_omega(model.masses(), k);
    const double w_max = std::max({s.omega_structure, s.omega_closed, s.omega_impact});
    s.dt_critical      = 2.0 / w_max;
    std::ostringstream g;
    if (w_max == s.omega_impact && !impact_name.empty())
      g << "contact '" << impact_name << "': omega_imp = sqrt(k_t/m_eff) = " << s.omega_impact
        << " rad/s with k_t at a penetration of " << expected_max_penetration << " m";
    else if (w_max == s.omega_structure)
      g << "structure: omega_max = " << s.omega_structure << " rad/s";
    else
      g << "structure with all contacts closed: omega_max = " << s.omega_closed
        << " rad/s with k_t at a penetration of " << expected_max_penetration << " m";
    s.governing = g.str();
    return s;
  }

  CentralDifference::CentralDifference(PoundingModel model, CentralDifferenceOptions options)
    : model_(std::move(model))
    , options_(std::move(options))
  {
    const auto fail = [](const char *key, const double v, const char *rule)
    {
      std::ostringstream msg;
      msg << "central_difference." << key << " = " << v << " (" << rule << ')';
      throw std::invalid_argument(msg.str());
    };
    if (!(options_.dt >= 0.0 && std::isfinite(options_.dt)))
      fail("dt", options_.dt, "must be > 0 s, or 0 for auto");
    if (!(options_.safety > 0.0 && options_.safety <= 1.0))
      fail("safety", options_.safety, "must be in (0, 1]");
    if (!(options_.duration >= 0.0 && std::isfinite(options_.duration)))
      fail("duration", options_.duration, "must be >= 0 s (0: the record's length)");
    if (!(options_.output_interval >= 0.0 && std::isfinite(options_.output_interval)))
      fail("output_interval", options_.output_interval, "must be >= 0 s (0: no histories)");
    if (!(options_.divergence_energy_factor > 1.0))
      fail("divergence_energy_factor", options_.divergence_energy_factor, "must be > 1");
    if (options_.vector_lanes != 0 && options_.vector_lanes != 2 && options_.vector_lanes != 4 &&
        options_.vector_lanes != 8)
      fail("vector_lanes",
           static_cast<double>(options_.vector_lanes),
           "must be 0 (widest available), 2, 4 or 8");
    const std::size_t n = model_.n_dofs();
    if (!options_.initial_displacement.empty() && options_.initial_displacement.size() != n)
      fail("initial_displacement.size",
           static_cast<double>(options_.initial_displacement.size()),
           "must be 0 or the number of DOFs");
    if (!options_.initial_velocity.empty() && options_.initial_velocity.size() != n)
      fail("initial_velocity.size",
           static_cast<double>(options_.initial_velocity.size()),
           "must be 0 or the number of DOFs");
    stability_ = stability_limit(model_, options_.expected_max_penetration);
  }

  double CentralDifference::time_step(const double record_dt) const
  {
    if (!(record_dt > 0.0 && std::isfinite(record_dt)))
    {
      std::ostringstream msg;
      msg << "ground motion dt = " << record_dt << " s (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
    if (options_.dt > 0.0)
    {
      if (options_.dt >= stability_.dt_critical)
      {
        std::ostringstream msg;
        msg << "time step dt = " << options_.dt
            << " s exceeds the stability limit of the central difference method dt_cr = "
               "2/omega_max = "
            << stability_.dt_critical << " s (governed by " << stability_.governing
            << "); use dt < " << stability_.dt_critical << " s or dt = auto";
        throw TimeStepError(msg.str(), options_.dt, stability_.dt_critical);
      }
      return options_.dt;
    }
    const double target = options_.safety * stability_.dt_critical;
    const double n_sub  = std::ceil(record_dt / target * (1.0 - 1e-12));
    return record_dt / std::max(n_sub, 1.0);
  }

  namespace
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

      explicit EffectiveMatrixInverse(const TridiagonalMatrix &a)
      {
        const std::size_t n     = a.size();
        std::size_t       first = 0;
        while (first < n)
        {
          std::size_t last = first;
          while (last + 1 < n && a.upper[last] != 0.0)
            ++last;
          Block b;
          b.first = first;
          b.size  = last - first + 1;
          TridiagonalMatrix sub(b.size);
          for (std::size_t i = 0; i < b.size; ++i)
            sub.diag[i] = a.diag[first + i];
          for (std::size_t i = 0; i + 1 < b.size; ++i)
            sub.upper[i] = a.upper[first + i];
          if (b.size <= max_dense)
          {
            const Eigen::MatrixXd inv = sub.to_dense().inverse();
            b.inverse.resize(b.size * b.size);
            // Column-major: y += A⁻¹(:, j)·x_j vectorises over the rows.
            for (std::size_t j = 0; j < b.size; ++j)
              for (std::size_t i = 0; i < b.size; ++i)
                b.inverse[j * b.size + i] =
                  inv(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
          }
          else
            b.thomas = TridiagonalSolver(sub);
          blocks_.push_back(std::move(b));
          first = last + 1;
        }
      }

      /// y = A⁻¹·x (x and y distinct).
      void apply(const double *x, double *y) const
      {
        for (const Block &b : blocks_)
        {
          const double     *xb = x + b.first;
          double           *yb = y + b.first;
          const std::size_t m  = b.size;
          if (!b.inverse.empty())
          {
            const double *col = b.inverse.data();
            for (std::size_t i = 0; i < m; ++i)
              yb[i] = col[i] * xb[0];
            for (std::size_t j = 1; j < m; ++j)
            {
              col += m;
              for (std::size_t i = 0; i < m; ++i)
                yb[i] += col[i] * xb[j];
            }
          }
          else
          {
            for (std::size_t i = 0; i < m; ++i)
              yb[i] = xb[i];
            b.thomas.solve_in_place(yb);
          }
        }
      }

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

    inline double law_rate(const LawVelocity scheme,
                           const double      x_n,
                           const double      x_nm1,
                           const double      x_nm2,
                           const double      inv_dt)
    {
      return scheme == LawVelocity::backward ? (x_n - x_nm1) * inv_dt :
                                               (3.0 * x_n - 4.0 * x_nm1 + x_nm2) * (0.5 * inv_dt);
    }

    /// Two doubles in one SSE register (GCC/Clang vector extension): element-wise operations
    /// round exactly like their scalar counterparts.
    typedef double Pair __attribute__((vector_size(16)));

    inline Pair load_pair(const double *p)
    {
      Pair x;
      std::memcpy(&x, p, sizeof(x));
      return x;
    }

    inline void store_pair(double *p, const Pair x)
    {
      std::memcpy(p, &x, sizeof(x));
    }

    /// |x| (clears the sign bits, as std::abs).
    inline Pair abs_pair(const Pair x)
    {
      typedef std::uint64_t Bits __attribute__((vector_size(16)));
      Bits                  b;
      std::memcpy(&b, &x, sizeof(b));
      b &= ~(Bits{1, 1} << 63);
      Pair y;
      std::memcpy(&y, &b, sizeof(y));
      return y;
    }

    /// std::max(a, b) = a < b ? b : a element-wise (one MAXPD on x86-64: it returns its second
    /// operand unless the first is greater, which is the same selection).
    inline Pair max_pair(const Pair a, const Pair b)
    {
#if defined(__SSE2__)
      return _mm_max_pd(b, a);
#else
      return a < b ? b : a;
#endif
    }

  } // namespace

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
    std::vector<double>                     mass;
    std::vector<double>                     b_diag, b_upper; ///< 2M/Δt² − K
    std::vector<double>                     d_diag, d_upper; ///< −M/Δt² + C/(2Δt)
    std::unique_ptr<EffectiveMatrixInverse> a_inverse;       ///< (M/Δt² + C/(2Δt))⁻¹
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
    std::vector<double>      gap_skip;
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
    bool        integral = false;
    long        sub      = 1;
    double      inv_sub  = 1.0;
    std::size_t rec_j    = 0;
    long        rec_s    = 0;
    long        every    = 0;
    /// Steps between check points (energy checks): at most 512, and a divisor of `every` when
    /// histories are recorded, so that check points and samples coincide (fewer, longer blocks).
    long check_every = 512;

    // laws
    std::unique_ptr<Isolator>              iso;
    std::vector<std::unique_ptr<ForceLaw>> laws;
    std::vector<int>                       left, right;
    std::vector<std::size_t>               left_row, right_row; ///< offsets in u_block + 2
    std::vector<double>                    gap, cf, delta_prev, delta_prev2, peak_force;
    std::vector<int>                       active, called_prev;
    std::vector<int>                       storey_low, storey_up;

    // energy sums (t_n of the last recorded step)
    double w_in = 0.0, w_visc = 0.0, w_contact = 0.0, p_in_prev = 0.0, p_visc_prev = 0.0;
    double e0 = 0.0, max_supplied = 0.0, e_kin = 0.0, e_strain = 0.0, max_residual = 0.0;

    Response r;

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

    void     init(const CentralDifference &cdm, const GroundMotion &g);
    void     advance(long count);
    void     bookkeeping(long len);
    void     checkpoint_energies(long len);
    void     checkpoint(long k);
    Response response() const;
  };

  namespace
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
          s_.r.contacts[c].impacts.push_back({t, rate});
        active_[c] = now_active;
        called_[c] = 1;
        // Contact work ∫F dδ, trapezoid between t_{n−1} and t_n.
        s_.w_contact += 0.5 * (cf_[c] + force) * (delta - dp);
        cf_[c] = force;
        f_[L] += force;
        f_[R] -= force;
        s_.peak_force[c] = std::max(s_.peak_force[c], force);
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

    // The fused kernel is written once for vectors of L doubles (GCC/Clang vector extensions) and
    // compiled for SSE2 (L = 2, the baseline x86-64 build), AVX2 (L = 4) and AVX-512F (L = 8),
    // picked at run time. Every operation is element-wise per DOF lane (no horizontal sums per
    // step, no FMA contraction: optimize("fp-contract=off")), so the three variants give
    // bitwise identical results. Helpers take vectors by reference only: passing wide vectors
    // by value from code compiled for the baseline would change the ABI.
    template <int L>
    struct Lanes
    {
      typedef double       V __attribute__((vector_size(8 * L)));
      typedef std::int64_t I __attribute__((vector_size(8 * L)));
      /// V at any double-aligned address (loads and stores by assignment, so that the vectors
      /// never have their address taken and stay in registers).
      typedef double U __attribute__((vector_size(8 * L), aligned(8), may_alias));
    };

    /// out = (x[j], x[j], ...).
    template <class V, class I, int j>
    inline __attribute__((always_inline)) void splat(V &out, const V &x)
    {
      constexpr int L = sizeof(V) / sizeof(double);
      I             mask;
      for (int l = 0; l < L; ++l)
        mask[l] = j;
#if defined(__clang__)
      out = V{} + x[j];
#else
      out = __builtin_shuffle(x, mask);
#endif
    }

    /// out = (x[1], ..., x[L−1], y[0]): the DOFs one further down the padded vector.
    template <class V, class I>
    inline __attribute__((always_inline)) void shift_down(V &out, const V &x, const V &y)
    {
      constexpr int L = sizeof(V) / sizeof(double);
      I             mask;
      for (int l = 0; l < L; ++l)
        mask[l] = l + 1;
#if defined(__clang__)
      for (int l = 0; l < L; ++l)
        out[l] = l + 1 < L ? x[l + 1] : y[0];
      (void)mask;
#else
      out = __builtin_shuffle(x, y, mask);
#endif
    }

    /// out = (w[L−1], x[0], ..., x[L−2]): the DOFs one further up.
    template <class V, class I>
    inline __attribute__((always_inline)) void shift_up(V &out, const V &w, const V &x)
    {
      constexpr int L = sizeof(V) / sizeof(double);
      I             mask;
      for (int l = 0; l < L; ++l)
        mask[l] = L - 1 + l;
#if defined(__clang__)
      for (int l = 0; l < L; ++l)
        out[l] = l == 0 ? w[L - 1] : x[l - 1];
      (void)mask;
#else
      out = __builtin_shuffle(w, x, mask);
#endif
    }

    /// peak = max(peak, |x|) element-wise (|x| clears the sign bit; max as std::max(peak, |x|)).
    template <class V, class I>
    inline __attribute__((always_inline)) void peak_abs(V &peak, const V &x)
    {
      const I bits = (I)x & ~(I{} + (std::int64_t{1} << 63)); // vector casts reinterpret
      const V ax   = (V)bits;
      peak         = peak < ax ? ax : peak;
    }


    /// f(std::integral_constant<int, j>) for j = 0..N−1 (unrolled at compile time).
    template <class F, std::size_t... js>
    inline __attribute__((always_inline)) void for_each_index(F &&f, std::index_sequence<js...>)
    {
      (f(std::integral_constant<int, static_cast<int>(js)>{}), ...);
    }

    /// A contact pre-check failed at step s0 + k (or the run is in its first two steps): the
    /// reference kernel's contact evaluation for every law, with δ_{n−1} and δ_{n−2} re-formed
    /// from the displacement columns if the previous step skipped the laws, then the pre-check
    /// re-armed. Returns true if a law was called (forces in Session::force).
    template <class IsolatorType>
    __attribute__((noinline)) bool
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

    /**
     * Fused kernel for N <= 8 DOFs (see CentralDifference), vectors of L doubles. With
     * z_n = A⁻¹K·u_n carried as z_n = z_{n−1} + A⁻¹K·Δu_n, the step is
     *   Δu_{n+1} = Δu_n − z_{n−1} − A⁻¹M·1·ü_g − (A⁻¹C/Δt + A⁻¹K)·Δu_n − A⁻¹f_n,
     * so only one product (summed as a tree) and the force term lie on the step-to-step chain;
     * z_n, the bookkeeping of the step (peaks, per-DOF running sums of ü_g·v_i, v_i² and
     * v_i·v_{i+1}) are independent work. The contact laws are called only when a pre-check
     * fails, outside the fast loop, so that no call forces the state out of the registers.
     */
    template <int L, class IsolatorType, int N>
    inline __attribute__((always_inline)) void fused_body(Session &s, const long len)
    {
      typedef typename Lanes<L>::V V;
      typedef typename Lanes<L>::I I;
      typedef typename Lanes<L>::U U;
      constexpr int                P  = (N + L - 1) / L; // vectors per DOF column
      constexpr std::size_t        LD = static_cast<std::size_t>(P * L);
      const std::size_t            S  = s.col_stride;
      ForceEvaluator<IsolatorType> forces(s);
      const auto at  = [](const double *p) -> const U  &{ return *reinterpret_cast<const U *>(p); };
      const auto put = [](double *p) -> U & { return *reinterpret_cast<U *>(p); };
      const double      *agb  = s.ag_block.data();
      const double      *a_f  = s.dense_f.data();
      const double      *a_g  = s.dense_g.data();
      const double      *a_i  = s.dense_inverse.data();
      double            *f    = s.force.data();
      const int         *fd   = s.force_dofs.data();
      const std::size_t  n_fd = s.force_dofs.size();
      const std::size_t  nc   = s.laws.size();
      const std::size_t *c_l  = s.left_row.data();
      const std::size_t *c_r  = s.right_row.data();
      const double      *c_g  = s.gap_skip.data();
      double            *ub   = s.u_block.data();
      const double       dt   = s.dt;
      const bool         iso  = forces.has_isolator();
      const V            zero = V{} * 0.0;
      const V            half = zero + 0.5 / dt;
      const V            idt2 = zero + 1.0 / (dt * dt);

      V          am[P], r0[P], mask[P];
      V          u[P], d[P], z[P], pu[P], pa[P], pd[P], s_agv[P], s_vv[P], s_vx[P], v[P], a[P];
      const auto load_state = [&]() __attribute__((always_inline))
      {
#pragma GCC unroll 16
        for (int i = 0; i < P; ++i)
        {
          const std::size_t o = static_cast<std::size_t>(i * L);
          u[i]                = at(s.fused_u.data() + o);
          d[i]                = at(s.fused_d.data() + o);
          z[i]                = at(s.fused_z.data() + o);
          pu[i]               = at(s.fused_peaks.data() + o);
          pa[i]               = at(s.fused_peaks.data() + LD + o);
          pd[i]               = at(s.fused_peaks.data() + 2 * LD + o);
          s_agv[i]            = at(s.fused_sums.data() + o);
          s_vv[i]             = at(s.fused_sums.data() + LD + o);
          s_vx[i]             = at(s.fused_sums.data() + 2 * LD + o);
          v[i]                = at(s.fused_v.data() + o);
          a[i]                = at(s.last_accel.data() + o);
        }
      };
      const auto store_state = [&]() __attribute__((always_inline))
      {
#pragma GCC unroll 16
        for (int i = 0; i < P; ++i)
        {
          const std::size_t o                    = static_cast<std::size_t>(i * L);
          put(s.fused_u.data() + o)              = u[i];
          put(s.fused_d.data() + o)              = d[i];
          put(s.fused_z.data() + o)              = z[i];
          put(s.fused_peaks.data() + o)          = pu[i];
          put(s.fused_peaks.data() + LD + o)     = pa[i];
          put(s.fused_peaks.data() + 2 * LD + o) = pd[i];
          put(s.fused_sums.data() + o)           = s_agv[i];
          put(s.fused_sums.data() + LD + o)      = s_vv[i];
          put(s.fused_sums.data() + 2 * LD + o)  = s_vx[i];
          put(s.fused_v.data() + o)              = v[i];
          put(s.last_accel.data() + o)           = a[i];
        }
      };
#pragma GCC unroll 16
      for (int i = 0; i < P; ++i)
      {
        const std::size_t o = static_cast<std::size_t>(i * L);
        am[i]               = at(s.dense_am.data() + o);
        r0[i]               = at(a_i + o);
        mask[i]             = at(s.drift_mask.data() + o);
      }
      load_state();

      // One step: isolator, Δu_{n+1}, u_{n+1} (stored as column k + 3), bookkeeping of step n.
      const auto one_step = [&](const long k, const bool touched) __attribute__((always_inline))
      {
        const double ag = agb[k];
        const double fi = iso ? forces.isolator(k, u[0][0]) : 0.0;
        V            dn[P], zn[P];
#pragma GCC unroll 16
        for (int i = 0; i < P; ++i)
        {
          V pf[N], pg[N];
          for_each_index(
            [&](auto jc)
            {
              constexpr int j = decltype(jc)::value;
              V             dj;
              splat<V, I, j % L>(dj, d[j / L]);
              pf[j] =
                at(a_f + static_cast<std::size_t>(j) * LD + static_cast<std::size_t>(i * L)) * dj;
              pg[j] =
                at(a_g + static_cast<std::size_t>(j) * LD + static_cast<std::size_t>(i * L)) * dj;
            },
            std::make_index_sequence<N>{});
// Pairwise (tree) sums: short dependency chains.
#pragma GCC unroll 16
          for (int w = 1; w < N; w *= 2)
#pragma GCC unroll 16
            for (int j = 0; j + w < N; j += 2 * w)
            {
              pf[j] += pf[j + w];
              pg[j] += pg[j + w];
            }
          dn[i] = ((d[i] - z[i]) - am[i] * ag - pf[0]) - r0[i] * fi;
          zn[i] = z[i] + pg[0];
        }
        if (touched)
        {
          for (std::size_t q = 0; q < n_fd; ++q)
          {
            const std::size_t j  = static_cast<std::size_t>(fd[q]);
            const double      fj = f[j];
            if (fj != 0.0)
#pragma GCC unroll 16
              for (int i = 0; i < P; ++i)
                dn[i] -= at(a_i + j * LD + static_cast<std::size_t>(i * L)) * fj;
            f[j] = 0.0;
          }
          f[s.n] = 0.0;
        }
        double *next = ub + static_cast<std::size_t>(k + 3) * S;
#pragma GCC unroll 16
        for (int i = 0; i < P; ++i)
        {
          const V un        = u[i] + dn[i];
          put(next + i * L) = un;
          v[i]              = (d[i] + dn[i]) * half;
          a[i]              = (dn[i] - d[i]) * idt2 + ag;
          V below;
          shift_up<V, I>(below, i == 0 ? zero : u[i - 1], u[i]);
          peak_abs<V, I>(pu[i], u[i]);
          peak_abs<V, I>(pa[i], a[i]);
          const V drift = u[i] - below * mask[i];
          peak_abs<V, I>(pd[i], drift);
          s_agv[i] += v[i] * ag;
          s_vv[i] += v[i] * v[i];
        }
#pragma GCC unroll 16
        for (int i = 0; i < P; ++i)
        {
          V above;
          shift_down<V, I>(above, v[i], i + 1 < P ? v[i + 1] : zero);
          s_vx[i] += v[i] * above;
        }
#pragma GCC unroll 16
        for (int i = 0; i < P; ++i)
        {
          u[i] = u[i] + dn[i];
          d[i] = dn[i];
          z[i] = zn[i];
        }
      };

      long k = 0;
      while (k < len)
      {
        // Fast loop: no law is called, so nothing leaves the registers.
        const long fast_from = k;
        for (; k < len; ++k)
        {
          const double *col = ub + static_cast<std::size_t>(k) * S;
          bool hit = s.step + k < 2; // the first steps use the initial δ_{−1}, δ_{−2}
          for (std::size_t c = 0; c < nc; ++c)
            hit |= col[c_l[c]] - col[c_r[c]] > c_g[c];
          if (hit)
            break;
          one_step(k, false);
        }
        if (k > fast_from)
          s.deltas_current = false;
        if (k == len)
          break;
        store_state();
        const bool touched = fused_contacts(s, forces, k);
        load_state();
        one_step(k, touched);
        ++k;
      }
      store_state();
      const std::size_t B    = static_cast<std::size_t>(block_steps);
      const std::size_t last = static_cast<std::size_t>(len - 1);
      for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i)
        s.velocity[i * B + last] = s.fused_v[i];
    }

    template <class IsolatorType, int N>
    __attribute__((optimize("fp-contract=off"))) void fused_sse2(Session &s, const long len)
    {
      fused_body<2, IsolatorType, N>(s, len);
    }

#if defined(__x86_64__) && defined(__GNUC__)
    template <class IsolatorType, int N>
    __attribute__((target("avx2"), optimize("fp-contract=off"))) void fused_avx2(Session   &s,
                                                                                 const long len)
    {
      fused_body<4, IsolatorType, N>(s, len);
    }

    template <class IsolatorType, int N>
    __attribute__((target("avx512f"), optimize("fp-contract=off"))) void
    fused_avx512(Session &s, const long len)
    {
      fused_body<8, IsolatorType, N>(s, len);
    }
#endif

    /// Widest vector (doubles per register) of the fused kernel on this processor, capped at
    /// `cap` (0: no cap).
    int fused_lanes(const int cap)
    {
#if defined(__x86_64__) && defined(__GNUC__)
      if (cap == 2)
        return 2;
      if ((cap == 0 || cap == 8) && __builtin_cpu_supports("avx512f"))
        return 8;
      if (__builtin_cpu_supports("avx2"))
        return 4;
#endif
      (void)cap;
      return 2;
    }

    template <class IsolatorType, int N>
    Session::Kernel fused_for(const int lanes)
    {
#if defined(__x86_64__) && defined(__GNUC__)
      if (lanes == 8)
        return fused_avx512<IsolatorType, N>;
      if (lanes == 4)
        return fused_avx2<IsolatorType, N>;
#endif
      (void)lanes;
      return fused_sse2<IsolatorType, N>;
    }

    template <class IsolatorType>
    Session::Kernel fused_kernel(const std::size_t n, const int lanes)
    {
      switch (n)
      {
        case 1:
          return fused_for<IsolatorType, 1>(lanes);
        case 2:
          return fused_for<IsolatorType, 2>(lanes);
        case 3:
          return fused_for<IsolatorType, 3>(lanes);
        case 4:
          return fused_for<IsolatorType, 4>(lanes);
        case 5:
          return fused_for<IsolatorType, 5>(lanes);
        case 6:
          return fused_for<IsolatorType, 6>(lanes);
        case 7:
          return fused_for<IsolatorType, 7>(lanes);
        case 8:
          return fused_for<IsolatorType, 8>(lanes);
        default:
          return nullptr;
      }
    }

    /// Dynamics of one block for any model: (M/Δt² + C/(2Δt))·u_{n+1} = B·u_n + D·u_{n−1}
    /// − M·1·ü_g − f_nl with B, D tridiagonal and A⁻¹ block-wise (dense or Thomas).
    template <class IsolatorType>
    void dynamics_general(Session &s, const long len)
    {
      const std::size_t            n = s.n;
      const std::size_t            W = s.width;
      ForceEvaluator<IsolatorType> forces(s);
      const double                *bd = s.b_diag.data(), *bu = s.b_upper.data();
      const double                *dd = s.d_diag.data(), *du = s.d_upper.data();
      const double                *m   = s.mass.data();
      const double                *f   = s.force.data();
      double                      *rhs = s.rhs.data();
      double                      *un  = s.solution.data();
      double                      *ub  = s.u_block.data();
      for (long k = 0; k < len; ++k)
      {
        const double ag = s.ag_block[static_cast<std::size_t>(k)];
        forces(k, static_cast<double>(s.step + k) * s.dt);
        const double *col = ub + k;
        const auto    u   = [&](const std::size_t i) { return col[i * W + 2]; };
        const auto    up  = [&](const std::size_t i) { return col[i * W + 1]; };
        for (std::size_t i = 0; i < n; ++i)
          rhs[i] = bd[i] * u(i) + dd[i] * up(i) - m[i] * ag - f[i];
        for (std::size_t i = 0; i + 1 < n; ++i)
        {
          rhs[i] += bu[i] * u(i + 1) + du[i] * up(i + 1);
          rhs[i + 1] += bu[i] * u(i) + du[i] * up(i);
        }
        s.a_inverse->apply(rhs, un);
        for (std::size_t i = 0; i < n; ++i)
          ub[i * W + static_cast<std::size_t>(k) + 3] = un[i];
      }
    }
  } // namespace

  void CentralDifferenceStepper::Session::init(const CentralDifference &cdm, const GroundMotion &g)
  {
    model  = &cdm.model();
    opt    = &cdm.options();
    motion = &g;
    if (!(g.dt > 0.0) || g.acceleration.empty())
      throw std::invalid_argument("ground motion '" + g.name +
                                  "': dt must be > 0 and the record non-empty");
    dt = cdm.time_step(g.dt);
    const double duration =
      opt->duration > 0.0 ? opt->duration : g.dt * static_cast<double>(g.acceleration.size());
    n_steps = std::lround(duration / dt);
    step    = 0;
    scheme  = opt->law_velocity;
    n       = model->n_dofs();
    mass    = model->masses();
    k       = &model->stiffness();
    c       = &model->damping();

    const double      inv_dt2     = 1.0 / (dt * dt);
    const double      half_inv_dt = 0.5 / dt;
    TridiagonalMatrix a(n);
    b_diag.assign(n, 0.0);
    d_diag.assign(n, 0.0);
    b_upper.assign(n > 0 ? n - 1 : 0, 0.0);
    d_upper.assign(n > 0 ? n - 1 : 0, 0.0);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double mi = mass[i];
      a.diag[i]       = mi * inv_dt2 + c->diag[i] * half_inv_dt;
      b_diag[i]       = 2.0 * mi * inv_dt2 - k->diag[i];
      d_diag[i]       = -mi * inv_dt2 + c->diag[i] * half_inv_dt;
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      a.upper[i] = c->upper[i] * half_inv_dt;
      b_upper[i] = -k->upper[i];
      d_upper[i] = c->upper[i] * half_inv_dt;
    }
    a_inverse = std::make_unique<EffectiveMatrixInverse>(a);

    const Isolator *proto = model->isolator();
    iso.reset();
    if (proto)
    {
      iso = proto->clone();
      iso->revert_to_start();
    }
    // The fused kernel: at most 8 DOFs (one or several buildings), every storey between DOF i − 1
    // and DOF i or between the ground and DOF i (its drift is then lane i of u − shifted u).
    bool fits = n >= 1 && n <= 8;
    drift_mask.assign(n, 0.0);
    for (const Storey &st : model->storeys())
    {
      fits = fits && st.upper_dof >= 0 && st.upper_dof < static_cast<int>(n) &&
             (st.lower_dof == st.upper_dof - 1 || st.lower_dof == -1);
      if (fits)
        drift_mask[static_cast<std::size_t>(st.upper_dof)] = st.lower_dof == -1 ? 0.0 : 1.0;
    }
    fused = opt->kernel == CdmKernel::automatic && fits;
    dense_inverse.clear();
    dense_f.clear();
    dense_g.clear();
    dense_am.clear();
    lanes    = fused_lanes(opt->vector_lanes);
    padded_n = (n + static_cast<std::size_t>(lanes) - 1) / static_cast<std::size_t>(lanes) *
               static_cast<std::size_t>(lanes);
    fused_u.assign(padded_n, 0.0);
    fused_z.assign(padded_n, 0.0);
    fused_v.assign(padded_n, 0.0);
    deltas_current = true;
    fused_d.assign(padded_n, 0.0);
    last_accel.assign(padded_n, 0.0);
    fused_peaks.assign(3 * padded_n, 0.0);
    fused_sums.assign(3 * padded_n, 0.0);
    drift_mask.resize(padded_n, 0.0);
    p_in_0 = p_visc_0 = 0.0;
    if (fused)
    {
      const std::size_t     p   = padded_n;
      const Eigen::MatrixXd inv = a.to_dense().inverse();
      const Eigen::MatrixXd kg  = inv * k->to_dense();
      const Eigen::MatrixXd h   = inv * (c->to_dense() * (1.0 / dt) + k->to_dense());
      const Eigen::VectorXd am =
        inv * Eigen::Map<const Eigen::VectorXd>(mass.data(), static_cast<Eigen::Index>(n));
      const auto pad = [&](const Eigen::MatrixXd &x, std::vector<double> &out)
      {
        out.assign(p * static_cast<std::size_t>(x.cols()), 0.0);
        for (Eigen::Index j = 0; j < x.cols(); ++j)
          for (Eigen::Index i = 0; i < x.rows(); ++i)
            out[static_cast<std::size_t>(j) * p + static_cast<std::size_t>(i)] = x(i, j);
      };
      pad(inv, dense_inverse);
      pad(h, dense_f);
      pad(kg, dense_g);
      pad(am, dense_am);
    }

    width = static_cast<std::size_t>(block_steps) + 3;
    if (fused)
    {
      // One column of padded_n (+ a vector if no padding lane is left for the ground) per step.
      row_stride = 1;
      col_stride = padded_n + (padded_n == n ? static_cast<std::size_t>(lanes) : 0);
      u_block.assign(width * col_stride, 0.0);
    }
    else
    {
      row_stride = width;
      col_stride = 1;
      u_block.assign((n + 1) * width, 0.0);
    }
    ag_block.assign(static_cast<std::size_t>(block_steps), 0.0);
    velocity.assign(n * static_cast<std::size_t>(block_steps), 0.0);
    mv.assign(static_cast<std::size_t>(block_steps), 0.0);
    cvv.assign(static_cast<std::size_t>(block_steps), 0.0);
    force.assign(n + 1, 0.0); // [n]: the ground, absorbs wall reactions
    rhs.assign(n, 0.0);
    solution.assign(n, 0.0);

    const int ground_slot = static_cast<int>(n);
    r                     = Response{};
    r.dt                  = dt;
    r.n_steps             = n_steps;
    r.duration            = static_cast<double>(n_steps) * dt;
    r.n_dofs              = n;
    r.n_storeys           = model->storeys().size();
    r.peak_displacement.assign(n, 0.0);
    r.peak_absolute_acceleration.assign(n, 0.0);
    r.peak_interstorey_drift.assign(r.n_storeys, 0.0);
    laws.clear();
    left.clear();
    right.clear();
    gap.clear();
    std::vector<char> carries_force(n + 1, 0);
    if (iso)
      carries_force[0] = 1;
    for (const ContactPair &cp : model->contacts())
    {
      std::unique_ptr<ForceLaw> law = cp.law->clone();
      law->revert_to_start();
      laws.push_back(std::move(law));
      left.push_back(cp.left_dof >= 0 ? cp.left_dof : ground_slot);
      right.push_back(cp.right_dof >= 0 ? cp.right_dof : ground_slot);
      carries_force[static_cast<std::size_t>(left.back())]  = 1;
      carries_force[static_cast<std::size_t>(right.back())] = 1;
      gap.push_back(cp.gap);
      ContactResult cr;
      cr.name = cp.name;
      r.contacts.push_back(std::move(cr));
    }
    left_row.clear();
    right_row.clear();
    for (std::size_t q = 0; q < left.size(); ++q)
    {
      left_row.push_back(static_cast<std::size_t>(left[q]) * row_stride + 2 * col_stride);
      right_row.push_back(static_cast<std::size_t>(right[q]) * row_stride + 2 * col_stride);
    }
    force_dofs.clear();
    for (std::size_t j = 0; j < n; ++j)
      if (carries_force[j])
        force_dofs.push_back(static_cast<int>(j));
    const std::size_t nc = laws.size();
    // Not armed at first: called_prev starts at 1, so the first step takes the full path.
    gap_skip.assign(nc, -std::numeric_limits<double>::infinity());
    cf.assign(nc, 0.0);
    active.assign(nc, 0);
    called_prev.assign(nc, 1);
    peak_force.assign(nc, 0.0);
    delta_prev.assign(nc, 0.0);
    delta_prev2.assign(nc, 0.0);
    storey_low.clear();
    storey_up.clear();
    for (const Storey &st : model->storeys())
    {
      storey_low.push_back(st.lower_dof >= 0 ? st.lower_dof : ground_slot);
      storey_up.push_back(st.upper_dof);
    }
    lane_peak_u.assign(n * static_cast<std::size_t>(block_steps), 0.0);
    lane_peak_a.assign(n * static_cast<std::size_t>(block_steps), 0.0);
    lane_peak_d.assign(storey_low.size() * static_cast<std::size_t>(block_steps), 0.0);

    // Initial conditions: u_{−1}, u_{−2} from a Taylor expansion with a_0 = M⁻¹(p_0 − C·v_0 −
    // K·u_0 − f_nl(u_0)); the laws are only trialled here, the first step commits them.
    std::vector<double> u0(n, 0.0), v0(n, 0.0);
    if (!opt->initial_displacement.empty())
      u0 = opt->initial_displacement;
    if (!opt->initial_velocity.empty())
      v0 = opt->initial_velocity;
    std::vector<double> f0(n + 1, 0.0), cv(n), ku(n);
    if (iso)
    {
      f0[0] += iso->set_trial(u0[0], v0[0]).force;
      iso->revert_to_last_commit();
    }
    std::vector<double> u0g = u0;
    u0g.push_back(0.0);
    std::vector<double> v0g = v0;
    v0g.push_back(0.0);
    for (std::size_t q = 0; q < nc; ++q)
    {
      const double delta =
        u0g[static_cast<std::size_t>(left[q])] - u0g[static_cast<std::size_t>(right[q])] - gap[q];
      const double rate =
        v0g[static_cast<std::size_t>(left[q])] - v0g[static_cast<std::size_t>(right[q])];
      delta_prev[q]  = delta - dt * rate;
      delta_prev2[q] = delta - 2.0 * dt * rate;
      if (delta > 0.0)
      {
        const double fq = laws[q]->set_trial(delta, rate).force;
        laws[q]->revert_to_last_commit();
        f0[static_cast<std::size_t>(left[q])] += fq;
        f0[static_cast<std::size_t>(right[q])] -= fq;
      }
    }
    c->multiply(v0.data(), cv.data());
    k->multiply(u0.data(), ku.data());
    const double ag0 = g.acceleration[0];
    for (std::size_t i = 0; i < n; ++i)
    {
      const double a0 = (-mass[i] * ag0 - cv[i] - ku[i] - f0[i]) / mass[i];
      *column(i, 2)   = u0[i];
      *column(i, 1)   = u0[i] - dt * v0[i] + 0.5 * dt * dt * a0;
      *column(i, 0)   = u0[i] - 2.0 * dt * v0[i] + 2.0 * dt * dt * a0;
      fused_u[i]      = u0[i];
      fused_d[i]      = dt * v0[i] - 0.5 * dt * dt * a0; // u_0 − u_{−1} without cancellation
    }
    if (fused)
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) // z_{−1} = A⁻¹K·u_{−1}
          fused_z[i] += dense_g[j * padded_n + i] * (fused_u[j] - fused_d[j]);

    const double ratio = g.dt / dt;
    sub                = std::lround(ratio);
    integral           = sub > 0 && std::abs(ratio - static_cast<double>(sub)) < 1e-9 * ratio;
    inv_sub            = 1.0 / static_cast<double>(sub > 0 ? sub : 1);
    rec_j              = 0;
    rec_s              = 0;
    every = opt->output_interval > 0.0 ? std::max(1L, std::lround(opt->output_interval / dt)) : 0L;
    check_every = 512;
    if (every > 0 && every <= 512)
      check_every = every * (512 / every);
    else if (every > 512)
      for (long parts = (every + 511) / 512; parts <= every; ++parts)
        if (every % parts == 0)
        {
          check_every = every / parts;
          break;
        }
    if (every > 0)
    {
      const std::size_t n_samples = static_cast<std::size_t>(n_steps / every + 1);
      const std::size_t ns        = storey_low.size();
      r.history.interval          = static_cast<double>(every) * dt;
      r.history.time.reserve(n_samples);
      r.history.displacement.reserve(n_samples * n);
      r.history.absolute_acceleration.reserve(n_samples * n);
      r.history.interstorey_drift.reserve(n_samples * ns);
      r.history.contact_force.reserve(n_samples * nc);
      r.history.energy_input.reserve(n_samples);
      r.history.energy_error.reserve(n_samples);
    }
    w_in = w_visc = w_contact = p_in_prev = p_visc_prev = 0.0;
    e0 = max_supplied = e_kin = e_strain = max_residual = 0.0;

    auto *bil = dynamic_cast<BilinearIsolator *>(iso.get());
    auto *lin = dynamic_cast<LinearIsolator *>(iso.get());
    if (fused)
      dynamics = bil ? fused_kernel<BilinearIsolator>(n, lanes) : fused_kernel<Isolator>(n, lanes);
    else if (bil)
      dynamics = dynamics_general<BilinearIsolator>;
    else if (lin)
      dynamics = dynamics_general<LinearIsolator>;
    else
      dynamics = dynamics_general<Isolator>;
  }

  void CentralDifferenceStepper::Session::advance(long count)
  {
    while (count > 0 && step <= n_steps)
    {
      // The block ends at the next checkpoint (history sample, every check_every steps, the
      // last step)
      // so that the checks see the laws and the isolator at exactly that step.
      long next = std::min(n_steps, (step + check_every - 1) / check_every * check_every);
      if (every > 0)
        next = std::min(next, (step + every - 1) / every * every);
      const long len = std::min({next - step + 1, block_steps, count});

      // ü_g(t_n), linear interpolation; integer sub-stepping when Δt divides the record's dt.
      const double     *rec   = motion->acceleration.data();
      const std::size_t n_rec = motion->acceleration.size();
      double           *agb   = ag_block.data();
      long              q     = 0;
      // Integer sub-stepping inside the record: a run of steps within one record interval
      // (rec[j] + frac·(rec[j+1] − rec[j]), frac = s/sub) at a time.
      while (integral && q < len && rec_j + 1 < n_rec)
      {
        const double r0  = rec[rec_j];
        const double dr  = rec[rec_j + 1] - rec[rec_j];
        const long   run = std::min(len - q, sub - rec_s);
        for (long m = 0; m < run; ++m)
          agb[q + m] = r0 + (static_cast<double>(rec_s + m) * inv_sub) * dr;
        q += run;
        rec_s += run;
        if (rec_s == sub)
        {
          rec_s = 0;
          ++rec_j;
        }
      }
      for (; q < len; ++q)
      {
        std::size_t j;
        double      frac;
        if (integral)
        {
          j    = rec_j;
          frac = static_cast<double>(rec_s) * inv_sub;
          if (++rec_s == sub)
          {
            rec_s = 0;
            ++rec_j;
          }
        }
        else
        {
          const double x = static_cast<double>(step + q) * dt / motion->dt;
          j              = static_cast<std::size_t>(x);
          frac           = x - static_cast<double>(j);
        }
        double ag;
        if (j + 1 < n_rec)
          ag = rec[j] + frac * (rec[j + 1] - rec[j]);
        else
          ag = (j + 1 == n_rec && frac == 0.0) ? rec[j] : 0.0;
        agb[q] = ag;
      }

      dynamics(*this, len);
      if (fused)
        checkpoint_energies(len);
      else
        bookkeeping(len);
      const long last = step + len - 1;
      if ((every > 0 && last % every == 0) || last % check_every == 0 || last == n_steps)
        checkpoint(len - 1);
      step += len;
      count -= len;
      // Keep u_{n−2}, u_{n−1}, u_n of the next step in columns 0-2.
      for (std::size_t i = 0; i < n; ++i)
        for (long c3 = 0; c3 < 3; ++c3)
          *column(i, c3) = *column(i, len + c3);
    }
  }

  /// E_kin and E_strain at the block's last step if it is a check point (E_0, checks, samples,
  /// end: the only places they are used); for the fused kernel also E_0 at step 0.
  void CentralDifferenceStepper::Session::checkpoint_energies(const long len)
  {
    const long last = step + len - 1;
    if ((every > 0 && last % every == 0) || last % check_every == 0 || last == n_steps)
    {
      const std::size_t B   = static_cast<std::size_t>(block_steps);
      const std::size_t q   = static_cast<std::size_t>(len - 1);
      double            mvv = 0.0, kuu = 0.0;
      for (std::size_t i = 0; i < n; ++i)
      {
        const double vi = velocity[i * B + q];
        const double ui = *column(i, len + 1);
        mvv += mass[i] * vi * vi;
        kuu += k->diag[i] * ui * ui;
      }
      for (std::size_t i = 0; i + 1 < n; ++i)
        kuu += 2.0 * k->upper[i] * *column(i, len + 1) * *column(i + 1, len + 1);
      e_kin    = 0.5 * mvv;
      e_strain = 0.5 * kuu + (iso ? iso->stored_energy() : 0.0);
    }
    if (!fused)
      return;
    // The fused kernel keeps per-DOF sums; the trapezoid rule over steps 0..n is
    // W(t_n) = Δt·(Σ_{q<=n} p_q − (p_0 + p_n)/2), evaluated here at the check points (step 0 is
    // a block of its own and a check point). max_supplied is therefore the maximum of E_0 + W_in
    // over the check points (the reference kernel: over every step).
    if (!((every > 0 && last % every == 0) || last % check_every == 0 || last == n_steps))
      return;
    const std::size_t B    = static_cast<std::size_t>(block_steps);
    const std::size_t q    = static_cast<std::size_t>(len - 1);
    const std::size_t p    = padded_n;
    double            mv_n = 0.0, cvv_n = 0.0, sum_in = 0.0, sum_visc = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double vi = velocity[i * B + q];
      mv_n += mass[i] * vi;
      cvv_n += c->diag[i] * vi * vi;
      sum_in -= mass[i] * fused_sums[i];
      sum_visc += c->diag[i] * fused_sums[p + i];
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      cvv_n += 2.0 * c->upper[i] * velocity[i * B + q] * velocity[(i + 1) * B + q];
      sum_visc += 2.0 * c->upper[i] * fused_sums[2 * p + i];
    }
    const double p_in_n = -ag_block[q] * mv_n;
    if (last == 0)
    {
      e0       = e_kin + e_strain;
      p_in_0   = p_in_n;
      p_visc_0 = cvv_n;
      w_in = w_visc = 0.0;
    }
    else
    {
      w_in   = dt * (sum_in - 0.5 * (p_in_0 + p_in_n));
      w_visc = dt * (sum_visc - 0.5 * (p_visc_0 + cvv_n));
    }
    max_supplied = std::max(max_supplied, e0 + w_in);
  }

  /// Central velocity v_n = (u_{n+1} − u_{n−1})/(2Δt), the step's acceleration
  /// (u_{n+1} − 2u_n + u_{n−1})/Δt² + ü_g(t_n), peaks and the input and viscous powers of every
  /// step of the block, then the trapezoid sums in step order.
  void CentralDifferenceStepper::Session::bookkeeping(const long len)
  {
    const std::size_t L       = static_cast<std::size_t>(len);
    const std::size_t B       = static_cast<std::size_t>(block_steps);
    const double      inv_dt  = 1.0 / dt;
    const double      inv_dt2 = inv_dt * inv_dt;
    const double      half    = 0.5 * inv_dt;
    const double     *agb     = ag_block.data();
    double           *mvb     = mv.data();
    double           *cvb     = cvv.data();
    for (std::size_t q = 0; q < L; ++q)
    {
      mvb[q] = 0.0;
      cvb[q] = 0.0;
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      const double *__restrict u  = column(i, 0);
      double *__restrict v        = velocity.data() + i * B;
      double *__restrict pu       = lane_peak_u.data() + i * B;
      double *__restrict pa       = lane_peak_a.data() + i * B;
      double *__restrict mvq      = mvb;
      double *__restrict cvq      = cvb;
      const double *__restrict ag = agb;
      const double mi             = mass[i];
      const double cdi            = c->diag[i];
      std::size_t  q              = 0;
      for (; q + 2 <= L; q += 2)
      {
        const Pair u1 = load_pair(u + q + 1), u2 = load_pair(u + q + 2), u3 = load_pair(u + q + 3);
        const Pair vi = (u3 - u1) * half;
        const Pair ai = (u3 - 2.0 * u2 + u1) * inv_dt2 + load_pair(ag + q);
        store_pair(v + q, vi);
        store_pair(mvq + q, load_pair(mvq + q) + mi * vi);
        store_pair(cvq + q, load_pair(cvq + q) + cdi * vi * vi);
        store_pair(pu + q, max_pair(load_pair(pu + q), abs_pair(u2)));
        store_pair(pa + q, max_pair(load_pair(pa + q), abs_pair(ai)));
      }
      for (; q < L; ++q)
      {
        const double vi = (u[q + 3] - u[q + 1]) * half;
        const double ai = (u[q + 3] - 2.0 * u[q + 2] + u[q + 1]) * inv_dt2 + ag[q];
        const double au = std::abs(u[q + 2]);
        const double aa = std::abs(ai);
        v[q]            = vi;
        mvq[q] += mi * vi;
        cvq[q] += cdi * vi * vi;
        pu[q] = std::max(pu[q], au);
        pa[q] = std::max(pa[q], aa);
      }
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      const double *__restrict v0 = velocity.data() + i * B;
      const double *__restrict v1 = v0 + B;
      double *__restrict cvq      = cvb;
      const double cui            = c->upper[i];
      for (std::size_t q = 0; q < L; ++q)
        cvq[q] += 2.0 * cui * v0[q] * v1[q];
    }
    for (std::size_t s = 0; s < storey_low.size(); ++s)
    {
      const double *__restrict hi = column(static_cast<std::size_t>(storey_up[s]), 2);
      const double *__restrict lo = column(static_cast<std::size_t>(storey_low[s]), 2);
      double *__restrict pd       = lane_peak_d.data() + s * B;
      std::size_t q               = 0;
      for (; q + 2 <= L; q += 2)
        store_pair(pd + q,
                   max_pair(load_pair(pd + q), abs_pair(load_pair(hi + q) - load_pair(lo + q))));
      for (; q < L; ++q)
        pd[q] = std::max(pd[q], std::abs(hi[q] - lo[q]));
    }

    checkpoint_energies(len);
    for (std::size_t q = 0; q < L; ++q)
    {
      const double p_in   = -agb[q] * mvb[q];
      const double p_visc = cvb[q];
      if (step + static_cast<long>(q) == 0)
        e0 = e_kin + e_strain;
      else
      {
        w_in += 0.5 * (p_in_prev + p_in) * dt;
        w_visc += 0.5 * (p_visc_prev + p_visc) * dt;
      }
      p_in_prev    = p_in;
      p_visc_prev  = p_visc;
      max_supplied = std::max(max_supplied, e0 + w_in);
    }
  }

  /// Energy balance, divergence checks and the history sample at the block's last step.
  void CentralDifferenceStepper::Session::checkpoint(const long q)
  {
    const long        this_step = step + q;
    const double      t         = static_cast<double>(this_step) * dt;
    const std::size_t B         = static_cast<std::size_t>(block_steps);
    const std::size_t qq        = static_cast<std::size_t>(q);
    EnergyBalance    &e         = r.energy;
    e.initial                   = e0;
    e.input                     = w_in;
    e.kinetic                   = e_kin;
    e.strain                    = e_strain;
    e.viscous                   = w_visc;
    e.hysteretic                = iso ? iso->dissipated_energy() : 0.0;
    e.contact_work              = w_contact;
    // Relative to the largest energy supplied so far, so that the first steps (where every term
    // is tiny) do not dominate the maximum.
    const double residual = std::abs(
      e.residual_relative_error() *
      std::max(std::abs(e0) + std::abs(w_in),
               e_kin + e_strain + std::abs(w_visc) + std::abs(e.hysteretic) + std::abs(w_contact)));
    const double err = residual / std::max(max_supplied, 1e-300);
    max_residual     = std::max(max_residual, residual);
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(*column(i, q + 3)))
      {
        std::ostringstream msg;
        msg << "central difference diverged: u[" << i << "] is not finite at t = " << t + dt
            << " s (step " << this_step + 1 << ", dt = " << dt << " s)";
        throw DivergenceError(msg.str(), t + dt, this_step + 1, static_cast<int>(i));
      }
    const double factor = opt->divergence_energy_factor;
    if (e_kin + e_strain > factor * max_supplied && e_kin + e_strain > 1e-12)
    {
      std::size_t worst = 0;
      for (std::size_t i = 1; i < n; ++i)
        if (std::abs(velocity[i * B + qq]) > std::abs(velocity[worst * B + qq]))
          worst = i;
      std::ostringstream msg;
      msg << "central difference diverged: mechanical energy " << e_kin + e_strain << " J exceeds "
          << factor << " x the energy supplied (" << max_supplied << " J) at t = " << t
          << " s (step " << this_step << ", fastest DoF " << worst << ", dt = " << dt << " s)";
      throw DivergenceError(msg.str(), t, this_step, static_cast<int>(worst));
    }
    if (every > 0 && this_step % every == 0)
    {
      ResponseHistory &h = r.history;
      h.time.push_back(t);
      for (std::size_t i = 0; i < n; ++i)
        h.displacement.push_back(*column(i, q + 2));
      // The step's acceleration (u_{n+1} − 2u_n + u_{n−1})/Δt² + ü_g(t_n), as in bookkeeping().
      const double inv_dt = 1.0 / dt;
      for (std::size_t i = 0; i < n; ++i)
        h.absolute_acceleration.push_back(
          fused ?
            last_accel[i] :
            (*column(i, q + 3) - 2.0 * *column(i, q + 2) + *column(i, q + 1)) * (inv_dt * inv_dt) +
              ag_block[qq]);
      for (std::size_t s = 0; s < storey_low.size(); ++s)
        h.interstorey_drift.push_back(*column(static_cast<std::size_t>(storey_up[s]), q + 2) -
                                      *column(static_cast<std::size_t>(storey_low[s]), q + 2));
      h.contact_force.insert(h.contact_force.end(), cf.begin(), cf.end());
      h.energy_input.push_back(e0 + w_in);
      h.energy_error.push_back(err);
    }
  }

  Response CentralDifferenceStepper::Session::response() const
  {
    Response          out    = r;
    const std::size_t B      = static_cast<std::size_t>(block_steps);
    const auto        reduce = [B](const std::vector<double> &per_lane, std::vector<double> &peak)
    {
      for (std::size_t i = 0; i < peak.size(); ++i)
        for (std::size_t q = 0; q < B; ++q)
          peak[i] = std::max(peak[i], per_lane[i * B + q]);
    };
    reduce(lane_peak_u, out.peak_displacement);
    reduce(lane_peak_a, out.peak_absolute_acceleration);
    reduce(lane_peak_d, out.peak_interstorey_drift);
    if (fused)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        out.peak_displacement[i]          = fused_peaks[i];
        out.peak_absolute_acceleration[i] = fused_peaks[padded_n + i];
      }
      for (std::size_t s = 0; s < storey_up.size(); ++s)
        out.peak_interstorey_drift[s] =
          fused_peaks[2 * padded_n + static_cast<std::size_t>(storey_up[s])];
    }
    EnergyBalance &e     = out.energy;
    e.relative_error     = e.residual_relative_error();
    e.max_relative_error = max_residual / std::max(max_supplied, 1e-300);
    e.impact_dissipated  = 0.0;
    for (std::size_t q = 0; q < laws.size(); ++q)
    {
      ContactResult &cr        = out.contacts[q];
      cr.peak_force            = peak_force[q];
      cr.permanent_indentation = laws[q]->permanent_indentation();
      cr.dissipated_energy     = laws[q]->dissipated_energy();
      e.impact_dissipated += cr.dissipated_energy;
    }
    return out;
  }

  CentralDifferenceStepper::CentralDifferenceStepper(const CentralDifference &integrator)
    : integrator_(&integrator)
    , session_(std::make_unique<Session>())
  {
  }

  CentralDifferenceStepper::~CentralDifferenceStepper() = default;
  CentralDifferenceStepper::CentralDifferenceStepper(CentralDifferenceStepper &&) noexcept =
    default;
  CentralDifferenceStepper &
  CentralDifferenceStepper::operator=(CentralDifferenceStepper &&) noexcept = default;

  void CentralDifferenceStepper::init(const GroundMotion &motion)
  {
    session_->init(*integrator_, motion);
    initialised_ = true;
  }

  void CentralDifferenceStepper::require_init(const char *what) const
  {
    if (!initialised_)
      throw std::logic_error(std::string("CentralDifferenceStepper::") + what +
                             " called before init()");
  }

  void CentralDifferenceStepper::step()
  {
    require_init("step");
    if (finished())
    {
      std::ostringstream msg;
      msg << "CentralDifferenceStepper::step: the run ended at step " << session_->n_steps
          << " (t = " << static_cast<double>(session_->n_steps) * session_->dt << " s)";
      throw std::logic_error(msg.str());
    }
    session_->advance(1);
  }

  long CentralDifferenceStepper::advance(const long count)
  {
    require_init("advance");
    const long before = session_->step;
    session_->advance(std::max(count, 0L));
    return session_->step - before;
  }

  long CentralDifferenceStepper::step_index() const
  {
    return session_->step;
  }

  double CentralDifferenceStepper::time() const
  {
    return static_cast<double>(session_->step) * session_->dt;
  }

  double CentralDifferenceStepper::dt() const
  {
    return session_->dt;
  }

  long CentralDifferenceStepper::last_step() const
  {
    return session_->n_steps;
  }

  bool CentralDifferenceStepper::uses_fused_kernel() const
  {
    require_init("uses_fused_kernel");
    return session_->fused;
  }

  bool CentralDifferenceStepper::finished() const
  {
    return initialised_ && session_->step > session_->n_steps;
  }

  std::vector<double> CentralDifferenceStepper::displacement(const int level) const
  {
    require_init("displacement");
    if (level < -2 || level > 0)
      throw std::invalid_argument("CentralDifferenceStepper::displacement: level = " +
                                  std::to_string(level) + " (must be 0, -1 or -2)");
    std::vector<double> u(session_->n);
    for (std::size_t i = 0; i < u.size(); ++i)
      u[i] = *session_->column(i, 2 + level);
    return u;
  }

  Response CentralDifferenceStepper::response() const
  {
    require_init("response");
    return session_->response();
  }

  Response CentralDifference::run(const GroundMotion &motion) const
  {
    CentralDifferenceStepper stepper(*this);
    stepper.init(motion);
    stepper.advance(stepper.last_step() + 1);
    return stepper.response();
  }
} // namespace kimp::lumped
