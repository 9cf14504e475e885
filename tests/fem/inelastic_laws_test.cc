// Inelastic laws at one quadrature point: Mohr-Coulomb / Drucker-Prager return mappings against
// closed forms and finite differences, the crack-band fracture energy and the compression curve,
// the steel bar of the smeared reinforcement.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/inelastic_laws.h"

namespace
{
  using namespace kimp::fem;
  constexpr double pi = 3.14159265358979323846;

  SoilParameters soil(double c, double phi_deg, double psi_deg, double cutoff, double nu = 0.3)
  {
    SoilParameters p;
    p.youngs_modulus = 50e6;
    p.poisson_ratio  = nu;
    p.cohesion       = c;
    p.friction_angle = phi_deg * pi / 180;
    p.dilatancy      = psi_deg * pi / 180;
    p.tension_cutoff = cutoff;
    return p;
  }

  /** Principal stresses {a, b, zz} of a plane-strain state. */
  std::array<double, 3> principal(const VoigtStress &s, double szz)
  {
    const double m = 0.5 * (s[0] + s[1]), r = std::hypot(0.5 * (s[0] - s[1]), s[2]);
    return {{m + r, m - r, szz}};
  }

  /** MC2010 concrete of f_cm = 38 MPa with nu = 0 (uniaxial strain is uniaxial stress). */
  ConcreteParameters uniaxial_concrete()
  {
    ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    c.poisson_ratio      = 0;
    return c;
  }

  /** The moat wall's vertical bars (0.8 %) with their crack spacing of 0.2 m. */
  ReinforcementParameters spaced_wall_bars()
  {
    ReinforcementParameters r;
    r.ratio_y       = 0.008;
    r.crack_spacing = 0.2;
    return r;
  }

  /** The stress path (all three components, step after step) of a virgin point of @p law in a
   *  cell of crack band @p h strained by strain(i), i = 1..n. */
  template <class Strain>
  std::vector<double> stress_path(const ConcreteDamageLaw &law, double h, int n, Strain strain)
  {
    std::vector<double> h0(law.n_history()), h1(law.n_history()), path;
    law.initialize_point(h0.data(), h);
    for (int i = 1; i <= n; ++i)
    {
      const VoigtStress s = law.stress(strain(i), h0.data(), h1.data());
      path.insert(path.end(), s.begin(), s.end());
      h0 = h1;
    }
    return path;
  }

  /** A fixed linear congruential sequence in [-1, 1): the random strain walks repeat run to run. */
  class UniformSequence
  {
  public:
    explicit UniformSequence(unsigned int seed)
      : seed_(seed)
    {
    }
    double operator()()
    {
      seed_ = 1103515245u * seed_ + 12345u;
      return static_cast<double>((seed_ >> 8) & 0xffffff) / 8388608.0 - 1.0;
    }

  private:
    unsigned int seed_;
  };

  /** The at-rest state (K0 = 1 - sin(phi), as the geostatic step) at which the random strain
   *  walk of `point` starts: one of five depths, sigma_v = -20 kPa to -100 kPa. */
  InitialStress at_rest(const SoilParameters &p, int point)
  {
    const double sv = -20e3 * (1 + point % 5), k0 = 1 - std::sin(p.friction_angle);
    return {{k0 * sv, sv, k0 * sv, 0}};
  }

  /** Drives @p law along strain = k * step (k = 1..n), committing each step. */
  struct Driver
  {
    const MaterialLaw  &law;
    std::vector<double> h0, h1;
    VoigtStress         sigma{};
    explicit Driver(const MaterialLaw &l)
      : law(l)
      , h0(l.n_history())
      , h1(l.n_history())
    {
      law.initial_history(h0.data());
    }
    void go(const VoigtStrain &e)
    {
      sigma = law.stress(e, h0.data(), h1.data());
      h0    = h1;
    }
    double szz(const VoigtStrain &e) const { return law.output(e, h0.data()).sigma_zz; }
  };

  /** Relative difference of the law's tangent and a central difference of its stress. */
  double tangent_error(const MaterialLaw &law, const VoigtStrain &e, const double *h)
  {
    const VoigtTangent  t = law.tangent(e, h);
    std::vector<double> scratch(law.n_history());
    double              err = 0, norm = 0;
    for (unsigned int j = 0; j < 3; ++j)
    {
      const double d = 1e-7 * std::max({std::abs(e[0]), std::abs(e[1]), std::abs(e[2])});
      // The stress at e with its component j moved by `step`.
      const auto stress_at = [&](double step)
      {
        VoigtStrain moved = e;
        moved[j] += step;
        return law.stress(moved, h, scratch.data());
      };
      const VoigtStress sp = stress_at(d), sm = stress_at(-d);
      for (unsigned int i = 0; i < 3; ++i)
      {
        const double fd = (sp[i] - sm[i]) / (2 * d);
        err             = std::max(err, std::abs(fd - t[3 * i + j]));
        norm            = std::max(norm, std::abs(t[3 * i + j]));
      }
    }
    std::printf("tangent vs central difference: relative error %.2e\n", err / norm);
    return err / norm;
  }

  TEST(MohrCoulomb, ShearPathFollowsTrescaClosedForm)
  {
    // phi = 0 (Tresca) in simple shear: tau = min(G gamma, c), main-plane returns.
    const SoilParameters p = soil(20e3, 0, 0, 1e9);
    const MohrCoulombLaw law(p);
    Driver               d(law);
    const double         G = p.youngs_modulus / (2 * (1 + p.poisson_ratio));
    for (int k = 1; k <= 40; ++k)
    {
      const double gamma = k * 5e-5;
      d.go({{0, 0, gamma}});
      EXPECT_NEAR(d.sigma[2], std::min(G * gamma, p.cohesion), 1e-10 * p.cohesion) << k;
      EXPECT_NEAR(d.sigma[0], 0, 1e-10 * p.cohesion);
      if (G * gamma > p.cohesion)
      {
        EXPECT_EQ(d.h0[6], static_cast<double>(ReturnType::main));
      }
    }
  }

  TEST(MohrCoulomb, OedometricCompressionEndsOnTheEdge)
  {
    // Uniaxial strain in compression: sigma_yy = sigma_zz, so the return is to an edge; the
    // stress stays on the surface (1 + s) s_lat - (1 - s) s_xx = 2 c cos(phi). nu = 0.1: the
    // elastic K0 = nu / (1 - nu) is below K_a, so the path yields.
    const SoilParameters p = soil(10e3, 30, 10, 1e9, 0.1);
    const MohrCoulombLaw law(p);
    Driver               d(law);
    const double         s    = std::sin(p.friction_angle);
    bool                 edge = false;
    for (int k = 1; k <= 50; ++k)
    {
      const VoigtStrain e{{-k * 1e-4, 0, 0}};
      d.go(e);
      const auto   ps = principal(d.sigma, d.szz(e));
      const double f  = law.yield_function(ps);
      EXPECT_LE(f, 1e-10 * p.cohesion);
      if (d.h0[6] != 0)
      {
        EXPECT_NEAR(f, 0, 1e-10 * std::abs(d.sigma[0]));
        EXPECT_NEAR(d.sigma[1], d.szz(e), 1e-10 * std::abs(d.sigma[0])); // on the edge
        EXPECT_NEAR((1 + s) * d.sigma[1] - (1 - s) * d.sigma[0],
                    2 * p.cohesion * std::cos(p.friction_angle),
                    1e-10 * std::abs(d.sigma[0]));
        edge = edge || d.h0[6] == static_cast<double>(ReturnType::edge);
      }
    }
    EXPECT_TRUE(edge);
  }

  TEST(MohrCoulomb, BiaxialCompressionEndsOnTheOtherEdge)
  {
    // eps_xx = eps_yy < 0: sigma_xx = sigma_yy < sigma_zz, the two smallest principal stresses
    // stay equal: the edge opposite to the oedometric one (nu = 0.1 so that it yields).
    const SoilParameters p = soil(10e3, 30, 0, 1e9, 0.1);
    const MohrCoulombLaw law(p);
    Driver               d(law);
    const double         s = std::sin(p.friction_angle);
    for (int k = 1; k <= 30; ++k)
    {
      const VoigtStrain e{{-k * 1e-4, -k * 1e-4, 0}};
      d.go(e);
      const double szz = d.szz(e);
      if (d.h0[6] != 0)
      {
        EXPECT_EQ(d.h0[6], static_cast<double>(ReturnType::edge));
        EXPECT_NEAR(d.sigma[0], d.sigma[1], 1e-10 * std::abs(d.sigma[0]));
        EXPECT_NEAR((1 + s) * szz - (1 - s) * d.sigma[0],
                    2 * p.cohesion * std::cos(p.friction_angle),
                    1e-10 * std::abs(d.sigma[0]));
      }
    }
    EXPECT_NE(d.h0[6], 0.0);
  }

