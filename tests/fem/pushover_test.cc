// Static pushover of wall and backfill (fem/pushover.h): the bare reinforced wall against a
// Timoshenko cantilever and a section analysis; a rigid wall pushed into the backfill between
// the Rankine and Coulomb passive resultants; the reinforced wall with its backfill (IMPL-EX
// damage) between hand bounds and converging from 10 cm to 5 cm cells, monotonic and cyclic;
// the bare wall to 5 % drift under its section's ceiling on two meshes; the rotating crack
// against the fixed one's locked tension; the IMPL-EX step error; a cyclic push of the bare
// wall (permanent set, reload on the envelope); the rigid wall's unloading and reload on the fine
// mesh; the crush band in compression (energy per unit area, the bare wall on the finest mesh);
// the capacity on two mesh levels; the cells' stresses against the band's moment at every row;
// the automatic step control against bisection and a fine fixed-step push. Numbers:
// docs/validation.md "Static pushover".
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "fem/inelastic_laws.h"
#include "fem/numerical_error.h"
#include "fem/pushover.h"
#include "fem/wall_sdof.h"

namespace
{
  using namespace kimp::fem;
  constexpr double pi = 3.14159265358979323846;

  /** The bare 1.25 m x 0.25 m wall, 0.5 % vertical steel (half at each face, 50 mm cover),
   *  elastic-perfectly plastic bars; concrete tension cut to 10 % so that the section analysis
   *  (no concrete in tension) describes it. */
  PushoverParameters bare_wall(double element_size)
  {
    PushoverParameters p;
    p.with_backfill  = false;
    p.concrete       = ConcreteParameters::from_f_cm(38e6);
    p.concrete.f_ctm = 0.1 * p.concrete.f_ctm;
    p.bars.ratio_y   = 0.005;
    p.bars.hardening = 0;
    p.element_size   = element_size;
    p.path           = {0.0125};
    p.increment      = 5e-4;
    return p;
  }

  /** bare_wall() cracking as a wall does: MC2010's full tensile strength, 0.5 % bars with 1 %
   *  hardening, H = 1.50 m loaded over its top 0.2 m, pushed to 20 mm on 5 cm / 2^level cells. */
  PushoverParameters cracking_bare_wall(int level)
  {
    PushoverParameters p = bare_wall(0.05 / (1 << level));
    p.concrete           = ConcreteParameters::from_f_cm(38e6);
    p.bars.hardening     = 0.01;
    p.wall_height        = 1.5;
    p.band_top           = 1.5;
    p.band_bottom        = 1.3;
    p.path               = {0.02};
    return p;
  }

  /** A rigid wall translated into medium sand: phi = 30 deg, psi = 0, c = 1 kPa, mu = tan 20. */
  PushoverParameters rigid_wall(double element_size)
  {
    PushoverParameters p;
    p.wall                = PushoverParameters::Wall::rigid;
    p.soil.friction_angle = 30 * pi / 180;
    p.soil.cohesion       = 1e3;
    p.soil.tension_cutoff = p.soil.cohesion / std::tan(p.soil.friction_angle);
    p.friction            = std::tan(20 * pi / 180);
    p.backfill_width      = 6;
    p.element_size        = element_size;
    p.max_element_size    = 4 * element_size;
    p.path                = {0.02};
    p.increment           = 2e-3;
    return p;
  }

  /** The reinforced wall (MC2010's full tensile strength, 0.5 % bars with 1 % hardening over a
   *  hinge of t / 2) against the sand of rigid_wall() with the contact interface, on 10 cm cells.
   */
  PushoverParameters reinforced_wall_with_backfill()
  {
    PushoverParameters p = rigid_wall(0.1);
    p.wall               = PushoverParameters::Wall::reinforced;
    p.concrete           = ConcreteParameters::from_f_cm(38e6);
    p.bars.ratio_y       = 0.005;
    p.bars.hardening     = 0.01;
    p.bars.hinge_length  = 0.5 * p.wall_thickness;
    p.max_element_size   = 0.2;
    return p;
  }

  TEST(Pushover, BareWallStiffnessIsTimoshenkoAndYieldIsTheSectionsPlasticMoment)
  {
    // The implicit damage update: with IMPL-EX the knee lies 10 % above M_p / h_c at 0.1 mm
    // steps, 17 % at 0.5 mm (the extrapolated damage lags the cracks; docs/validation.md).
    PushoverParameters p    = bare_wall(0.05);
    p.implex                = false;
    const PushoverResult  r = run_pushover(p);
    const PushoverSummary s = summarise_pushover(r.curve);

    // Timoshenko cantilever under the uniform band load (load-weighted mean deflection).
    const Material concrete{p.concrete.youngs_modulus, p.concrete.poisson_ratio, 2400};
    const double   k_beam = timoshenko_band_stiffness(p.wall_height,
                                                    p.wall_thickness,
                                                    concrete,
                                                    p.band_top - p.band_bottom);
    EXPECT_NEAR(s.initial_stiffness / k_beam, 1.0, 0.05);

    // Section at the base, per metre: A_s = rho t / 2 at each face, d = t - cover, d' = cover.
    // Both layers yield in tension when the compression block is shallower than the cover
    // (checked below); block 0.85 f_cm over 0.8 x; axial force N = the wall's weight.
    const double t = p.wall_thickness, cover = p.cover, fy = p.bars.yield_stress;
    const double as = p.bars.ratio_y * t / 2, d = t - cover, d2 = cover;
    const double n = p.wall_density * p.gravity * t * p.wall_height;
    const double x = (2 * as * fy + n) / (0.85 * p.concrete.f_cm * 0.8);
    ASSERT_LT(x, d2) << "the top layer is in tension";
    const double lever_1 = d - 0.4 * x, lever_2 = d2 - 0.4 * x; // about the block's resultant
    const double m_p = as * fy * (lever_1 + lever_2) + n * (t / 2 - 0.4 * x);
    const double h_c = 0.5 * (p.band_bottom + p.band_top);
    const double f_p = m_p / h_c;
    // The yield force: the band force at the knee of the curve, a drift of 0.8 % (with the
    // rotating crack; the fixed frame's locked tension put the knee at 0.6 %). Past it the force
    // rises towards the ceiling of a compression block shrunk to the face, 68.7 kN/m, as the
    // plane-strain block is confined (docs/validation.md).
    const double f_drift = envelope_force(r.curve, 0.008 * p.wall_height);
    EXPECT_NEAR(f_drift / f_p, 1.0, 0.05);
    std::cout << "bare wall: k0 = " << s.initial_stiffness / 1e6 << " kN/mm/m, Timoshenko "
              << k_beam / 1e6 << " (ratio " << s.initial_stiffness / k_beam << "); x = " << x
              << " m, M_p = " << m_p / 1e3 << " kNm/m, M_p / h_c = " << f_p / 1e3
              << " kN/m; F at 0.6 / 0.8 / 0.99 % drift = "
              << envelope_force(r.curve, 0.006 * p.wall_height) / 1e3 << " / " << f_drift / 1e3
              << " / " << envelope_force(r.curve, 0.0099 * p.wall_height) / 1e3 << " kN/m (ratio "
              << f_drift / f_p << "); loose steps " << r.step_control.n_loose_steps << '\n';
  }

