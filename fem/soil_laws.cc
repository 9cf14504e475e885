// The perfectly plastic soil laws (see inelastic_laws.h; the soil presets are in
// soil_presets.cc): what Mohr-Coulomb and Drucker-Prager share (PlasticSoilLaw), the Mohr-Coulomb
// return mapping over the active sets of its 9 planes and the Drucker-Prager cone and apex returns.
// Everything on the stack: no allocation per quadrature point. One file of ~600 lines:
// PlasticSoilLaw's members are instantiated here for both laws, next to the return mappings they
// call (inlined).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fem/inelastic_laws.h"
#include "fem/principal_2d.h"

namespace kimp::fem
{
  using detail::eigen2;
  using detail::principal2;

  namespace
  {
    using Vec3 = std::array<double, 3>;
    using Mat3 = std::array<double, 9>;

    constexpr double pi = 3.14159265358979323846;

    /** Solves the k x k system m x = b (k <= 3, row-major, stride 3) by Gauss with partial
     *  pivoting; false if (nearly) singular relative to @p scale. */
    bool solve_small(unsigned int k, double m[3][3], double b[3], double x[3], double scale)
    {
      unsigned int perm[3] = {0, 1, 2};
      for (unsigned int c = 0; c < k; ++c)
      {
        unsigned int piv = c;
        for (unsigned int r = c + 1; r < k; ++r)
          if (std::abs(m[perm[r]][c]) > std::abs(m[perm[piv]][c]))
            piv = r;
        std::swap(perm[c], perm[piv]);
        const double d = m[perm[c]][c];
        if (std::abs(d) <= 1e-10 * scale)
          return false;
        for (unsigned int r = c + 1; r < k; ++r)
        {
          const double f = m[perm[r]][c] / d;
          for (unsigned int j = c; j < k; ++j)
            m[perm[r]][j] -= f * m[perm[c]][j];
          b[perm[r]] -= f * b[perm[c]];
        }
      }
      for (int c = static_cast<int>(k) - 1; c >= 0; --c)
      {
        double s = b[perm[c]];
        for (unsigned int j = c + 1; j < k; ++j)
          s -= m[perm[c]][j] * x[j];
        x[c] = s / m[perm[c]][c];
      }
      return true;
    }
  } // namespace

  // ---------------------------------------------------------------- Mohr-Coulomb

  namespace
  {
    /** The 9 planes a.sigma <= b in principal space and their flow directions g. */
    struct MohrCoulombPlanes
    {
      double a[9][3], b[9], g[9][3];
      MohrCoulombPlanes(const SoilParameters &p)
      {
        const double sp = std::sin(p.friction_angle), sd = std::sin(p.dilatancy);
        unsigned int n = 0;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            if (i != j)
            {
              for (unsigned int k = 0; k < 3; ++k)
                a[n][k] = g[n][k] = 0;
              a[n][i] = 1 + sp;
              a[n][j] = -(1 - sp);
              g[n][i] = 1 + sd;
              g[n][j] = -(1 - sd);
              b[n]    = 2 * p.cohesion * std::cos(p.friction_angle);
              ++n;
            }
        for (unsigned int i = 0; i < 3; ++i, ++n)
        {
          for (unsigned int k = 0; k < 3; ++k)
            a[n][k] = g[n][k] = (k == i ? 1.0 : 0.0);
          b[n] = p.tension_cutoff;
        }
      }
    };
  } // namespace

