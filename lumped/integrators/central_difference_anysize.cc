// Any-size fused kernel of the central difference method (models of more than 8 DOFs: an isolated
// building between neighbours, tall buildings): the fused kernel's increment form with the dense
// products restricted to each building's block; SSE2, AVX2 and AVX-512F, bitwise equal results.
#include <algorithm>
#include <cstddef>

#include "lumped/integrators/central_difference_session.h"
#include "lumped/integrators/central_difference_simd.h"
#include "lumped/isolators/bilinear_isolator.h"

namespace kimp::lumped
{
  namespace
  {
    using cdm::block_steps;
    using cdm::ForceEvaluator;
    using cdm::fused_contacts;
    using cdm::Lanes;
    using cdm::peak_abs;
    using cdm::Session;
    using cdm::shift_down;
    using cdm::shift_up;

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
     * 9-100 DOFs it would not fit, and the products, not the loads, set the pace.
     */
    template <int L, class IsolatorType>
    inline __attribute__((always_inline)) void anysize_body(Session &s, const long len)
    {
      typedef typename Lanes<L>::V V;
      typedef typename Lanes<L>::U U;
      const auto at  = [](const double *p) -> const U  &{ return *reinterpret_cast<const U *>(p); };
      const auto put = [](double *p) -> U & { return *reinterpret_cast<U *>(p); };
      // Broadcast by reference (returning a wide vector from a lambda would change the ABI);
      // x − (+0) is x for every x, −0 included, and compiles to one broadcast.
      const auto bcast = [](V & out, const double x) __attribute__((always_inline))
      {
        out = x - V{};
      };
      ForceEvaluator<IsolatorType> forces(s);
      const std::size_t            n    = s.n;
      const std::size_t            LD   = s.padded_n;
      const std::size_t            P    = LD / L;
      const std::size_t            S    = s.col_stride;
      const std::size_t            LD4  = std::max(LD, (n + 3) / 4 * 4);
      const int                   *lo   = s.any_lo.data();
      const int                   *hi   = s.any_hi.data();
      const double                *agb  = s.ag_block.data();
      const double                *a_f  = s.dense_f.data();
      const double                *a_g  = s.dense_g.data();
      const double                *a_i  = s.dense_inverse.data();
      const double                *am   = s.dense_am.data();
      const double                *mask = s.drift_mask.data();
      double                      *f    = s.force.data();
      const int                   *fd   = s.force_dofs.data();
      const std::size_t            n_fd = s.force_dofs.size();
      const std::size_t            nc   = s.laws.size();
      const std::size_t           *c_l  = s.left_row.data();
      const std::size_t           *c_r  = s.right_row.data();
      const double                *c_g  = s.gap_skip.data();
      double                      *ub   = s.u_block.data();
      const double                 dt   = s.dt;
      const bool                   iso  = forces.has_isolator();
      const V                      zero = V{} * 0.0;
      const V                      half = zero + 0.5 / dt;
      const V                      idt2 = zero + 1.0 / (dt * dt);

      // Scratch: [L zeros | u | d (LD4) | v | L zeros | Δu_{n+1} | z_n]; the zeros are u_{−1}
      // below DOF 0 (drifts) and v above the last DOF (the running sums of v_i·v_{i+1}).
      double *const wu = s.any_work.data() + L;
      double *const wd = wu + LD;
      double *const wv = wd + LD4;
      double *const dn = wv + LD + L;
      double *const zn = dn + LD;
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
        const double ag = agb[k];
        const double fi = iso ? forces.isolator(k, wu[0]) : 0.0;
        V            vg;
        bcast(vg, ag);
        V vf;
        bcast(vf, fi);
        for (std::size_t i = 0; i < P; ++i)
        {
          const std::size_t o  = i * L;
          V                 f0 = zero, f1 = zero, f2 = zero, f3 = zero;
          V                 g0 = zero, g1 = zero, g2 = zero, g3 = zero;
          const double     *F = a_f + o;
          const double     *G = a_g + o;
          for (std::size_t j = static_cast<std::size_t>(lo[i]); j < static_cast<std::size_t>(hi[i]);
               j += 4)
          {
            V d0, d1, d2, d3;
            bcast(d0, wd[j]);
            bcast(d1, wd[j + 1]);
            bcast(d2, wd[j + 2]);
            bcast(d3, wd[j + 3]);
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
          put(dn + o) = ((at(wd + o) - at(z + o)) - at(am + o) * vg - sf) - at(a_i + o) * vf;
          put(zn + o) = at(z + o) + sg3;
        }
        if (touched)
        {
          for (std::size_t q = 0; q < n_fd; ++q)
          {
            const std::size_t j  = static_cast<std::size_t>(fd[q]);
            const double      fj = f[j];
            if (fj != 0.0)
            {
              V vj;
              bcast(vj, fj);
              for (std::size_t i = 0; i < P; ++i)
                put(dn + i * L) = at(dn + i * L) - at(a_i + j * LD + i * L) * vj;
            }
            f[j] = 0.0;
          }
          f[n] = 0.0;
        }
        double *next = ub + static_cast<std::size_t>(k + 3) * S;
        for (std::size_t i = 0; i < P; ++i)
        {
          const std::size_t o  = i * L;
          const V           u  = at(wu + o);
          const V           d  = at(wd + o);
          const V           dd = at(dn + o);
          put(next + o)        = u + dd;
          const V v            = (d + dd) * half;
          const V acc          = (dd - d) * idt2 + vg;
          put(wv + o)          = v;
          put(a + o)           = acc;
          V peak               = at(pu + o);
          peak_abs<V, typename Lanes<L>::I>(peak, u);
          put(pu + o) = peak;
          peak        = at(pa + o);
          peak_abs<V, typename Lanes<L>::I>(peak, acc);
          put(pa + o) = peak;
          // u_{r−1} from whole vectors (an unaligned load across two stores of the last step
          // would defeat store forwarding).
          const V u_prev = i == 0 ? zero : at(wu + o - L); // by value: U is under-aligned
          V       below;
          shift_up<V, typename Lanes<L>::I>(below, u_prev, u);
          const V drift = u - below * at(mask + o);
          peak          = at(pd + o);
          peak_abs<V, typename Lanes<L>::I>(peak, drift);
          put(pd + o) = peak;
          put(sg + o) = at(sg + o) + v * vg;
          put(sv + o) = at(sv + o) + v * v;
        }
        for (std::size_t i = 0; i < P; ++i)
        {
          const std::size_t o   = i * L;
          const V           v   = at(wv + o);
          const V           v_1 = at(wv + o + L); // by value: U is under-aligned
          V                 above;
          shift_down<V, typename Lanes<L>::I>(above, v, v_1);
          put(sx + o) = at(sx + o) + v * above;
        }
        for (std::size_t i = 0; i < P; ++i)
        {
          const std::size_t o = i * L;
          put(wu + o)         = at(wu + o) + at(dn + o);
          put(wd + o)         = at(dn + o);
          put(z + o)          = at(zn + o);
        }
      };

      for (long k = 0; k < len; ++k)
      {
        const double *col = ub + static_cast<std::size_t>(k) * S;
        bool          hit = s.step + k < 2; // the first steps use the initial δ_{−1}, δ_{−2}
        for (std::size_t c = 0; c < nc; ++c)
          hit |= col[c_l[c]] - col[c_r[c]] > c_g[c];
        if (!hit)
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
      const std::size_t B    = static_cast<std::size_t>(block_steps);
      const std::size_t last = static_cast<std::size_t>(len - 1);
      for (std::size_t i = 0; i < n; ++i)
        s.velocity[i * B + last] = s.fused_v[i];
    }

    template <class IsolatorType>
    __attribute__((optimize("fp-contract=off"))) void anysize_sse2(Session &s, const long len)
    {
      anysize_body<2, IsolatorType>(s, len);
    }

#if defined(__x86_64__) && defined(__GNUC__)
    template <class IsolatorType>
    __attribute__((target("avx2"), optimize("fp-contract=off"))) void anysize_avx2(Session   &s,
                                                                                   const long len)
    {
      anysize_body<4, IsolatorType>(s, len);
    }

    template <class IsolatorType>
    __attribute__((target("avx512f"), optimize("fp-contract=off"))) void
    anysize_avx512(Session &s, const long len)
    {
      anysize_body<8, IsolatorType>(s, len);
    }
#endif

    template <class IsolatorType>
    Session::Kernel anysize_for(const int lanes)
    {
#if defined(__x86_64__) && defined(__GNUC__)
      if (lanes == 8)
        return anysize_avx512<IsolatorType>;
      if (lanes == 4)
        return anysize_avx2<IsolatorType>;
#endif
      (void)lanes;
      return anysize_sse2<IsolatorType>;
    }
  } // namespace

  namespace cdm
  {
    Session::Kernel anysize_kernel(const int lanes, const Isolator *isolator)
    {
      return dynamic_cast<const BilinearIsolator *>(isolator) ?
               anysize_for<BilinearIsolator>(lanes) :
               anysize_for<Isolator>(lanes);
    }
  } // namespace cdm
} // namespace kimp::lumped