  /** Rankine (smooth wall) and Coulomb (wall friction, horizontal component) passive
   *  resultants of the backfill of @p p, N/m. */
  std::array<double, 2> passive_resultants(const PushoverParameters &p)
  {
    const double phi = p.soil.friction_angle, c = p.soil.cohesion, H = p.backfill_height;
    const double gamma = p.soil.density * p.gravity, delta = std::atan(p.friction);
    // Rankine: K_p = tan^2(45 + phi / 2); P = K_p gamma H^2 / 2 + 2 c sqrt(K_p) H.
    const double kp_r = std::pow(std::tan(pi / 4 + phi / 2), 2);
    // Coulomb (wall friction delta, vertical wall, level fill).
    const double kp_c =
      std::pow(std::cos(phi), 2) /
      (std::cos(delta) *
       std::pow(1 - std::sqrt(std::sin(phi + delta) * std::sin(phi) / std::cos(delta)), 2));
    return {{0.5 * kp_r * gamma * H * H + 2 * c * std::sqrt(kp_r) * H,
             (0.5 * kp_c * gamma * H * H + 2 * c * std::sqrt(kp_c) * H) * std::cos(delta)}};
  }

  /** M_p / h_c of the bare wall's base section (bars elastic-perfectly plastic, no concrete in
   *  tension): A_s = rho t / 2 at each face, d = t - cover, d' = cover, block 0.85 f_cm over
   *  0.8 x, axial force N = the wall's weight; both layers yield in tension when x < d'. */
  double plastic_band_force(const PushoverParameters &p)
  {
    const double t = p.wall_thickness, cover = p.cover, fy = p.bars.yield_stress;
    const double as = p.bars.ratio_y * t / 2, d = t - cover, d2 = cover;
    const double n = p.wall_density * p.gravity * t * p.wall_height;
    const double x = (2 * as * fy + n) / (0.85 * p.concrete.f_cm * 0.8);
    EXPECT_LT(x, d2) << "the top layer is in tension";
    const double m_p = as * fy * (d - 0.4 * x + d2 - 0.4 * x) + n * (t / 2 - 0.4 * x);
    return m_p / (0.5 * (p.band_bottom + p.band_top));
  }

  /** What a row of wall cells passes across its mid-height (PushoverCell): N/m and N m/m. */
  struct RowResultants
  {
    double y = 0;
    double n = 0, n_bars = 0, n_concrete_tension = 0;
    /** Moment about the wall's centre line, positive with tension at the band's face x = 0:
     *  in equilibrium with the loads (CellState::stress_moment), and of sigma_yy alone. */
    double m = 0, m_sigma_yy = 0;
    /** The bars' force in the column at the band face and in the one at the back. */
    double front_bars = 0, back_bars = 0;
    double front_bars_plastic_strain = 0;
  };

  std::map<long, RowResultants> row_resultants(const PushoverResult &r, double t)
  {
    std::map<long, RowResultants> rows;
    for (const PushoverCell &cell : r.cells)
    {
      if (!cell.in_wall)
        continue;
      const auto    &c   = cell.state;
      RowResultants &row = rows[std::lround(c.centre[1] * 1e4)];
      const double   w = c.size[0], arm = t / 2 - c.centre[0];
      const double   syy = c.stress[1], bars = c.reinforcement_stress[1];
      // The cell's own moment that the row passes (StaticPlasticityResult::CellState).
      const double own = 0.5 * (c.stress_moment[1] - c.stress_moment[0]);
      row.y            = c.centre[1];
      row.n += syy * w;
      row.n_bars += bars * w;
      row.n_concrete_tension += std::max(0.0, syy - bars) * w;
      row.m_sigma_yy += (syy * arm - own) * w;
      row.m += (syy * arm - own - c.stress_moment[3]) * w;
      if (cell.in_bars && c.centre[0] < t / 2)
      {
        row.front_bars                = bars * w;
        row.front_bars_plastic_strain = c.plastic_strain;
      }
      else if (cell.in_bars)
        row.back_bars = bars * w;
    }
    return rows;
  }

  TEST(Pushover, ReinforcedWallWithBackfillConvergesBetweenMeshesAndLiesBetweenHandBounds)
  {
    // The reinforced wall (MC2010's full tensile strength, 0.5 % bars with 1 % hardening)
    // against the sand of rigid_wall() with the contact interface and the geostatic state,
    // pushed to 5 % drift on 10 cm and 5 cm cells (IMPL-EX with its step control, rotating
    // crack). With the fixed crack frame the two meshes gave 145.0 and 120.3 kN/m (−17 %):
    // tension locked across the hinge's cracks. The bars yield over several rows of cells
    // (the moment gradient spreads the hinge), so no hinge-length scaling (L_p = 0): with
    // L_p = t / 2, which assumes one yielding row, the change is −3.2 %.
    PushoverParameters p   = reinforced_wall_with_backfill();
    p.bars.hinge_length    = 0;
    p.path                 = {0.05 * p.wall_height};
    p.increment            = 1e-3;
    double capacity[2]     = {0, 0};
    double force_at_1cm[2] = {0, 0};
    for (int level = 0; level < 2; ++level)
    {
      p.element_size          = 0.1 / (1 << level);
      const PushoverResult  r = run_pushover(p);
      const PushoverSummary s = summarise_pushover(r.curve);
      EXPECT_NEAR(r.curve.back().displacement, 0.05 * p.wall_height, 1e-9);
      EXPECT_EQ(r.step_control.n_loose_steps, 0u);
      EXPECT_EQ(r.step_control.n_large_error_steps, 0u);
      // Hand bounds at the band: the wall's plastic resistance M_p / h_c plus the backfill's.
      // From above, Coulomb's passive resultant with the wall friction taken at the band;
      // from below, the smooth-wall Rankine resultant at its own height H / 3 (the wall turns
      // about its base, so the soil resists the band force through the moment P H / 3).
      const double                f_wall  = plastic_band_force(p);
      const std::array<double, 2> passive = passive_resultants(p);
      const double                h_c     = 0.5 * (p.band_bottom + p.band_top);
      const double                lower   = f_wall + passive[0] * p.backfill_height / 3 / h_c;
      const double                upper   = f_wall + passive[1];
      EXPECT_GT(s.capacity, lower);
      EXPECT_LT(s.capacity, upper);
      EXPECT_GT(s.cracked_stiffness, 0);
      EXPECT_LT(s.cracked_stiffness, s.initial_stiffness);
      // The hinge spreads: the bars yield in several rows of cells (the reason for L_p = 0).
      std::set<long> yielded_rows;
      for (const PushoverCell &cell : r.cells)
        if (cell.in_wall && cell.state.plastic_strain > 1e-3)
          yielded_rows.insert(std::lround(cell.state.centre[1] * 1e4));
      EXPECT_GE(yielded_rows.size(), 3u);
      capacity[level]     = s.capacity;
      force_at_1cm[level] = s.force_at_1cm;
      std::cout << "reinforced wall with backfill, h = " << p.element_size * 100 << " cm: capacity "
                << s.capacity / 1e3 << " kN/m at " << s.displacement_at_capacity * 1e3
                << " mm; bounds M_p / h_c " << f_wall / 1e3 << " + Rankine " << passive[0] / 1e3
                << " at H / 3 = " << lower / 1e3 << ", + Coulomb " << passive[1] / 1e3
                << " at the band = " << upper / 1e3 << " kN/m; k0 " << s.initial_stiffness / 1e6
                << ", cracked " << s.cracked_stiffness / 1e6 << " kN/mm/m, F(1 cm) "
                << s.force_at_1cm / 1e3 << " kN/m; " << r.curve.size() - 1 << " steps, "
                << r.step_control.n_error_cuts << " halved for the IMPL-EX error; bars yielded in "
                << yielded_rows.size() << " rows\n";
    }
    EXPECT_NEAR(capacity[1] / capacity[0], 1.0, 0.03);
    EXPECT_NEAR(force_at_1cm[1] / force_at_1cm[0], 1.0, 0.03);
    std::cout << "capacity 5 cm / 10 cm: " << 100 * (capacity[1] / capacity[0] - 1)
              << " %, F(1 cm): " << 100 * (force_at_1cm[1] / force_at_1cm[0] - 1) << " %\n";
  }

