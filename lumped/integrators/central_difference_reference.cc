// Reference kernel of the central difference method (any model): the right-hand side with the
// tridiagonal B = 2M/Δt² − K and D = −M/Δt² + C/(2Δt), A⁻¹ block-wise (dense or Thomas), and the
// bookkeeping of each block vectorised over its steps. The oracle for the fused kernel.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#if defined(__SSE2__)
#  include <emmintrin.h>
#endif

#include "lumped/integrators/central_difference_session.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/linear_isolator.h"

namespace kimp::lumped
{
  namespace cdm
  {
    EffectiveMatrixInverse::EffectiveMatrixInverse(const TridiagonalMatrix &a)
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

    void EffectiveMatrixInverse::apply(const double *x, double *y) const
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
  } // namespace cdm

  namespace
  {
    using cdm::block_steps;
    using cdm::ForceEvaluator;
    using cdm::Session;

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
      p_in_prev   = p_in;
      p_visc_prev = p_visc;
      rec.supplied(e0 + w_in);
    }
  }

  namespace cdm
  {
    Session::Kernel reference_kernel(const Isolator *isolator)
    {
      if (dynamic_cast<const BilinearIsolator *>(isolator))
        return dynamics_general<BilinearIsolator>;
      if (dynamic_cast<const LinearIsolator *>(isolator))
        return dynamics_general<LinearIsolator>;
      return dynamics_general<Isolator>;
    }
  } // namespace cdm
} // namespace kimp::lumped