  MohrCoulombLaw::MohrCoulombLaw(const SoilParameters &p, bool exhaustive)
    : PlasticSoilLaw(p)
    , exhaustive_(exhaustive)
  {
    if (!(p.youngs_modulus > 0) || !(p.poisson_ratio >= 0 && p.poisson_ratio < 0.5) ||
        !(p.cohesion >= 0) || !(p.friction_angle >= 0 && p.friction_angle < 0.5 * pi) ||
        !(p.dilatancy >= 0 && p.dilatancy <= p.friction_angle) || !(p.tension_cutoff >= 0))
      throw std::invalid_argument("Mohr-Coulomb: need E > 0, 0 <= nu < 0.5, c >= 0, "
                                  "0 <= psi <= phi < 90 deg, tension cut-off >= 0");
    if (p.friction_angle > 0 && p.tension_cutoff > p.cohesion / std::tan(p.friction_angle))
      p_.tension_cutoff = p.cohesion / std::tan(p.friction_angle); // the apex bounds it

    // Constants of every return mapping, computed once instead of per point.
    set_index_.fill(-1);
    const MohrCoulombPlanes pl(p_);
    for (unsigned int n = 0; n < 9; ++n)
    {
      b_[n]           = pl.b[n];
      const double tg = pl.g[n][0] + pl.g[n][1] + pl.g[n][2];
      for (unsigned int k = 0; k < 3; ++k)
      {
        a_[n][k]  = pl.a[n][k];
        dg_[n][k] = lambda_ * tg + 2 * mu_ * pl.g[n][k];
      }
    }
    // Every set of <= 3 planes, eliminated once as solve_small() would (same pivots, same
    // multipliers); singular ones are dropped as solve_small() would reject them.
    for (unsigned int set = 1; set < (1u << 9); ++set)
    {
      ActiveSet as;
      bool      too_many = false;
      for (unsigned int n = 0; n < 9; ++n)
        if (set & (1u << n))
        {
          if (as.k == 3)
          {
            too_many = true;
            break;
          }
          as.idx[as.k++] = n;
        }
      if (too_many)
        continue;
      as.set = set;
      double m[3][3];
      for (unsigned int i = 0; i < as.k; ++i)
        for (unsigned int j = 0; j < as.k; ++j)
          m[i][j] = a_[as.idx[i]][0] * dg_[as.idx[j]][0] + a_[as.idx[i]][1] * dg_[as.idx[j]][1] +
                    a_[as.idx[i]][2] * dg_[as.idx[j]][2];
      bool singular = false;
      for (unsigned int c = 0; c < as.k && !singular; ++c)
      {
        unsigned int piv = c;
        for (unsigned int r = c + 1; r < as.k; ++r)
          if (std::abs(m[as.perm[r]][c]) > std::abs(m[as.perm[piv]][c]))
            piv = r;
        std::swap(as.perm[c], as.perm[piv]);
        const double d = m[as.perm[c]][c];
        if (std::abs(d) <= 1e-10 * mu_)
        {
          singular = true;
          break;
        }
        for (unsigned int r = c + 1; r < as.k; ++r)
        {
          const double f = m[as.perm[r]][c] / d;
          for (unsigned int j = c; j < as.k; ++j)
            m[as.perm[r]][j] -= f * m[as.perm[c]][j];
          as.op_dst[as.n_ops] = as.perm[r];
          as.op_src[as.n_ops] = as.perm[c];
          as.op_f[as.n_ops]   = f;
          ++as.n_ops;
        }
      }
      if (singular)
        continue;
      for (unsigned int r = 0; r < 3; ++r)
        for (unsigned int j = 0; j < 3; ++j)
          as.upper[r][j] = r < as.k && j < as.k ? m[r][j] : 0.0;
      if (as.k == 1)
        single_set_[as.idx[0]] = static_cast<int>(active_sets_.size());
      set_index_[set] = static_cast<int>(active_sets_.size());
      active_sets_.push_back(as);
    }
  }

  double MohrCoulombLaw::yield_function(const Vec3 &s) const
  {
    double f = -std::numeric_limits<double>::max();
    for (unsigned int n = 0; n < 9; ++n)
      f = std::max(f, a_[n][0] * s[0] + a_[n][1] * s[1] + a_[n][2] * s[2] - b_[n]);
    return f;
  }