  TEST(Pushover, BareWallKeepsTheSectionsPlasticForceToFivePercentDriftOnTwoMeshes)
  {
    // The bare wall of the section check (elastic-perfectly plastic bars, tension cut to 10 %)
    // pushed on to 5 % drift (IMPL-EX, 1 mm steps): its force cannot exceed what the section
    // can carry with the concrete in compression only, the bars' pull about a compression
    // block shrunk to the far face, A_s f_y (d + d') + N t / 2, over h_c. The fixed crack frame
    // locks tension across the hinge's cracks: 122.5 kN/m on 10 cm cells, 104.9 on 5 cm.
    const PushoverParameters base = bare_wall(0.1);
    const double             t = base.wall_thickness, as = base.bars.ratio_y * t / 2;
    const double             n           = base.wall_density * base.gravity * t * base.wall_height;
    const double             h_c         = 0.5 * (base.band_bottom + base.band_top);
    const double             ceiling     = (as * base.bars.yield_stress * t + n * t / 2) / h_c;
    const double             f_p         = plastic_band_force(base);
    double                   capacity[2] = {0, 0};
    for (int level = 0; level < 2; ++level)
    {
      PushoverParameters p    = bare_wall(0.1 / (1 << level));
      p.path                  = {0.05 * p.wall_height};
      p.increment             = 1e-3;
      const PushoverResult  r = run_pushover(p);
      const PushoverSummary s = summarise_pushover(r.curve);
      capacity[level]         = s.capacity;
      EXPECT_GT(s.capacity, f_p);
      EXPECT_LT(s.capacity, 1.1 * ceiling);
      // No collapse: the force at 5 % drift is still the section's.
      EXPECT_GT(r.curve.back().force, 0.95 * f_p);
      p.rotating_crack         = false;
      const double fixed_frame = summarise_pushover(run_pushover(p).curve).capacity;
      std::cout << "bare wall to 5 % drift, h = " << p.element_size * 100 << " cm: capacity "
                << s.capacity / 1e3 << " kN/m (fixed crack frame " << fixed_frame / 1e3
                << "), F(5 %) " << r.curve.back().force / 1e3 << "; M_p / h_c " << f_p / 1e3
                << ", ceiling " << ceiling / 1e3 << " kN/m\n";
    }
    EXPECT_NEAR(capacity[1] / capacity[0], 1.0, 0.07);
  }

  TEST(Pushover, CrushingKeepsItsEnergyPerUnitAreaOnEveryMesh)
  {
    // The compression curve past its peak at a point of crack band h with the crush band l_c:
    // the strain beyond eps_c1 scaled by h / l_c, so h times the post-peak energy density is
    // l_c times the local curve's (the integral's substitution), whatever h.
    ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    c.compression_band   = 0.3;
    const auto post_peak = [&](double h)
    {
      double       energy = 0;
      const double de     = 1e-7;
      for (double e = c.eps_c1; e < c.eps_c1 + (2 * c.eps_c_lim) * c.compression_band / h; e += de)
        energy += 0.5 * (c.compression_curve(e, h) + c.compression_curve(e + de, h)) * de;
      return energy * h;
    };
    double local = 0;
    for (double e = c.eps_c1; e < 2 * c.eps_c_lim; e += 1e-7)
      local += 0.5 * (c.compression_curve(e) + c.compression_curve(e + 1e-7)) * 1e-7;
    for (const double h : {0.025, 0.05, 0.1})
      EXPECT_NEAR(post_peak(h) / (local * c.compression_band), 1.0, 1e-3) << "h = " << h;
    EXPECT_EQ(c.compression_curve(0.5 * c.eps_c1, 0.025), c.compression_curve(0.5 * c.eps_c1));
    std::cout << "crushing energy per unit area: " << post_peak(0.025) / 1e3 << " kN/m at h = "
              << "2.5 cm, " << post_peak(0.1) / 1e3 << " at 10 cm (l_c times the local curve's "
              << local / 1e3 << " kJ/m^3)\n";
  }

  TEST(Pushover, BareWallHoldsItsForceToFivePercentDriftOnTheFinestMesh)
  {
    // The bare wall of the section check pushed to 5 % drift on 5 cm and 2.5 cm cells: with
    // the local compression curve the 2.5 cm toe crushes with a quarter of the 10 cm cells'
    // energy and the force falls (measured 69.4 against 47.5 kN/m); with the crush band both
    // meshes hold the section's force.
    double end_force[2] = {0, 0}, local_end = 0;
    for (int level = 0; level < 2; ++level)
    {
      PushoverParameters p = bare_wall(0.05 / (1 << level));
      p.path               = {0.05 * p.wall_height};
      p.increment          = 1e-3;
      end_force[level]     = run_pushover(p).curve.back().force;
      if (level == 1)
      {
        p.compression_band = 0;
        local_end          = run_pushover(p).curve.back().force;
      }
    }
    EXPECT_NEAR(end_force[1] / end_force[0], 1.0, 0.03);
    EXPECT_LT(local_end, 0.9 * end_force[1]); // what the crush band removes
    std::cout << "bare wall, F(5 % drift): 5 cm " << end_force[0] / 1e3 << ", 2.5 cm "
              << end_force[1] / 1e3 << " kN/m (local compression curve " << local_end / 1e3
              << ")\n";
  }

