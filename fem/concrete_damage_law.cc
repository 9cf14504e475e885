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

  double ConcreteParameters::compression_curve(double e, double band) const
  {
    if (!(compression_band > 0) || !(band > 0) || e <= eps_c1)
      return compression_curve(e);
    return compression_curve(eps_c1 + (e - eps_c1) * band / compression_band);
  }

  ConcreteDamageLaw::ConcreteDamageLaw(const ConcreteParameters      &p,
                                       const ReinforcementParameters &reinforcement,
                                       DamageUpdate                   update)
    : p_(p)
    , r_(reinforcement)
    , steel_(reinforcement)
    , reinforced_(reinforcement.any())
    , plastic_(p.plastic_fraction > 0)
    , bars_(p.plastic_fraction > 0 ? p_slot + 4 : p_slot)
    , bar_slots_(reinforced_ ? (reinforcement.strain_penetration > 0 ? 7 : 6) : 0)
    , implex_on_(update == DamageUpdate::implex)
    , implex_(bars_ + bar_slots_)
  {
    // beta falls over the opening d_agg / 2: below 1 mm its slope (a stiffness of the opening
    // against the shear energy) would outrun the explicit step.
    if (!(p.aggregate_size >= 1e-3) ||
        !(p.shear_retention_floor >= 0 && p.shear_retention_floor <= 1))
      throw std::invalid_argument("concrete damage law: need aggregate_size >= 1 mm and 0 <= "
                                  "shear_retention_floor <= 1");
    if (!(reinforcement.dowel_coefficient >= 0) || !(reinforcement.hinge_length >= 0) ||
        !(reinforcement.strain_penetration >= 0) || !(reinforcement.base_joint_tension >= 0))
      throw std::invalid_argument("reinforcement: need dowel_coefficient, hinge_length, "
                                  "strain_penetration and base_joint_tension >= 0");
    // The base joint acts on the cells strain penetration marks as the base row.
    if (reinforcement.base_joint_tension > 0 && !(reinforcement.strain_penetration > 0))
      throw std::invalid_argument("reinforcement: base_joint_tension needs strain_penetration > 0");
    if (reinforcement.tension_stiffening &&
        !(reinforcement.crack_spacing > 0 && (reinforced_ || reinforcement.bridging_ratio_x > 0 ||
                                              reinforcement.bridging_ratio_y > 0)))
      throw std::invalid_argument("reinforcement: tension stiffening needs bars and a crack "
                                  "spacing > 0");
    if (!(p.plastic_fraction >= 0 && p.plastic_fraction < 1))
      throw std::invalid_argument("concrete damage law: need 0 <= plastic_fraction < 1");
    if (n_history() > max_history)
      throw std::logic_error("concrete damage law: more history values than the tangent's scratch");
    const ReinforcementParameters &r = reinforcement;
    if (!(r.ratio_x >= 0 && r.ratio_x < 1) || !(r.ratio_y >= 0 && r.ratio_y < 1) ||
        !(r.yield_stress > 0) || !(r.youngs_modulus > 0) || !(r.hardening >= 0 && r.hardening < 1))
      throw std::invalid_argument("reinforcement: need 0 <= ratio_x, ratio_y < 1, f_y > 0, "
                                  "E_s > 0, 0 <= hardening < 1");
    if (!(p.youngs_modulus > 0) || !(p.poisson_ratio >= 0 && p.poisson_ratio < 0.5) ||
        !(p.f_ctm > 0) || !(p.fracture_energy > 0) || !(p.eps_c1 > 0) ||
        !(p.eps_c_lim > p.eps_c1) || !(p.f_cm > 0) || !(p.compression_band >= 0))
      throw std::invalid_argument("concrete damage law: need E, f_cm, f_ctm, G_F, eps_c1 > 0, "
                                  "eps_c_lim > eps_c1, 0 <= nu < 0.5, compression_band >= 0");
    const Lame l = lame(p.youngs_modulus, p.poisson_ratio);
    lambda_      = l.lambda;
    mu_          = l.mu;
  }

  SteelBar ConcreteDamageLaw::steel_at(double h) const
  {
    SteelBar s = steel_;
    if (r_.hinge_length > 0)
      s.H = r_.hardening_modulus() * h / r_.hinge_length;
    return s;
  }

  void ConcreteDamageLaw::initial_history(double *h) const
  {
    initialize_point(h, 0.1); // a 0.1 m crack band when the element size is not known
  }

  void ConcreteDamageLaw::initialize_point(double *h, double length) const
  {
    std::fill(h, h + n_history(), 0.0);
    h[5] = length > 0 ? length : 0.1;
    h[6] = 1; // crack normal (1, 0) until the point cracks (no effect while d_t = 0)
    if (bar_slots_ > 6)
      h[bars_ + 6] = 1; // the y bars read the point's strain
  }

  void ConcreteDamageLaw::initialize_anchored_point(double *h, double length, double height) const
  {
    initialize_point(h, length);
    if (bar_slots_ > 6)
      h[bars_ + 6] = height / (height + r_.strain_penetration);
  }

  double ConcreteDamageLaw::tension_band(double h) const
  {
    return r_.crack_spacing > 0 ? r_.crack_spacing : h;
  }

  double ConcreteDamageLaw::effective_tensile_strength(double cell_band) const
  {
    const double h = tension_band(cell_band);
    // Keep the softening branch at least as long as the elastic one (no snap-back):
    // G_F / (h f_t) - f_t / (2 E) >= f_t / E.
    const double ft = p_.f_ctm * p_.dif_tension;
    return std::min(ft, std::sqrt(p_.youngs_modulus * p_.fracture_energy / (1.5 * h)));
  }

  namespace
  {
    constexpr double max_damage = 1 - 1e-6;

    /** The strain {xx, yy, gamma_xy} in the crack frame n = (c, s), t = (-s, c): {nn, tt,
     *  gamma_nt}. The stress of the frame goes back by the transpose (work conjugacy). */
    VoigtStrain to_crack_frame(const VoigtStrain &e, double c, double s)
    {
      const double cc = c * c, ss = s * s, cs = c * s;
      return {{cc * e[0] + ss * e[1] + cs * e[2],
               ss * e[0] + cc * e[1] - cs * e[2],
               -2 * cs * e[0] + 2 * cs * e[1] + (cc - ss) * e[2]}};
    }
    VoigtStress from_crack_frame(const VoigtStress &f, double c, double s)
    {
      const double cc = c * c, ss = s * s, cs = c * s;
      return {{cc * f[0] + ss * f[1] - 2 * cs * f[2],
               ss * f[0] + cc * f[1] + 2 * cs * f[2],
               cs * f[0] - cs * f[1] + (cc - ss) * f[2]}};
    }
  } // namespace

  void ConcreteDamageLaw::begin_step(double *h, double step_ratio) const
  {
    if (!implex_on_)
      return;
    // kappa~_n+1 = kappa_n + (dlambda_n+1 / dlambda_n) (kappa_n - kappa_n-1).
    h[implex_]     = h[0] + step_ratio * (h[0] - h[implex_ + 2]);
    h[implex_ + 1] = h[1] + step_ratio * (h[1] - h[implex_ + 3]);
  }

  double ConcreteDamageLaw::step_error(const double *h) const
  {
    if (!implex_on_)
      return 0;
    const double kt = h[0], band = h[5];
    const double lag =
      std::clamp(tension_damage(kt, band, h[6], h[7], anchor_scale(h)), 0.0, max_damage) - h[2];
    return std::max(0.0, lag) * p_.youngs_modulus * kt / effective_tensile_strength(band);
  }

  std::array<double, 2> ConcreteDamageLaw::implex_damage(const double *h0, double *h1) const
  {
    // The committed (implicit) measures become the previous ones once this step is committed.
    h1[implex_ + 2] = h0[0];
    h1[implex_ + 3] = h0[1];
    const double kt = h0[implex_], kc = h0[implex_ + 1];
    const double el = kc - plastic_strain(kc, h0[5]);
    const double dc =
      kc > 0 && el > 0 ? 1 - p_.compression_curve(kc, h0[5]) / (p_.youngs_modulus * el) : 0.0;
    return {{std::clamp(std::max(tension_damage(kt, h0[5], h0[6], h0[7], anchor_scale(h0)), h0[2]),
                        0.0,
                        max_damage),
             std::clamp(std::max(dc, h0[3]), 0.0, max_damage)}};
  }

  double ConcreteDamageLaw::shear_retention(double w) const
  {
    const double w_max = 0.5 * p_.aggregate_size, b0 = p_.shear_retention_floor;
    return w >= w_max ? b0 : b0 + (1 - b0) * (1 - w / w_max);
  }

  ConcreteDamageLaw::Split
  ConcreteDamageLaw::split(const VoigtStrain &e, double c, double s, double h) const
  {
    if (c == 0 && s == 0)
      c = 1; // a history written before the crack frame existed: any frame, d_t = 0 there
    // Plane-strain energy in the crack frame: psi_0 = 1/2 (enn, ett) Q (enn, ett) + mu g^2 / 2,
    // Q = [[a, lam], [lam, a]], a = lam + 2 mu. A fully cracked point keeps the no-tension
    // energy of the normal block, min over crack strains e_c >= 0 of 1/2 (eps - e_c) Q
    // (eps - e_c) (four regions: both closed, n open, t open, both open), and beta mu g^2 / 2 of
    // the shear. The loss L = psi_0 - psi_cracked >= 0 is what the tension damage removes.
    const double      lam = lambda_, mu = mu_, a = lam + 2 * mu, ep = a - lam * lam / a;
    const VoigtStrain f   = to_crack_frame(e, c, s);
    const double      enn = f[0], ett = f[1], g = f[2];
    const double      snn = a * enn + lam * ett, stt = lam * enn + a * ett;
    double            kn = 0, kt = 0;         // crack strains of the projection
    double            rn = snn, rt = stt;     // stress the cracked normal block keeps
    double            open_n = 0, open_t = 0; // d(opening) / d(enn, ett)
    if (snn <= 0 && stt <= 0)
    {
      // Both cracks closed: the normal block is intact.
    }
    else if (enn >= 0 && ett >= 0)
    {
      kn = enn;
      kt = ett;
      rn = rt                        = 0;
      (enn >= ett ? open_n : open_t) = 1;
    }
    else if (snn > 0 && ett <= 0)
    {
      kn     = snn / a;
      rn     = 0;
      rt     = ep * ett;
      open_n = 1;
      open_t = lam / a;
    }
    else
    {
      kt     = stt / a;
      rn     = ep * enn;
      rt     = 0;
      open_n = lam / a;
      open_t = 1;
    }
    Split r;
    r.opening      = std::max(kn, kt);
    const double w = tension_band(h) * r.opening, beta = shear_retention(w);
    const double dbw       = w < 0.5 * p_.aggregate_size ?
                               -(1 - p_.shear_retention_floor) / (0.5 * p_.aggregate_size) :
                               0.0;
    const double psi_shear = 0.5 * mu * g * g;
    r.psi0                 = 0.5 * (snn * enn + stt * ett) + psi_shear;
    r.loss = 0.5 * (snn * enn + stt * ett) - 0.5 * (rn * (enn - kn) + rt * (ett - kt)) +
             (1 - beta) * psi_shear;
    r.sigma0 = from_crack_frame({{snn, stt, mu * g}}, c, s);
    // dL / d(enn, ett, g): the normal block's released stress, and the shear's, with the
    // change of beta with the opening (w = h e_open).
    const double dbeta = -dbw * tension_band(h) * psi_shear;
    r.dloss            = from_crack_frame(
      {{snn - rn + dbeta * open_n, stt - rt + dbeta * open_t, (1 - beta) * mu * g}},
      c,
      s);
    r.szz0     = lam * (enn + ett);
    r.dloss_zz = lam * (kn + kt);
    r.beta     = beta;
    return r;
  }

  VoigtStress ConcreteDamageLaw::stress(const VoigtStrain &e, const double *h0, double *h1) const
  {
    VoigtStress s = plastic_ ? plastic_concrete_stress(e, h0, h1) : concrete_stress(e, h0, h1);
    if (reinforced_)
    {
      // Bars along x and y strained as the concrete (perfect bond), in parallel with it.
      const double  *b0    = h0 + bars_;
      double        *b1    = h1 + bars_;
      const SteelBar steel = steel_at(h0[5]);
      // The y bars of a point on the base stretch over h + L_sp: their strain, and the work
      // density per unit of the row's volume, scale by 1 / (that over h).
      const double     ys = bar_slots_ > 6 ? b0[6] : 1.0;
      const SteelState sx = steel.update(e[0], b0[0], b0[1]);
      const SteelState sy = steel.update(ys * e[1], b0[2], b0[3]);
      b1[0]               = sx.plastic_strain;
      b1[1]               = sx.back_stress;
      b1[2]               = sy.plastic_strain;
      b1[3]               = sy.back_stress;
      b1[4] = b0[4] + r_.ratio_x * sx.plastic_work + r_.ratio_y * sy.plastic_work / ys;
      if (bar_slots_ > 6)
        b1[6] = ys;
      s[0] += r_.ratio_x * sx.stress;
      s[1] += r_.ratio_y * sy.stress;
      // Dowel action of the bars crossing the crack, once there is one (h1[2] > 0): elastic-
      // perfectly plastic in the crack's shear strain, from zero at the cracking step.
      b1[5] = b0[5];
      if (h1[2] > 0 && !p_.rotating_crack)
      {
        const double c = h1[6], sn = h1[7];
        const double g = to_crack_frame(e, c, sn)[2];
        if (!(h0[2] > 0))
          b1[5] = g; // the dowel starts unloaded at the state the crack formed in
        const Dowel dw  = dowel(c, sn);
        double      tau = dw.stiffness * (g - b1[5]);
        if (dw.stiffness > 0 && std::abs(tau) > dw.strength)
        {
          const double slip = (std::abs(tau) - dw.strength) / dw.stiffness;
          b1[5] += std::copysign(slip, tau);
          b1[4] += dw.strength * slip;
          tau = std::copysign(dw.strength, tau);
        }
        const VoigtStress d = from_crack_frame({{0, 0, tau}}, c, sn);
        for (unsigned int i = 0; i < 3; ++i)
          s[i] += d[i];
      }
    }
    return s;
  }

  ConcreteDamageLaw::Dowel ConcreteDamageLaw::dowel(double c, double s) const
  {
    // Bars along x cross a crack of normal (c, s) with the weight c^2, bars along y with s^2.
    const double rho = r_.ratio_x * c * c + r_.ratio_y * s * s;
    const double fy = r_.yield_stress, G_s = r_.youngs_modulus / (2 * (1 + steel_poisson_ratio));
    constexpr double pi = 3.14159265358979323846;
    // Per bar D_u = k d_b^2 sqrt(f_c f_y) over its area pi d_b^2 / 4 (no bar diameter left), at
    // most the bar's shear yield f_y / sqrt(3).
    const double tau_bar =
      std::min(fy / std::sqrt(3.0), r_.dowel_coefficient * 4 / pi * std::sqrt(p_.f_cm * fy));
    return {rho * G_s, rho * tau_bar};
  }

  double ConcreteDamageLaw::tension_damage(const double kt,
                                           const double cell_band,
                                           const double c,
                                           const double s,
                                           const double a) const
  {
    const double E = p_.youngs_modulus;
    if (a < 1 && r_.base_joint_tension > 0)
    {
      const double kj = r_.base_joint_tension / E;
      return kt > 0 ? kt / (kt + kj) : 0.0;
    }
    if (r_.tension_stiffening)
    {
      // No softening branch to keep from snapping back: the material's own f_t.
      const double ft = p_.f_ctm * p_.dif_tension;
      return kt > ft / E ? 1 - stiffened_tension(kt, c, s, a) / (E * kt) : 0.0;
    }
    const double h  = tension_band(cell_band);
    const double ft = effective_tensile_strength(cell_band), k0 = ft / E;
    if (!(kt > k0))
      return 0;
    const double ef = p_.fracture_energy / (h * ft) - 0.5 * k0;
    return 1 - k0 / kt * std::exp(-(kt - k0) / ef);
  }

  double ConcreteDamageLaw::stiffened_tension(double kt, double c, double s, const double a) const
  {
    // Collins and Mitchell's average tension, capped by the bars' reserve at a crack: a bar at
    // angle theta to the crack normal strains eps_1 cos^2 theta and carries its force across
    // the crack with the weight cos^2 theta. On the clamped base the joint's opening along y
    // spreads over h + L_sp (the bond length both the bars and the concrete beside them take
    // their share over), so the y part of the strain is a kappa_t there; off the base a = 1.
    const double ft = p_.f_ctm * p_.dif_tension, fy = r_.yield_stress, Es = r_.youngs_modulus;
    const double cc = c * c, ss = s * s;
    const double rx = r_.bridging_ratio_x >= 0 ? r_.bridging_ratio_x : r_.ratio_x;
    const double ry = r_.bridging_ratio_y >= 0 ? r_.bridging_ratio_y : r_.ratio_y;
    const double ey = a < 1 ? a * kt : kt, em = a < 1 ? kt * cc + ey * ss : kt;
    const double reserve =
      rx * std::max(0.0, fy - Es * kt * cc) * cc + ry * std::max(0.0, fy - Es * ey * ss) * ss;
    return std::min(ft / (1 + std::sqrt(500 * em)), reserve);
  }

  double ConcreteDamageLaw::plastic_strain(double kc, double band) const
  {
    return p_.plastic_fraction *
           std::max(0.0, kc - p_.compression_curve(kc, band) / p_.youngs_modulus);
  }

  VoigtStress ConcreteDamageLaw::damaged_stress(const VoigtStrain &ee,
                                                const double      *h0,
                                                double            *h1,
                                                double             dt,
                                                double             dc,
                                                double             sa_x,
                                                double             sa_y) const
  {
    // The crack frame is fixed when the point first cracks: n along the largest principal
    // effective stress of that step, (sa_x, sa_y).
    // IMPL-EX: the frame of the converged step before the point cracks (tracked while
    // uncracked), so that the stress stays piecewise linear in the strain within a step.
    // A rotating crack follows the principal direction (IMPL-EX: that of the converged step,
    // so that the frame is fixed within a step).
    const bool rotating = p_.rotating_crack;
    if (rotating || (!(h0[2] > 0) && (implex_on_ ? !(dt > 0) : dt > 0)))
    {
      h1[6] = sa_x;
      h1[7] = sa_y;
    }
    const double c = rotating && implex_on_ ? h0[6] : h1[6];
    const double s = rotating && implex_on_ ? h0[7] : h1[7];
    h1[2]          = dt;
    h1[3]          = dc;
    if (dt == 0 && h0[2] == 0)
    {
      // Uncracked before and after the step: the tension split does not enter (d_t = 0), so the
      // stress is (1 - d_c) times the effective one, and the energy released below is
      // (d_c - d_c,0) psi_0 with psi_0 = sigma_0 : eps / 2. The split's rotation into the crack
      // frame and back gives the same up to round-off and is most of an uncracked point's cost.
      const double      tr = ee[0] + ee[1];
      const VoigtStress s0{
        {lambda_ * tr + 2 * mu_ * ee[0], lambda_ * tr + 2 * mu_ * ee[1], mu_ * ee[2]}};
      const double psi0 = 0.5 * (s0[0] * ee[0] + s0[1] * ee[1] + s0[2] * ee[2]);
      h1[4]             = h0[4] + ((1 - h0[3]) * psi0 - (1 - dc) * psi0);
      const double w    = 1 - dc;
      return {{w * s0[0], w * s0[1], w * s0[2]}};
    }
    const Split  sp = split(ee, c, s, h0[5]);
    const double e0 = (1 - h0[3]) * (sp.psi0 - h0[2] * sp.loss);
    const double e1 = (1 - dc) * (sp.psi0 - dt * sp.loss);
    // Dissipation: the energy the damage growth released at the step's strain (>= 0: L >= 0).
    h1[4]          = h0[4] + (e0 - e1);
    const double w = 1 - dc;
    return {{w * (sp.sigma0[0] - dt * sp.dloss[0]),
             w * (sp.sigma0[1] - dt * sp.dloss[1]),
             w * (sp.sigma0[2] - dt * sp.dloss[2])}};
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
    const double dp = plastic_strain(kc, h0[5]) - plastic_strain(h0[1], h0[5]);
    // n = (-s, c), the eigenvector of tb: n (x) n = {s^2, c^2, -2 c s} (engineering shear).
    const double nxx = sn * sn, nyy = c * c, nxy = -2 * c * sn;
    if (dp > 0)
    {
      h1[p_slot]     = h0[p_slot] - dp * nxx;
      h1[p_slot + 1] = h0[p_slot + 1] - dp * nyy;
      h1[p_slot + 2] = h0[p_slot + 2] - dp * nxy;
    }
    // Elastic strain and its (effective) stress; the tension measure acts on that stress.
    const VoigtStrain ee{{e[0] - h1[p_slot], e[1] - h1[p_slot + 1], e[2] - h1[p_slot + 2]}};
    tr               = ee[0] + ee[1];
    const double sxx = lam * tr + 2 * mu * ee[0], syy = lam * tr + 2 * mu * ee[1], szz = lam * tr,
                 sxy = mu * ee[2];
    double sa, sb, ca, sa_n;
    eigen2(sxx, syy, sxy, sa, sb, ca, sa_n);
    const double kt = std::max(h0[0], std::max(std::max(sa, szz), 0.0) / E);
    h1[0]           = kt;
    h1[1]           = kc;
    // The crack normal the damage is measured across: the fixed one of a cracked point, else
    // the largest principal effective stress's (damaged_stress() fixes it when it cracks).
    const bool cracked = h0[2] > 0 && !p_.rotating_crack;
    double     dt =
      tension_damage(kt, h0[5], cracked ? h0[6] : ca, cracked ? h0[7] : sa_n, anchor_scale(h0));
    // sigma_c(kappa_c) = (1 - d_c) E (kappa_c - eps_p) in uniaxial compression.
    const double el = kc - plastic_strain(kc, h0[5]);
    double       dc = kc > 0 && el > 0 ? 1 - p_.compression_curve(kc, h0[5]) / (E * el) : 0.0;
    dt              = std::clamp(std::max(dt, h0[2]), 0.0, max_damage);
    dc              = std::clamp(std::max(dc, h0[3]), 0.0, max_damage);
    if (implex_on_)
    {
      const std::array<double, 2> d = implex_damage(h0, h1);
      dt                            = d[0];
      dc                            = d[1];
    }
    const VoigtStress s = damaged_stress(ee, h0, h1, dt, dc, ca, sa_n);
    // Plastic work sigma : d eps_p = -dp sigma_nn (sigma_nn < 0 in compression).
    if (dp > 0)
    {
      const double s_nn = s[0] * nxx + s[1] * nyy + s[2] * nxy;
      h1[p_slot + 3]    = h0[p_slot + 3] - dp * s_nn;
    }
    return s;
  }

  VoigtStress
  ConcreteDamageLaw::concrete_stress(const VoigtStrain &e, const double *h0, double *h1) const
  {
    const double E = p_.youngs_modulus, lam = lambda_, mu = mu_;
    const double tr  = e[0] + e[1];
    const double sxx = lam * tr + 2 * mu * e[0], syy = lam * tr + 2 * mu * e[1], szz = lam * tr,
                 sxy = mu * e[2];
    double sa, sb, c, s;
    eigen2(sxx, syy, sxy, sa, sb, c, s);
    const double smax = std::max(sa, szz), smin = std::min(sb, szz);
    std::copy(h0, h0 + n_history(), h1);
    const double kt = std::max(h0[0], std::max(smax, 0.0) / E);
    const double kc = std::max(h0[1], std::max(-smin, 0.0) / E);
    h1[0]           = kt;
    h1[1]           = kc;
    // Neither measure grows: the damage stays (the damage functions are non-decreasing).
    double dt = h0[2], dc = h0[3];
    if (implex_on_)
    {
      const std::array<double, 2> d = implex_damage(h0, h1);
      dt                            = d[0];
      dc                            = d[1];
    }
    else if (kt > h0[0] || kc > h0[1])
    {
      const bool cracked = h0[2] > 0 && !p_.rotating_crack;
      dt                 = std::clamp(
        std::max(
          tension_damage(kt, h0[5], cracked ? h0[6] : c, cracked ? h0[7] : s, anchor_scale(h0)),
          h0[2]),
        0.0,
        max_damage);
      dc =
        std::clamp(std::max(kc > 0 ? 1 - p_.compression_curve(kc, h0[5]) / (E * kc) : 0.0, h0[3]),
                   0.0,
                   max_damage);
    }
    return damaged_stress(e, h0, h1, dt, dc, c, s);
  }

  bool ConcreteDamageLaw::step_grows_damage(const VoigtStrain &e, const double *h) const
  {
    // The concrete's update alone (the bars' yielding is in their exact tangent either way).
    std::array<double, max_history> trial{};
    if (plastic_)
      plastic_concrete_stress(e, h, trial.data());
    else
      concrete_stress(e, h, trial.data());
    return trial[2] > h[2] || trial[3] > h[3] || (plastic_ && trial[1] > h[1]);
  }

  VoigtTangent ConcreteDamageLaw::growing_damage_tangent(const VoigtStrain &e,
                                                         const double      *h) const
  {
    // The central difference of the implicit update's concrete stress from the committed state:
    // it has the damage's growth, the crack frame an uncracked point takes from the step's
    // principal stress (and turns with the strain), beta's change with the opening, the plastic
    // strain. The bars' and dowels' tangent is added exactly (a difference across a bar's yield
    // point would average its two slopes).
    std::array<double, max_history> trial{};
    const double                    d =
      1e-6 *
      std::max({std::abs(e[0]), std::abs(e[1]), std::abs(e[2]), p_.f_ctm / p_.youngs_modulus});
    VoigtTangent t = central_difference_tangent(
      [&](const VoigtStrain &x)
      {
        return plastic_ ? plastic_concrete_stress(x, h, trial.data()) :
                          concrete_stress(x, h, trial.data());
      },
      e,
      d);
    add_reinforcement_tangent(t, e, h);
    return t;
  }

  VoigtTangent ConcreteDamageLaw::tangent(const VoigtStrain &e, const double *h) const
  {
    if (!implex_on_ && step_grows_damage(e, h))
      return growing_damage_tangent(e, h);
    // The tangent of the committed damage at e with beta frozen (its change with the opening is
    // of the order of the shear energy over the opening, left out), and the bars' and dowel's.
    const double      lam = lambda_, mu = mu_, a = lam + 2 * mu, ep = a - lam * lam / a;
    const double      dt = h[2], wc = 1 - h[3], c = h[6] == 0 && h[7] == 0 ? 1.0 : h[6], sn = h[7];
    const VoigtStrain ee =
      plastic_ ? VoigtStrain{{e[0] - h[p_slot], e[1] - h[p_slot + 1], e[2] - h[p_slot + 2]}} : e;
    const Split       sp  = split(ee, c, sn, h[5]);
    const VoigtStrain f   = to_crack_frame(ee, c, sn);
    const double      snn = a * f[0] + lam * f[1], stt = lam * f[0] + a * f[1];
    // The cracked normal block's tangent in the frame, by region.
    double qnn = a, qnt = lam, qtt = a;
    if (snn <= 0 && stt <= 0)
    {
    }
    else if (f[0] >= 0 && f[1] >= 0)
      qnn = qnt = qtt = 0;
    else if (snn > 0 && f[1] <= 0)
    {
      qnn = qnt = 0;
      qtt       = ep;
    }
    else
    {
      qtt = qnt = 0;
      qnn       = ep;
    }
    const double cnn = wc * ((1 - dt) * a + dt * qnn), cnt = wc * ((1 - dt) * lam + dt * qnt),
                 ctt = wc * ((1 - dt) * a + dt * qtt), css = wc * mu * (1 - dt * (1 - sp.beta));
    // T = A^T C' A, A the strain transformation of to_crack_frame().
    VoigtTangent t = detail::tangent_from_frame({{cnn, cnt, 0, cnt, ctt, 0, 0, 0, css}}, c, sn);
    add_reinforcement_tangent(t, e, h);
    return t;
  }

  void ConcreteDamageLaw::add_reinforcement_tangent(VoigtTangent      &t,
                                                    const VoigtStrain &e,
                                                    const double      *h) const
  {
    if (!reinforced_)
      return;
    const double  *b     = h + bars_;
    const SteelBar steel = steel_at(h[5]);
    t[0] += r_.ratio_x * steel.update(e[0], b[0], b[1]).tangent;
    const double ys = bar_slots_ > 6 ? b[6] : 1.0;
    t[4] += r_.ratio_y * ys * steel.update(ys * e[1], b[2], b[3]).tangent;
    // The dowel acts across a committed crack (one that forms in the step starts unloaded at
    // the step's strain, so it adds no stiffness to it).
    if (h[2] > 0 && !p_.rotating_crack)
    {
      // The dowel's shear stiffness on g = a2 . e, a2 the shear row of to_crack_frame().
      const double c = h[6], sn = h[7];
      const Dowel  dw = dowel(c, sn);
      const double g  = to_crack_frame(e, c, sn)[2];
      const double cs = c * sn, a2[3] = {-2 * cs, 2 * cs, c * c - sn * sn};
      if (std::abs(dw.stiffness * (g - b[5])) <= dw.strength)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            t[3 * i + j] += a2[i] * dw.stiffness * a2[j];
    }
  }

  PointOutput ConcreteDamageLaw::output(const VoigtStrain &e, const double *h) const
  {
    const double dt = h[2], wc = 1 - h[3];
    // Elastic strain: the total one less the concrete's compressive plastic strain (if any).
    const VoigtStrain ee =
      plastic_ ? VoigtStrain{{e[0] - h[p_slot], e[1] - h[p_slot + 1], e[2] - h[p_slot + 2]}} : e;
    const Split sp = split(ee, h[6], h[7], h[5]);
    PointOutput o;
    o.sigma_zz           = wc * (sp.szz0 - dt * sp.dloss_zz);
    o.stored_energy      = wc * (sp.psi0 - dt * sp.loss);
    o.damage             = 1 - (1 - dt) * wc;
    o.damage_dissipation = h[4];
    o.tension_damage     = dt;
    {
      const double c = h[6] == 0 && h[7] == 0 ? 1.0 : h[6], sn = h[7];
      o.crack_normal_yy = sn * sn / (c * c + sn * sn);
    }
    if (plastic_)
    {
      o.plastic_dissipation       = h[p_slot + 3];
      o.equivalent_plastic_strain = plastic_strain(h[1], h[5]);
    }
    if (reinforced_)
    {
      // The bars' elastic energy is stored; their plastic work (hardening included) dissipated.
      const double *b  = h + bars_;
      const double  ys = bar_slots_ > 6 ? b[6] : 1.0;
      const double  ex = e[0] - b[0], ey = ys * e[1] - b[2], Es = r_.youngs_modulus;
      o.stored_energy += 0.5 * Es * (r_.ratio_x * ex * ex + r_.ratio_y * ey * ey / ys);
      o.reinforcement_stress_xx = r_.ratio_x * Es * ex;
      o.reinforcement_stress_yy = r_.ratio_y * Es * ey;
      if (dt > 0 && !p_.rotating_crack)
      {
        const double g = to_crack_frame(e, h[6], h[7])[2] - b[5];
        o.stored_energy += 0.5 * dowel(h[6], h[7]).stiffness * g * g;
      }
      o.plastic_dissipation += b[4];
      o.equivalent_plastic_strain =
        std::max({o.equivalent_plastic_strain, std::abs(b[0]), std::abs(b[2])});
    }
    return o;
  }
} // namespace kimp::fem
