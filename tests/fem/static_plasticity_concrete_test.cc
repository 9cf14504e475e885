// Concrete through the static inelastic solver (fem/static_plasticity.h): one element in uniaxial
// compression following the input curve (with and without compression plasticity), the crack
// band dissipating G_F on every mesh, a reinforced bar whose one crack opens and whose bars yield.
// Numbers and set-ups: docs/validation.md, physics.md §6.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <memory>
#include <vector>

#include "fem/inelastic_laws.h"
#include "fem/static_plasticity.h"
#include "tests/fem/static_plasticity_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  /** Concrete from f_cm = 38 MPa by fib MC2010 with nu = 0 (uniaxial states stay uniaxial). */
  ConcreteParameters concrete()
  {
    ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    c.poisson_ratio      = 0;
    return c;
  }

  /**
   * One element [0, a]^2 of @p law, bottom and left smooth, its top pushed down by
   * strain_end a in 40 steps. Entry 2 of the reactions is the top's.
   */
  StaticPlasticityParameters
  compressed_element(double a, double strain_end, std::shared_ptr<const MaterialLaw> law)
  {
    const double               tol = 1e-9 * a;
    StaticPlasticityParameters p;
    p.mesh       = tensor_product_mesh({0, a},
                                 {0, a},
                                 0,
                                 [&](double x, double y) {
                                   return y > a - tol ? footing :
                                                y < tol     ? base :
                                                x < tol     ? symmetry :
                                                              free_surface;
                                 });
    p.laws[0]    = std::move(law);
    p.prescribed = {{base, false, true, 0, 0},
                    {symmetry, true, false, 0, 0},
                    {footing, false, true, 0, -strain_end * a}};
    p.n_steps    = 40;
    return p;
  }

  /**
   * A bar [0, length] x [0, h] of n square elements (h = length / n; left end and base smooth),
   * the middle element of material 1 (@p weak_law), the others of material 0 (@p law), both
   * with the numerical tangent; its right end pulled by @p opening in @p n_steps steps. Entry 2
   * of the reactions is the right end's.
   */
  StaticPlasticityParameters tension_bar(double                             length,
                                         unsigned int                       n,
                                         std::shared_ptr<const MaterialLaw> law,
                                         std::shared_ptr<const MaterialLaw> weak_law,
                                         double                             opening,
                                         unsigned int                       n_steps)
  {
    const double               h = length / n, tol = 1e-9 * h;
    StaticPlasticityParameters p;
    p.mesh                       = tensor_product_mesh(uniform(0, length, n),
                                 {0, h},
                                 0,
                                 [&](double x, double y) {
                                   return x < tol          ? symmetry :
                                                                x > length - tol ? wall :
                                                                y < tol          ? base :
                                                                                   free_surface;
                                 });
    p.mesh.cells[n / 2].material = 1;
    p.laws[0]                    = std::move(law);
    p.laws[1]                    = std::move(weak_law);
    p.prescribed                 = {{base, false, true, 0, 0},
                                    {symmetry, true, false, 0, 0},
                                    {wall, true, false, opening, 0}};
    p.n_steps                    = n_steps;
    p.numerical_tangent          = {0, 1};
    return p;
  }

  /** Work of the pulling force of a tension_bar() run (trapezoid over the steps), J/m. */
  double pulling_work(const StaticPlasticityResult &r, double opening)
  {
    double work = 0;
    for (std::size_t k = 1; k < r.steps.size(); ++k)
      work += 0.5 * (r.steps[k].reactions[2][0] + r.steps[k - 1].reactions[2][0]) *
              (r.steps[k].load_factor - r.steps[k - 1].load_factor) * opening;
    return work;
  }

  // Uniaxial compression of one concrete element through the solver (bottom and left smooth,
  // top pushed down to 1.5 eps_c,lim in 40 steps: past the peak and down the descending
  // branch): the stress -R_y / width follows the input curve (MC2010 eq. 5.1-26, then the linear
  // descent) at every step within 1e-9 f_cm; a step lands within 0.1 % of the peak f_cm.
  TEST(StaticPlasticity, ConcreteUniaxialCompressionFollowsTheInputCurve)
  {
    constexpr double         a = 0.1, tolerance = 1e-9;
    const ConcreteParameters c          = concrete();
    const double             strain_end = 1.5 * c.eps_c_lim;
    const auto               r          = run_static_plasticity(
      compressed_element(a, strain_end, std::make_shared<ConcreteDamageLaw>(c)));
    double worst = 0, peak = 0;
    for (const auto &st : r.steps)
    {
      const double e = st.load_factor * strain_end;
      const double s = -st.reactions[2][1] / a;
      worst          = std::max(worst, std::abs(s - c.compression_curve(e)));
      peak           = std::max(peak, s);
    }
    std::printf("uniaxial compression: %zu steps, peak %.5g MPa (f_cm %.5g), largest "
                "difference from the curve %.2e MPa\n",
                r.steps.size(),
                peak / 1e6,
                c.f_cm / 1e6,
                worst / 1e6);
    EXPECT_LT(worst, tolerance * c.f_cm);
    EXPECT_NEAR(peak / c.f_cm, 1, 1e-3); // a step lands within 0.1 % of the peak
  }

  // The same element with compression plasticity (b_c = 0.7): the loading path is the input
  // curve again (d_c compensates the plastic strain), within 1e-9 f_cm, and the plastic work
  // of the element at the end is b_c eps_in's share: sum of -dp sigma over the steps, > 0.
  TEST(StaticPlasticity, ConcreteWithCompressionPlasticityFollowsTheInputCurve)
  {
    constexpr double   a = 0.1, tolerance = 1e-9;
    ConcreteParameters c    = concrete();
    c.plastic_fraction      = 0.7;
    const double strain_end = 1.5 * c.eps_c_lim;
    const auto   r          = run_static_plasticity(
      compressed_element(a, strain_end, std::make_shared<ConcreteDamageLaw>(c)));
    double worst = 0;
    for (const auto &st : r.steps)
    {
      const double e = st.load_factor * strain_end;
      worst          = std::max(worst, std::abs(-st.reactions[2][1] / a - c.compression_curve(e)));
    }
    std::printf("uniaxial compression with b_c = 0.7: largest difference from the curve %.2e "
                "MPa, plastic dissipation %.5g J/m, damage %.5g J/m\n",
                worst / 1e6,
                r.plastic_dissipation,
                r.damage_dissipation);
    EXPECT_LT(worst, tolerance * c.f_cm);
    EXPECT_GT(r.plastic_dissipation, 0);
  }

  // Crack band through the solver: a bar of square elements of size h (h = 0.1, 0.05, 0.025 m,
  // length 0.3 m < the characteristic length E G_F / f_t^2 = 0.56 m, so no snap-back) pulled
  // apart until the crack is open; the middle element is 1 % weaker so that the crack localises
  // there. The dissipated energy per unit crack area (J/m per metre of bar height) is G_F within
  // 5 % on every mesh.
  TEST(StaticPlasticity, CrackBandDissipatesTheFractureEnergyOnEveryMesh)
  {
    constexpr double         length = 0.3, tolerance = 0.05;
    const ConcreteParameters c    = concrete();
    ConcreteParameters       weak = c;
    weak.f_ctm                    = 0.99 * c.f_ctm;
    for (const unsigned int n : {3u, 6u, 12u})
    {
      const double h = length / n;
      // Opened to 10 x the crack's characteristic opening G_F / f_t (the rest of the energy
      // < 1e-4 G_F).
      const double opening = 10 * c.fracture_energy / c.f_ctm;
      const auto   r       = run_static_plasticity(tension_bar(length,
                                                       n,
                                                       std::make_shared<ConcreteDamageLaw>(c),
                                                       std::make_shared<ConcreteDamageLaw>(weak),
                                                       opening,
                                                       200));
      // Work of the pulling force (the bar ends unloaded) per unit crack area; the damage
      // dissipation of the Gauss points beside it.
      const double g_f = pulling_work(r, opening) / h;
      std::printf("crack band h = %.4f m: work %.5g N/m, damage dissipation %.5g N/m (G_F "
                  "%.5g), end stress %.3g MPa\n",
                  h,
                  g_f,
                  r.damage_dissipation / h,
                  c.fracture_energy,
                  r.steps.back().reactions[2][0] / h / 1e6);
      EXPECT_NEAR(g_f / c.fracture_energy, 1, tolerance) << "h = " << h;
    }
  }

  // Reinforced bar in tension: the crack-band bar above (length 0.3 m, h = 0.1, 0.05,
  // 0.025 m; the middle element's f_ct 25 % lower, 2.17 MPa, so that the crack localises there
  // rather than in all elements at once, which the steel's positive stiffness would allow) with
  // smeared bars along x, rho = 0.4 %, B500 (f_y = 500 MPa, E_s = 200 GPa, hardening b = 1 %),
  // pulled until the cracked element's strain is 5 %. As rho f_y (+ hardening: 2.4 MPa at the
  // end) stays below the others' f_ct = 2.9 MPa, one crack forms and its bars yield; the other
  // elements stay elastic. Closed forms with eps_c, the cracked element's strain (from its nodes):
  // the end force per area is rho (f_y + b E_s (eps_c - eps_y)) (the concrete's residual
  // (1 - d) E eps_c < 1e-4 of it) within 1 %; the bars' plastic work rho A h (f_y eps_p +
  // H eps_p^2 / 2) (H = b E_s / (1 - b)) within 1 %; the work of the pulling force minus the
  // elastic energy left equals G_F A + the bars' plastic work within 3 % (found: < 0.05 %). The
  // damage law's own dissipation Y_n+1 (d_n+1 - d_n) is first order in the step (here 20 steps
  // per softening strain e_f at h = 0.1 m: 6.6 % above G_F A, as the plain bar's 7.4 %): within
  // 10 %.
  TEST(StaticPlasticity, ReinforcedBarCracksOnceAndItsBarsYield)
  {
    constexpr double         length = 0.3, eps_end = 0.05;
    const ConcreteParameters c    = concrete();
    ConcreteParameters       weak = c;
    weak.f_ctm                    = 0.75 * c.f_ctm;
    ReinforcementParameters bars;
    bars.ratio_x     = 0.004;
    const double rho = bars.ratio_x, fy = bars.yield_stress, Es = bars.youngs_modulus;
    const double Et = bars.hardening * Es, H = bars.hardening_modulus(), ey = fy / Es;
    const double Ec = c.youngs_modulus;
    for (const unsigned int n : {3u, 6u, 12u})
    {
      const double h = length / n, tol = 1e-9 * h;
      const double opening = eps_end * h + (length - h) * 1e-4;
      const auto   p       = tension_bar(length,
                                 n,
                                 std::make_shared<ConcreteDamageLaw>(c, bars),
                                 std::make_shared<ConcreteDamageLaw>(weak, bars),
                                 opening,
                                 2000);
      const auto   r       = run_static_plasticity(p);
      const double work    = pulling_work(r, opening);
      // The cracked element's strain from the x displacements of its bottom nodes.
      double u0 = 0, u1 = 0;
      for (std::size_t v = 0; v < p.mesh.vertices.size(); ++v)
        if (std::abs(p.mesh.vertices[v][1]) < tol)
        {
          if (std::abs(p.mesh.vertices[v][0] - (n / 2) * h) < tol)
            u0 = r.vertex_displacements[v][0];
          if (std::abs(p.mesh.vertices[v][0] - (n / 2 + 1) * h) < tol)
            u1 = r.vertex_displacements[v][0];
        }
      const double eps_c   = (u1 - u0) / h;
      const double sigma_s = fy + Et * (eps_c - ey), eps_p = eps_c - sigma_s / Es;
      const double w_p     = rho * h * h * (fy * eps_p + 0.5 * H * eps_p * eps_p);
      const double f_end   = r.steps.back().reactions[2][0] / h; // Pa
      const double eps_out = f_end / (Ec + rho * Es);
      const double stored =
        (length - h) * h * 0.5 * f_end * eps_out + h * h * 0.5 * rho * sigma_s * sigma_s / Es;
      const double g_f = c.fracture_energy * h;
      std::printf("reinforced bar h = %.4f m: crack strain %.4f, end stress %.4g MPa (closed "
                  "form %.4g), plastic dissipation %.5g J/m (closed form %.5g), damage %.5g J/m "
                  "(G_F A %.5g), work - stored %.5g J/m (G_F A + plastic %.5g)\n",
                  h,
                  eps_c,
                  f_end / 1e6,
                  rho * sigma_s / 1e6,
                  r.plastic_dissipation,
                  w_p,
                  r.damage_dissipation,
                  g_f,
                  work - stored,
                  g_f + w_p);
      EXPECT_NEAR(f_end / (rho * sigma_s), 1, 0.01) << "h = " << h;
      EXPECT_NEAR(r.plastic_dissipation / w_p, 1, 0.01) << "h = " << h;
      EXPECT_NEAR(r.damage_dissipation / g_f, 1, 0.10) << "h = " << h;
      EXPECT_NEAR((work - stored) / (g_f + w_p), 1, 0.03) << "h = " << h;
      EXPECT_GT(eps_c, 0.9 * eps_end);
    }
  }
} // namespace