  TEST(Pushover, RotatingCrackLocksNoTensionWhereTheFixedOneDoes)
  {
    // A point cracked open along x (eps_xx = 2e-3, d_t ~ 0.99), then sheared (gamma = 2e-3):
    // the principal direction turns by 22.5 deg. The fixed crack keeps its frame and carries
    // the shear with the retention beta ~ 1 of a 0.1 mm opening, so its largest principal
    // stress is ~10 f_t; the rotating crack follows the principal direction and its damage
    // releases the tension there (largest principal stress <= f_t).
    const ConcreteParameters fixed    = ConcreteParameters::from_f_cm(38e6);
    ConcreteParameters       rotating = fixed;
    rotating.rotating_crack           = true;
    double largest[2]                 = {0, 0};
    int    k                          = 0;
    for (const ConcreteParameters &c : {fixed, rotating})
    {
      const ConcreteDamageLaw law(c, ReinforcementParameters{});
      std::vector<double>     h0(law.n_history()), h1(h0.size());
      law.initialize_point(h0.data(), 0.05);
      law.stress({{2e-3, 0, 0}}, h0.data(), h1.data());
      h0                = h1;
      const auto   s    = law.stress({{2e-3, 0, 2e-3}}, h0.data(), h1.data());
      const double mean = 0.5 * (s[0] + s[1]);
      largest[k++]      = mean + std::hypot(0.5 * (s[0] - s[1]), s[2]);
    }
    EXPECT_GT(largest[0], 3 * fixed.f_ctm);
    EXPECT_LT(largest[1], fixed.f_ctm);
    std::cout << "largest principal stress after the turn: fixed " << largest[0] / 1e6
              << " MPa, rotating " << largest[1] / 1e6 << " MPa (f_t " << fixed.f_ctm / 1e6
              << ")\n";
  }

  TEST(Pushover, ImplexStepErrorIsTheTensionTheLaggingDamageLetThrough)
  {
    // A virgin point strained in one step to 3 kappa_0 in uniaxial tension: IMPL-EX has nothing
    // to extrapolate (d_t used 0), so it lets E 3 kappa_0 = 3 f_t through where the implicit
    // update's stress is (1 - d(3 kappa_0)) 3 f_t: the error is 3 d(3 kappa_0) (in f_t) with
    // the exponential softening d = 1 - kappa_0 / kappa exp(-(kappa - kappa_0) / eps_f),
    // eps_f = G_F / (h f_t) - kappa_0 / 2. The implicit update reports no error.
    const ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    const double             h = 0.05, k0 = c.f_ctm / c.youngs_modulus, kappa = 3 * k0;
    const double             eps_f = c.fracture_energy / (h * c.f_ctm) - 0.5 * k0;
    const double             d     = 1 - k0 / kappa * std::exp(-(kappa - k0) / eps_f);
    const double             nu = c.poisson_ratio, e_xx = kappa * (1 + nu) * (1 - 2 * nu) /
                                              (1 - nu); // sigma_xx = E kappa, eps_yy = 0
    for (const auto update :
         {ConcreteDamageLaw::DamageUpdate::implex, ConcreteDamageLaw::DamageUpdate::implicit})
    {
      const ConcreteDamageLaw law(c, ReinforcementParameters{}, update);
      std::vector<double>     h0(law.n_history()), h1(h0.size());
      law.initialize_point(h0.data(), h);
      law.begin_step(h0.data(), 0.0);
      law.stress({{e_xx, 0, 0}}, h0.data(), h1.data());
      const double expected = update == ConcreteDamageLaw::DamageUpdate::implex ? 3 * d : 0.0;
      EXPECT_NEAR(law.step_error(h1.data()), expected, 1e-9);
    }
  }

  TEST(Pushover, RigidWallInSandLiesBetweenRankineAndCoulomb)
  {
    const PushoverParameters p = rigid_wall(0.05);
    const PushoverResult     r = run_pushover(p);
    const PushoverSummary    s = summarise_pushover(r.curve);
    const double phi = p.soil.friction_angle, c = p.soil.cohesion, H = p.backfill_height;
    const double gamma = p.soil.density * p.gravity, delta = std::atan(p.friction);
    // Rankine (smooth wall): K_p = tan^2(45 + phi / 2); P = K_p gamma H^2 / 2 + 2 c sqrt(K_p) H.
    const double kp_r    = std::pow(std::tan(pi / 4 + phi / 2), 2);
    const double rankine = 0.5 * kp_r * gamma * H * H + 2 * c * std::sqrt(kp_r) * H;
    // Coulomb (wall friction delta, vertical wall, level fill), horizontal component.
    const double kp_c =
      std::pow(std::cos(phi), 2) /
      (std::cos(delta) *
       std::pow(1 - std::sqrt(std::sin(phi + delta) * std::sin(phi) / std::cos(delta)), 2));
    const double coulomb =
      (0.5 * kp_c * gamma * H * H + 2 * c * std::sqrt(kp_c) * H) * std::cos(delta);
    EXPECT_GT(s.capacity, rankine);
    EXPECT_LT(s.capacity, coulomb);
    std::cout << "rigid wall: capacity " << s.capacity / 1e3 << " kN/m at "
              << s.displacement_at_capacity * 1e3 << " mm; Rankine " << rankine / 1e3
              << ", Coulomb " << coulomb / 1e3 << " kN/m; k0 = " << s.initial_stiffness / 1e6
              << " kN/mm/m, F(1 cm) = " << s.force_at_1cm / 1e3 << " kN/m\n";
  }

  TEST(Pushover, NewtonConvergesSuperlinearlyInThePlasticBackfill)
  {
    // An elastic wall pushed 5 mm into the sand of rigid_wall() (contact interface, geostatic
    // state) on 10 cm cells, with a tolerance tight enough to show Newton's rate: the passive
    // wedge is plastic from the first millimetre. Every pair of successive relative residuals
    // r_k, r_k+1 in the asymptotic range (r_k <= 1e-5, r_k+1 above the round-off floor 1e-11)
    // must contract by at least 20 times (superlinear: the ratio falls with r_k). With the
    // Newton matrix's tangent floor fixed at 1e-3 the rate was linear, r_k+1 / r_k = 0.26-0.33
    // in every such pair, and the push took 87 Newton iterations instead of 46.
    PushoverParameters p   = rigid_wall(0.1);
    p.wall                 = PushoverParameters::Wall::elastic;
    p.max_element_size     = 0.2;
    p.path                 = {0.005};
    p.increment            = 1e-3;
    p.tolerance            = 1e-10;
    p.loose_tolerance      = 1e-3;
    const PushoverResult r = run_pushover(p);
    ASSERT_NEAR(r.curve.back().displacement, 0.005, 1e-9);
    EXPECT_EQ(r.step_control.n_loose_steps, 0u);
    unsigned int n_pairs = 0, n_slow = 0;
    double       largest = 0; // the largest r_k+1 / r_k of the asymptotic pairs
    for (std::size_t k = 0; k < r.step_residuals.size(); ++k)
    {
      const std::vector<double> &res = r.step_residuals[k];
      std::cout << "step " << k + 1 << " (" << r.curve[k + 1].displacement * 1e3 << " mm):";
      for (const double x : res)
        std::cout << ' ' << x;
      std::cout << '\n';
      for (std::size_t i = 0; i + 1 < res.size(); ++i)
        if (res[i] <= 1e-5 && res[i + 1] > 1e-11 && res[i + 1] < res[i])
        {
          const double ratio = res[i + 1] / res[i];
          largest            = std::max(largest, ratio);
          ++n_pairs;
          n_slow += ratio > 0.05 ? 1 : 0;
        }
    }
    std::cout << "asymptotic pairs " << n_pairs << ", largest r_k+1 / r_k " << largest
              << ", above 0.05: " << n_slow << "; " << r.step_control.n_newton_iterations
              << " Newton iterations\n";
    EXPECT_GE(n_pairs, 3u);
    EXPECT_EQ(n_slow, 0u);
  }

