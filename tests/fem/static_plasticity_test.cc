// Static inelastic solver (fem/static_plasticity.h) on soil against closed forms: quadratic
// Newton convergence with the consistent tangent, Rankine passive earth pressure on a smooth rigid
// wall (gravity, K0 initial stress), Prandtl's strip footing on Tresca soil, non-convergence.
// Concrete through the solver: static_plasticity_concrete_test.cc. Numbers and set-ups:
// docs/validation.md, physics.md §6.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <memory>
#include <string>
#include <vector>

#include "fem/inelastic_laws.h"
#include "fem/static_plasticity.h"
#include "tests/fem/static_plasticity_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;
  constexpr double pi = 3.14159265358979323846;
  constexpr double g  = 9.81;

  SoilParameters soil(double E, double nu, double c, double phi_deg, double cutoff)
  {
    SoilParameters p;
    p.youngs_modulus = E;
    p.poisson_ratio  = nu;
    p.density        = 1700;
    p.cohesion       = c;
    p.friction_angle = phi_deg * pi / 180;
    p.dilatancy      = p.friction_angle; // associated flow: the Rankine and Prandtl hypothesis
    p.tension_cutoff = cutoff;
    return p;
  }


  /** Joins two graded coordinate lists sharing an end point. */
  std::vector<double> join(std::vector<double> a, const std::vector<double> &b)
  {
    a.insert(a.end(), b.begin() + 1, b.end());
    return a;
  }

  /**
   * Smooth rigid wall x = 0, 0 <= y <= H, translated by delta into a backfill [0, L] x [0, H]
   * (rough or smooth base, far side on rollers), n cells over H, L / H n over L. Entry 2 of the
   * reactions is the wall's.
   */
  StaticPlasticityParameters rankine_problem(const SoilParameters &s,
                                             double                H,
                                             double                k0,
                                             double                delta,
                                             unsigned int          n,
                                             unsigned int          n_steps,
                                             bool                  rough_base,
                                             unsigned int          length_over_height)
  {
    const double               L = length_over_height * H, tol = 1e-9 * H;
    StaticPlasticityParameters p;
    p.mesh           = tensor_product_mesh(uniform(0, L, length_over_height * n),
                                 uniform(0, H, n),
                                 0,
                                 backfill_sides(L, tol));
    p.laws[0]        = std::make_shared<MohrCoulombLaw>(s);
    p.densities[0]   = s.density;
    p.gravity        = g;
    p.initial_stress = geostatic_stress(H, s.density * g, k0);
    p.prescribed     = {{base, rough_base, true, 0, 0},
                        {far_side, true, false, 0, 0},
                        {wall, true, false, delta, 0}};
    p.n_steps        = n_steps;
    return p;
  }

  /** Prints the load path of the reaction entry @p entry (its magnitude / @p exact). */
  void print_path(const char *name, const StaticPlasticityResult &r, double exact, unsigned entry)
  {
    std::printf("%s: %u DoFs, initial out-of-balance %.2e of the weight\n",
                name,
                r.n_dofs,
                r.initial_out_of_balance);
    for (const auto &st : r.steps)
      std::printf("  load factor %.3f  P / exact %.5f  Newton iterations %zu  residual %.1e\n",
                  st.load_factor,
                  std::hypot(st.reactions[entry][0], st.reactions[entry][1]) / exact,
                  st.residuals.size(),
                  st.residuals.empty() ? 0.0 : st.residuals.back());
  }

  /**
   * Rigid smooth strip footing of half-width b = 1 m on weightless Tresca soil (half model
   * [0, 4b] x [-3b, 0], symmetry x = 0, rollers at x = 4b, rough base), pushed down by delta;
   * grid lines graded towards the footing edge and the surface; level 1: 14 x 10 cells, level
   * l: l times as many lines in each direction.
   */
  StaticPlasticityParameters
  prandtl_problem(std::shared_ptr<const MaterialLaw> law, double level, double delta)
  {
    constexpr double b = 1, width = 4 * b, depth = 3 * b, tol = 1e-9;
    // Cell size ratios across each segment: 4 under the footing, 8 outside and with depth.
    const auto grade = [&](double x0, double x1, double n_1, double end_over_start)
    {
      const auto n = static_cast<unsigned int>(std::lround(n_1 * level));
      return graded_coordinates(x0, x1, n, std::pow(end_over_start, 1.0 / (n - 1)));
    };
    const std::vector<double>  xs = join(grade(0, b, 6, 1.0 / 4), grade(b, width, 8, 8));
    const std::vector<double>  ys = grade(-depth, 0, 10, 1.0 / 8);
    StaticPlasticityParameters p;
    p.mesh       = tensor_product_mesh(xs,
                                 ys,
                                 0,
                                 [&](double x, double y)
                                 {
                                   return x < tol          ? symmetry :
                                                x > width - tol  ? far_side :
                                                y < -depth + tol ? base :
                                                x < b            ? footing :
                                                                   free_surface;
                                 });
    p.laws[0]    = std::move(law);
    p.prescribed = {{base, true, true, 0, 0},
                    {symmetry, true, false, 0, 0},
                    {far_side, true, false, 0, 0},
                    {footing, false, true, 0, -delta}};
    p.n_steps    = 8;
    return p;
  }

  /** Collapse load estimate of a run: the reaction magnitude of @p entry at the last step. */
  double final_load(const StaticPlasticityResult &r, unsigned int entry)
  {
    const auto &f = r.steps.back().reactions[entry];
    return std::hypot(f[0], f[1]);
  }

  /** The wall thrust P (N/m) of a Rankine run on @p n cells over H, its load path printed. */
  double rankine_thrust(const char *name, const StaticPlasticityResult &r, unsigned n, double exact)
  {
    print_path(name, r, exact, 2);
    const double P = final_load(r, 2);
    std::printf("n = %u: P = %.5g N/m, exact %.5g N/m, ratio %.4f\n", n, P, exact, P / exact);
    return P;
  }

  /** Asserts that P converges monotonically from above to @p exact and ends within @p tol. */
  void expect_converges_from_above(const std::vector<double> &P, double exact, double tol)
  {
    for (std::size_t i = 0; i < P.size(); ++i)
    {
      EXPECT_GT(P[i], exact) << "mesh " << i;
      if (i > 0)
      {
        EXPECT_LT(P[i], P[i - 1]) << "mesh " << i;
      }
    }
    EXPECT_LT(std::abs(P.back() / exact - 1), tol);
  }

  // Newton's rate: relative residuals after each solve of every load step of a Prandtl run
  // (plastic from step 2 on). Asymptotic pairs are those with r_k <= 1e-4 whose successor is
  // above the round-off floor (r_k+1 >= 1e-12; the floor is about 1e-14). Quadratic convergence
  // keeps r_k+1 / r_k^2 bounded there (measured <= 7.6; a linear rate q would give q / r_k,
  // >= 1e3 q) and the order log(r_k+1) / log(r_k) >= 1.8 (measured >= 1.86; theory 2, minus the
  // house margin 0.1 and 0.1 for the constant). Half the steps must show such a pair.
  TEST(StaticPlasticity, NewtonConvergesQuadraticallyWithTheConsistentTangent)
  {
    constexpr double     max_ratio = 100, min_order = 1.8, asymptotic = 1e-4, floor = 1e-12;
    const SoilParameters c        = soil(10e6, 0.45, 20e3, 0, 1e9);
    auto                 p        = prandtl_problem(std::make_shared<MohrCoulombLaw>(c), 1, 0.05);
    p.newton_tolerance            = 1e-12;
    const auto   r                = run_static_plasticity(p);
    unsigned int steps_with_pairs = 0;
    for (std::size_t n = 1; n < r.steps.size(); ++n)
    {
      const auto &res = r.steps[n].residuals;
      std::printf("step %zu (load factor %.3f): r_k", n, r.steps[n].load_factor);
      for (const double x : res)
        std::printf(" %.2e", x);
      std::printf("\n   r_k+1 / r_k^2:");
      for (std::size_t k = 1; k < res.size(); ++k)
        std::printf(" %.2e", res[k] / (res[k - 1] * res[k - 1]));
      std::printf("\n");
      bool found = false;
      for (std::size_t k = 1; k < res.size(); ++k)
        if (res[k - 1] <= asymptotic && res[k] >= floor)
        {
          const double ratio = res[k] / (res[k - 1] * res[k - 1]);
          const double order = std::log(res[k]) / std::log(res[k - 1]);
          std::printf("   asymptotic pair %.2e -> %.2e: ratio %.2f, order %.2f\n",
                      res[k - 1],
                      res[k],
                      ratio,
                      order);
          EXPECT_LE(ratio, max_ratio) << "step " << n << ", iteration " << k;
          EXPECT_GE(order, min_order) << "step " << n << ", iteration " << k;
          found = true;
        }
      steps_with_pairs += found ? 1 : 0;
    }
    EXPECT_GE(2 * steps_with_pairs, r.steps.size() - 1) << "too few steps show the asymptotic rate";
  }

  /**
   * Rankine runs of the clay c = 20 kPa (E = 5 MPa, nu = 0.45, tension cut-off @p cutoff) with
   * the Law (smooth wall H = 2 m pushed by 0.03 H, K0 = 1, rough base, L = 3 H) on n = 4, 8 and
   * 16 cells over H: the wall thrust converges from above to P_p = gamma H^2 / 2 + 2 c H, within
   * 5 % on the finest mesh. Returns the runs.
   */
  template <class Law>
  std::vector<StaticPlasticityResult> expect_rankine_thrust_of_clay(const char *name, double cutoff)
  {
    const SoilParameters                c   = soil(5e6, 0.45, 20e3, 0, cutoff);
    const auto                          law = std::make_shared<Law>(c);
    constexpr double                    H = 2, tolerance = 0.05;
    const double                        exact = 0.5 * c.density * g * H * H + 2 * c.cohesion * H;
    std::vector<double>                 P;
    std::vector<StaticPlasticityResult> runs;
    for (const unsigned int n : {4u, 8u, 16u})
    {
      auto p    = rankine_problem(c, H, 1.0, 0.03 * H, n, 10, true, 3);
      p.laws[0] = law;
      runs.push_back(run_static_plasticity(p));
      P.push_back(rankine_thrust(name, runs.back(), n, exact));
    }
    expect_converges_from_above(P, exact, tolerance);
    return runs;
  }

  // Rankine passive thrust of clay (phi = 0, c = 20 kPa, E = 5 MPa, nu = 0.45, gravity with
  // K0 = 1 - sin 0 = 1), smooth wall H = 2 m, rough base, L = 3 H (the Rankine wedge reaches
  // H / tan 45 deg = H behind the wall). P_p = gamma H^2 / 2 + 2 c H = 113.4 kN/m; the displacement
  // FE solution converges from above; within 5 % on the finest mesh (the required tolerance).
  TEST(StaticPlasticity, RankinePassivePressureOfCohesiveSoil)
  {
    for (const auto &r :
         expect_rankine_thrust_of_clay<MohrCoulombLaw>("Rankine, phi = 0, c = 20 kPa", 1e9))
      EXPECT_LT(r.initial_out_of_balance, 1e-12);
  }

  // The same with Drucker-Prager matched to Mohr-Coulomb in plane strain (phi = 0: von Mises,
  // sqrt(J2) = c, Tresca's t = c in steady plane-strain flow).
  TEST(StaticPlasticity, RankinePassivePressureOfCohesiveSoilDruckerPrager)
  {
    expect_rankine_thrust_of_clay<DruckerPragerLaw>("Rankine, Drucker-Prager, phi = 0, c = 20 kPa",
                                                    0);
  }

  // Rankine passive thrust of sand (phi = 30 deg, c = 0, associated psi = phi, E = 20 MPa,
  // nu = 1/3 so that the elastic K0 = nu / (1 - nu) equals Jaky's 1 - sin phi = 0.5 and the
  // initial sigma_zz is K0 gamma z too), smooth wall H = 2 m on a smooth base, L = 4 H: the whole
  // backfill reaches the Rankine state, P_p = K_p gamma H^2 / 2 = 100.1 kN/m (K_p = 3). Within
  // 5 % and mesh-independent to 1 % (the Rankine zone is homogeneous in x). With a rough base
  // (a wedge from the heel) the Q1 B-bar element locks under dilatant flow: docs/validation.md.
  TEST(StaticPlasticity, RankinePassivePressureOfSand)
  {
    constexpr double     H = 2, tolerance = 0.05, mesh_spread = 0.01;
    const SoilParameters s     = soil(20e6, 1.0 / 3.0, 0, 30, 0);
    const double         k0    = 1 - std::sin(s.friction_angle);
    const double         kp    = std::pow(std::tan(pi / 4 + s.friction_angle / 2), 2);
    const double         exact = 0.5 * kp * s.density * g * H * H;
    std::vector<double>  P;
    for (const unsigned int n : {2u, 4u, 8u})
    {
      const auto r = run_static_plasticity(rankine_problem(s, H, k0, 0.03 * H, n, 10, false, 4));
      P.push_back(rankine_thrust("Rankine, phi = 30 deg, c = 0", r, n, exact));
      // Step 0: the geostatic state is in equilibrium and the wall carries K0 gamma H^2 / 2.
      EXPECT_LT(r.initial_out_of_balance, 1e-12);
      EXPECT_NEAR(r.steps.front().reactions[2][0] / (0.5 * k0 * s.density * g * H * H), 1, 1e-6);
      EXPECT_LT(std::abs(P.back() / exact - 1), tolerance);
    }
    EXPECT_LT(std::abs(P[2] / P[0] - 1), mesh_spread);
  }

  /**
   * The bearing pressures q (Pa) of the Prandtl problem with the Law of the soil c = 20 kPa
   * (E = 10 MPa, nu = 0.45, tension cut-off @p cutoff) on mesh levels 1, 1.5 and 2 converge from
   * above to q_u = (2 + pi) c, within 3 % on the finest.
   */
  template <class Law>
  void expect_prandtl_bearing_capacity(const char *name, double cutoff)
  {
    const SoilParameters c         = soil(10e6, 0.45, 20e3, 0, cutoff);
    const auto           law       = std::make_shared<Law>(c);
    constexpr double     tolerance = 0.03;
    const double         exact     = (2 + pi) * c.cohesion;
    std::vector<double>  q;
    for (const double level : {1.0, 1.5, 2.0})
    {
      const auto r = run_static_plasticity(prandtl_problem(law, level, 0.05));
      print_path(name, r, exact, 3);
      q.push_back(final_load(r, 3) / 1.0); // half-width b = 1 m
      std::printf("level %.1f: q = %.5g Pa, exact %.5g Pa, ratio %.4f\n",
                  level,
                  q.back(),
                  exact,
                  q.back() / exact);
    }
    expect_converges_from_above(q, exact, tolerance);
  }

  // Prandtl: rigid smooth strip footing on weightless Tresca soil (Mohr-Coulomb with phi = 0,
  // c = 20 kPa, E = 10 MPa, nu = 0.45, no tension cut-off), q_u = (2 + pi) c = 102.8 kPa,
  // within 3 % on the finest of three meshes, from above and monotonically.
  TEST(StaticPlasticity, PrandtlBearingCapacity)
  {
    expect_prandtl_bearing_capacity<MohrCoulombLaw>("Prandtl, Mohr-Coulomb", 1e9);
  }

  // The same with Drucker-Prager matched to Mohr-Coulomb in plane strain (phi = 0: von Mises
  // with sqrt(J2) = c, which in steady plane-strain flow is Tresca's t = c).
  TEST(StaticPlasticity, PrandtlBearingCapacityDruckerPrager)
  {
    expect_prandtl_bearing_capacity<DruckerPragerLaw>("Prandtl, Drucker-Prager", 0);
  }
} // namespace

namespace
{
  using namespace kimp::fem;

  // A step that Newton cannot finish is a NumericalError naming the load step, never a result;
  // a mesh material without a law is bad input.
  TEST(StaticPlasticity, NonConvergenceIsANumericalError)
  {
    const SoilParameters c = soil(10e6, 0.45, 20e3, 0, 1e9);
    auto                 p = prandtl_problem(std::make_shared<MohrCoulombLaw>(c), 1, 0.05);
    p.n_steps              = 1;
    p.max_iterations       = 2;
    p.max_cuts             = 0;
    try
    {
      run_static_plasticity(p);
      FAIL() << "expected NumericalError";
    }
    catch (const NumericalError &e)
    {
      EXPECT_NE(std::string(e.what()).find("load step 1"), std::string::npos) << e.what();
      EXPECT_EQ(e.step, 1u);
    }
    p.laws.clear();
    EXPECT_THROW(run_static_plasticity(p), std::invalid_argument);
  }
} // namespace