  TEST(MohrCoulomb, ApexAndTensionCutOff)
  {
    // A large biaxial extension returns to the apex sigma = c cot(phi) (no smaller cut-off).
    const SoilParameters p = soil(10e3, 30, 30, 1e9);
    const MohrCoulombLaw law(p);
    Driver               d(law);
    const VoigtStrain    e{{0.05, 0.05, 0}};
    d.go(e);
    const double apex = p.cohesion / std::tan(p.friction_angle);
    EXPECT_EQ(d.h0[6], static_cast<double>(ReturnType::apex));
    EXPECT_NEAR(d.sigma[0], apex, 1e-10 * apex);
    EXPECT_NEAR(d.sigma[1], apex, 1e-10 * apex);
    EXPECT_NEAR(d.szz(e), apex, 1e-10 * apex);

    // With a 2 kPa cut-off, uniaxial extension in x stops at sigma_xx = 2 kPa.
    const SoilParameters pt = soil(10e3, 30, 0, 2e3);
    const MohrCoulombLaw lt(pt);
    Driver               dt(lt);
    for (int k = 1; k <= 10; ++k)
      dt.go({{k * 2e-5, 0, 0}});
    EXPECT_NEAR(dt.sigma[0], 2e3, 1e-10 * 2e3);
    EXPECT_NE(dt.h0[6], 0.0);
    EXPECT_GT(dt.h0[4], 0.0); // equivalent plastic strain
  }

  TEST(MohrCoulomb, ActiveSetShortcutsGiveTheExhaustiveSearchsStress)
  {
    // The return mapping tries the most violated plane alone and the point's last active set
    // before the search over every set of <= 3 planes; it must end where the exhaustive search
    // ends. Random strain walks from an at-rest state (K0 = 1 - sin(phi), as the geostatic
    // step) through main-plane, edge, apex and cut-off returns, for a cohesionless sand (the
    // medium-dense preset), a c-phi soil with a cut-off and a phi = 0 clay.
    const SoilParameters cases[] = {soil(0, 34, 4, 0),
                                    soil(10e3, 30, 10, 2e3),
                                    soil(20e3, 0, 0, 1e9)};
    UniformSequence      uniform(12345);
    for (const SoilParameters &p : cases)
    {
      const MohrCoulombLaw fast(p), exhaustive(p, true);
      unsigned int         n_type[8] = {};
      double               worst     = 0;
      for (int point = 0; point < 40; ++point)
      {
        Driver              a(fast), b(exhaustive);
        const InitialStress s0 = at_rest(p, point);
        fast.set_initial_stress(a.h0.data(), s0);
        exhaustive.set_initial_stress(b.h0.data(), s0);
        VoigtStrain e{{0, 0, 0}};
        for (int step = 0; step < 400; ++step)
        {
          for (double &x : e)
            x += 1.5e-4 * uniform();
          a.go(e);
          b.go(e);
          const double scale = std::max(
            {std::abs(b.sigma[0]), std::abs(b.sigma[1]), std::abs(b.sigma[2]), p.cohesion, 1e3});
          for (unsigned int i = 0; i < 3; ++i)
            worst = std::max(worst, std::abs(a.sigma[i] - b.sigma[i]) / scale);
          for (unsigned int i = 0; i < 6; ++i)
            worst =
              std::max(worst, std::abs(a.h0[i] - b.h0[i]) / std::max(std::abs(b.h0[i]), 1e-3));
          ++n_type[static_cast<unsigned int>(a.h0[6]) % 8];
        }
      }
      std::printf("c = %g kPa, phi = %g deg: largest difference %.3g; returns: elastic %u, main "
                  "%u, edge %u, apex %u, tension %u, mixed %u\n",
                  p.cohesion / 1e3,
                  p.friction_angle * 180 / pi,
                  worst,
                  n_type[static_cast<unsigned int>(ReturnType::elastic)],
                  n_type[static_cast<unsigned int>(ReturnType::main)],
                  n_type[static_cast<unsigned int>(ReturnType::edge)],
                  n_type[static_cast<unsigned int>(ReturnType::apex)],
                  n_type[static_cast<unsigned int>(ReturnType::tension)],
                  n_type[static_cast<unsigned int>(ReturnType::mixed)]);
      EXPECT_LT(worst, 1e-9);
      EXPECT_GT(n_type[static_cast<unsigned int>(ReturnType::main)], 100u);
      EXPECT_GT(n_type[static_cast<unsigned int>(ReturnType::edge)] +
                  n_type[static_cast<unsigned int>(ReturnType::apex)] +
                  n_type[static_cast<unsigned int>(ReturnType::tension)] +
                  n_type[static_cast<unsigned int>(ReturnType::mixed)],
                100u);
    }
  }

  TEST(MohrCoulomb, ConsistentTangentEqualsFiniteDifference)
  {
    // Main plane (general state), the oedometric edge and an elastic state.
    const SoilParameters p = soil(10e3, 30, 10, 1e9);
    const MohrCoulombLaw law(p);
    std::vector<double>  h(law.n_history());
    law.initial_history(h.data());
    const VoigtStrain cases[] = {{{-3e-4, 1e-4, 4e-4}}, {{-5e-3, 0, 0}}, {{-1e-5, 2e-6, 1e-6}}};
    for (const auto &e : cases)
    {
      EXPECT_LT(tangent_error(law, e, h.data()), 1e-6) << e[0];
      std::vector<double> trial(law.n_history());
      law.stress(e, h.data(), trial.data());
    }
    // From a committed plastic state.
    std::vector<double> h1(law.n_history());
    law.stress({{-3e-4, 1e-4, 4e-4}}, h.data(), h1.data());
    EXPECT_LT(tangent_error(law, {{-3.5e-4, 1.2e-4, 4.5e-4}}, h1.data()), 1e-6);
  }

  TEST(MohrCoulomb, ConsistentTangentOfEveryReturnTypeEqualsFiniteDifference)
  {
    // The tangent of the return mapping (what a Newton solver assembles) against a central
    // difference of its stress, at every committed state of random strain walks from an
    // at-rest state: elastic points, the main plane, both edges (sigma_1 = sigma_2, the
    // extension edge, and sigma_2 = sigma_3, the compression edge), the apex, the cut-off and
    // the mixed corners. A point whose +-d neighbours end on another active set is skipped
    // (the return mapping has a kink there; the tangent is one-sided).
    const SoilParameters cases[] = {soil(0, 34, 4, 0),
                                    soil(1e3, 30, 0, 1e3),
                                    soil(10e3, 30, 10, 2e3),
                                    soil(20e3, 0, 0, 1e9)};
    UniformSequence      uniform(424242);
    // Per kind: 0 elastic, 1 main, 2 extension edge, 3 compression edge, 4 apex, 5 cut-off,
    // 6 mixed.
    const char *names[7] =
      {"elastic", "main", "extension edge", "compression edge", "apex", "cut-off", "mixed"};
    unsigned int counted[7] = {}, skipped = 0;
    double       worst[7] = {};
    for (const SoilParameters &p : cases)
    {
      const MohrCoulombLaw law(p);
      for (int point = 0; point < 40; ++point)
      {
        Driver              a(law);
        const InitialStress s0 = at_rest(p, point);
        law.set_initial_stress(a.h0.data(), s0);
        VoigtStrain e{{0, 0, 0}};
        for (int step = 0; step < 300; ++step)
        {
          for (double &x : e)
            x += 1.5e-4 * uniform();
          // The state at e from the committed history a.h0, then commit it.
          std::vector<double> h1(law.n_history()), hp(law.n_history()), hm(law.n_history());
          const VoigtStress   s     = law.stress(e, a.h0.data(), h1.data());
          const VoigtTangent  t     = law.tangent(e, a.h0.data());
          const double        scale = std::max(
            {std::abs(e[0] - a.h0[0]), std::abs(e[1] - a.h0[1]), std::abs(e[2] - a.h0[3]), 1e-9});
          const double d   = 1e-5 * scale;
          double       err = 0, norm = 0;
          bool         kink = false;
          for (unsigned int j = 0; j < 3; ++j)
          {
            VoigtStrain ep = e, em = e;
            ep[j] += d;
            em[j] -= d;
            const VoigtStress sp_ = law.stress(ep, a.h0.data(), hp.data());
            const VoigtStress sm_ = law.stress(em, a.h0.data(), hm.data());
            kink                  = kink || hp[7] != h1[7] || hm[7] != h1[7];
            for (unsigned int i = 0; i < 3; ++i)
            {
              const double fd = (sp_[i] - sm_[i]) / (2 * d);
              err             = std::max(err, std::abs(fd - t[3 * i + j]));
            }
          }
          for (unsigned int k = 0; k < 9; ++k)
            norm = std::max(norm, std::abs(t[k]));
          norm = std::max(norm, 1e-3 * p.youngs_modulus); // an apex tangent is zero
          a.h0 = h1;
          if (kink)
          {
            ++skipped;
            continue;
          }
          const auto type = static_cast<ReturnType>(static_cast<int>(h1[6]));
          int        kind = 0;
          if (type == ReturnType::main)
            kind = 1;
          else if (type == ReturnType::edge)
          {
            // Which pair of principal stresses is equal: the largest two (extension edge) or
            // the smallest two (compression edge).
            auto ps = principal(s, law.output(e, h1.data()).sigma_zz);
            std::sort(ps.begin(), ps.end());
            kind = std::abs(ps[2] - ps[1]) < std::abs(ps[1] - ps[0]) ? 2 : 3;
          }
          else if (type == ReturnType::apex)
            kind = 4;
          else if (type == ReturnType::tension)
            kind = 5;
          else if (type == ReturnType::mixed)
            kind = 6;
          ++counted[kind];
          worst[kind] = std::max(worst[kind], err / norm);
        }
      }
    }
    for (unsigned int k = 0; k < 7; ++k)
      std::printf("%-16s %5u points, largest relative error of the tangent %.2e\n",
                  names[k],
                  counted[k],
                  worst[k]);
    std::printf("skipped (a kink within +-d): %u\n", skipped);
    for (unsigned int k = 0; k < 7; ++k)
    {
      EXPECT_GT(counted[k], 20u) << names[k];
      EXPECT_LT(worst[k], 1e-6) << names[k];
    }
  }