  // Long by design: one return mapping in principal stresses. The active-set search, the
  // plastic strain of the chosen set and its consistent tangent read the same trial stress,
  // eigenframe and set, and this is the innermost call of every step of an impact.
  VoigtStress MohrCoulombLaw::update(const VoigtStrain &eps,
                                     const double      *h0,
                                     double            *h1,
                                     VoigtTangent      *tangent) const
  {
    const double lam = lambda_, mu = mu_;
    // Trial elastic strain (total eps_zz = 0).
    const double exx = eps[0] - h0[0], eyy = eps[1] - h0[1], ezz = -h0[2];
    const double exy = 0.5 * (eps[2] - h0[3]);
    double       ea, eb, c, s;
    principal2(exx, eyy, exy, ea, eb);
    const double tr = ea + eb + ezz;
    Vec3         st{{lam * tr + 2 * mu * ea, lam * tr + 2 * mu * eb, lam * tr + 2 * mu * ezz}};

    const double scale =
      std::max({std::abs(st[0]), std::abs(st[1]), std::abs(st[2]), p_.cohesion, 1.0});
    const double tol = 1e-12 * scale;
    double       ftr[9];
    bool         plastic = false;
    for (unsigned int n = 0; n < 9; ++n)
    {
      ftr[n]  = a_[n][0] * st[0] + a_[n][1] * st[1] + a_[n][2] * st[2] - b_[n];
      plastic = plastic || ftr[n] > tol;
    }
    std::copy(h0, h0 + n_history(), h1);
    if (!plastic && tangent == nullptr)
    {
      // Elastic predictor inside the surface: no history change (the plastic increment below
      // would be zero), and the stress is the trial stress, here without the eigenframe's
      // trigonometry (equal to the rotated principal stresses up to round-off).
      h1[6]           = static_cast<double>(ReturnType::elastic);
      h1[7]           = 0;
      const double tv = exx + eyy + ezz;
      return {{lam * tv + 2 * mu * exx, lam * tv + 2 * mu * eyy, 2 * mu * exy}};
    }
    eigen2(exx, eyy, exy, ea, eb, c, s);
    Vec3         sig      = st;
    unsigned int best_set = 0, best_k = 0, best_idx[3] = {0, 0, 0};
    const auto  &Dg = dg_;
    if (plastic)
    {
      // Active-set search (de Souza Neto et al. 2008 Box 8.4 in spirit): first the most
      // violated plane alone (the main-plane return of the textbook, three quarters of the
      // plastic points of an impact); if its stress violates another plane or its multiplier is
      // negative, every set of <= 3 planes, keeping the admissible one (all multipliers >= 0,
      // every plane satisfied) closest to the trial state in the complementary energy. Each
      // set's elimination is precomputed: only its right-hand side is processed here.
      const double E = p_.youngs_modulus, nu = p_.poisson_ratio;
      // Returns the complementary-energy distance of the set's stress (written to sn), or a
      // negative number if the set is not admissible.
      const auto try_set = [&](const ActiveSet &as, Vec3 &sn) -> double
      {
        const unsigned int  k   = as.k;
        const unsigned int *idx = as.idx;
        double              rhs[3], dg[3];
        for (unsigned int i = 0; i < k; ++i)
          rhs[i] = ftr[idx[i]];
        for (unsigned int o = 0; o < as.n_ops; ++o)
          rhs[as.op_dst[o]] -= as.op_f[o] * rhs[as.op_src[o]];
        for (int col = static_cast<int>(k) - 1; col >= 0; --col)
        {
          double sum = rhs[as.perm[col]];
          for (unsigned int j = col + 1; j < k; ++j)
            sum -= as.upper[as.perm[col]][j] * dg[j];
          const double pivot = as.upper[as.perm[col]][col];
          // A negative multiplier rejects the set: known from the signs, before the division.
          if ((sum < 0 && pivot > 0) || (sum > 0 && pivot < 0))
            return -1.0;
          dg[col] = sum / pivot;
        }
        for (unsigned int i = 0; i < k; ++i)
          if (!(dg[i] >= 0))
            return -1.0;
        sn = st;
        for (unsigned int i = 0; i < k; ++i)
          for (unsigned int q = 0; q < 3; ++q)
            sn[q] -= dg[i] * Dg[idx[i]][q];
        for (unsigned int n = 0; n < 9; ++n)
          if (!(a_[n][0] * sn[0] + a_[n][1] * sn[1] + a_[n][2] * sn[2] - b_[n] <= tol))
            return -1.0;
        // Complementary energy of the stress jump, C = D^-1 in principal space.
        const Vec3 d{{st[0] - sn[0], st[1] - sn[1], st[2] - sn[2]}};
        return ((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) -
                2 * nu * (d[0] * d[1] + d[1] * d[2] + d[0] * d[2])) /
               E;
      };
      const auto accept = [&](const ActiveSet &as, const Vec3 &sn)
      {
        best_set = as.set;
        best_k   = as.k;
        std::copy(as.idx, as.idx + as.k, best_idx);
        sig = sn;
      };
      unsigned int worst = 0;
      for (unsigned int n = 1; n < 9; ++n)
        if (ftr[n] > ftr[worst])
          worst = n;
      // The set of the point's last plastic return (an edge or the apex stays so for many steps).
      const int last = static_cast<int>(h0[7]) > 0 ? set_index_[static_cast<int>(h0[7])] : -1;
      Vec3      sn;
      if (!exhaustive_ && single_set_[worst] >= 0 &&
          try_set(active_sets_[single_set_[worst]], sn) >= 0)
        accept(active_sets_[single_set_[worst]], sn);
      else if (!exhaustive_ && last >= 0 && try_set(active_sets_[last], sn) >= 0)
        accept(active_sets_[last], sn);
      else
      {
        double best_dist = std::numeric_limits<double>::max();
        for (const ActiveSet &as : active_sets_)
        {
          const double dist = try_set(as, sn);
          if (dist >= 0 && dist < best_dist)
          {
            best_dist = dist;
            accept(as, sn);
          }
        }
      }
      if (best_set == 0)
        throw std::runtime_error("Mohr-Coulomb return mapping found no admissible stress");
    }

    // Plastic strain increment in the eigenframe, then in x-y.
    const double E = p_.youngs_modulus, nu = p_.poisson_ratio;
    Vec3         dep;
    for (unsigned int i = 0; i < 3; ++i)
    {
      const double ds0 = st[i] - sig[i], ds1 = st[(i + 1) % 3] - sig[(i + 1) % 3],
                   ds2 = st[(i + 2) % 3] - sig[(i + 2) % 3];
      dep[i]           = (ds0 - nu * (ds1 + ds2)) / E;
    }
    h1[0] = h0[0] + c * c * dep[0] + s * s * dep[1];
    h1[1] = h0[1] + s * s * dep[0] + c * c * dep[1];
    h1[2] = h0[2] + dep[2];
    h1[3] = h0[3] + 2 * c * s * (dep[0] - dep[1]);
    h1[4] = h0[4] + std::sqrt(2.0 / 3.0 * (dep[0] * dep[0] + dep[1] * dep[1] + dep[2] * dep[2]));
    h1[5] = h0[5] + sig[0] * dep[0] + sig[1] * dep[1] + sig[2] * dep[2];
    h1[7] = static_cast<double>(best_set);
    if (!plastic)
      h1[6] = static_cast<double>(ReturnType::elastic);
    else
    {
      unsigned int n_mc = 0, n_t = 0;
      for (unsigned int i = 0; i < best_k; ++i)
        (best_idx[i] < 6 ? n_mc : n_t) += 1;
      ReturnType type = n_t == 0  ? (n_mc == 1 ? ReturnType::main :
                                     n_mc == 2 ? ReturnType::edge :
                                                 ReturnType::apex) :
                        n_mc == 0 ? (n_t == 3 ? ReturnType::apex : ReturnType::tension) :
                                    ReturnType::mixed;
      h1[6]           = static_cast<double>(type);
    }

    if (tangent != nullptr)
    {
      // Principal tangent T = (I - Dg M^-1 A) D of the active set.
      Mat3 T{};
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          T[3 * i + j] = lam + (i == j ? 2 * mu : 0.0);
      if (plastic && best_k > 0)
      {
        // X = M^-1 A D (k x 3), column by column.
        double AD[3][3];
        for (unsigned int r = 0; r < best_k; ++r)
          for (unsigned int j = 0; j < 3; ++j)
            AD[r][j] = a_[best_idx[r]][0] * T[j] + a_[best_idx[r]][1] * T[3 + j] +
                       a_[best_idx[r]][2] * T[6 + j];
        double X[3][3] = {};
        for (unsigned int j = 0; j < 3; ++j)
        {
          double m[3][3], rhs[3], x[3] = {0, 0, 0};
          for (unsigned int r = 0; r < best_k; ++r)
          {
            rhs[r] = AD[r][j];
            for (unsigned int q = 0; q < best_k; ++q)
              m[r][q] = a_[best_idx[r]][0] * Dg[best_idx[q]][0] +
                        a_[best_idx[r]][1] * Dg[best_idx[q]][1] +
                        a_[best_idx[r]][2] * Dg[best_idx[q]][2];
          }
          solve_small(best_k, m, rhs, x, 0.0);
          for (unsigned int r = 0; r < best_k; ++r)
            X[r][j] = x[r];
        }
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            for (unsigned int r = 0; r < best_k; ++r)
              T[3 * i + j] -= Dg[best_idx[r]][i] * X[r][j];
      }
      // Eigenframe Voigt tangent (a, b, gamma_ab); the spin term couples the shear.
      const double gap   = ea - eb;
      const double shear = std::abs(gap) > 1e-9 * std::max({std::abs(ea), std::abs(eb), 1e-12}) ?
                             0.5 * (sig[0] - sig[1]) / gap :
                             0.25 * (T[0] - T[1] - T[3] + T[4]);
      const VoigtTangent cp{{T[0], T[1], 0, T[3], T[4], 0, 0, 0, shear}};
      *tangent = detail::tangent_from_frame(cp, c, s);
    }
    return {{c * c * sig[0] + s * s * sig[1],
             s * s * sig[0] + c * c * sig[1],
             c * s * (sig[0] - sig[1])}};
  }

