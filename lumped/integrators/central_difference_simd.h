// What the fused kernels of the central difference method share (the <= 8-DOF kernel and the
// any-size kernel): vectors of L doubles (GCC/Clang vector extensions), the session arrays a step
// reads, and the compilation of a kernel body for SSE2, AVX2 and AVX-512F. Internal to
// lumped/integrators.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lumped/integrators/central_difference_session.h"
#include "lumped/isolators/bilinear_isolator.h"

namespace kimp::lumped::cdm
{
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
    out = x[j] - V{}; // x − (+0) is x, −0 included
#else
    out = __builtin_shuffle(x, mask);
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

  /// The Session arrays and sizes the steps of a fused kernel read, as plain pointers.
  struct KernelArrays
  {
    explicit KernelArrays(Session &s)
      : S(s.col_stride)
      , agb(s.ag_block.data())
      , a_f(s.dense_f.data())
      , a_g(s.dense_g.data())
      , a_i(s.dense_inverse.data())
      , f(s.force.data())
      , fd(s.force_dofs.data())
      , n_fd(s.force_dofs.size())
      , nc(s.laws.size())
      , c_l(s.left_row.data())
      , c_r(s.right_row.data())
      , c_g(s.gap_skip.data())
      , ub(s.u_block.data())
      , dt(s.dt)
    {
    }

    /**
     * The pre-check of step k of a block that starts at step `step`: whether some contact may
     * be closed (δ above its skip gap in the block column of step k), or k is one of the run's
     * first two steps (they use the initial δ_{−1}, δ_{−2}). The laws are called only then.
     */
    inline __attribute__((always_inline)) bool contact_possible(const long step, const long k) const
    {
      const double *col = ub + static_cast<std::size_t>(k) * S;
      bool          hit = step + k < 2;
      for (std::size_t c = 0; c < nc; ++c)
        hit |= col[c_l[c]] - col[c_r[c]] > c_g[c];
      return hit;
    }

    std::size_t        S;         ///< column stride of the displacement block
    const double      *agb;       ///< ü_g of the block's steps
    const double      *a_f, *a_g; ///< A⁻¹C/Δt + A⁻¹K and A⁻¹K, padded columns
    const double      *a_i;       ///< A⁻¹, padded columns
    double            *f;         ///< nonlinear forces (Session::force)
    const int         *fd;        ///< the DOFs they act on
    std::size_t        n_fd, nc;  ///< their number; the number of contacts
    const std::size_t *c_l, *c_r; ///< block rows of each contact's left and right DOF
    const double      *c_g;       ///< each contact's skip gap
    double            *ub;        ///< the displacement block
    double             dt;        ///< Δt, s
  };

  /// After a block of len steps: the velocity at its last step, where the recorder reads it.
  inline void store_last_velocity(Session &s, const long len)
  {
    const std::size_t B    = static_cast<std::size_t>(block_steps);
    const std::size_t last = static_cast<std::size_t>(len - 1);
    for (std::size_t i = 0; i < s.n; ++i)
      s.velocity[i * B + last] = s.fused_v[i];
  }

  /**
   * A kernel body, a type with `template <int L> static void run(Session &, long len)` (always
   * inlined), compiled for SSE2 (L = 2), AVX2 (L = 4) and AVX-512F (L = 8) with FMA contraction
   * off, so that the three give the same bits (see above).
   */
  template <class Body>
  __attribute__((optimize("fp-contract=off"))) void run_sse2(Session &s, const long len)
  {
    Body::template run<2>(s, len);
  }

#if defined(__x86_64__) && defined(__GNUC__)
  template <class Body>
  __attribute__((target("avx2"), optimize("fp-contract=off"))) void run_avx2(Session   &s,
                                                                             const long len)
  {
    Body::template run<4>(s, len);
  }

  template <class Body>
  __attribute__((target("avx512f"), optimize("fp-contract=off"))) void run_avx512(Session   &s,
                                                                                  const long len)
  {
    Body::template run<8>(s, len);
  }
#endif

  /// The variant of Body for `lanes` (fused_lanes()).
  template <class Body>
  Session::Kernel kernel_for_lanes(const int lanes)
  {
#if defined(__x86_64__) && defined(__GNUC__)
    if (lanes == 8)
      return run_avx512<Body>;
    if (lanes == 4)
      return run_avx2<Body>;
#endif
    (void)lanes;
    return run_sse2<Body>;
  }

  /// Body<BilinearIsolator> (its isolator law inlined) for a bilinear isolator, else
  /// Body<Isolator>, for `lanes`.
  template <template <class> class Body>
  Session::Kernel kernel_for(const int lanes, const Isolator *isolator)
  {
    return dynamic_cast<const BilinearIsolator *>(isolator) ?
             kernel_for_lanes<Body<BilinearIsolator>>(lanes) :
             kernel_for_lanes<Body<Isolator>>(lanes);
  }
} // namespace kimp::lumped::cdm