  TEST(Pushover, InitialStateWithTheContactInterfaceConvergesOnTheFinestMesh)
  {
    // The shipped scene's reinforced H = 1.5 m wall against the medium-dense sand with the
    // contact interface on the study's finest cells (1.25 cm), pushed 1 mm: the initial state
    // (gravity and K0 stress) starts with every interface pair exactly at its normal kink. The
    // central difference there gave half k_N and no tangential stiffness, the first Newton
    // update let the backfill slide down the wall (a third of the pairs slipping) and the damped
    // iteration did not get back within its 40 iterations; with the closed side's springs at
    // the kink the initial state converges in a few.
    PushoverParameters p      = reinforced_wall_with_backfill();
    p.soil                    = soil_preset("medium_dense_sand");
    p.friction                = std::tan(2.0 / 3.0 * p.soil.friction_angle);
    p.wall_height             = 1.5;
    p.backfill_height         = 1.5;
    p.band_top                = 1.5;
    p.band_bottom             = 1.3;
    p.backfill_width          = 2;
    p.bars                    = {};
    p.bars.ratio_y            = 0.008;
    p.bars.ratio_x            = 0.002;
    p.bars.strain_penetration = 0.13;
    p.bars.crack_spacing      = 0.2;
    p.bars.tension_stiffening = true;
    p.element_size            = 0.0125;
    p.max_element_size        = 0.1;
    p.path                    = {0.001};
    p.increment               = 0.001;
    const PushoverResult r    = run_pushover(p);
    std::cout << "initial state with the interface, 1.25 cm: " << r.n_interface_pairs
              << " pairs, geostatic force " << r.geostatic_force << " N/m, "
              << r.step_control.n_newton_iterations << " Newton iterations in all\n";
    EXPECT_NEAR(r.curve.back().displacement, 0.001, 1e-9);
  }

  TEST(Pushover, CyclicPushLeavesASetAndReloadsOntoTheEnvelope)
  {
    // The bare wall past the yield of its bars (0.6 % drift = 7.5 mm), unloaded and reloaded.
    PushoverParameters p           = bare_wall(0.05);
    p.path                         = {0.011};
    const PushoverResult monotonic = run_pushover(p);
    p.path                         = {0.009, 0.0, 0.011};
    const PushoverResult  cyclic   = run_pushover(p);
    const PushoverSummary s        = summarise_pushover(cyclic.curve);
    ASSERT_TRUE(std::isfinite(s.permanent_set));
    // The bars yielded: a permanent set, and the unloading is stiffer than the loading secant.
    EXPECT_GT(s.permanent_set, 0.1 * s.unloaded_from);
    EXPECT_LT(s.permanent_set, s.unloaded_from);
    EXPECT_GT(s.unloading_stiffness, envelope_force(monotonic.curve, 0.009) / 0.009);
    // The reload meets the monotonic envelope at the end of the push.
    const double end_force = cyclic.curve.back().force;
    EXPECT_NEAR(end_force / envelope_force(monotonic.curve, 0.011), 1.0, 0.03);
    std::cout << "cyclic: unloaded from " << s.unloaded_from * 1e3
              << " mm, K_ur = " << s.unloading_stiffness / 1e6 << " kN/mm/m, set "
              << s.permanent_set * 1e3 << " mm; F(11 mm) cyclic " << end_force / 1e3
              << ", monotonic " << envelope_force(monotonic.curve, 0.011) / 1e3 << " kN/m\n";
  }

  TEST(Pushover, CyclicPushOfTheWallWithItsBackfillUnloadsStifferAndKeepsASet)
  {
    // The reinforced wall with its backfill of the test above, pushed to 1 cm, unloaded to
    // zero force and pushed on to 1.5 cm.
    PushoverParameters p    = reinforced_wall_with_backfill();
    p.path                  = {0.01, 0.0, 0.015};
    p.increment             = 1e-3;
    const PushoverResult  r = run_pushover(p);
    const PushoverSummary s = summarise_pushover(r.curve);
    ASSERT_TRUE(std::isfinite(s.permanent_set)) << "the unloading reaches zero force";
    const double top    = envelope_force(r.curve, s.unloaded_from);
    const double secant = top / s.unloaded_from;
    EXPECT_GT(s.unloading_stiffness, secant);
    EXPECT_GT(s.permanent_set, 0.0);
    EXPECT_LT(s.permanent_set, s.unloaded_from);
    EXPECT_NEAR(r.curve.back().displacement, 0.015, 1e-9);
    // The reload passes the force of the unloading point.
    EXPECT_GT(r.curve.back().force, top);
    std::cout << "wall with backfill cyclic: unloaded from " << s.unloaded_from * 1e3 << " mm (F "
              << top / 1e3 << " kN/m, loading secant " << secant / 1e6
              << " kN/mm/m), K_ur = " << s.unloading_stiffness / 1e6 << " kN/mm/m, set "
              << s.permanent_set * 1e3 << " mm; F(15 mm) " << r.curve.back().force / 1e3
              << " kN/m\n";
  }