  namespace
  {
    /** sigma_zz and stored energy of a plastic law with plastic strain h[0..3]. */
    PointOutput plastic_output(const VoigtStrain &e, const double *h, double lam, double mu)
    {
      const double exx = e[0] - h[0], eyy = e[1] - h[1], ezz = -h[2], gxy = e[2] - h[3];
      const double tr  = exx + eyy + ezz;
      const double sxx = lam * tr + 2 * mu * exx, syy = lam * tr + 2 * mu * eyy,
                   szz = lam * tr + 2 * mu * ezz, sxy = mu * gxy;
      PointOutput o;
      o.sigma_zz                  = szz;
      o.stored_energy             = 0.5 * (sxx * exx + syy * eyy + szz * ezz + sxy * gxy);
      o.equivalent_plastic_strain = h[4];
      o.plastic_dissipation       = h[5];
      return o;
    }

    /** Plastic-strain slots {xx, yy, zz, gamma_xy} = -D^-1 sigma0 (isotropic compliance). */
    void initial_elastic_strain(double *h, const InitialStress &s, double E, double nu)
    {
      h[0] = -(s[0] - nu * (s[1] + s[2])) / E;
      h[1] = -(s[1] - nu * (s[0] + s[2])) / E;
      h[2] = -(s[2] - nu * (s[0] + s[1])) / E;
      h[3] = -2 * (1 + nu) * s[3] / E;
    }
  } // namespace

