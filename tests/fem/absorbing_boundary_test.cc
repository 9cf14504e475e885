// Lysmer-Kuhlemeyer absorbing boundary (fem::ImpactParameters::absorbing_boundaries): plane P and
// S pulses through soil columns reflect almost nothing at the dashpots and everything at a fixed
// end; the viscous-spring boundary's springs pull a bar back at the continuum's rate; energy
// balance with the radiated and the springs' energy; 1 vs 2 MPI ranks (Mpi.*).
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <string>

#include "tests/fem/impact_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  /** Largest energy fraction an absorbing end may send back (plane wave, normal incidence). */
  constexpr double max_absorbed_reflection = 0.05;
  /** A fixed end sends back the whole pulse: only the time-integration error is missing. */
  constexpr double min_fixed_reflection = 0.95;
  /** Energy balance E_kin + E_strain - W_contact + E_radiated = E_0. */
  constexpr double energy_tolerance = 0.01;

  double s_wave_speed(const Material &m)
  {
    return std::sqrt(m.youngs_modulus / (2 * (1 + m.poisson_ratio)) / m.density);
  }

  /** The index of the history sample nearest to time t. */
  std::size_t sample_at(const ImpactResult &r, double t)
  {
    const auto &time = r.history.time;
    std::size_t best = 0;
    for (std::size_t i = 0; i < time.size(); ++i)
      if (std::abs(time[i] - t) < std::abs(time[best] - t))
        best = i;
    return best;
  }

  /** Kinetic + strain energy at the sample nearest to time t, over E_0 (the initial kinetic). */
  double energy_left(const ImpactResult &r, double t)
  {
    const auto       &h = r.history;
    const std::size_t i = sample_at(r, t);
    return (h.kinetic[i] + h.strain[i]) / h.kinetic.front();
  }

  constexpr double h_cell      = 0.025; // m, element size of the columns
  constexpr double width       = 2 * h_cell;
  constexpr double dummy_gap   = 0.1; // m: the contact that run_impact() requires, never touched
  constexpr double dummy_width = 0.1;

  /** Cells of size h_cell along a column length. */
  unsigned int cells(double length)
  {
    return static_cast<unsigned int>(std::lround(length / h_cell));
  }

  /** The sides of the soil and slab blocks of a column: rollers (u_x = 0). */
  constexpr unsigned int rollers = ids::soil_far_side;

  /**
   * A block of a column: [a0, a1] along it (y if @p along_y, else x) in n cells and
   * [0, width] across it in 2 cells; @p low and @p high the ids of its ends at a0 and a1,
   * @p sides the id of its sides.
   */
  Block column_block(bool         along_y,
                     double       a0,
                     double       a1,
                     unsigned int n,
                     unsigned int material,
                     unsigned int low,
                     unsigned int high,
                     unsigned int sides)
  {
    return along_y ? Block{0, width, a0, a1, 2, n, material, sides, sides, low, high} :
                     Block{a0, a1, 0, width, n, 2, material, low, high, sides, sides};
  }

  /**
   * A soil column of mesh @p file: soil, slab and dummy blocks all of soil, the slab started at
   * v in +y, no contact ever starting (the run goes to end_time), sampled every 0.1 ms.
   */
  ImpactParameters column_parameters(const std::filesystem::path &file)
  {
    ImpactParameters p;
    p.mesh_file = file;
    for (const unsigned int material : {ids::soil_material, ids::slab_material, ids::wall_material})
      p.materials[material] = soil;
    p.initial_velocity_along_y = true;
    p.separation_hold_time     = 1; // s: no contact ever starts; run to end_time
    p.output_interval          = 1e-4;
    return p;
  }

  /**
   * P-wave column along y: soil [0, w] x [0, L], a bonded slab-material segment [L, L + L_s] on
   * top that starts at v in +y (initial_velocity_along_y), sides on rollers (u_x = 0), base
   * fixed_base; a free dummy block above to satisfy the contact setup.
   */
  ImpactParameters p_column(double L, double L_s, const std::string &name)
  {
    const double top = L + L_s, dummy = top + dummy_gap, dummy_end = dummy + dummy_width;
    return column_parameters(write_blocks(
      {column_block(true, 0, L, cells(L), ids::soil_material, ids::fixed_base, 0, rollers),
       column_block(true, L, top, cells(L_s), ids::slab_material, 0, ids::slab_contact, rollers),
       column_block(true, dummy, dummy_end, 4, ids::wall_material, ids::wall_contact, 0, 0)},
      name));
  }

  /**
   * S-wave column along x: soil [0, L] x [0, w], a bonded slab-material segment [-L_s, 0] that
   * starts at v in +y, top and bottom on rollers (u_x = 0: the shear traction of a plane S-wave
   * is carried), right end fixed_base; a free dummy block on the left.
   */
  ImpactParameters s_column(double L, double L_s, const std::string &name)
  {
    const double dummy_end = -L_s - dummy_gap, dummy = dummy_end - dummy_width;
    return column_parameters(write_blocks(
      {column_block(false, 0, L, cells(L), ids::soil_material, 0, ids::fixed_base, rollers),
       column_block(false, -L_s, 0, cells(L_s), ids::slab_material, ids::slab_contact, 0, rollers),
       column_block(false, dummy, dummy_end, 4, ids::wall_material, 0, ids::wall_contact, 0)},
      name));
  }

  /** A run with the end @p end fixed and one with @p end absorbing, measured at t_measure. */
  struct FixedAndAbsorbing
  {
    ImpactResult fixed, absorbed;
    double       r_fixed, r_abs; ///< energy_left() at t_measure
  };

  FixedAndAbsorbing
  run_fixed_and_absorbing(ImpactParameters p, unsigned int end, double t_measure, const char *what)
  {
    p.end_time = t_measure;
    FixedAndAbsorbing runs;
    runs.fixed             = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.absorbing_boundaries = {end};
    runs.absorbed          = run_impact(p, MPI_COMM_WORLD, nullptr);
    runs.r_fixed           = energy_left(runs.fixed, t_measure);
    runs.r_abs             = energy_left(runs.absorbed, t_measure);
    if (rank() == 0)
      std::cout << what << " (t = " << t_measure * 1e3 << " ms): energy left with the end fixed "
                << runs.r_fixed << ", absorbing " << runs.r_abs << ", radiated "
                << runs.absorbed.summary.radiated_energy / runs.absorbed.history.kinetic.front()
                << ", |dE/E0| " << runs.absorbed.summary.energy_error << '\n';
    return runs;
  }

  /** The absorbing end sends back almost nothing, the fixed one almost all; the balance closes. */
  void expect_absorbed(const FixedAndAbsorbing &runs)
  {
    EXPECT_LT(runs.r_abs, max_absorbed_reflection);
    EXPECT_GT(runs.r_fixed, min_fixed_reflection);
    EXPECT_LT(runs.absorbed.summary.energy_error, energy_tolerance);
  }

  TEST(AbsorbingBoundary, PlanePWaveLeavesThroughTheBaseAndReflectsFromAFixedOne)
  {
    // A velocity pulse of length 2 L_s (v/2 in both halves) runs down the column; the train's
    // tail passes the base at (L + 2 L_s) / c_p, a reflected front would reach the top at
    // (2 L + L_s) / c_p. Measure between the two.
    const double L = 4.0, L_s = 0.5, c = p_wave_speed(soil);
    const double t_measure = 0.5 * ((L + 2 * L_s) / c + (2 * L + L_s) / c);
    for (const auto integrator : {ImpactParameters::Integrator::explicit_central_difference,
                                  ImpactParameters::Integrator::implicit_newmark})
    {
      auto p       = p_column(L, L_s, "p_column.msh");
      p.integrator = integrator;
      const auto runs =
        run_fixed_and_absorbing(p,
                                ids::fixed_base,
                                t_measure,
                                integrator == ImpactParameters::Integrator::implicit_newmark ?
                                  "implicit P-wave column" :
                                  "explicit P-wave column");
      expect_absorbed(runs);
      const double e0 = runs.absorbed.history.kinetic.front();
      EXPECT_NEAR(runs.absorbed.summary.radiated_energy / e0, 1 - runs.r_abs, energy_tolerance);
      EXPECT_EQ(runs.fixed.summary.radiated_energy, 0);
      EXPECT_TRUE(runs.fixed.history.radiation.empty());
    }
  }

  TEST(AbsorbingBoundary, PlaneSWaveLeavesThroughTheTangentialDashpot)
  {
    const double L = 3.0, L_s = 0.25, c = s_wave_speed(soil);
    const double t_measure = 0.5 * ((L + 2 * L_s) / c + (2 * L + L_s) / c);
    expect_absorbed(run_fixed_and_absorbing(s_column(L, L_s, "s_column.msh"),
                                            ids::fixed_base,
                                            t_measure,
                                            "S-wave column"));
  }

  TEST(AbsorbingBoundary, ImpactPWaveLeavesThroughTheFarSide)
  {
    // The real contact: a slab bar strikes a soil bar (nu = 0: a free-sided bar is exactly 1D)
    // whose far end is soil_far_side: rollers (u_x = 0, a fixed end for this wave) or dashpots.
    const Material   bar{50e6, 0.0, 1900};
    const double     L = 4.0, L_s = 0.5, t = 0.05, c = p_wave_speed(bar);
    const double     t_measure = 0.5 * ((L + 2 * L_s) / c + (2 * L) / c);
    ImpactParameters p;
    p.mesh_file = write_blocks(
      {{-0.5e-3 - L_s, -0.5e-3, 0, t, 20, 2, ids::slab_material, 0, ids::slab_contact, 0, 0},
       {0, L, 0, t, 160, 2, ids::soil_material, ids::wall_contact, ids::soil_far_side, 0, 0}},
      "far_bar.msh");
    p.materials[ids::slab_material] = bar;
    p.materials[ids::soil_material] = bar;
    p.separation_hold_time          = 1;
    p.output_interval               = 1e-4;
    expect_absorbed(run_fixed_and_absorbing(p,
                                            ids::soil_far_side,
                                            t_measure,
                                            "impact P-wave through the far side (rollers)"));
  }

  /** The slab's mean x displacement at the sample nearest to time t. */
  double slab_at(const ImpactResult &r, double t)
  {
    return r.history.slab_displacement[sample_at(r, t)];
  }

  TEST(AbsorbingBoundary, ViscousSpringBoundaryPullsABarBackAtTheContinuumsRate)
  {
    // A bar (nu = 0: exactly 1D) of slab [-L_s, 0] bonded to soil [0, L], free at -L_s, its end
    // x = L on dashpots C = rho c w and springs K = alpha_n G w / R (R from the end's face
    // midpoints to the centre of a far dummy wall face, which the slab never reaches). The slab
    // starts at v in +x. Once the pulse has left through the dashpot, the bar's displacement is
    // the slowest mode u = cosh(s x / c) e^(s t) of the free-ended bar (x from the free end):
    // at the end E w u' + C u_t + K u = 0 with E w / c = C gives, for s = -lambda,
    // K = C lambda (1 - tanh(lambda L_t / c)). The dashpots alone hold the displacement the
    // pulse left (lambda = 0).
    const Material   bar{50e6, 0.0, 1900};
    const double     L = 0.5, L_s = 0.1, w = 0.05, gap = 5.4, c = p_wave_speed(bar), L_t = L + L_s;
    const double     d = L_s + gap + L; // x distance from the dummy face to the bar's end
    ImpactParameters p;
    p.mesh_file =
      write_blocks({{-L_s, 0, 0, w, cells(L_s), 2, ids::slab_material, ids::slab_contact, 0, 0, 0},
                    {0, L, 0, w, cells(L), 2, ids::soil_material, 0, ids::soil_far_side, 0, 0},
                    {-L_s - gap - dummy_width,
                     -L_s - gap,
                     0,
                     w,
                     4,
                     2,
                     ids::wall_material,
                     0,
                     ids::wall_contact,
                     0,
                     0}},
                   "spring_bar.msh");
    for (const unsigned int material : {ids::soil_material, ids::slab_material, ids::wall_material})
      p.materials[material] = bar;
    p.separation_hold_time       = 1; // s: no contact ever starts; run to end_time
    p.output_interval            = 1e-4;
    p.end_time                   = 0.16;
    p.absorbing_boundaries       = {ids::soil_far_side};
    const ImpactResult dashpots  = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.boundary_spring_normal     = 1.0;
    p.boundary_spring_tangential = 0.5;
    const ImpactResult springs   = run_impact(p, MPI_COMM_WORLD, nullptr);

    const double g = bar.youngs_modulus / 2, r = std::hypot(d, w / 4);
    const double k = g * w / r, damper = bar.density * c * w;
    double       lo = 0, hi = 2 * k / damper; // K - C l (1 - tanh(l L_t / c)) changes sign
    for (int i = 0; i < 100; ++i)
    {
      const double mid                                                  = 0.5 * (lo + hi);
      (k - damper * mid * (1 - std::tanh(mid * L_t / c)) > 0 ? lo : hi) = mid;
    }
    const double lambda = 0.5 * (lo + hi);
    const double t1 = 0.03, t2 = 0.15; // after the pulse's exit (2 L_t / c = 7.4 ms)
    const double measured = std::log(slab_at(springs, t1) / slab_at(springs, t2)) / (t2 - t1);
    const double held     = slab_at(dashpots, t2) / slab_at(dashpots, t1) - 1;
    if (rank() == 0)
      std::cout << "bar on a viscous-spring end: decay rate " << measured << " 1/s against "
                << lambda << " 1/s (K/C = " << k / damper
                << "); dashpots alone: " << slab_at(dashpots, t1) * 1e3 << " mm at " << t1 * 1e3
                << " ms, changed by " << held << " by " << t2 * 1e3
                << " ms; springs' energy at the end " << springs.summary.boundary_spring_energy
                << " J/m of " << springs.history.kinetic.front() << " J/m\n";
    EXPECT_NEAR(measured / lambda, 1.0, 0.01);
    EXPECT_LT(std::abs(held), 1e-3);
    EXPECT_GT(slab_at(dashpots, t1), 0);
    // The springs store energy, within the balance; the dashpots alone have none. (E_0 is the
    // first sample's kinetic energy: the bonded bar's shared nodes move with the slab, so the
    // summary's 1/2 m_slab v^2 is not it.)
    ASSERT_EQ(springs.history.boundary_springs.size(), springs.history.time.size());
    const auto  &h = springs.history;
    const double balance =
      (h.kinetic.back() + h.strain.back() + h.radiation.back() + h.boundary_springs.back()) /
        h.kinetic.front() -
      1;
    EXPECT_LT(std::abs(balance), energy_tolerance);
    EXPECT_GT(springs.summary.boundary_spring_energy, 0);
    EXPECT_TRUE(dashpots.history.boundary_springs.empty());
  }

  TEST(AbsorbingBoundary, SceneImpactEnergyBalanceClosesWithTheRadiatedEnergy)
  {
    // Dashpots alone and with the viscous-spring boundary's springs, whose energy is stored.
    for (const bool springs : {false, true})
      for (const auto integrator : {ImpactParameters::Integrator::explicit_central_difference,
                                    ImpactParameters::Integrator::implicit_newmark})
      {
        auto p                       = scene_parameters(0.05, false, "scene_absorbing.msh");
        p.integrator                 = integrator;
        p.absorbing_boundaries       = {ids::fixed_base, ids::soil_far_side};
        p.boundary_spring_normal     = springs ? 1.0 : 0.0;
        p.boundary_spring_tangential = springs ? 0.5 : 0.0;
        const auto   r               = run_impact(p, MPI_COMM_WORLD, nullptr);
        const double e0              = r.history.kinetic.front();
        double       stored          = 0;
        for (const double e : r.history.boundary_springs)
          stored = std::max(stored, e);
        if (rank() == 0)
          std::cout << "scene, absorbing far side and soil base" << (springs ? " with springs" : "")
                    << ": " << summary_line(r) << ", radiated " << r.summary.radiated_energy / e0
                    << " E_0, largest in the springs " << stored / e0 << " E_0\n";
        EXPECT_LT(r.summary.energy_error, energy_tolerance);
        EXPECT_GT(r.summary.radiated_energy, 0);
        ASSERT_EQ(r.history.radiation.size(), r.history.time.size());
        if (springs)
        {
          ASSERT_EQ(r.history.boundary_springs.size(), r.history.time.size());
          EXPECT_GT(stored, 0);
          EXPECT_LT(stored, 0.5 * e0);
        }
      }
  }

  TEST(AbsorbingBoundary, RefusesAnIdWithoutDashpotMeaning)
  {
    auto p                 = scene_parameters(0.05, false, "scene_absorbing_bad.msh");
    p.absorbing_boundaries = {ids::wall_contact};
    EXPECT_ANY_THROW(run_impact(p, MPI_COMM_WORLD, nullptr));
  }

  TEST(Mpi, DistributedAbsorbingRunMatchesSerialRun)
  {
    constexpr double tolerance = 1e-10; // as the linear Mpi.* tests of impact_test.cc
    auto             p         = scene_parameters(0.05, false, "scene_mpi_absorbing.msh");
    p.absorbing_boundaries     = {ids::fixed_base, ids::soil_far_side};
    p.end_time                 = 0.02;
    expect_same_absorbing_run(p, tolerance, "MPI absorbing");
    p.boundary_spring_normal     = 1.0; // the viscous-spring boundary
    p.boundary_spring_tangential = 0.5;
    expect_same_absorbing_run(p, tolerance, "MPI viscous-spring");
  }
} // namespace