  TEST(DruckerPrager, ConsistentTangentAndSurface)
  {
    const SoilParameters   p = soil(10e3, 30, 10, 0);
    const DruckerPragerLaw law(p);
    std::vector<double>    h(law.n_history()), h1(law.n_history());
    law.initial_history(h.data());
    const VoigtStrain e{{-3e-3, 1e-3, 4e-3}};
    EXPECT_LT(tangent_error(law, e, h.data()), 1e-6);
    const VoigtStress s = law.stress(e, h.data(), h1.data());
    EXPECT_EQ(h1[6], static_cast<double>(ReturnType::dp_cone));
    const double szz = law.output(e, h1.data()).sigma_zz;
    EXPECT_NEAR(law.yield_function({{s[0], s[1], szz, s[2]}}), 0, 1e-10 * p.cohesion);
  }

  TEST(DruckerPrager, PlaneStrainStrengthMatchesMohrCoulomb)
  {
    // Steady plane-strain flow (stress no longer changing) of both laws must satisfy
    // t + m sin(phi) = c cos(phi). Path: a biaxial precompression, then principal strain
    // rates -(1 - sin psi) / 2, (1 + sin psi) / 2 (the flow kinematics of the dilatancy psi).
    // Tolerance 1e-6 of c cos(phi) after 2000 steps.
    for (const double psi : {0.0, 15.0, 30.0})
    {
      const SoilParameters   p = soil(20e3, 30, psi, 1e9);
      const MohrCoulombLaw   mc(p);
      const DruckerPragerLaw dp(p);
      const double           sd = std::sin(p.dilatancy);
      for (const MaterialLaw *law :
           {static_cast<const MaterialLaw *>(&mc), static_cast<const MaterialLaw *>(&dp)})
      {
        Driver d(*law);
        for (int k = 0; k <= 2000; ++k)
          d.go({{-1e-3 - k * 5e-5 * (1 - sd), -1e-3 + k * 5e-5 * (1 + sd), 0}});
        const double m  = 0.5 * (d.sigma[0] + d.sigma[1]);
        const double t  = std::hypot(0.5 * (d.sigma[0] - d.sigma[1]), d.sigma[2]);
        const double cc = p.cohesion * std::cos(p.friction_angle);
        EXPECT_NEAR(t + m * std::sin(p.friction_angle), cc, 1e-6 * cc)
          << "psi " << psi << (law == &mc ? " MC" : " DP");
      }
    }
  }

  TEST(Concrete, ModelCodeParametersFromFcm)
  {
    // f_cm = 38 MPa: f_ck = 30, E_ci = 21.5 (3.8)^(1/3) = 33.55 GPa, f_ctm = 0.3 30^(2/3) =
    // 2.896 MPa, G_F = 73 38^0.18 = 140.5 N/m, eps_c1 = 0.7 38^0.31 = 2.16e-3, eps_cu1 = 3.5e-3.
    const ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    EXPECT_NEAR(c.youngs_modulus, 33.55e9, 0.01e9);
    EXPECT_NEAR(c.f_ctm, 2.896e6, 0.001e6);
    EXPECT_NEAR(c.fracture_energy, 140.5, 0.1);
    EXPECT_NEAR(c.eps_c1, 2.16e-3, 0.01e-3);
    EXPECT_DOUBLE_EQ(c.eps_c_lim, 3.5e-3);
    ConcreteParameters r = c;
    r.apply_strain_rate(1.0); // (1 / 30e-6)^0.014 = 1.157, (1 / 1e-6)^0.018 = 1.282
    EXPECT_NEAR(r.dif_compression, 1.157, 0.001);
    EXPECT_NEAR(r.dif_tension, 1.282, 0.001);
  }

  TEST(Concrete, CrackBandDissipatesFractureEnergyForThreeElementSizes)
  {
    // A bar of elements of length h pulled apart: one element localises, the others unload
    // elastically, so the work per unit area is h * integral(sigma d eps) of the softening
    // element. nu = 0: uniaxial strain is uniaxial stress. Tolerance 5 % (found: < 0.5 %).
    ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    c.poisson_ratio      = 0;
    const ConcreteDamageLaw law(c);
    for (const double h : {0.025, 0.1, 0.4})
    {
      std::vector<double> h0(law.n_history()), h1(law.n_history());
      law.initialize_point(h0.data(), h);
      const double ft = law.effective_tensile_strength(h), e0 = ft / c.youngs_modulus;
      double       work = 0, s_prev = 0, e_prev = 0, peak = 0;
      const double de = e0 / 2000;
      for (double e = de; e < 2000 * e0; e += de * (e > 2 * e0 ? 10 : 1))
      {
        const double s = law.stress({{e, 0, 0}}, h0.data(), h1.data())[0];
        work += 0.5 * (s + s_prev) * (e - e_prev);
        peak   = std::max(peak, s);
        s_prev = s;
        e_prev = e;
        h0     = h1;
        if (h0[2] >= 1 - 1.0001e-6) // fully softened: the law keeps 1e-6 of E
          break;
      }
      std::printf("crack band h = %.3f m: f_t = %.4g MPa, G_F = %.2f N/m, h * int(sigma deps) = "
                  "%.2f N/m, h * damage dissipation = %.2f N/m\n",
                  h,
                  ft / 1e6,
                  c.fracture_energy,
                  h * work,
                  h * h0[4]);
      EXPECT_NEAR(peak, ft, 1e-3 * ft);
      EXPECT_NEAR(h * work, c.fracture_energy, 0.05 * c.fracture_energy) << "h = " << h;
      EXPECT_NEAR(h * h0[4], c.fracture_energy, 0.05 * c.fracture_energy) << "h = " << h;
    }
  }

  // The bars' crack spacing (ReinforcementParameters::crack_spacing): a reinforced point
  // softens in tension over s_rm, whatever its cell's crack band h. Pulled along x with a
  // growing shear (the bars along y), the stress path is the same to the last bit on three
  // cells, and s_rm times the work per unit volume is G_F (as the crack band's h times it is
  // without the key: CrackBandDissipatesFractureEnergyForThreeElementSizes).
  TEST(Concrete, CrackSpacingMakesTheTensionSofteningTheSameOnEveryCell)
  {
    const ConcreteParameters      c    = uniaxial_concrete();
    const ReinforcementParameters r    = spaced_wall_bars();
    ReinforcementParameters       bare = r;
    bare.crack_spacing                 = 0;
    const ConcreteDamageLaw law(c, r), unspaced(c, bare);
    const double            ft = law.effective_tensile_strength(0.0125), e0 = ft / c.youngs_modulus;
    EXPECT_DOUBLE_EQ(ft, unspaced.effective_tensile_strength(r.crack_spacing));
    const double                     de = e0 / 500;
    std::vector<std::vector<double>> paths;
    for (const double h : {0.0125, 0.025, 0.05})
    {
      // Uniaxial: s_rm times the work per unit volume to 60 e_0, the crack open through.
      std::vector<double> h0(law.n_history()), h1(law.n_history());
      law.initialize_point(h0.data(), h);
      double work = 0, s_prev = 0;
      for (double e = de; e < 60 * e0; e += de)
      {
        const double s = law.stress({{e, 0, 0}}, h0.data(), h1.data())[0];
        work += 0.5 * (s + s_prev) * de;
        s_prev = s;
        h0     = h1;
      }
      EXPECT_NEAR(r.crack_spacing * work, c.fracture_energy, 0.05 * c.fracture_energy)
        << "h = " << h;
      // With a growing shear: the whole stress path, bit for bit.
      paths.push_back(stress_path(law,
                                  h,
                                  30000,
                                  [&](int i) {
                                    return VoigtStrain{{i * de, 0, 0.3 * i * de}};
                                  }));
    }
    EXPECT_EQ(paths[0], paths[1]);
    EXPECT_EQ(paths[0], paths[2]);
    // Without the key the finest cell still carries tension at 20 e_0, where s_rm has softened:
    // its softening strain G_F / (h f_t) is 16 times s_rm's.
    std::vector<double> h0(unspaced.n_history()), h1(unspaced.n_history());
    unspaced.initialize_point(h0.data(), 0.0125);
    EXPECT_GT(unspaced.stress({{20 * e0, 0, 0}}, h0.data(), h1.data())[0], 0.3 * ft);
    law.initialize_point(h0.data(), 0.0125);
    EXPECT_LT(law.stress({{20 * e0, 0, 0}}, h0.data(), h1.data())[0], 0.01 * ft);
  }

