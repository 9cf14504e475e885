// Any-size fused kernel of the central difference method (models of more than 8 DOFs: an isolated
// building between neighbours, tall buildings): the fused kernel's increment form with the dense
// products restricted to each building's block; SSE2, AVX2 and AVX-512F, bitwise equal results.
#include <algorithm>
#include <cstddef>
#include <utility>

#include "lumped/integrators/central_difference_simd.h"

namespace kimp::lumped::cdm
{
  namespace
  {
    /**
     * Splats of the four DOFs j..j+3 (j a multiple of 4) of the padded vector at `x` (L-aligned
     * vectors), each from a whole-vector load: a scalar turned into a vector inside this
     * target-less template would be built lane by lane (one masked broadcast per lane), while
     * a shuffle of a loaded vector is one instruction, and a load of a whole stored vector is
     * forwarded from the store.
     */
    template <class V, class I, int L, class At>
    inline __attribute__((always_inline)) void
    splat4(V &d0, V &d1, V &d2, V &d3, const double *x, const std::size_t j, const At &at)
    {
      if constexpr (L == 2)
      {
        const V a = at(x + j), b = at(x + j + 2);
        splat<V, I, 0>(d0, a);
        splat<V, I, 1>(d1, a);
        splat<V, I, 0>(d2, b);
        splat<V, I, 1>(d3, b);
      }
      else if constexpr (L == 4)
      {
        const V a = at(x + j);
        splat<V, I, 0>(d0, a);
        splat<V, I, 1>(d1, a);
        splat<V, I, 2>(d2, a);
        splat<V, I, 3>(d3, a);
      }
      else
      {
        static_assert(L == 8, "vectors of 2, 4 or 8 doubles");
        const V a = at(x + (j & ~std::size_t{7}));
        if (j & 4)
        {
          splat<V, I, 4>(d0, a);
          splat<V, I, 5>(d1, a);
          splat<V, I, 6>(d2, a);
          splat<V, I, 7>(d3, a);
        }
        else
        {
          splat<V, I, 0>(d0, a);
          splat<V, I, 1>(d1, a);
          splat<V, I, 2>(d2, a);
          splat<V, I, 3>(d3, a);
        }
      }
    }