  // ---------------------------------------------------------------- Drucker-Prager

  DruckerPragerLaw::DruckerPragerLaw(const SoilParameters &p)
    : PlasticSoilLaw(p)
  {
    if (!(p.youngs_modulus > 0) || !(p.poisson_ratio >= 0 && p.poisson_ratio < 0.5) ||
        !(p.cohesion >= 0) || !(p.friction_angle >= 0 && p.friction_angle < 0.5 * pi) ||
        !(p.dilatancy >= 0 && p.dilatancy <= p.friction_angle))
      throw std::invalid_argument(
        "Drucker-Prager: need E > 0, 0 <= nu < 0.5, c >= 0, 0 <= psi <= phi < 90 deg");
    const double E = p.youngs_modulus, nu = p.poisson_ratio;
    bulk_ = E / (3 * (1 - 2 * nu));
    // Plane-strain match: at plastic flow with d eps_p_zz = 0 the DP surface reduces to
    // t + m sin(phi) = c cos(phi) (t, m: in-plane Mohr radius and centre).
    const double tp = std::tan(p.dilatancy), sp = std::sin(p.friction_angle);
    eta_bar_       = 3 * tp / std::sqrt(9 + 12 * tp * tp);
    const double r = std::sqrt(1 - eta_bar_ * eta_bar_ / 3);
    eta_           = sp / (r + sp * eta_bar_ / 3);
    xi_            = std::cos(p.friction_angle) * (1 - eta_ * eta_bar_ / 3) / r;
  }