  TEST(Pushover, RigidWallInSandUnloadsOnTheFineMeshAndReloads)
  {
    // The rigid wall of the test above on 5 cm cells, pushed to 1 cm, unloaded to zero force
    // and pushed on to 1.5 cm. The soil unloads elastically, so the unloading starts at about
    // the initial (elastic) stiffness; the passive wedge's plastic strain leaves a set; and the
    // wall never pulls: the force beyond the at-rest state falls to zero before the soil's
    // thrust would (the active state lies below the at-rest one). Newton used to stall
    // mid-unloading here (a singular tangent: soil at its yield surface's apex next to open
    // interface pairs).
    // The first unloading step is 0.25 mm (path entry 9.75 mm): its secant is the unloading's
    // initial stiffness whatever halvings the step control makes after it.
    PushoverParameters p    = rigid_wall(0.05);
    p.path                  = {0.01, 0.00975, 0.0, 0.015};
    p.increment             = 1e-3;
    const PushoverResult  r = run_pushover(p);
    const PushoverSummary s = summarise_pushover(r.curve);
    ASSERT_TRUE(std::isfinite(s.permanent_set)) << "the unloading reaches zero force";
    EXPECT_GT(s.permanent_set, 0.0);
    EXPECT_LT(s.permanent_set, s.unloaded_from);
    // The first unloading step's secant against the initial stiffness.
    std::size_t first = 0;
    while (!r.curve[first].unloading)
      ++first;
    const PushoverPoint &top = r.curve[first - 1], &next = r.curve[first];
    const double k_unload = (top.force - next.force) / (top.displacement - next.displacement);
    EXPECT_NEAR(k_unload / s.initial_stiffness, 1.0, 0.2);
    EXPECT_GT(s.unloading_stiffness, top.force / top.displacement); // stiffer than the loading
    double lowest = 0;
    for (const PushoverPoint &point : r.curve)
      lowest = std::min(lowest, point.force);
    EXPECT_GT(lowest + r.geostatic_force, 0.0) << "the wall pulls on the soil";
    // The reload climbs back onto the plateau.
    EXPECT_NEAR(r.curve.back().displacement, 0.015, 1e-9);
    EXPECT_NEAR(r.curve.back().force / envelope_force(r.curve, s.unloaded_from), 1.0, 0.03);
    std::cout << "rigid wall, 5 cm, cyclic: unloaded from " << s.unloaded_from * 1e3 << " mm (F "
              << top.force / 1e3 << " kN/m), first unloading step " << k_unload / 1e6
              << " kN/mm/m against k0 " << s.initial_stiffness / 1e6 << ", secant to zero "
              << s.unloading_stiffness / 1e6 << " kN/mm/m, set " << s.permanent_set * 1e3
              << " mm; lowest force " << lowest / 1e3 << " kN/m (at rest "
              << r.geostatic_force / 1e3 << "); F(15 mm) " << r.curve.back().force / 1e3
              << " kN/m; " << r.curve.size() - 1 << " steps\n";
  }

  TEST(Pushover, CapacityConvergesBetweenTwoMeshLevels)
  {
    double capacity[2];
    for (int level = 0; level < 2; ++level)
      capacity[level] =
        summarise_pushover(run_pushover(rigid_wall(0.1 / (1 << level))).curve).capacity;
    EXPECT_NEAR(capacity[1] / capacity[0], 1.0, 0.03);
    std::cout << "capacity h = 10 cm: " << capacity[0] / 1e3 << " kN/m, 5 cm: " << capacity[1] / 1e3
              << " kN/m (" << 100 * (capacity[1] / capacity[0] - 1) << " %)\n";
  }

  TEST(Pushover, HingeLengthMakesTheBarsPostYieldForceThatOfTheHinge)
  {
    // A point of crack band h stretched along y past the bars' yield: with L_p, its bar stress
    // is that of a hinge of length L_p carrying the same plastic elongation eps_p h, i.e. it
    // hardens with H h / L_p (closed form of the linear kinematic hardening bar).
    const ConcreteParameters c = ConcreteParameters::from_f_cm(38e6);
    ReinforcementParameters  r;
    r.ratio_y                     = 0.01;
    r.hardening                   = 0.05;
    r.hinge_length                = 0.2;
    ReinforcementParameters plain = r;
    plain.hinge_length            = 0;
    const ConcreteDamageLaw with_hinge(c, r), without(c, plain);
    const double            eps = 5 * r.yield_stress / r.youngs_modulus;
    for (const double h : {0.025, 0.05, 0.1})
    {
      std::vector<double> h0(with_hinge.n_history()), h1(h0.size()), g0(h0), g1(h0);
      with_hinge.initialize_point(h0.data(), h);
      without.initialize_point(g0.data(), h);
      const double d_sigma = with_hinge.stress({{0, eps, 0}}, h0.data(), h1.data())[1] -
                             without.stress({{0, eps, 0}}, g0.data(), g1.data())[1];
      const auto bar = [&](double H)
      {
        const double Es = r.youngs_modulus, ep = (Es * eps - r.yield_stress) / (Es + H);
        return r.yield_stress + H * ep;
      };
      const double H = r.hardening_modulus();
      EXPECT_NEAR(d_sigma,
                  r.ratio_y * (bar(H * h / r.hinge_length) - bar(H)),
                  1e-6 * r.yield_stress)
        << "h = " << h;
    }
  }

  // Strain penetration (ReinforcementParameters::strain_penetration): the bars of the base row
  // slip out of the clamped base by s = sigma_s L_sp / E_s. The bare wall keeps its section's
  // plastic force, and at half of it moves further by the rotation the tension bars'
  // slip gives the base, s / (d - x) with x the cracked elastic section's neutral axis, times
  // the band's height (no concrete in tension, the whole base turning as a plane). The wall
  // moves 0.59 of that hand value (0.83 against 1.39 mm); why it moves less was not separated
  // (the concrete's residual tension, the slip of the top layer, the neutral axis of the FE
  // section are candidates). The test holds it to 0.4-1.0 of it, well away from the 0 of a base
  // whose bars did not slip.
  TEST(Pushover, StrainPenetrationTurnsTheBaseByTheBarsSlipAndKeepsTheCapacity)
  {
    PushoverParameters bonded = bare_wall(0.05), anchored = bare_wall(0.05);
    bonded.implex = anchored.implex  = false;
    anchored.bars.strain_penetration = 0.13;
    const PushoverResult rb = run_pushover(bonded), ra = run_pushover(anchored);
    const double         t = bonded.wall_thickness, cover = bonded.cover;
    const double         d = t - cover, as = bonded.bars.ratio_y * t / 2;
    const double         es = bonded.bars.youngs_modulus, n = es / bonded.concrete.youngs_modulus;
    // Cracked elastic section per metre: concrete above the neutral axis x, the layers at d
    // and d' transformed by n. From the first moment about x, both layers in tension (x < d'):
    // x^2 / 2 + 2 n A_s x - n A_s (d + d') = 0.
    const double x = -2 * n * as + std::sqrt(4 * n * n * as * as + 2 * n * as * (d + cover));
    ASSERT_LT(x, cover) << "the top layer is in tension";
    const double i_cr =
      x * x * x / 3 + n * as * (cover - x) * (cover - x) + n * as * (d - x) * (d - x);
    const double h_c = 0.5 * (bonded.band_bottom + bonded.band_top);
    const double f_p = plastic_band_force(bonded);
    // Displacement where the envelope first reaches force f (linear between points).
    const auto at_force = [](const std::vector<PushoverPoint> &curve, double f)
    {
      for (std::size_t i = 1; i < curve.size(); ++i)
        if (curve[i].force >= f)
          return curve[i - 1].displacement + (f - curve[i - 1].force) /
                                               (curve[i].force - curve[i - 1].force) *
                                               (curve[i].displacement - curve[i - 1].displacement);
      return -1.0;
    };
    const double f       = 0.5 * f_p;
    const double sigma_s = n * f * h_c * (d - x) / i_cr;
    const double slip    = sigma_s * anchored.bars.strain_penetration / es;
    const double extra   = slip / (d - x) * h_c;
    const double moved   = at_force(ra.curve, f) - at_force(rb.curve, f);
    ASSERT_GT(at_force(rb.curve, f), 0);
    EXPECT_GT(moved / extra, 0.4);
    EXPECT_LT(moved / extra, 1.0);
    const double fb = envelope_force(rb.curve, 0.012), fa = envelope_force(ra.curve, 0.012);
    EXPECT_NEAR(fa / fb, 1.0, 0.05);
    EXPECT_NEAR(fa / f_p, 1.0, 0.1);
    std::cout << "strain penetration 0.13 m: at M_p / (2 h_c) = " << f / 1e3 << " kN/m the wall "
              << "moves " << moved * 1e3 << " mm further (hand: bar stress " << sigma_s / 1e6
              << " MPa, slip " << slip * 1e3 << " mm, x = " << x * 1e3 << " mm, " << extra * 1e3
              << " mm); force at 12 mm " << fa / 1e3 << " against " << fb / 1e3
              << " kN/m bonded, M_p / h_c = " << f_p / 1e3 << " kN/m\n";
  }

