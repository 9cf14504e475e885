// Mohr-Coulomb / Drucker-Prager return mappings and the concrete damage law (see
// inelastic_laws.h). Everything on the stack: no allocation per quadrature point.
#include "fem/inelastic_laws.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kimp::fem
{
  namespace
  {
    using Vec3 = std::array<double, 3>;
    using Mat3 = std::array<double, 9>;

    constexpr double pi = 3.14159265358979323846;
    double           deg(double d)
    {
      return d * pi / 180;
    }

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

    /** In-plane eigen-decomposition of a symmetric 2 x 2 tensor {xx, yy, xy}: values a >= b,
     *  unit eigenvector of a = (c, s) = (cos t, sin t), t = atan2(xy, d) / 2 in (-pi/2, pi/2],
     *  from the half-angle formulas (no trigonometric calls; equal to them up to round-off). */
    void eigen2(double xx, double yy, double xy, double &a, double &b, double &c, double &s)
    {
      const double m = 0.5 * (xx + yy), d = 0.5 * (xx - yy);
      const double r = std::sqrt(d * d + xy * xy);
      a              = m + r;
      b              = m - r;
      if (!(r > 0))
      {
        c = 1;
        s = 0;
      }
      else if (d >= 0)
      {
        // cos 2t = d / r >= 0: c >= 1 / sqrt(2), s from sin 2t = 2 s c.
        c = std::sqrt(0.5 * (1 + d / r));
        s = xy / (2 * r * c);
      }
      else
      {
        // |t| > pi / 4: |s| >= 1 / sqrt(2) with the sign of xy (t = +-pi/2 at xy = +-0).
        s = std::copysign(std::sqrt(0.5 * (1 - d / r)), xy);
        c = xy / (2 * r * s);
      }
    }

    /** The eigenvalues a >= b of eigen2(), without the eigenvector (no trigonometry). */
    void principal2(double xx, double yy, double xy, double &a, double &b)
    {
      const double m = 0.5 * (xx + yy), d = 0.5 * (xx - yy);
      const double r = std::sqrt(d * d + xy * xy);
      a              = m + r;
      b              = m - r;
    }

    /** Plane-strain Voigt tangent from an eigenframe tangent: C = R^T C' R with R the
     *  engineering-strain rotation into the frame (c, s). */
    VoigtTangent rotate_back(const VoigtTangent &cp, double c, double s)
    {
      const double R[3][3] = {{c * c, s * s, c * s},
                              {s * s, c * c, -c * s},
                              {-2 * c * s, 2 * c * s, c * c - s * s}};
      VoigtTangent out{};
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
        {
          double v = 0;
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              v += R[k][i] * cp[3 * k + l] * R[l][j];
          out[3 * i + j] = v;
        }
      return out;
    }
  } // namespace

  // ---------------------------------------------------------------- presets

  const std::vector<SoilPreset> &soil_presets()
  {
    // E, nu, rho, c, phi, psi: docs/physics.md (inelastic materials) gives the sources.
    static const std::vector<SoilPreset> presets = {
      {"loose_sand", {20e6, 0.3, 1700, 0, deg(30), deg(0), 0}},
      {"medium_dense_sand", {40e6, 0.3, 1850, 0, deg(34), deg(4), 0}},
      {"dense_sand", {70e6, 0.3, 2000, 0, deg(38), deg(8), 0}},
      {"soft_clay", {5e6, 0.45, 1700, 20e3, deg(0), deg(0), 0}},
      {"stiff_clay", {40e6, 0.45, 2000, 100e3, deg(0), deg(0), 0}},
    };
    return presets;
  }

  const SoilParameters &soil_preset(const std::string &name)
  {
    std::string names;
    for (const auto &p : soil_presets())
    {
      if (p.name == name)
        return p.parameters;
      names += (names.empty() ? "" : ", ") + p.name;
    }
    throw std::invalid_argument("unknown soil preset '" + name + "' (expected one of: " + names +
                                ")");
  }

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
    : p_(p)
    , exhaustive_(exhaustive)
  {
    if (!(p.youngs_modulus > 0) || !(p.poisson_ratio >= 0 && p.poisson_ratio < 0.5) ||
        !(p.cohesion >= 0) || !(p.friction_angle >= 0 && p.friction_angle < 0.5 * pi) ||
        !(p.dilatancy >= 0 && p.dilatancy <= p.friction_angle) || !(p.tension_cutoff >= 0))
      throw std::invalid_argument("Mohr-Coulomb: need E > 0, 0 <= nu < 0.5, c >= 0, "
                                  "0 <= psi <= phi < 90 deg, tension cut-off >= 0");
    if (p.friction_angle > 0 && p.tension_cutoff > p.cohesion / std::tan(p.friction_angle))
      p_.tension_cutoff = p.cohesion / std::tan(p.friction_angle); // the apex bounds it
    const double E = p.youngs_modulus, nu = p.poisson_ratio;
    lambda_ = E * nu / ((1 + nu) * (1 - 2 * nu));
    mu_     = E / (2 * (1 + nu));

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
      *tangent = rotate_back(cp, c, s);
    }
    return {{c * c * sig[0] + s * s * sig[1],
             s * s * sig[0] + c * c * sig[1],
             c * s * (sig[0] - sig[1])}};
  }

  VoigtStress
  MohrCoulombLaw::stress(const VoigtStrain &strain, const double *committed, double *trial) const
  {
    return update(strain, committed, trial, nullptr);
  }

  VoigtTangent MohrCoulombLaw::tangent(const VoigtStrain &strain, const double *committed) const
  {
    double       scratch[8];
    VoigtTangent t{};
    update(strain, committed, scratch, &t);
    return t;
  }

  namespace
  {
    /** sigma_zz and stored energy of a plastic law with plastic strain h[0..3]. */
    PointOutput plastic_output(const VoigtStrain &e,
                               const double      *h,
                               double             lam,
                               double             mu,
                               double             E,
                               double             nu)
    {
      const double exx = e[0] - h[0], eyy = e[1] - h[1], ezz = -h[2], gxy = e[2] - h[3];
      const double tr  = exx + eyy + ezz;
      const double sxx = lam * tr + 2 * mu * exx, syy = lam * tr + 2 * mu * eyy,
                   szz = lam * tr + 2 * mu * ezz, sxy = mu * gxy;
      (void)E;
      (void)nu;
      PointOutput o;
      o.sigma_zz                  = szz;
      o.stored_energy             = 0.5 * (sxx * exx + syy * eyy + szz * ezz + sxy * gxy);
      o.equivalent_plastic_strain = h[4];
      o.plastic_dissipation       = h[5];
      return o;
    }
  } // namespace

  PointOutput MohrCoulombLaw::output(const VoigtStrain &strain, const double *history) const
  {
    return plastic_output(strain, history, lambda_, mu_, p_.youngs_modulus, p_.poisson_ratio);
  }
  void MohrCoulombLaw::update_points(unsigned int           n,
                                     const VoigtStrain     *strain,
                                     const double          *committed,
                                     double                *trial,
                                     unsigned int           stride,
                                     VoigtStress           *stress,
                                     std::array<double, 3> *energy) const
  {
    update_points_of(*this, n, strain, committed, trial, stride, stress, energy);
  }


  namespace
  {
    /** Plastic-strain slots {xx, yy, zz, gamma_xy} = -D^-1 sigma0 (isotropic compliance). */
    void initial_elastic_strain(double *h, const InitialStress &s, double E, double nu)
    {
      h[0] = -(s[0] - nu * (s[1] + s[2])) / E;
      h[1] = -(s[1] - nu * (s[0] + s[2])) / E;
      h[2] = -(s[2] - nu * (s[0] + s[1])) / E;
      h[3] = -2 * (1 + nu) * s[3] / E;
    }
  } // namespace

  bool MohrCoulombLaw::set_initial_stress(double *history, const InitialStress &sigma0) const
  {
    initial_elastic_strain(history, sigma0, p_.youngs_modulus, p_.poisson_ratio);
    return true;
  }

  // ---------------------------------------------------------------- Drucker-Prager

  DruckerPragerLaw::DruckerPragerLaw(const SoilParameters &p)
    : p_(p)
  {
    if (!(p.youngs_modulus > 0) || !(p.poisson_ratio >= 0 && p.poisson_ratio < 0.5) ||
        !(p.cohesion >= 0) || !(p.friction_angle >= 0 && p.friction_angle < 0.5 * pi) ||
        !(p.dilatancy >= 0 && p.dilatancy <= p.friction_angle))
      throw std::invalid_argument(
        "Drucker-Prager: need E > 0, 0 <= nu < 0.5, c >= 0, 0 <= psi <= phi < 90 deg");
    const double E = p.youngs_modulus, nu = p.poisson_ratio;
    lambda_ = E * nu / ((1 + nu) * (1 - 2 * nu));
    mu_     = E / (2 * (1 + nu));
    bulk_   = E / (3 * (1 - 2 * nu));
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

  VoigtStress
  DruckerPragerLaw::stress(const VoigtStrain &strain, const double *committed, double *trial) const
  {
    return update(strain, committed, trial, nullptr);
  }

  VoigtTangent DruckerPragerLaw::tangent(const VoigtStrain &strain, const double *committed) const
  {
    double       scratch[7];
    VoigtTangent t{};
    update(strain, committed, scratch, &t);
    return t;
  }

  PointOutput DruckerPragerLaw::output(const VoigtStrain &strain, const double *history) const
  {
    return plastic_output(strain, history, lambda_, mu_, p_.youngs_modulus, p_.poisson_ratio);
  }
  void DruckerPragerLaw::update_points(unsigned int           n,
                                       const VoigtStrain     *strain,
                                       const double          *committed,
                                       double                *trial,
                                       unsigned int           stride,
                                       VoigtStress           *stress,
                                       std::array<double, 3> *energy) const
  {
    update_points_of(*this, n, strain, committed, trial, stride, stress, energy);
  }


  bool DruckerPragerLaw::set_initial_stress(double *history, const InitialStress &sigma0) const
  {
    initial_elastic_strain(history, sigma0, p_.youngs_modulus, p_.poisson_ratio);
    return true;
  }

  // ---------------------------------------------------------------- concrete

  ConcreteParameters ConcreteParameters::from_f_cm(double f_cm)
  {
    if (!(f_cm > 8e6))
      throw std::invalid_argument("concrete f_cm must exceed 8 MPa");
    ConcreteParameters p;
    const double       fcm = f_cm / 1e6, fck = fcm - 8;
    p.f_cm           = f_cm;
    p.youngs_modulus = 21.5e9 * std::cbrt(fcm / 10);
    p.f_ctm = 1e6 * (fck <= 50 ? 0.3 * std::pow(fck, 2.0 / 3.0) : 2.12 * std::log(1 + 0.1 * fcm));
    p.fracture_energy = 73 * std::pow(fcm, 0.18);
    p.eps_c1          = 1e-3 * std::min(0.7 * std::pow(fcm, 0.31), 2.8);
    p.eps_c_lim       = 1e-3 * (fck < 50 ? 3.5 : 2.8 + 27 * std::pow((98 - fcm) / 100, 4));
    return p;
  }

  void ConcreteParameters::apply_strain_rate(double rate)
  {
    const double rc = 30e-6, rt = 1e-6;
    dif_compression = rate <= rc ? 1.0 :
                      rate <= 30 ? std::pow(rate / rc, 0.014) :
                                   0.012 * std::cbrt(rate / rc);
    dif_tension     = rate <= rt ? 1.0 :
                      rate <= 10 ? std::pow(rate / rt, 0.018) :
                                   0.0062 * std::cbrt(rate / rt);
  }

  double ConcreteParameters::compression_curve(double e) const
  {
    if (e <= 0)
      return 0;
    const auto curve = [&](double x)
    {
      const double k = youngs_modulus * eps_c1 / f_cm, eta = x / eps_c1;
      return f_cm * (k * eta - eta * eta) / (1 + (k - 2) * eta);
    };
    double s;
    if (e <= eps_c_lim)
      s = curve(e);
    else
      s = curve(eps_c_lim) * std::max(0.0, (2 * eps_c_lim - e) / eps_c_lim);
    return dif_compression * std::max(0.0, s);
  }

  ConcreteDamageLaw::ConcreteDamageLaw(const ConcreteParameters      &p,
                                       const ReinforcementParameters &reinforcement)
    : p_(p)
    , r_(reinforcement)
    , steel_(reinforcement)
    , reinforced_(reinforcement.any())
    , plastic_(p.plastic_fraction > 0)
    , bars_(p.plastic_fraction > 0 ? 10 : 6)
  {
    if (!(p.plastic_fraction >= 0 && p.plastic_fraction < 1))
      throw std::invalid_argument("concrete damage law: need 0 <= plastic_fraction < 1");
    const ReinforcementParameters &r = reinforcement;
    if (!(r.ratio_x >= 0 && r.ratio_x < 1) || !(r.ratio_y >= 0 && r.ratio_y < 1) ||
        !(r.yield_stress > 0) || !(r.youngs_modulus > 0) || !(r.hardening >= 0 && r.hardening < 1))
      throw std::invalid_argument("reinforcement: need 0 <= ratio_x, ratio_y < 1, f_y > 0, "
                                  "E_s > 0, 0 <= hardening < 1");
    if (!(p.youngs_modulus > 0) || !(p.poisson_ratio >= 0 && p.poisson_ratio < 0.5) ||
        !(p.f_ctm > 0) || !(p.fracture_energy > 0) || !(p.eps_c1 > 0) ||
        !(p.eps_c_lim > p.eps_c1) || !(p.f_cm > 0))
      throw std::invalid_argument("concrete damage law: need E, f_cm, f_ctm, G_F, eps_c1 > 0, "
                                  "eps_c_lim > eps_c1, 0 <= nu < 0.5");
    const double E = p.youngs_modulus, nu = p.poisson_ratio;
    lambda_ = E * nu / ((1 + nu) * (1 - 2 * nu));
    mu_     = E / (2 * (1 + nu));
  }

  void ConcreteDamageLaw::initial_history(double *h) const
  {
    initialize_point(h, 0.1); // a 0.1 m crack band when the element size is not known
  }

  void ConcreteDamageLaw::initialize_point(double *h, double length) const
  {
    std::fill(h, h + n_history(), 0.0);
    h[5] = length > 0 ? length : 0.1;
  }

  double ConcreteDamageLaw::effective_tensile_strength(double h) const
  {
    // Keep the softening branch at least as long as the elastic one (no snap-back):
    // G_F / (h f_t) - f_t / (2 E) >= f_t / E.
    const double ft = p_.f_ctm * p_.dif_tension;
    return std::min(ft, std::sqrt(p_.youngs_modulus * p_.fracture_energy / (1.5 * h)));
  }

  namespace
  {
    constexpr double max_damage = 1 - 1e-6;
  }

  VoigtStress ConcreteDamageLaw::stress(const VoigtStrain &e, const double *h0, double *h1) const
  {
    VoigtStress s = plastic_ ? plastic_concrete_stress(e, h0, h1) : concrete_stress(e, h0, h1);
    if (reinforced_)
    {
      // Bars along x and y strained as the concrete (perfect bond), in parallel with it.
      const double    *b0 = h0 + bars_;
      double          *b1 = h1 + bars_;
      const SteelState sx = steel_.update(e[0], b0[0], b0[1]);
      const SteelState sy = steel_.update(e[1], b0[2], b0[3]);
      b1[0]               = sx.plastic_strain;
      b1[1]               = sx.back_stress;
      b1[2]               = sy.plastic_strain;
      b1[3]               = sy.back_stress;
      b1[4]               = b0[4] + r_.ratio_x * sx.plastic_work + r_.ratio_y * sy.plastic_work;
      s[0] += r_.ratio_x * sx.stress;
      s[1] += r_.ratio_y * sy.stress;
    }
    return s;
  }

  double ConcreteDamageLaw::plastic_strain(double kc) const
  {
    return p_.plastic_fraction * std::max(0.0, kc - p_.compression_curve(kc) / p_.youngs_modulus);
  }

  VoigtStress ConcreteDamageLaw::plastic_concrete_stress(const VoigtStrain &e,
                                                         const double      *h0,
                                                         double            *h1) const
  {
    const double E = p_.youngs_modulus, lam = lambda_, mu = mu_;
    std::copy(h0, h0 + n_history(), h1);
    // Compression measure on the total strain (so that uniaxial compression follows the curve
    // exactly whatever b_c); the plastic strain grows along the largest compression.
    double       tr  = e[0] + e[1];
    const double txx = lam * tr + 2 * mu * e[0], tyy = lam * tr + 2 * mu * e[1], tzz = lam * tr,
                 txy = mu * e[2];
    double ta, tb, c, sn;
    eigen2(txx, tyy, txy, ta, tb, c, sn);
    const double kc = std::max(h0[1], std::max(-std::min(tb, tzz), 0.0) / E);
    const double dp = plastic_strain(kc) - plastic_strain(h0[1]);
    // n = (-s, c), the eigenvector of tb: n (x) n = {s^2, c^2, -2 c s} (engineering shear).
    const double nxx = sn * sn, nyy = c * c, nxy = -2 * c * sn;
    if (dp > 0)
    {
      h1[6] = h0[6] - dp * nxx;
      h1[7] = h0[7] - dp * nyy;
      h1[8] = h0[8] - dp * nxy;
    }
    // Elastic strain and its (effective) stress; the tension measure acts on that stress.
    const double exx = e[0] - h1[6], eyy = e[1] - h1[7], gxy = e[2] - h1[8];
    tr               = exx + eyy;
    const double sxx = lam * tr + 2 * mu * exx, syy = lam * tr + 2 * mu * eyy, szz = lam * tr,
                 sxy = mu * gxy;
    double sa, sb;
    principal2(sxx, syy, sxy, sa, sb);
    const double kt = std::max(h0[0], std::max(std::max(sa, szz), 0.0) / E);
    h1[0]           = kt;
    h1[1]           = kc;
    const double hb = h0[5], ft = effective_tensile_strength(hb), k0 = ft / E;
    double       dt = 0;
    if (kt > k0)
    {
      const double ef = p_.fracture_energy / (hb * ft) - 0.5 * k0;
      dt              = 1 - k0 / kt * std::exp(-(kt - k0) / ef);
    }
    // sigma_c(kappa_c) = (1 - d_c) E (kappa_c - eps_p) in uniaxial compression.
    const double el = kc - plastic_strain(kc);
    double       dc = kc > 0 && el > 0 ? 1 - p_.compression_curve(kc) / (E * el) : 0.0;
    dt              = std::clamp(std::max(dt, h0[2]), 0.0, max_damage);
    dc              = std::clamp(std::max(dc, h0[3]), 0.0, max_damage);
    h1[2]           = dt;
    h1[3]           = dc;
    const double d0 = 1 - (1 - h0[2]) * (1 - h0[3]), d1 = 1 - (1 - dt) * (1 - dc);
    const double Y = 0.5 * (sxx * exx + syy * eyy + sxy * gxy);
    h1[4]          = h0[4] + Y * (d1 - d0);
    const double w = 1 - d1;
    // Plastic work sigma : d eps_p = -dp sigma_nn (sigma_nn < 0 in compression).
    if (dp > 0)
    {
      const double s_nn = w * (sxx * nxx + syy * nyy + sxy * nxy);
      h1[9]             = h0[9] - dp * s_nn;
    }
    return {{w * sxx, w * syy, w * sxy}};
  }

  VoigtStress
  ConcreteDamageLaw::concrete_stress(const VoigtStrain &e, const double *h0, double *h1) const
  {
    const double E = p_.youngs_modulus, lam = lambda_, mu = mu_;
    const double tr  = e[0] + e[1];
    const double sxx = lam * tr + 2 * mu * e[0], syy = lam * tr + 2 * mu * e[1], szz = lam * tr,
                 sxy = mu * e[2];
    double sa, sb;
    principal2(sxx, syy, sxy, sa, sb);
    const double smax = std::max(sa, szz), smin = std::min(sb, szz);
    std::copy(h0, h0 + n_history(), h1);
    if (std::max(smax, 0.0) / E <= h0[0] && std::max(-smin, 0.0) / E <= h0[1])
    {
      // Neither measure grows: the damage stays. The full update below would recompute the
      // committed damage from the same kappa (the damage functions are non-decreasing) and add
      // no dissipation; this gives the same numbers without the softening and curve evaluations.
      const double d = 1 - (1 - h0[2]) * (1 - h0[3]);
      const double w = 1 - d;
      return {{w * sxx, w * syy, w * sxy}};
    }
    const double kt = std::max(h0[0], std::max(smax, 0.0) / E);
    const double kc = std::max(h0[1], std::max(-smin, 0.0) / E);
    h1[0]           = kt;
    h1[1]           = kc;
    // Tension: exponential softening with the crack-band energy G_F / h.
    const double hb = h0[5], ft = effective_tensile_strength(hb), k0 = ft / E;
    double       dt = 0;
    if (kt > k0)
    {
      const double ef = p_.fracture_energy / (hb * ft) - 0.5 * k0;
      dt              = 1 - k0 / kt * std::exp(-(kt - k0) / ef);
    }
    double dc       = kc > 0 ? 1 - p_.compression_curve(kc) / (E * kc) : 0.0;
    dt              = std::clamp(std::max(dt, h0[2]), 0.0, max_damage);
    dc              = std::clamp(std::max(dc, h0[3]), 0.0, max_damage);
    h1[2]           = dt;
    h1[3]           = dc;
    const double d0 = 1 - (1 - h0[2]) * (1 - h0[3]), d1 = 1 - (1 - dt) * (1 - dc);
    // Y = psi_0 = eps : D eps / 2, the energy release rate of the scalar damage.
    const double Y = 0.5 * (sxx * e[0] + syy * e[1] + sxy * e[2]);
    h1[4]          = h0[4] + Y * (d1 - d0);
    const double w = 1 - d1;
    return {{w * sxx, w * syy, w * sxy}};
  }

  VoigtTangent ConcreteDamageLaw::tangent(const VoigtStrain &e, const double *h) const
  {
    const double w   = (1 - h[2]) * (1 - h[3]);
    const double lam = lambda_, mu = mu_;
    VoigtTangent t{{w * (lam + 2 * mu), w * lam, 0, w * lam, w * (lam + 2 * mu), 0, 0, 0, w * mu}};
    if (reinforced_)
    {
      const double *b = h + bars_;
      t[0] += r_.ratio_x * steel_.update(e[0], b[0], b[1]).tangent;
      t[4] += r_.ratio_y * steel_.update(e[1], b[2], b[3]).tangent;
    }
    return t;
  }

  PointOutput ConcreteDamageLaw::output(const VoigtStrain &e, const double *h) const
  {
    const double w = (1 - h[2]) * (1 - h[3]);
    // Elastic strain: the total one less the concrete's compressive plastic strain (if any).
    const double exx = plastic_ ? e[0] - h[6] : e[0], eyy = plastic_ ? e[1] - h[7] : e[1],
                 gxy = plastic_ ? e[2] - h[8] : e[2];
    const double tr  = exx + eyy;
    const double sxx = lambda_ * tr + 2 * mu_ * exx, syy = lambda_ * tr + 2 * mu_ * eyy,
                 sxy = mu_ * gxy;
    PointOutput o;
    o.sigma_zz           = w * lambda_ * tr;
    o.stored_energy      = 0.5 * w * (sxx * exx + syy * eyy + sxy * gxy);
    o.damage             = 1 - w;
    o.damage_dissipation = h[4];
    if (plastic_)
    {
      o.plastic_dissipation       = h[9];
      o.equivalent_plastic_strain = plastic_strain(h[1]);
    }
    if (reinforced_)
    {
      // The bars' elastic energy is stored; their plastic work (hardening included) dissipated.
      const double *b  = h + bars_;
      const double  ex = e[0] - b[0], ey = e[1] - b[2], Es = r_.youngs_modulus;
      o.stored_energy += 0.5 * Es * (r_.ratio_x * ex * ex + r_.ratio_y * ey * ey);
      o.plastic_dissipation += b[4];
      o.equivalent_plastic_strain =
        std::max({o.equivalent_plastic_strain, std::abs(b[0]), std::abs(b[2])});
    }
    return o;
  }
  void ConcreteDamageLaw::update_points(unsigned int           n,
                                        const VoigtStrain     *strain,
                                        const double          *committed,
                                        double                *trial,
                                        unsigned int           stride,
                                        VoigtStress           *stress,
                                        std::array<double, 3> *energy) const
  {
    update_points_of(*this, n, strain, committed, trial, stride, stress, energy);
  }

} // namespace kimp::fem