  double DruckerPragerLaw::yield_function(const std::array<double, 4> &s) const
  {
    const double p = (s[0] + s[1] + s[2]) / 3;
    const double j2 =
      0.5 * ((s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p)) +
      s[3] * s[3];
    return std::sqrt(j2) + eta_ * p - xi_ * p_.cohesion;
  }

  VoigtStress DruckerPragerLaw::update(const VoigtStrain &eps,
                                       const double      *h0,
                                       double            *h1,
                                       VoigtTangent      *tangent) const
  {
    const double mu = mu_, K = bulk_;
    // Trial elastic strain as a tensor {xx, yy, zz, xy}.
    const double e[4] = {eps[0] - h0[0], eps[1] - h0[1], -h0[2], 0.5 * (eps[2] - h0[3])};
    const double ev   = e[0] + e[1] + e[2];
    const double d[4] = {e[0] - ev / 3, e[1] - ev / 3, e[2] - ev / 3, e[3]};
    const double dn =
      std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2 * d[3] * d[3]); // ||e_dev||
    const double sqj2 = std::sqrt(2.0) * mu * dn, ptr = K * ev;
    const double f     = sqj2 + eta_ * ptr - xi_ * p_.cohesion;
    const double scale = std::max({sqj2, std::abs(ptr), p_.cohesion, 1.0});
    std::copy(h0, h0 + n_history(), h1);

    double       sig[4], dg = 0;
    int          mode = 0; // 0 elastic, 1 cone, 2 apex
    const double A    = 1 / (mu + K * eta_ * eta_bar_);
    if (f <= 1e-12 * scale)
    {
      for (unsigned int i = 0; i < 4; ++i)
        sig[i] = 2 * mu * d[i] + (i < 3 ? ptr : 0.0);
    }
    else
    {
      dg = f * A;
      if (sqj2 - mu * dg >= 0)
      {
        mode              = 1;
        const double fac  = 1 - mu * dg / sqj2;
        const double pnew = ptr - K * eta_bar_ * dg;
        for (unsigned int i = 0; i < 4; ++i)
          sig[i] = 2 * mu * fac * d[i] + (i < 3 ? pnew : 0.0);
      }
      else
      {
        mode             = 2;
        const double pap = eta_ > 0 ? xi_ * p_.cohesion / eta_ : ptr;
        for (unsigned int i = 0; i < 4; ++i)
          sig[i] = i < 3 ? pap : 0.0;
      }
    }
    if (mode > 0)
    {
      // Plastic strain = trial elastic strain - C sigma.
      const double ps = (sig[0] + sig[1] + sig[2]) / 3;
      double       dep[4];
      for (unsigned int i = 0; i < 4; ++i)
        dep[i] = e[i] - ((sig[i] - (i < 3 ? ps : 0.0)) / (2 * mu) + (i < 3 ? ps / (3 * K) : 0.0));
      h1[0] = h0[0] + dep[0];
      h1[1] = h0[1] + dep[1];
      h1[2] = h0[2] + dep[2];
      h1[3] = h0[3] + 2 * dep[3];
      h1[4] =
        h0[4] +
        std::sqrt(2.0 / 3.0 *
                  (dep[0] * dep[0] + dep[1] * dep[1] + dep[2] * dep[2] + 2 * dep[3] * dep[3]));
      h1[5] = h0[5] + sig[0] * dep[0] + sig[1] * dep[1] + sig[2] * dep[2] + 2 * sig[3] * dep[3];
    }
    h1[6] = static_cast<double>(mode == 0 ? ReturnType::elastic :
                                mode == 1 ? ReturnType::dp_cone :
                                            ReturnType::dp_apex);

