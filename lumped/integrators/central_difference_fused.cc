// Fused dense kernel of the central difference method for models of at most 8 DOFs, in the
// increment form (see CentralDifference): written once for vectors of L doubles and compiled for
// SSE2, AVX2 and AVX-512F, picked at run time; bitwise equal results for every width.
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include "lumped/integrators/central_difference_simd.h"

namespace kimp::lumped::cdm
{
  namespace
  {
    /// f(std::integral_constant<int, j>) for j = 0..N−1 (unrolled at compile time).
    template <class F, std::size_t... js>
    inline __attribute__((always_inline)) void for_each_index(F &&f, std::index_sequence<js...>)
    {
      (f(std::integral_constant<int, static_cast<int>(js)>{}), ...);
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
      ForceEvaluator<IsolatorType> forces(s);
      const auto at  = [](const double *p) -> const U  &{ return *reinterpret_cast<const U *>(p); };
      const auto put = [](double *p) -> U & { return *reinterpret_cast<U *>(p); };
      const KernelArrays ka(s);
      const bool         iso  = forces.has_isolator();
      const V            zero = V{} * 0.0;
      const V            half = zero + 0.5 / ka.dt;
      const V            idt2 = zero + 1.0 / (ka.dt * ka.dt);

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
        r0[i]               = at(ka.a_i + o);
        mask[i]             = at(s.drift_mask.data() + o);
      }
      load_state();

      // One step: isolator, Δu_{n+1}, u_{n+1} (stored as column k + 3), bookkeeping of step n.
      const auto one_step = [&](const long k, const bool touched) __attribute__((always_inline))
      {
        const double ag = ka.agb[k];
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
                at(ka.a_f + static_cast<std::size_t>(j) * LD + static_cast<std::size_t>(i * L)) *
                dj;
              pg[j] =
                at(ka.a_g + static_cast<std::size_t>(j) * LD + static_cast<std::size_t>(i * L)) *
                dj;
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
          for (std::size_t q = 0; q < ka.n_fd; ++q)
          {
            const std::size_t j  = static_cast<std::size_t>(ka.fd[q]);
            const double      fj = ka.f[j];
            if (fj != 0.0)
#pragma GCC unroll 16
              for (int i = 0; i < P; ++i)
                dn[i] -= at(ka.a_i + j * LD + static_cast<std::size_t>(i * L)) * fj;
            ka.f[j] = 0.0;
          }
          ka.f[s.n] = 0.0;
        }
        double *next = ka.ub + static_cast<std::size_t>(k + 3) * ka.S;
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
          if (ka.contact_possible(s.step, k))
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
      store_last_velocity(s, len);
    }

    /// fused_body() for N DOFs as a kernel body of kernel_for().
    template <int N>
    struct Fused
    {
      template <class IsolatorType>
      struct Body
      {
        template <int L>
        static inline __attribute__((always_inline)) void run(Session &s, const long len)
        {
          fused_body<L, IsolatorType, N>(s, len);
        }
      };
    };

    /// kernel_for<Fused<n>::Body> for n = 1..sizeof...(js), else nullptr.
    template <std::size_t... js>
    Session::Kernel fused_kernel_of(const std::size_t n,
                                    const int         lanes,
                                    const Isolator   *isolator,
                                    std::index_sequence<js...>)
    {
      using Pick                   = Session::Kernel (*)(int, const Isolator *);
      static constexpr Pick pick[] = {
        kernel_for<Fused<static_cast<int>(js) + 1>::template Body>...};
      return n >= 1 && n <= sizeof...(js) ? pick[n - 1](lanes, isolator) : nullptr;
    }
  } // namespace

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

  Session::Kernel fused_kernel(const std::size_t n, const int lanes, const Isolator *isolator)
  {
    return fused_kernel_of(n, lanes, isolator, std::make_index_sequence<8>{});
  }
} // namespace kimp::lumped::cdm