    /**
     * The step of the fused kernel (see CentralDifference) for any n, vectors of L doubles:
     *   Δu_{n+1} = Δu_n − z_{n−1} − A⁻¹M·1·ü_g − (A⁻¹C/Δt + A⁻¹K)·Δu_n − A⁻¹f_n,
     *   z_n = z_{n−1} + A⁻¹K·Δu_n.
     * A is block-diagonal (one block per building), so the rows of one vector need only the
     * columns of their buildings ([any_lo, any_hi), set at init()). Each product row is summed
     * in four partial sums by column index j mod 4, each over ascending j, then
     * (s0 + s1) + (s2 + s3): the order depends on j only, and a column a vector includes for
     * another of its rows adds an exact zero, so every vector width gives bitwise the same
     * result. The state lives in L1 (scratch in Session::any_work) instead of registers: with
     * 9-100 DOFs it would not fit, and the products, not the loads, set the pace. Δu is double
     * buffered (the products of every row read Δu_n while Δu_{n+1} is written), z is updated in
     * place (row i's products do not read it), and the bookkeeping of step n and the update of
     * u run in one pass over the vectors.
     */
    template <int L, class IsolatorType>
    inline __attribute__((always_inline)) void anysize_body(Session &s, const long len)
    {
      typedef typename Lanes<L>::V V;
      typedef typename Lanes<L>::I I;
      typedef typename Lanes<L>::U U;
      const auto at  = [](const double *p) -> const U  &{ return *reinterpret_cast<const U *>(p); };
      const auto put = [](double *p) -> U & { return *reinterpret_cast<U *>(p); };
      ForceEvaluator<IsolatorType> forces(s);
      const KernelArrays           ka(s);
      const std::size_t            n    = s.n;
      const std::size_t            LD   = s.padded_n;
      const std::size_t            P    = LD / L;
      const std::size_t            LD4  = std::max(LD, (n + 3) / 4 * 4);
      const int                   *lo   = s.any_lo.data();
      const int                   *hi   = s.any_hi.data();
      const double                *am   = s.dense_am.data();
      const double                *mask = s.drift_mask.data();
      const bool                   iso  = forces.has_isolator();
      const V                      zero = V{} * 0.0;
      const V                      half = zero + 0.5 / ka.dt;
      const V                      idt2 = zero + 1.0 / (ka.dt * ka.dt);

      // Scratch: [u | Δu (LD4) | Δu (LD4) | v]; the two Δu alternate between Δu_n and Δu_{n+1}.
      double *const wu = s.any_work.data();
      double       *wd = wu + LD;
      double       *dn = wd + LD4;
      double *const wv = dn + LD4;
      double *const z  = s.fused_z.data();
      double *const a  = s.last_accel.data();
      double *const pu = s.fused_peaks.data();
      double *const pa = pu + LD;
      double *const pd = pa + LD;
      double *const sg = s.fused_sums.data();
      double *const sv = sg + LD;
      double *const sx = sv + LD;
      std::copy(s.fused_u.begin(), s.fused_u.end(), wu);
      std::copy(s.fused_d.begin(), s.fused_d.end(), wd);
      std::copy(s.fused_v.begin(), s.fused_v.end(), wv);

      const auto one_step = [&](const long k, const bool touched) __attribute__((always_inline))
      {
        const double ag = ka.agb[k];
        const double fi = iso ? forces.isolator(k, wu[0]) : 0.0;
        // ü_g and f_iso as vectors: splats of vectors whose lane 0 holds them (see splat4).
        V vg = zero, vf = zero;
        vg[0] = ag;
        vf[0] = fi;
        splat<V, I, 0>(vg, vg);
        splat<V, I, 0>(vf, vf);
        for (std::size_t i = 0; i < P; ++i)
        {
          const std::size_t o  = i * L;
          V                 f0 = zero, f1 = zero, f2 = zero, f3 = zero;
          V                 g0 = zero, g1 = zero, g2 = zero, g3 = zero;
          const double     *F = ka.a_f + o;
          const double     *G = ka.a_g + o;
          for (std::size_t j = static_cast<std::size_t>(lo[i]); j < static_cast<std::size_t>(hi[i]);
               j += 4)
          {
            V d0, d1, d2, d3;
            splat4<V, I, L>(d0, d1, d2, d3, wd, j, at);
            f0 += at(F + j * LD) * d0;
            g0 += at(G + j * LD) * d0;
            f1 += at(F + (j + 1) * LD) * d1;
            g1 += at(G + (j + 1) * LD) * d1;
            f2 += at(F + (j + 2) * LD) * d2;
            g2 += at(G + (j + 2) * LD) * d2;
            f3 += at(F + (j + 3) * LD) * d3;
            g3 += at(G + (j + 3) * LD) * d3;
          }
          const V sf  = (f0 + f1) + (f2 + f3);
          const V sg3 = (g0 + g1) + (g2 + g3);
          const V zo  = at(z + o);
          put(dn + o) = ((at(wd + o) - zo) - at(am + o) * vg - sf) - at(ka.a_i + o) * vf;
          put(z + o)  = zo + sg3;
        }
        if (touched)
        {
          for (std::size_t q = 0; q < ka.n_fd; ++q)
          {
            const std::size_t j  = static_cast<std::size_t>(ka.fd[q]);
            const double      fj = ka.f[j];
            if (fj != 0.0)
            {
              V vj  = zero;
              vj[0] = fj;
              splat<V, I, 0>(vj, vj);
              for (std::size_t i = 0; i < P; ++i)
                put(dn + i * L) = at(dn + i * L) - at(ka.a_i + j * LD + i * L) * vj;
            }
            ka.f[j] = 0.0;
          }
          ka.f[n] = 0.0;
        }
        // Bookkeeping of step n and u_{n+1}, one pass: the drift of vector i needs the old u
        // of vector i − 1, the running sum of v_i·v_{i+1} the new v of vector i + 1.
        double *next   = ka.ub + static_cast<std::size_t>(k + 3) * ka.S;
        V       u_prev = zero, v_prev = zero;
        for (std::size_t i = 0; i < P; ++i)
        {
          const std::size_t o  = i * L;
          const V           u  = at(wu + o);
          const V           d  = at(wd + o);
          const V           dd = at(dn + o);
          const V           un = u + dd;
          put(next + o)        = un;
          put(wu + o)          = un;
          const V v            = (d + dd) * half;
          const V acc          = (dd - d) * idt2 + vg;
          put(a + o)           = acc;
          V peak               = at(pu + o);
          peak_abs<V, I>(peak, u);
          put(pu + o) = peak;
          peak        = at(pa + o);
          peak_abs<V, I>(peak, acc);
          put(pa + o) = peak;
          V below;
          shift_up<V, I>(below, u_prev, u);
          const V drift = u - below * at(mask + o);
          peak          = at(pd + o);
          peak_abs<V, I>(peak, drift);
          put(pd + o) = peak;
          put(sg + o) = at(sg + o) + v * vg;
          put(sv + o) = at(sv + o) + v * v;
          put(wv + o) = v;
          if (i > 0)
          {
            V above;
            shift_down<V, I>(above, v_prev, v);
            put(sx + o - L) = at(sx + o - L) + v_prev * above;
          }
          u_prev = u;
          v_prev = v;
        }
        V above;
        shift_down<V, I>(above, v_prev, zero);
        put(sx + LD - L) = at(sx + LD - L) + v_prev * above;
        std::swap(wd, dn);
      };

      for (long k = 0; k < len; ++k)
      {
        if (!ka.contact_possible(s.step, k))
        {
          s.deltas_current = false;
          one_step(k, false);
          continue;
        }
        one_step(k, fused_contacts(s, forces, k));
      }
      std::copy(wu, wu + LD, s.fused_u.begin());
      std::copy(wd, wd + LD, s.fused_d.begin());
      std::copy(wv, wv + LD, s.fused_v.begin());
      store_last_velocity(s, len);
    }

    /// anysize_body() as a kernel body of kernel_for().
    template <class IsolatorType>
    struct AnySize
    {
      template <int L>
      static inline __attribute__((always_inline)) void run(Session &s, const long len)
      {
        anysize_body<L, IsolatorType>(s, len);
      }
    };
  } // namespace

  Session::Kernel anysize_kernel(const int lanes, const Isolator *isolator)
  {
    return kernel_for<AnySize>(lanes, isolator);
  }
} // namespace kimp::lumped::cdm