  // The bars' crack spacing (ReinforcementParameters::crack_spacing): the bare wall with
  // MC2010's full tensile strength, 0.5 % bars with 1 % hardening, pushed to 20 mm on 5 and
  // 2.5 cm cells. With the crack band the finer mesh's cracked rows carry tension to twice the
  // strain (G_F / (h f_t)), so its force past cracking is the higher (+9 % at 10 mm at
  // H = 1.50 m); with s_rm = 0.2 m every mesh's cracked concrete softens alike and the forces
  // at 10 and 20 mm agree to 3 %.
  TEST(Pushover, CrackSpacingMakesTheCrackedWallsForceTheSameOnTwoMeshes)
  {
    double force[2][2][2] = {}; // [spacing off/on][level][10 mm, 20 mm]
    for (int on = 0; on < 2; ++on)
      for (int level = 0; level < 2; ++level)
      {
        PushoverParameters p   = cracking_bare_wall(level);
        p.bars.crack_spacing   = on ? 0.2 : 0.0;
        const PushoverResult r = run_pushover(p);
        force[on][level][0]    = envelope_force(r.curve, 0.01);
        force[on][level][1]    = envelope_force(r.curve, 0.02);
        std::cout << "bare wall, crack spacing " << (on ? "0.2 m" : "off") << ", "
                  << p.element_size * 100 << " cm: F(10 mm) " << force[on][level][0] / 1e3
                  << ", F(20 mm) " << force[on][level][1] / 1e3 << " kN/m\n";
      }
    EXPECT_GT(force[0][1][0] / force[0][0][0], 1.04) << "the crack band's finer rows are stiffer";
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(force[1][1][i] / force[1][0][i], 1.0, 0.03) << (i ? "20 mm" : "10 mm");
  }

  // Tension stiffening (ReinforcementParameters::tension_stiffening) on the wall of
  // CrackSpacingMakesTheCrackedWallsForceTheSameOnTwoMeshes (s_rm = 0.2 m): the concrete between
  // the cracks keeps f_t / (1 + sqrt(500 eps)), so the cracked wall is stiffer than its bars
  // alone (+26 % at 5 mm: 52.57 against 41.59 kN/m), nearly the same on 5 and 2.5 cm cells
  // (-3.1 %, -2.1 %, -3.1 % at 5, 10, 20 mm; held to 4 %). Past the bars' yield the force at
  // 20 mm is 6.4 % above the bars alone (9.1 % above M_p / h_c), held to 10 %. It is not
  // concrete tension at the base (under 0.1 kN/m there): the rows above it keep their concrete's
  // tension, so the hinge turns in fewer rows, the base's back bar layer yields (305 against
  // 228 kN/m) and its front bars harden further (CellStressesBalanceTheBandAndShowWhere-
  // TensionStiffeningAddsForce). Part of it is the point check's: each point checks its own
  // strain, not the section's bars at the crack, so rows whose moment exceeds the cracked
  // section's yield moment (y < 0.35 m) keep tension their bars could not carry at a crack.
  TEST(Pushover, TensionStiffeningStiffensTheCrackedWallAlikeOnTwoMeshes)
  {
    const auto push = [](int level, bool stiffening)
    {
      PushoverParameters p      = cracking_bare_wall(level);
      p.bars.crack_spacing      = 0.2;
      p.bars.tension_stiffening = stiffening;
      const PushoverResult r    = run_pushover(p);
      std::cout << "bare wall, s_rm 0.2 m, tension stiffening " << (stiffening ? "on" : "off")
                << ", " << p.element_size * 100 << " cm: F(5 mm) "
                << envelope_force(r.curve, 0.005) / 1e3 << ", F(10 mm) "
                << envelope_force(r.curve, 0.01) / 1e3 << ", F(20 mm) "
                << envelope_force(r.curve, 0.02) / 1e3 << " kN/m; M_p / h_c "
                << plastic_band_force(p) / 1e3 << " kN/m\n";
      return std::pair{r, plastic_band_force(p)};
    };
    const auto [bars_alone, f_p] = push(0, false);
    const auto [coarse, f_p0]    = push(0, true);
    const auto [fine, f_p1]      = push(1, true);
    EXPECT_GT(envelope_force(coarse.curve, 0.005) / envelope_force(bars_alone.curve, 0.005), 1.1);
    for (const double u : {0.005, 0.01, 0.02})
      EXPECT_NEAR(envelope_force(fine.curve, u) / envelope_force(coarse.curve, u), 1.0, 0.04)
        << "at " << u * 1e3 << " mm";
    const double past_yield =
      envelope_force(coarse.curve, 0.02) / envelope_force(bars_alone.curve, 0.02);
    EXPECT_GT(past_yield, 1.0);
    EXPECT_LT(past_yield, 1.1);
    EXPECT_NEAR(envelope_force(coarse.curve, 0.02) / f_p, 1.0, 0.12);
  }