  // Tension stiffening (ReinforcementParameters::tension_stiffening): a tie with bars along y
  // (rho_y = 0.8 %, nu = 0) pulled along y. The concrete's part of sigma_yy, the total less the
  // bars' rho E_s eps, follows min(f_t / (1 + sqrt(500 eps)), rho (f_y - E_s eps)) written out
  // here (Collins and Mitchell's average tension and the crack check), so the tie's force at
  // the bars' yield strain is rho f_y exactly; the path is the same on three cells; unloading
  // is secant (the damage) and the law is refused without a crack spacing.
  TEST(Concrete, TensionStiffeningFollowsTheAverageTensionAndTheBarsReserve)
  {
    const ConcreteParameters c = uniaxial_concrete();
    ReinforcementParameters  r = spaced_wall_bars();
    r.tension_stiffening       = true;
    const ConcreteDamageLaw law(c, r);
    const double            ft = c.f_ctm, E = c.youngs_modulus, Es = r.youngs_modulus;
    const double            ey = r.yield_stress / Es, e0 = ft / E;
    // Along y: the path's sigma_yy less the bars' f_y + b E_s (eps - eps_y) past yield.
    const auto   along_y = [&](int i) { return VoigtStrain{{0, 1.5 * ey * i / 400, 0}}; };
    const auto   path    = stress_path(law, 0.0125, 400, along_y);
    const double b       = r.hardening;
    for (int i = 1; i <= 400; ++i)
    {
      const double e        = along_y(i)[1];
      const double bar      = e <= ey ? Es * e : r.yield_stress + b * Es * (e - ey);
      const double concrete = path[3 * (i - 1) + 1] - r.ratio_y * bar;
      const double expected = e <= e0 ?
                                E * e :
                                std::min(ft / (1 + std::sqrt(500 * e)),
                                         r.ratio_y * std::max(0.0, r.yield_stress - Es * e));
      // A fully damaged point keeps 10^-6 of E (the damage's cap).
      EXPECT_NEAR(concrete, expected, 1e-9 * ft + 1e-6 * E * e) << "eps = " << e;
    }
    EXPECT_EQ(path, stress_path(law, 0.025, 400, along_y));
    EXPECT_EQ(path, stress_path(law, 0.05, 400, along_y));
    // At the bars' yield strain the concrete between the cracks has nothing left to carry.
    std::vector<double> h0(law.n_history()), h1(law.n_history());
    law.initialize_point(h0.data(), 0.025);
    for (const double e : {0.5 * ey, ey})
    {
      const double s = law.stress({{0, e, 0}}, h0.data(), h1.data())[1];
      h0             = h1;
      if (e == ey)
        EXPECT_NEAR(s, r.ratio_y * r.yield_stress, 1.01e-6 * E * ey);
      else
      {
        // Unloading from 0.5 eps_y to 0.25 eps_y: the concrete's part halves (secant).
        const double ts =
          law.stress({{0, 0.25 * ey, 0}}, h0.data(), h1.data())[1] - r.ratio_y * Es * 0.25 * ey;
        EXPECT_NEAR(ts, 0.5 * (s - r.ratio_y * Es * 0.5 * ey), 1e-9 * ft);
      }
    }
    // Refused without the crack spacing it is defined over.
    ReinforcementParameters unspaced = r;
    unspaced.crack_spacing           = 0;
    EXPECT_THROW(ConcreteDamageLaw(c, unspaced), std::invalid_argument);
  }

  // Tension stiffening on the clamped base with strain penetration (L_sp = 0.13 m): the joint's
  // opening w spreads over h + L_sp for the bars and the concrete beside them alike, so the base
  // row's concrete follows min(f_t / (1 + sqrt(500 eps_s)), rho (f_y - E_s eps_s)) at the bars'
  // strain eps_s = w / (h + L_sp), not at the row's w / h. Its tension is gone at the opening
  // eps_y (h + L_sp) on every row height (0.39 mm on 2.5 cm rows), where reading w / h took it
  // away at eps_y h (0.06 mm), the finer the row the sooner.
  TEST(Concrete, TensionStiffeningOnTheBaseReadsTheOpeningOverTheBondLength)
  {
    const ConcreteParameters c = uniaxial_concrete();
    ReinforcementParameters  r = spaced_wall_bars();
    r.tension_stiffening       = true;
    r.strain_penetration       = 0.13;
    const ConcreteDamageLaw law(c, r);
    const double            ft = c.f_ctm, E = c.youngs_modulus, Es = r.youngs_modulus;
    const double            ey = r.yield_stress / Es;
    for (const double h : {0.0125, 0.025, 0.05})
    {
      std::vector<double> h0(law.n_history()), h1(law.n_history());
      law.initialize_anchored_point(h0.data(), h, h);
      const double reach = ey * (h + r.strain_penetration); // the opening at the bars' yield
      for (int i = 1; i <= 200; ++i)
      {
        const double w = 1.2 * reach * i / 200, e = w / h, es = w / (h + r.strain_penetration);
        const double syy      = law.stress({{0, e, 0}}, h0.data(), h1.data())[1];
        const double bar      = es <= ey ? Es * es : r.yield_stress + r.hardening * Es * (es - ey);
        const double concrete = syy - r.ratio_y * bar;
        const double expected = e <= ft / E ?
                                  E * e :
                                  std::min(ft / (1 + std::sqrt(500 * es)),
                                           r.ratio_y * std::max(0.0, r.yield_stress - Es * es));
        EXPECT_NEAR(concrete, expected, 1e-9 * ft + 1e-6 * E * e)
          << "h = " << h << ", w = " << w * 1e3 << " mm";
        if (w < 0.9 * reach && e > 2 * ft / E)
        {
          EXPECT_GT(concrete, 0.05 * ft) << "h = " << h << ", w = " << w * 1e3 << " mm";
        }
        h0 = h1;
      }
    }
  }

  // The base joint (ReinforcementParameters::base_joint_tension): on the base row the concrete's
  // tension is E e f_j / (E e + f_j) at the row's strain e (uniaxial, nu = 0), from the first
  // strain, below f_j at every strain, never softening, on every row height; unloading follows the
  // secant of the damage reached; off the base the concrete still reaches f_t before it cracks.
  TEST(Concrete, BaseJointCarriesItsTensionWithoutAStrengthAndWithoutSoftening)
  {
    const ConcreteParameters c = uniaxial_concrete();
    ReinforcementParameters  r = spaced_wall_bars();
    r.tension_stiffening       = true;
    r.strain_penetration       = 0.13;
    r.base_joint_tension       = 0.3e6;
    const ConcreteDamageLaw law(c, r);
    const double            E = c.youngs_modulus, fj = r.base_joint_tension, ej = fj / E;
    const double            Es = r.youngs_modulus;
    for (const double h : {0.0125, 0.025, 0.05})
    {
      std::vector<double> h0(law.n_history()), h1(law.n_history()), off(law.n_history());
      law.initialize_anchored_point(h0.data(), h, h);
      law.initialize_point(off.data(), h);
      const double scale = h / (h + r.strain_penetration); // the bars' strain scale on the base
      for (const double m : {0.1, 0.5, 1.0, 3.0, 10.0, 100.0, 1000.0})
      {
        const double e        = m * ej;
        const double syy      = law.stress({{0, e, 0}}, h0.data(), h1.data())[1];
        const double concrete = syy - r.ratio_y * Es * scale * e; // bars elastic here
        EXPECT_NEAR(concrete, E * e * fj / (E * e + fj), 1e-9 * fj) << "h = " << h << ", " << m;
        EXPECT_LT(concrete, fj);
        h0 = h1;
      }
      // Unloading to half the last strain: the secant of the damage reached.
      const double e = 500 * ej, d = h0[2];
      const double syy = law.stress({{0, e, 0}}, h0.data(), h1.data())[1];
      EXPECT_NEAR(syy - r.ratio_y * Es * scale * e, (1 - d) * E * e, 1e-9 * fj);
      // Off the base: uncracked up to f_t.
      const double et = 0.99 * c.f_ctm / E;
      EXPECT_NEAR(law.stress({{0, et, 0}}, off.data(), h1.data())[1] - r.ratio_y * Es * et,
                  E * et,
                  1e-9 * c.f_ctm);
    }
  }