    if (tangent != nullptr)
    {
      // d sigma = 2 mu (1 - a) de + b (n:de) n - c1 (tr de) n - c2 (n:de) 1 + c3 (tr de) 1.
      double a = 0, b = 0, c1 = 0, c2 = 0, c3 = K, n[4] = {0, 0, 0, 0};
      if (mode == 1)
      {
        for (unsigned int i = 0; i < 4; ++i)
          n[i] = d[i] / dn;
        a  = dg / (std::sqrt(2.0) * dn);
        b  = 2 * mu * a - 2 * mu * mu * A;
        c1 = std::sqrt(2.0) * mu * A * eta_ * K;
        c2 = std::sqrt(2.0) * mu * A * K * eta_bar_;
        c3 = K * (1 - K * eta_ * eta_bar_ * A);
      }
      for (unsigned int col = 0; col < 3; ++col)
      {
        // Strain direction of the Voigt column (gamma: eps_xy = 1/2).
        double de[4]           = {0, 0, 0, 0};
        de[col == 2 ? 3 : col] = col == 2 ? 0.5 : 1.0;
        const double tr        = de[0] + de[1] + de[2];
        const double ndn       = n[0] * de[0] + n[1] * de[1] + n[2] * de[2] + 2 * n[3] * de[3];
        double       ds[4];
        for (unsigned int i = 0; i < 4; ++i)
        {
          const double dev = de[i] - (i < 3 ? tr / 3 : 0.0);
          ds[i]            = (mode == 2 ? 0.0 :
                                          2 * mu * (1 - a) * dev + b * ndn * n[i] - c1 * tr * n[i] +
                                 (i < 3 ? c3 * tr - c2 * ndn : 0.0));
        }
        (*tangent)[col]     = ds[0];
        (*tangent)[3 + col] = ds[1];
        (*tangent)[6 + col] = ds[3];
      }
    }
    return {{sig[0], sig[1], sig[3]}};
  }

  template <class Law>
  PlasticSoilLaw<Law>::PlasticSoilLaw(const SoilParameters &p)
    : p_(p)
  {
    const Lame l = lame(p.youngs_modulus, p.poisson_ratio);
    lambda_      = l.lambda;
    mu_          = l.mu;
  }

  template <class Law>
  VoigtTangent PlasticSoilLaw<Law>::tangent(const VoigtStrain &strain,
                                            const double      *committed) const
  {
    double       scratch[8]; // the trial history, discarded (n_history() <= 8)
    VoigtTangent t{};
    static_cast<const Law &>(*this).update(strain, committed, scratch, &t);
    return t;
  }

  template <class Law>
  PointOutput PlasticSoilLaw<Law>::output(const VoigtStrain &strain, const double *history) const
  {
    return plastic_output(strain, history, lambda_, mu_);
  }

  template <class Law>
  bool PlasticSoilLaw<Law>::set_initial_stress(double *history, const InitialStress &sigma0) const
  {
    initial_elastic_strain(history, sigma0, p_.youngs_modulus, p_.poisson_ratio);
    return true;
  }

  template class PlasticSoilLaw<MohrCoulombLaw>;
  template class PlasticSoilLaw<DruckerPragerLaw>;
} // namespace kimp::fem
