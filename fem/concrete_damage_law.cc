// The concrete damage law (see inelastic_laws.h): fib Model Code 2010 parameters, the tension
// and compression damage with crack band, compressive plastic strain and smeared steel bars.
// Everything on the stack: no allocation per quadrature point.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fem/inelastic_laws.h"
#include "fem/principal_2d.h"

namespace kimp::fem
{
  using detail::eigen2;
  using detail::principal2;

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
    const Lame l = lame(p.youngs_modulus, p.poisson_ratio);
    lambda_      = l.lambda;
    mu_          = l.mu;
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

  double ConcreteDamageLaw::tension_damage(const double kt, const double h) const
  {
    const double ft = effective_tensile_strength(h), k0 = ft / p_.youngs_modulus;
    if (!(kt > k0))
      return 0;
    const double ef = p_.fracture_energy / (h * ft) - 0.5 * k0;
    return 1 - k0 / kt * std::exp(-(kt - k0) / ef);
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
    double dt       = tension_damage(kt, h0[5]);
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
    double dt       = tension_damage(kt, h0[5]);
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
} // namespace kimp::fem