  // The implicit update's Newton tangent is consistent where the step's strain grows the tension
  // damage (what the geostatic step assembles from the committed state): against a central
  // difference of the stress at the same committed state (a tenth of the law's own step), for
  // softening plain concrete, tension stiffening off the base and on it, and the base joint
  // (base_joint_tension), each from an uncracked and from a cracked committed state, strains off
  // the axes. And it does what it is for: Newton on the point's strain finds the strain of a
  // given stress from the committed state in a few iterations, where the committed damage's
  // tangent (the secant of a saturating joint) creeps.
  TEST(Concrete, TangentOfGrowingTensionDamageIsTheDerivativeOfTheStress)
  {
    const ConcreteParameters c         = uniaxial_concrete();
    const double             e0        = c.f_ctm / c.youngs_modulus;
    ReinforcementParameters  stiffened = spaced_wall_bars(), joint = spaced_wall_bars();
    stiffened.tension_stiffening = joint.tension_stiffening = true;
    stiffened.strain_penetration = joint.strain_penetration = 0.13;
    joint.base_joint_tension                                = 0.3e6;
    const ConcreteDamageLaw plain(c), bars(c, stiffened), base(c, joint);
    struct Case
    {
      const char              *name;
      const ConcreteDamageLaw &law;
      bool                     anchored;
      double                   to; ///< the committed state's strain, in e0
    };
    for (const Case &k : {Case{"softening", plain, false, 1.3},
                          Case{"stiffened", bars, false, 3},
                          Case{"stiffened, base", bars, true, 3},
                          Case{"joint", base, true, 0},
                          Case{"joint", base, true, 2}})
    {
      std::vector<double> h0(k.law.n_history()), h1(k.law.n_history());
      if (k.anchored)
        k.law.initialize_anchored_point(h0.data(), 0.025, 0.025);
      else
        k.law.initialize_point(h0.data(), 0.025);
      if (k.to > 0)
      {
        k.law.stress({{-0.2 * k.to * e0, k.to * e0, 0.3 * k.to * e0}}, h0.data(), h1.data());
        h0 = h1;
      }
      for (const double f : {1.2, 2.0, 4.0})
      {
        const double      m = std::max(k.to, 1.0) * f;
        const VoigtStrain e{{-0.2 * m * e0, m * e0, 0.35 * m * e0}};
        k.law.stress(e, h0.data(), h1.data());
        ASSERT_GT(h1[2], h0[2]) << k.name << ": the step grows the damage";
        std::printf("%-16s from %.1f e0 to %.2f e0: ", k.name, k.to, m);
        EXPECT_LT(tangent_error(k.law, e, h0.data()), 1e-4) << k.name << " at " << m;
        // Not on the softening branch, where the stress falls with the strain and a given
        // stress has two strains.
        if (&k.law != &plain)
        {
          const VoigtStress target = k.law.stress(e, h0.data(), h1.data());
          // From the committed strain (on its loading surface).
          VoigtStrain  x{{-0.2 * k.to * e0, k.to * e0, 0.3 * k.to * e0}};
          unsigned int n = 0;
          for (; n < 30; ++n)
          {
            const VoigtStress s = k.law.stress(x, h0.data(), h1.data());
            const VoigtStress r{{s[0] - target[0], s[1] - target[1], s[2] - target[2]}};
            if (std::hypot(r[0], r[1], r[2]) < 1e-9 * std::abs(target[1]))
              break;
            const VoigtStrain dx = solve_tangent(k.law.tangent(x, h0.data()), r);
            for (unsigned int i = 0; i < 3; ++i)
              x[i] -= dx[i];
          }
          std::printf("  Newton to its stress: %u iterations\n", n);
          EXPECT_LE(n, 8u) << k.name << " at " << m;
        }
      }
    }
  }

  TEST(Concrete, UniaxialCompressionFollowsTheModelCodeCurve)
  {
    // sigma / f_cm = (k eta - eta^2) / (1 + (k - 2) eta), eta = eps / eps_c1,
    // k = E_ci eps_c1 / f_cm (fib MC2010 eq. 5.1-26, EN 1992-1-1 eq. 3.14); unloading on the
    // degraded secant (1 - d) E. nu = 0 so that uniaxial strain is uniaxial stress.
    ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    c.poisson_ratio      = 0;
    const ConcreteDamageLaw law(c);
    std::vector<double>     h0(law.n_history()), h1(law.n_history());
    law.initial_history(h0.data());
    const double k = c.youngs_modulus * c.eps_c1 / c.f_cm;
    for (int i = 1; i <= 35; ++i)
    {
      const double e   = i * 1e-4;
      const double s   = -law.stress({{-e, 0, 0}}, h0.data(), h1.data())[0];
      const double eta = e / c.eps_c1;
      EXPECT_NEAR(s, c.f_cm * (k * eta - eta * eta) / (1 + (k - 2) * eta), 1e-9 * c.f_cm) << e;
      h0 = h1;
    }
    // Unload to half the strain: the secant of the peak-strain state.
    const double d = 1 - (1 - h0[2]) * (1 - h0[3]);
    const double s = -law.stress({{-1.75e-3, 0, 0}}, h0.data(), h1.data())[0];
    EXPECT_NEAR(s, (1 - d) * c.youngs_modulus * 1.75e-3, 1e-9 * c.f_cm);
    EXPECT_GT(d, 0.3);
  }

  // The reinforcement's steel bar (linear kinematic hardening, b = 5 %): loading to 3 eps_y
  // follows sigma = f_y + b E_s (eps - eps_y); unloading is elastic over 2 f_y, so reversed
  // yielding starts at sigma_max - 2 f_y = alpha - f_y (Bauschinger) and not at -f_y; at the
  // end of the cycle the plastic work (the law's increments) equals int sigma d eps (trapezoid
  // over fine steps) minus the stored sigma^2 / (2 E_s), and the closed form
  // f_y sum |d eps_p| + H (eps_p)^2 / 2 |_0^end.
  TEST(Steel, KinematicHardeningYieldsAndShowsTheBauschingerEffect)
  {
    ReinforcementParameters r;
    r.hardening = 0.05;
    const SteelBar bar(r);
    const double   fy = r.yield_stress, Es = r.youngs_modulus, ey = fy / Es;
    const double   Et = r.hardening * Es, H = r.hardening_modulus();
    EXPECT_NEAR(Es * H / (Es + H), Et, 1e-9 * Et);

    double     ep = 0, alpha = 0, work = 0, external = 0, s_prev = 0, e_prev = 0;
    double     path = 0; // sum |d eps_p|
    SteelState st;
    const auto go = [&](double e)
    {
      st = bar.update(e, ep, alpha);
      path += std::abs(st.plastic_strain - ep);
      ep    = st.plastic_strain;
      alpha = st.back_stress;
      work += st.plastic_work;
      external += 0.5 * (st.stress + s_prev) * (e - e_prev);
      s_prev = st.stress;
      e_prev = e;
    };
    const int n = 3000;
    // Elastic, then hardening.
    go(0.5 * ey);
    EXPECT_NEAR(st.stress, 0.5 * fy, 1e-12 * fy);
    EXPECT_DOUBLE_EQ(st.tangent, Es);
    EXPECT_EQ(st.plastic_work, 0);
    for (int i = 1; i <= n; ++i)
      go(0.5 * ey + 2.5 * ey * i / n);
    const double s_max = fy + Et * 2 * ey;
    EXPECT_NEAR(st.stress, s_max, 1e-9 * fy);
    EXPECT_NEAR(st.tangent, Et, 1e-9 * Et);
    EXPECT_NEAR(alpha, H * ep, 1e-9 * fy);
    // Reversed: elastic down to s_max - 2 f_y, then yielding at alpha - f_y.
    const double e_rev = 3 * ey - 2 * fy / Es;
    for (int i = 1; i <= n; ++i)
    {
      const double e = 3 * ey - 2.2 * fy / Es * i / n;
      go(e);
      if (e > e_rev + 1e-9 * ey)
      {
        EXPECT_NEAR(st.stress, s_max - Es * (3 * ey - e), 1e-9 * fy) << e;
      }
    }
    const double e_end = 3 * ey - 2.2 * fy / Es;
    EXPECT_NEAR(st.stress, s_max - 2 * fy - Et * (e_rev - e_end), 1e-9 * fy);
    EXPECT_GT(st.stress, -fy); // Bauschinger: reversed yield well above -f_y
    EXPECT_NEAR(st.stress, alpha - fy, 1e-9 * fy);
    // Energy: the increments, the closed form and the work of the cycle agree.
    const double closed = fy * path + 0.5 * H * ep * ep;
    const double stored = 0.5 * st.stress * st.stress / Es;
    std::printf("steel cycle: sigma_max %.4g MPa, reversed yield %.4g MPa, plastic work %.6g "
                "J/m^3 (closed form %.6g, external - stored %.6g)\n",
                s_max / 1e6,
                (s_max - 2 * fy) / 1e6,
                work,
                closed,
                external - stored);
    EXPECT_NEAR(work, closed, 1e-9 * closed);
    EXPECT_NEAR(external - stored, work, 1e-6 * work);
  }