  // The cells' stresses (PushoverCell) of the wall of TensionStiffeningStiffensTheCrackedWall-
  // AlikeOnTwoMeshes at 20 mm on 5 cm cells, with and without tension stiffening. Every row of
  // cells passes the band's moment F (h_c - y) and the weight above it (to round-off; sigma_yy
  // alone: 3.6 % and 4.2 % short at the base row, the rest a shear couple of the bilinear
  // cells). The base row's tension is all in the bars (its concrete: under 0.1 kN/m); with
  // tension stiffening the back layer (50 mm from the compression face) has yielded there
  // (305 against 228 kN/m, A_s f_y = 312.5 kN/m) and the front bars harden further (plastic
  // strain 10.6e-3 against 4.8e-3): the concrete of the rows above the base, 0.2-0.5 m, keeps
  // 155-360 kN/m of tension and holds their bars below yield (201 against 487 MPa at 0.275 m),
  // so the bars yield up to y = 0.2 m instead of 0.3 m (docs/physics.md §6 "Tension
  // stiffening").
  TEST(Pushover, CellStressesBalanceTheBandAndShowWhereTensionStiffeningAddsForce)
  {
    std::map<long, RowResultants> rows[2];
    for (int on = 0; on < 2; ++on)
    {
      PushoverParameters p      = cracking_bare_wall(0);
      p.bars.crack_spacing      = 0.2;
      p.bars.tension_stiffening = on;
      const PushoverResult r    = run_pushover(p);
      const double         f = r.curve.back().force, h_c = 0.5 * (p.band_bottom + p.band_top);
      const double         t = p.wall_thickness, weight = p.wall_density * p.gravity * t;
      ASSERT_NEAR(r.curve.back().displacement, 0.02, 1e-9);
      rows[on] = row_resultants(r, t);
      for (const auto &[key, row] : rows[on])
        if (row.y < p.band_bottom)
        {
          EXPECT_NEAR(row.m / (f * (h_c - row.y)), 1.0, 1e-3) << "row at y = " << row.y;
          EXPECT_NEAR(row.n, -weight * (p.wall_height - row.y), 0.01 * weight) << row.y;
        }
      const RowResultants &base = rows[on].begin()->second;
      const double         a_fy = p.bars.ratio_y * t / 2 * p.bars.yield_stress;
      EXPECT_GT(base.m_sigma_yy / base.m, 0.95);
      EXPECT_LT(base.m_sigma_yy / base.m, 0.98);
      EXPECT_LT(base.n_concrete_tension, 1e-3 * base.n_bars) << "the bars carry the base";
      EXPECT_GT(base.front_bars, a_fy);
      EXPECT_GT(base.back_bars, on ? 0.95 * a_fy : 0.6 * a_fy);
      EXPECT_LT(base.back_bars, on ? 1.05 * a_fy : 0.8 * a_fy);
      std::cout << "tension stiffening " << (on ? "on" : "off")
                << ", base row: M = " << base.m / 1e3 << " kN m/m (sigma_yy "
                << base.m_sigma_yy / 1e3 << "), bars " << base.front_bars / 1e3 << " + "
                << base.back_bars / 1e3 << " kN/m, concrete tension "
                << base.n_concrete_tension / 1e3 << " kN/m\n";
    }
    // Where the hinge stops: the row at y = 0.275 m.
    const RowResultants &off = rows[0].at(2750), &on = rows[1].at(2750);
    EXPECT_GT(off.front_bars_plastic_strain, 0);
    EXPECT_EQ(on.front_bars_plastic_strain, 0);
    EXPECT_GT(on.n_concrete_tension, 200e3);
    EXPECT_LT(off.n_concrete_tension, 50e3);
  }

  // The automatic step control (docs/physics.md §6 "Static pushover", "Steps"): a push whose
  // Newton iteration cannot finish a step cuts it below what bisection reaches and grows it back
  // after easy steps. The scene: the reinforced wall with its backfill on 10 cm cells (L_p = 0),
  // pushed to 5 % of H in steps of at most 8 mm with 10 Newton iterations per attempt: the first
  // cracks then need steps below 1 mm (increment / 8, the bisection's three halvings), as the
  // 1.25 cm mesh's do below 0.125 mm at 1 mm steps and 40 iterations.
  TEST(Pushover, StepControlCutsBelowTheBisectionAndMatchesAFineFixedStepPush)
  {
    PushoverParameters p    = reinforced_wall_with_backfill();
    p.bars.hinge_length     = 0;
    p.path                  = {0.05 * p.wall_height};
    PushoverParameters hard = p;
    hard.increment          = 8e-3;
    hard.max_iterations     = 10;

    PushoverParameters fixed = hard; // no halving at all
    fixed.min_increment      = fixed.increment;
    EXPECT_THROW(run_pushover(fixed), NumericalError);
    PushoverParameters bisection = hard; // three halvings, back to 8 mm after them
    bisection.min_increment      = bisection.increment / 8;
    bisection.grow_after         = 0;
    EXPECT_THROW(run_pushover(bisection), NumericalError);

    const PushoverResult  controlled = run_pushover(hard); // the defaults: 20 um, grow after 2
    const PushoverSummary c          = summarise_pushover(controlled.curve);
    PushoverParameters    fine       = p; // 0.25 mm steps, never halved, 40 iterations
    fine.increment                   = 2.5e-4;
    fine.min_increment               = fine.increment;
    const PushoverResult  reference  = run_pushover(fine);
    const PushoverSummary f          = summarise_pushover(reference.curve);

    ASSERT_NEAR(controlled.curve.back().displacement, 0.05 * p.wall_height, 1e-9);
    EXPECT_GT(controlled.step_control.n_newton_cuts, 0u);
    EXPECT_LT(controlled.smallest_increment, hard.increment / 8);
    // Grown back: far fewer steps than the smallest step would take.
    EXPECT_LT(controlled.curve.size(), 0.05 * p.wall_height / controlled.smallest_increment / 2);
    EXPECT_EQ(controlled.step_control.n_loose_steps, 0u);
    EXPECT_NEAR(c.capacity / f.capacity, 1.0, 0.03);
    EXPECT_NEAR(c.force_at_1cm / f.force_at_1cm, 1.0, 0.02);
    for (const double u : {0.005, 0.02, 0.04})
      EXPECT_NEAR(envelope_force(controlled.curve, u) / envelope_force(reference.curve, u),
                  1.0,
                  0.02)
        << "at " << u * 1e3 << " mm";
    std::cout << "step control (8 mm, 10 iterations): " << controlled.curve.size() - 1 << " steps, "
              << controlled.step_control.n_newton_cuts << " halved for Newton, smallest "
              << controlled.smallest_increment * 1e3 << " mm, "
              << controlled.step_control.n_newton_iterations << " iterations; capacity "
              << c.capacity / 1e3 << " kN/m, at 1 cm " << c.force_at_1cm / 1e3
              << ", at 5 / 20 / 40 mm " << envelope_force(controlled.curve, 0.005) / 1e3 << " / "
              << envelope_force(controlled.curve, 0.02) / 1e3 << " / "
              << envelope_force(controlled.curve, 0.04) / 1e3
              << " kN/m; fixed 0.25 mm steps: " << reference.curve.size() - 1 << " steps, capacity "
              << f.capacity / 1e3 << " kN/m, at 1 cm " << f.force_at_1cm / 1e3
              << ", at 5 / 20 / 40 mm " << envelope_force(reference.curve, 0.005) / 1e3 << " / "
              << envelope_force(reference.curve, 0.02) / 1e3 << " / "
              << envelope_force(reference.curve, 0.04) / 1e3 << " kN/m (ratio capacity "
              << c.capacity / f.capacity << ", at 1 cm " << c.force_at_1cm / f.force_at_1cm
              << ")\n";
  }

  TEST(Pushover, RefusesBadParameters)
  {
    PushoverParameters p = bare_wall(0.05);
    p.band_top           = 2.0;
    EXPECT_THROW(run_pushover(p), std::invalid_argument);
    p      = bare_wall(0.05);
    p.path = {};
    EXPECT_THROW(run_pushover(p), std::invalid_argument);
    p               = bare_wall(0.05);
    p.min_increment = 2 * p.increment;
    EXPECT_THROW(run_pushover(p), std::invalid_argument);
    p.min_increment = 0;
    EXPECT_THROW(run_pushover(p), std::invalid_argument);
  }
} // namespace
