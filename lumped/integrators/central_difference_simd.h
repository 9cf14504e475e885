// Vectors of L doubles shared by the fused kernels of the central difference method (GCC/Clang
// vector extensions). Internal to lumped/integrators.
#pragma once

#include <cstdint>

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

} // namespace kimp::lumped::cdm