  // Smeared bars in the concrete law: the stress is the plain concrete's plus ratio_i
  // sigma_s(eps_ii) (x, y) plus, once cracked, the dowel shear tau = k_d (gamma_nt - slip) in the
  // crack frame, the tangent gains ratio_i E_t, the stored energy the bars' and dowels' elastic
  // energy and the plastic dissipation their plastic work; ratio 0 is the plain law with its 8
  // history values.
  TEST(Concrete, SmearedBarsAddTheirStressTangentAndEnergy)
  {
    ConcreteParameters      c = ConcreteParameters::from_f_cm(38e6);
    ReinforcementParameters r;
    r.ratio_x = 0.005;
    r.ratio_y = 0.01;
    const ConcreteDamageLaw plain(c), none(c, ReinforcementParameters{}), rc(c, r);
    EXPECT_EQ(none.n_history(), 8u);
    EXPECT_EQ(rc.n_history(), 14u);
    const unsigned int  bars = 8;
    const SteelBar      bar(r);
    std::vector<double> hp(plain.n_history()), hp1(plain.n_history()), h0(rc.n_history()),
      h1(rc.n_history());
    plain.initialize_point(hp.data(), 0.05);
    rc.initialize_point(h0.data(), 0.05);
    // Past the steel's yield strain in x (cracked concrete), compressed in y, sheared.
    double       ep_x = 0, ep_y = 0, a_x = 0, a_y = 0, w = 0;
    const double ey = r.yield_stress / r.youngs_modulus;
    for (int i = 1; i <= 20; ++i)
    {
      const VoigtStrain e{{2 * ey * i / 20, -1e-3 * i / 20, 2e-4 * i / 20}};
      const VoigtStress sp = plain.stress(e, hp.data(), hp1.data());
      const VoigtStress s  = rc.stress(e, h0.data(), h1.data());
      const SteelState  sx = bar.update(e[0], ep_x, a_x), sy = bar.update(e[1], ep_y, a_y);
      // Dowel shear in the crack frame (c, sn), zero before the point cracks.
      const double cn = h1[6], sn = h1[7];
      const double g = -2 * cn * sn * e[0] + 2 * cn * sn * e[1] + (cn * cn - sn * sn) * e[2];
      const ConcreteDamageLaw::Dowel dw  = rc.dowel(cn, sn);
      const double                   tau = h1[2] > 0 ? dw.stiffness * (g - h1[bars + 5]) : 0.0;
      EXPECT_LE(std::abs(tau), dw.strength * (1 + 1e-12)) << i;
      EXPECT_NEAR(s[0], sp[0] + r.ratio_x * sx.stress - 2 * cn * sn * tau, 1e-9 * r.yield_stress)
        << i;
      EXPECT_NEAR(s[1], sp[1] + r.ratio_y * sy.stress + 2 * cn * sn * tau, 1e-9 * r.yield_stress)
        << i;
      EXPECT_NEAR(s[2], sp[2] + (cn * cn - sn * sn) * tau, 1e-9 * r.yield_stress) << i;
      for (unsigned int k = 0; k < bars; ++k)
        EXPECT_DOUBLE_EQ(h1[k], hp1[k]) << k;
      const VoigtTangent tp = plain.tangent(e, hp.data()), t = rc.tangent(e, h0.data());
      // The dowel's elastic tangent k_d a a^T, a = d gamma_nt / d eps (committed crack only).
      const double c0 = hp[6], s0 = hp[7];
      const double a_d[3] = {-2 * c0 * s0, 2 * c0 * s0, c0 * c0 - s0 * s0};
      const double k_d    = hp[2] > 0 ? rc.dowel(c0, s0).stiffness : 0.0;
      EXPECT_NEAR(t[0] - tp[0],
                  r.ratio_x * sx.tangent + k_d * a_d[0] * a_d[0],
                  1e-6 * r.youngs_modulus);
      EXPECT_NEAR(t[4] - tp[4],
                  r.ratio_y * sy.tangent + k_d * a_d[1] * a_d[1],
                  1e-6 * r.youngs_modulus);
      w += r.ratio_x * sx.plastic_work + r.ratio_y * sy.plastic_work;
      ep_x                 = sx.plastic_strain;
      a_x                  = sx.back_stress;
      ep_y                 = sy.plastic_strain;
      a_y                  = sy.back_stress;
      const PointOutput op = plain.output(e, hp1.data()), o = rc.output(e, h1.data());
      const double      ex = e[0] - ep_x, eyy = e[1] - ep_y;
      const double      dowel_energy = dw.stiffness > 0 ? 0.5 * tau * tau / dw.stiffness : 0.0;
      EXPECT_NEAR(o.stored_energy - op.stored_energy,
                  0.5 * r.youngs_modulus * (r.ratio_x * ex * ex + r.ratio_y * eyy * eyy) +
                    dowel_energy,
                  1e-9 * r.yield_stress * ey);
      if (h1[2] > 0 && h0[2] > 0)
        w += dw.strength * std::abs(h1[bars + 5] - h0[bars + 5]);
      EXPECT_NEAR(o.plastic_dissipation, w, 1e-12 * r.yield_stress);
      EXPECT_DOUBLE_EQ(o.damage_dissipation, op.damage_dissipation);
      hp = hp1;
      h0 = h1;
    }
    EXPECT_GT(ep_x, 0.5 * ey); // the x bars yielded
    EXPECT_EQ(ep_y, 0);        // the y bars did not
    EXPECT_GT(h0[2], 0.9);     // the concrete cracked
  }

  // Strain penetration (ReinforcementParameters::strain_penetration): the y bars of a point on
  // the clamped base stretch over h + L_sp. Pulled along y (the concrete cracked through), a
  // row of height h opens by h eps_yy: its bars yield at the opening eps_y (h + L_sp) on two
  // rows (perfect bond: eps_y h), their force follows the opening, not h, and the work of the
  // row's stress is the bars' stored energy plus their plastic work on a load-unload path. A
  // point off the base, and every point without L_sp, is unchanged.
  TEST(Concrete, StrainPenetrationMakesTheBaseRowsBarsYieldAtAnOpeningIndependentOfTheRow)
  {
    const ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    ReinforcementParameters  r;
    r.ratio_y                  = 0.01;
    ReinforcementParameters rp = r;
    rp.strain_penetration      = 0.13;
    const ConcreteDamageLaw plain(c), bonded(c, r), anchored(c, rp);
    EXPECT_EQ(anchored.n_history(), bonded.n_history() + 1);
    const double ey = r.yield_stress / r.youngs_modulus, l_sp = rp.strain_penetration;
    for (const double h : {0.025, 0.0125})
    {
      std::vector<double> hp(plain.n_history()), hp1(hp), hb(bonded.n_history()), hb1(hb),
        ha(anchored.n_history()), ha1(ha), ho(ha), ho1(ha);
      plain.initialize_point(hp.data(), h);
      bonded.initialize_point(hb.data(), h);
      anchored.initialize_anchored_point(ha.data(), h, h);
      anchored.initialize_point(ho.data(), h);
      // Opening w of the row: out to 3 eps_y (h + L_sp), then closed by eps_y (h + L_sp), an
      // elastic unloading that leaves the bars in tension; the work of the bars' part of
      // sigma_yy over the row, per unit volume, by the trapezoid rule.
      const double w_y = ey * (h + l_sp), w_max = 3 * w_y;
      const int    n    = 600;
      double       work = 0, previous_bar = 0, previous_e = 0, opening_at_yield = -1;
      for (int i = 1; i <= n; ++i)
      {
        const double w = i <= n / 2 ? w_max * 2.0 * i / n : w_max - w_y * 2.0 * (i - n / 2) / n;
        const VoigtStrain e   = {{0, w / h, 0}};
        const VoigtStress sp  = plain.stress(e, hp.data(), hp1.data());
        const VoigtStress sb  = bonded.stress(e, hb.data(), hb1.data());
        const VoigtStress sa  = anchored.stress(e, ha.data(), ha1.data());
        const VoigtStress so  = anchored.stress(e, ho.data(), ho1.data());
        const double      bar = (sa[1] - sp[1]) / r.ratio_y; // the bars' stress, Pa
        EXPECT_DOUBLE_EQ(so[1], sb[1]) << "a point off the base is perfectly bonded, " << i;
        // Below yield the bar's stress is E_s w / (h + L_sp).
        if (w < ey * (h + l_sp) * (1 - 1e-9) && i <= n / 2)
        {
          EXPECT_NEAR(bar, r.youngs_modulus * w / (h + l_sp), 1e-9 * r.yield_stress) << i;
        }
        // The y bars' plastic strain: slot 2 of the bars' block (at p_slot without b_c).
        if (opening_at_yield < 0 && ha1[ConcreteDamageLaw::p_slot + 2] != 0)
          opening_at_yield = w;
        // The consistent tangent of the bars' part: dsigma/deps_yy = rho E_t h / (h + L_sp).
        const VoigtTangent ta = anchored.tangent(e, ha.data()), tp = plain.tangent(e, hp.data());
        const double       scale = h / (h + l_sp);
        const bool         yielding =
          ha1[ConcreteDamageLaw::p_slot + 2] != ha[ConcreteDamageLaw::p_slot + 2];
        const double e_t = yielding ? SteelBar(r).update(0.1, 0, 0).tangent : r.youngs_modulus;
        if (i <= n / 2)
        {
          EXPECT_NEAR(ta[4] - tp[4], r.ratio_y * e_t * scale, 1e-6 * r.youngs_modulus) << i;
        }
        work += 0.5 * (bar + previous_bar) * r.ratio_y * (e[1] - previous_e);
        previous_bar = bar;
        previous_e   = e[1];
        hp = hp1, hb = hb1, ha = ha1, ho = ho1;
      }
      // Yield at the opening eps_y (h + L_sp): at the first step past it.
      EXPECT_NEAR(opening_at_yield, ey * (h + l_sp), 1.5 * 2 * w_max / n) << "h = " << h;
      // Work of the row = the bars' stored energy + plastic work (per unit volume of the row).
      const VoigtStrain end{{0, (w_max - w_y) / h, 0}};
      const PointOutput oa = anchored.output(end, ha.data()), op = plain.output(end, hp.data());
      const double      stored  = oa.stored_energy - op.stored_energy;
      const double      plastic = oa.plastic_dissipation - op.plastic_dissipation;
      EXPECT_GT(plastic, 0);
      EXPECT_NEAR(work, stored + plastic, 1e-3 * plastic) << "h = " << h;
      // The plastic work per unit area of the row, h (stored + plastic): the bars' f_y times
      // their plastic elongation, the same on both rows (up to the 1 % hardening's share).
      const double elongation_work = h * plastic / r.ratio_y;
      const double expected        = r.yield_stress * (w_max - ey * (h + l_sp));
      EXPECT_NEAR(elongation_work / expected, 1.0, 0.03) << "h = " << h;
      std::cout << "h = " << h << " m: yield at opening " << opening_at_yield * 1e3
                << " mm (eps_y (h + L_sp) = " << ey * (h + l_sp) * 1e3 << " mm), plastic work "
                << elongation_work << " J/m^2 (f_y x plastic opening " << expected << ")\n";
    }
  }

  // Compression plasticity (b_c = 0.7, Birtel & Mark 2006): uniaxial compression (nu = 0) to
  // 1.5 eps_c1, past the peak, follows the MC2010 curve as with b_c = 0; unloading is linear,
  // sigma = (1 - d) E (eps - eps_p), and reaches zero stress at the permanent strain
  // eps_p = -b_c (kappa - sigma_c(kappa) / E); reloading returns on the same line to the curve.
  // The work int sigma d eps of the cycle to zero stress equals the damage + plastic dissipation
  // (stored energy 0 there) within 1 %.
  TEST(Concrete, CompressionPlasticityLeavesThePermanentStrainAndFollowsTheCurve)
  {
    ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    c.poisson_ratio      = 0;
    c.plastic_fraction   = 0.7;
    const ConcreteDamageLaw law(c);
    EXPECT_EQ(law.n_history(), 12u);
    std::vector<double> h0(law.n_history()), h1(law.n_history());
    law.initialize_point(h0.data(), 0.05);
    const double E = c.youngs_modulus, e_max = 1.5 * c.eps_c1;
    const int    n    = 3000;
    double       work = 0, s_prev = 0, e_prev = 0, worst = 0;
    const auto   step = [&](double e)
    {
      const double s = law.stress({{e, 0, 0}}, h0.data(), h1.data())[0];
      work += 0.5 * (s + s_prev) * (e - e_prev);
      s_prev = s;
      e_prev = e;
      h0     = h1;
      return s;
    };
    for (int i = 1; i <= n; ++i)
    {
      const double e = -e_max * i / n;
      worst          = std::max(worst, std::abs(-step(e) - c.compression_curve(-e)));
    }
    EXPECT_LT(worst, 1e-9 * c.f_cm);
    const double eps_p = -0.7 * (e_max - c.compression_curve(e_max) / E);
    EXPECT_NEAR(h0[ConcreteDamageLaw::p_slot], eps_p, 1e-12);
    EXPECT_NEAR(h0[ConcreteDamageLaw::p_slot + 1], 0, 1e-15);
    // Unloading: linear from (-e_max, -sigma_c) to (eps_p, 0).
    const double slope = c.compression_curve(e_max) / (e_max + eps_p);
    double       s     = 0;
    for (int i = 1; i <= n; ++i)
    {
      const double e = -e_max + (e_max + eps_p) * i / n;
      s              = step(e);
      EXPECT_NEAR(s, slope * (e - eps_p), 1e-9 * c.f_cm) << e;
    }
    EXPECT_NEAR(s, 0, 1e-9 * c.f_cm);
    const PointOutput o = law.output({{eps_p, 0, 0}}, h0.data());
    std::printf("compression plasticity b_c = 0.7: eps_p = %.4g (closed form %.4g), work %.6g "
                "J/m^3, damage %.6g + plastic %.6g = %.6g J/m^3, stored %.2g\n",
                h0[ConcreteDamageLaw::p_slot],
                eps_p,
                work,
                o.damage_dissipation,
                o.plastic_dissipation,
                o.damage_dissipation + o.plastic_dissipation,
                o.stored_energy);
    EXPECT_NEAR(o.stored_energy, 0, 1e-9 * work);
    EXPECT_NEAR(o.damage_dissipation + o.plastic_dissipation, work, 0.01 * work);
    EXPECT_GT(o.plastic_dissipation, 0.3 * work);
    // Reloading: back along the same line, then on the curve again.
    for (int i = 1; i <= n; ++i)
    {
      const double e = eps_p - (e_max + eps_p) * i / n;
      EXPECT_NEAR(step(e), slope * (e - eps_p), 1e-9 * c.f_cm) << e;
    }
    const double e_more = -1.6 * c.eps_c1;
    EXPECT_NEAR(-step(e_more), c.compression_curve(-e_more), 1e-9 * c.f_cm);
  }

  /** Pulls a point of @p law (band h) along y (eps_xx = gamma = 0) until the tension damage is
   *  complete (d_t at its cap 1 - 1e-6); the committed history is left in @p h0. */
  void crack_fully_along_y(const ConcreteDamageLaw &law, std::vector<double> &h0, double h)
  {
    std::vector<double> h1(law.n_history());
    law.initialize_point(h0.data(), h);
    const double e0 = law.effective_tensile_strength(h) / law.parameters().youngs_modulus;
    for (double e = e0 / 100; h0[2] < 1 - 1.0001e-6; e += e0 / 10)
    {
      law.stress({{0, e, 0}}, h0.data(), h1.data());
      h0 = h1;
      ASSERT_LT(e, 1.0) << "the point never cracked through";
    }
  }

  // A band fully cracked in tension (d_t = 1 - 1e-6, crack normal y) and held open at the
  // normal strain e_n (opening w = h e_n) still carries shear: tau = mu (1 - d_t (1 - beta(w)))
  // gamma with beta(w) = beta_min + (1 - beta_min)(1 - 2 w / d_agg) up to w = d_agg / 2, beta_min
  // beyond; the smeared bars crossing it (rho_y) add the dowel tau_d = rho_y G_s gamma up to
  // rho_y min(f_y / sqrt 3, 1.3 (4 / pi) sqrt(f_cm f_y)). Before the change the law kept 1e-6 of
  // mu: a frictionless slide.
  TEST(Concrete, FullyCrackedBandStillCarriesShear)
  {
    constexpr double        tolerance = 1e-9;
    ConcreteParameters      c         = ConcreteParameters::from_f_cm(38e6);
    const double            h = 0.05, d_agg = c.aggregate_size, b0 = c.shear_retention_floor;
    const ConcreteDamageLaw law(c);
    std::vector<double>     h0(law.n_history()), h1(law.n_history());
    crack_fully_along_y(law, h0, h);
    EXPECT_NEAR(std::abs(h0[7]), 1.0, 1e-12) << "crack normal along y";
    const double mu = c.youngs_modulus / (2 * (1 + c.poisson_ratio)), dt = h0[2];
    for (const double w : {0.0005, 0.002, 0.006, 0.012})
    {
      const double en = w / h, gamma = 1e-5;
      const double beta     = w >= 0.5 * d_agg ? b0 : b0 + (1 - b0) * (1 - 2 * w / d_agg);
      const double tau_p    = law.stress({{0, en, gamma}}, h0.data(), h1.data())[2];
      const double tau_m    = law.stress({{0, en, -gamma}}, h0.data(), h1.data())[2];
      const double G        = (tau_p - tau_m) / (2 * gamma);
      const double expected = mu * (1 - dt * (1 - beta));
      std::printf("cracked band, opening w = %.1f mm: shear modulus %.6g MPa, closed form mu (1 "
                  "- d_t (1 - beta)) = %.6g MPa (beta = %.4f), intact mu = %.6g MPa\n",
                  w * 1e3,
                  G / 1e6,
                  expected / 1e6,
                  beta,
                  mu / 1e6);
      EXPECT_NEAR(G, expected, tolerance * mu) << "w " << w;
      EXPECT_NEAR(law.shear_retention(w), beta, 1e-15);
      EXPECT_GE(G, 0.5 * b0 * mu) << "w " << w;
    }

    // Reinforced: the dowels of the y bars add rho_y G_s, then yield at their strength.
    ReinforcementParameters r;
    r.ratio_y = 0.008;
    const ConcreteDamageLaw rc(c, r);
    std::vector<double>     g0(rc.n_history()), g1(rc.n_history());
    crack_fully_along_y(rc, g0, h);
    const double w = 0.012, en = w / h; // beyond d_agg / 2: only beta_min and the dowels
    const double G_s = r.youngs_modulus / 2.6, pi = 3.14159265358979323846;
    const double tau_bar =
      std::min(r.yield_stress / std::sqrt(3.0), 1.3 * 4 / pi * std::sqrt(c.f_cm * r.yield_stress));
    const ConcreteDamageLaw::Dowel dw = rc.dowel(0, 1);
    EXPECT_NEAR(dw.stiffness, r.ratio_y * G_s, 1e-9 * G_s);
    EXPECT_NEAR(dw.strength, r.ratio_y * tau_bar, 1e-9 * tau_bar);
    // Open the crack (the dowel started unloaded at the cracking step, gamma = 0 then).
    rc.stress({{0, en, 0}}, g0.data(), g1.data());
    g0                  = g1;
    const double gamma  = 1e-5;
    const double tau    = rc.stress({{0, en, gamma}}, g0.data(), g1.data())[2];
    const double expect = (mu * (1 - g0[2] * (1 - b0)) + r.ratio_y * G_s) * gamma;
    std::printf("reinforced cracked band (rho_y 0.8 %%), w = 12 mm: tau = %.6g kPa at gamma = "
                "1e-5, closed form (mu beta_min + rho_y G_s) gamma = %.6g kPa; dowel strength "
                "%.4g MPa\n",
                tau / 1e3,
                expect / 1e3,
                dw.strength / 1e6);
    EXPECT_NEAR(tau, expect, tolerance * mu * gamma);
    // Slide 2 % (far past the dowel's yield slip): the dowels carry their strength.
    const double big     = 0.02;
    const double tau_big = rc.stress({{0, en, big}}, g0.data(), g1.data())[2];
    EXPECT_NEAR(tau_big, mu * (1 - g0[2] * (1 - b0)) * big + dw.strength, 1e-9 * dw.strength);
    EXPECT_NEAR(g1[8 + 4] - g0[8 + 4],
                dw.strength * (big - dw.strength / dw.stiffness),
                1e-9 * dw.strength * big)
      << "plastic work of the dowels";
  }

  // Load reversal: a point cracked through in tension along x (d_t = 1 - 1e-6), then compressed
  // along x, has the undamaged stiffness: the crack closes. nu = 0: sigma = -sigma_c(eps), the
  // virgin compression curve, whose tangent at zero is E; unloading back into tension finds the
  // crack open again (1e-6 E). nu = 0.2 (uniaxial strain): the plane-strain modulus lambda + 2 mu.
  TEST(Concrete, CrackClosesUnderLoadReversal)
  {
    for (const double nu : {0.0, 0.2})
    {
      ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
      c.poisson_ratio      = nu;
      const ConcreteDamageLaw law(c);
      const double            h = 0.05, E = c.youngs_modulus;
      std::vector<double>     h0(law.n_history()), h1(law.n_history());
      law.initialize_point(h0.data(), h);
      const double e0 = law.effective_tensile_strength(h) / E;
      double       e  = 0;
      for (e = e0 / 100; h0[2] < 1 - 1.0001e-6; e += e0 / 10)
      {
        law.stress({{e, 0, 0}}, h0.data(), h1.data());
        h0 = h1;
      }
      const double tension_slope =
        law.stress({{e, 0, 0}}, h0.data(), h1.data())[0] / e; // secant of the open crack
      const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
      // Compression in small steps: the secant at 1e-6 is the tangent at zero.
      const double de      = 1e-6;
      const double s_small = law.stress({{-de, 0, 0}}, h0.data(), h1.data())[0];
      const double modulus = -s_small / de;
      std::printf("crack closure, nu = %.1f: tension secant after cracking %.4g MPa, "
                  "compression modulus %.6g MPa vs undamaged lambda + 2 mu = %.6g MPa\n",
                  nu,
                  tension_slope / 1e6,
                  modulus / 1e6,
                  (lam + 2 * mu) / 1e6);
      EXPECT_LT(tension_slope, 1e-5 * E);
      // The first compressive step already damages (d_c ~ 1e-3 eta): 1e-3 relative.
      EXPECT_NEAR(modulus, lam + 2 * mu, 1e-3 * (lam + 2 * mu));
      if (nu == 0)
      {
        // The whole virgin compression curve, then back to tension: open again.
        for (int i = 1; i <= 30; ++i)
        {
          const double ec = i * 1e-4;
          const double s  = -law.stress({{-ec, 0, 0}}, h0.data(), h1.data())[0];
          EXPECT_NEAR(s, c.compression_curve(ec), 1e-9 * c.f_cm) << ec;
          h0 = h1;
        }
        const double s_back = law.stress({{e, 0, 0}}, h0.data(), h1.data())[0];
        EXPECT_LT(s_back, 1e-5 * E * e);
        EXPECT_GE(s_back, 0);
      }
    }
  }

  // A cracked point is elastic at fixed damage: the law's stress derives from its stored energy
  // (a closed strain cycle returns the work it took, central-difference tangent = tangent()
  // where beta is constant, i.e. beyond d_agg / 2 and for a closed crack).
  TEST(Concrete, CrackedPointDerivesFromItsStoredEnergy)
  {
    ConcreteParameters      c = ConcreteParameters::from_f_cm(38e6);
    ReinforcementParameters r;
    r.ratio_x = 0.002;
    r.ratio_y = 0.008;
    const ConcreteDamageLaw law(c, r);
    std::vector<double>     h0(law.n_history()), h1(law.n_history());
    crack_fully_along_y(law, h0, 0.05);
    // Crushed a little too, beyond every compression of the checks below (so that d_c is fixed
    // in them), then the crack frame turned off the axes: a tilted crack (30 degrees).
    law.stress({{-2.5e-3, -2.5e-3, 0}}, h0.data(), h1.data());
    h0    = h1;
    h0[6] = std::cos(pi / 6);
    h0[7] = std::sin(pi / 6);
    for (const VoigtStrain &e : {VoigtStrain{{-1e-4, 0.3, 1e-5}},
                                 VoigtStrain{{-2e-4, -1e-4, 3e-5}},
                                 VoigtStrain{{0.4, -1e-3, 2e-5}},
                                 VoigtStrain{{0.3, 0.35, -1e-5}}})
    {
      const double err = tangent_error(law, e, h0.data());
      EXPECT_LT(err, 1e-5) << e[0] << " " << e[1] << " " << e[2];
    }
    // A closed loop through open, closed and sheared states: work = change of stored energy = 0.
    const auto path = [](double t) -> VoigtStrain
    {
      const double a = 2 * pi * t;
      return {{1e-3 * std::cos(a), 1.5e-3 * std::sin(a), 1e-3 * std::sin(2 * a)}};
    };
    double      work = 0, scale = 0;
    const int   n      = 20000;
    VoigtStrain e_prev = path(0);
    VoigtStress s_prev = law.stress(e_prev, h0.data(), h1.data());
    for (int i = 1; i <= n; ++i)
    {
      const VoigtStrain e = path(static_cast<double>(i) / n);
      const VoigtStress s = law.stress(e, h0.data(), h1.data());
      for (unsigned int k = 0; k < 3; ++k)
      {
        work += 0.5 * (s[k] + s_prev[k]) * (e[k] - e_prev[k]);
        scale += 0.5 * std::abs((s[k] + s_prev[k]) * (e[k] - e_prev[k]));
      }
      e_prev = e;
      s_prev = s;
    }
    std::printf("cracked point, closed strain loop: net work %.3g J/m^3 of %.3g J/m^3 gross\n",
                work,
                scale);
    EXPECT_LT(std::abs(work), 1e-4 * scale);
  }

  // Crack parameters outside their range are refused with their name.
  TEST(Concrete, CrackParametersOutsideTheirRangeAreRefused)
  {
    const auto refused =
      [](const ConcreteParameters &c, const ReinforcementParameters &r, const char *name)
    {
      try
      {
        const ConcreteDamageLaw law(c, r);
        ADD_FAILURE() << name << " accepted";
      }
      catch (const std::invalid_argument &e)
      {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      }
    };
    const ConcreteParameters good = ConcreteParameters::from_f_cm(38e6);
    ConcreteParameters       c    = good;
    c.aggregate_size              = 5e-4;
    refused(c, {}, "aggregate_size");
    c                       = good;
    c.shear_retention_floor = 1.5;
    refused(c, {}, "shear_retention_floor");
    ReinforcementParameters r;
    r.ratio_y           = 0.01;
    r.dowel_coefficient = -1;
    refused(good, r, "dowel_coefficient");
    r.dowel_coefficient  = 1.3;
    r.base_joint_tension = -1e6;
    refused(good, r, "base_joint_tension");
    r.base_joint_tension = 0.3e6; // no strain penetration: no base row for the joint
    refused(good, r, "base_joint_tension");
  }
} // namespace
