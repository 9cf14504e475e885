// Lysmer-Kuhlemeyer absorbing boundary (fem::ImpactParameters::absorbing_boundaries): plane P and
// S pulses through soil columns reflect almost nothing at the dashpots and everything at a fixed
// end; energy balance with the radiated energy; 1 vs 2 MPI ranks (Mpi.*).
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

  /** Kinetic + strain energy at the sample nearest to time t, over E_0 (the initial kinetic). */
  double energy_left(const ImpactResult &r, double t)
  {
    const auto &h    = r.history;
    std::size_t best = 0;
    for (std::size_t i = 0; i < h.time.size(); ++i)
      if (std::abs(h.time[i] - t) < std::abs(h.time[best] - t))
        best = i;
    return (h.kinetic[best] + h.strain[best]) / h.kinetic.front();
  }

  constexpr double h_cell      = 0.025; // m, element size of the columns
  constexpr double width       = 2 * h_cell;
  constexpr double dummy_gap   = 0.1; // m: the contact that run_impact() requires, never touched
  constexpr double dummy_width = 0.1;

  /**
   * P-wave column along y: soil [0, w] x [0, L], a bonded slab-material segment [L, L + L_s] on
   * top that starts at v in +y (initial_velocity_along_y), sides on rollers (u_x = 0), base
   * fixed_base; a free dummy block above to satisfy the contact setup.
   */
  ImpactParameters p_column(double L, double L_s, const std::string &name)
  {
    const auto file = scratch(name);
    if (rank() == 0)
    {
      const auto n = [](double length)
      { return static_cast<unsigned>(std::lround(length / h_cell)); };
      write_blocks_msh({{0,
                         width,
                         0,
                         L,
                         2,
                         n(L),
                         ids::soil_material,
                         ids::soil_far_side,
                         ids::soil_far_side,
                         ids::fixed_base,
                         0},
                        {0,
                         width,
                         L,
                         L + L_s,
                         2,
                         n(L_s),
                         ids::slab_material,
                         ids::soil_far_side,
                         ids::soil_far_side,
                         0,
                         ids::slab_contact},
                        {0,
                         width,
                         L + L_s + dummy_gap,
                         L + L_s + dummy_gap + dummy_width,
                         2,
                         4,
                         ids::wall_material,
                         0,
                         0,
                         ids::wall_contact,
                         0}},
                       file);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    ImpactParameters p;
    p.mesh_file                     = file;
    p.materials[ids::soil_material] = soil;
    p.materials[ids::slab_material] = soil;
    p.materials[ids::wall_material] = soil;
    p.initial_velocity_along_y      = true;
    p.separation_hold_time          = 1; // s: no contact ever starts; run to end_time
    p.output_interval               = 1e-4;
    return p;
  }

  /**
   * S-wave column along x: soil [0, L] x [0, w], a bonded slab-material segment [-L_s, 0] that
   * starts at v in +y, top and bottom on rollers (u_x = 0: the shear traction of a plane S-wave
   * is carried), right end fixed_base; a free dummy block on the left.
   */
  ImpactParameters s_column(double L, double L_s, const std::string &name)
  {
    const auto file = scratch(name);
    if (rank() == 0)
    {
      const auto n = [](double length)
      { return static_cast<unsigned>(std::lround(length / h_cell)); };
      write_blocks_msh({{0,
                         L,
                         0,
                         width,
                         n(L),
                         2,
                         ids::soil_material,
                         0,
                         ids::fixed_base,
                         ids::soil_far_side,
                         ids::soil_far_side},
                        {-L_s,
                         0,
                         0,
                         width,
                         n(L_s),
                         2,
                         ids::slab_material,
                         ids::slab_contact,
                         0,
                         ids::soil_far_side,
                         ids::soil_far_side},
                        {-L_s - dummy_gap - dummy_width,
                         -L_s - dummy_gap,
                         0,
                         width,
                         4,
                         2,
                         ids::wall_material,
                         0,
                         ids::wall_contact,
                         0,
                         0}},
                       file);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    ImpactParameters p;
    p.mesh_file                     = file;
    p.materials[ids::soil_material] = soil;
    p.materials[ids::slab_material] = soil;
    p.materials[ids::wall_material] = soil;
    p.initial_velocity_along_y      = true;
    p.separation_hold_time          = 1;
    p.output_interval               = 1e-4;
    return p;
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
      auto p                 = p_column(L, L_s, "p_column.msh");
      p.integrator           = integrator;
      p.end_time             = t_measure;
      const auto fixed       = run_impact(p, MPI_COMM_WORLD, nullptr);
      p.absorbing_boundaries = {ids::fixed_base};
      const auto   absorbed  = run_impact(p, MPI_COMM_WORLD, nullptr);
      const double r_fixed   = energy_left(fixed, t_measure),
                   r_abs     = energy_left(absorbed, t_measure);
      const double e0        = absorbed.history.kinetic.front();
      if (rank() == 0)
        std::cout << (integrator == ImpactParameters::Integrator::implicit_newmark ? "implicit" :
                                                                                     "explicit")
                  << " P-wave column (c_p = " << c << " m/s, t = " << t_measure * 1e3
                  << " ms): energy left with fixed base " << r_fixed << ", absorbing base " << r_abs
                  << ", radiated " << absorbed.summary.radiated_energy / e0 << ", |dE/E0| "
                  << absorbed.summary.energy_error << '\n';
      EXPECT_LT(r_abs, max_absorbed_reflection);
      EXPECT_GT(r_fixed, min_fixed_reflection);
      EXPECT_NEAR(absorbed.summary.radiated_energy / e0, 1 - r_abs, energy_tolerance);
      EXPECT_LT(absorbed.summary.energy_error, energy_tolerance);
      EXPECT_EQ(fixed.summary.radiated_energy, 0);
      EXPECT_TRUE(fixed.history.radiation.empty());
    }
  }

  TEST(AbsorbingBoundary, PlaneSWaveLeavesThroughTheTangentialDashpot)
  {
    const double L = 3.0, L_s = 0.25, c = s_wave_speed(soil);
    const double t_measure = 0.5 * ((L + 2 * L_s) / c + (2 * L + L_s) / c);
    auto         p         = s_column(L, L_s, "s_column.msh");
    p.end_time             = t_measure;
    const auto fixed       = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.absorbing_boundaries = {ids::fixed_base};
    const auto   absorbed  = run_impact(p, MPI_COMM_WORLD, nullptr);
    const double r_fixed = energy_left(fixed, t_measure), r_abs = energy_left(absorbed, t_measure);
    if (rank() == 0)
      std::cout << "S-wave column (c_s = " << c << " m/s, t = " << t_measure * 1e3
                << " ms): energy left with fixed end " << r_fixed << ", absorbing end " << r_abs
                << ", |dE/E0| " << absorbed.summary.energy_error << '\n';
    EXPECT_LT(r_abs, max_absorbed_reflection);
    EXPECT_GT(r_fixed, min_fixed_reflection);
    EXPECT_LT(absorbed.summary.energy_error, energy_tolerance);
  }

  TEST(AbsorbingBoundary, ImpactPWaveLeavesThroughTheFarSide)
  {
    // The real contact: a slab bar strikes a soil bar (nu = 0: a free-sided bar is exactly 1D)
    // whose far end is soil_far_side: rollers (u_x = 0, a fixed end for this wave) or dashpots.
    const Material bar{50e6, 0.0, 1900};
    const double   L = 4.0, L_s = 0.5, t = 0.05, c = p_wave_speed(bar);
    const double   t_measure = 0.5 * ((L + 2 * L_s) / c + (2 * L) / c);
    const auto     file      = scratch("far_bar.msh");
    if (rank() == 0)
      write_blocks_msh(
        {{-0.5e-3 - L_s, -0.5e-3, 0, t, 20, 2, ids::slab_material, 0, ids::slab_contact, 0, 0},
         {0, L, 0, t, 160, 2, ids::soil_material, ids::wall_contact, ids::soil_far_side, 0, 0}},
        file);
    MPI_Barrier(MPI_COMM_WORLD);
    ImpactParameters p;
    p.mesh_file                     = file;
    p.materials[ids::slab_material] = bar;
    p.materials[ids::soil_material] = bar;
    p.separation_hold_time          = 1;
    p.end_time                      = t_measure;
    p.output_interval               = 1e-4;
    const auto fixed                = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.absorbing_boundaries          = {ids::soil_far_side};
    const auto   absorbed           = run_impact(p, MPI_COMM_WORLD, nullptr);
    const double r_fixed = energy_left(fixed, t_measure), r_abs = energy_left(absorbed, t_measure);
    if (rank() == 0)
      std::cout << "impact P-wave through the far side: energy left with rollers " << r_fixed
                << ", absorbing " << r_abs << ", |dE/E0| " << absorbed.summary.energy_error << '\n';
    EXPECT_LT(r_abs, max_absorbed_reflection);
    EXPECT_GT(r_fixed, min_fixed_reflection);
    EXPECT_LT(absorbed.summary.energy_error, energy_tolerance);
  }

  TEST(AbsorbingBoundary, SceneImpactEnergyBalanceClosesWithTheRadiatedEnergy)
  {
    for (const auto integrator : {ImpactParameters::Integrator::explicit_central_difference,
                                  ImpactParameters::Integrator::implicit_newmark})
    {
      auto p                 = scene_parameters(0.05, false, "scene_absorbing.msh");
      p.integrator           = integrator;
      p.absorbing_boundaries = {ids::fixed_base, ids::soil_far_side};
      const auto   r         = run_impact(p, MPI_COMM_WORLD, nullptr);
      const double e0        = r.history.kinetic.front();
      if (rank() == 0)
        std::cout << "scene, absorbing far side and soil base: " << summary_line(r) << ", radiated "
                  << r.summary.radiated_energy / e0 << " E_0\n";
      EXPECT_LT(r.summary.energy_error, energy_tolerance);
      EXPECT_GT(r.summary.radiated_energy, 0);
      ASSERT_EQ(r.history.radiation.size(), r.history.time.size());
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
    const auto world           = run_impact(p, MPI_COMM_WORLD, nullptr);
    const auto self            = run_impact(p, MPI_COMM_SELF, nullptr);
    ASSERT_EQ(world.history.time.size(), self.history.time.size());
    const auto [max_force, max_difference] = force_history_difference(world, self);
    ASSERT_GT(max_force, 0);
    EXPECT_LT(max_difference, tolerance * max_force);
    EXPECT_NEAR(world.summary.radiated_energy,
                self.summary.radiated_energy,
                tolerance * self.history.kinetic.front());
    if (rank() == 0)
      std::cout << "MPI absorbing: " << world.summary.n_ranks
                << " ranks vs 1, max |dF| / max F = " << max_difference / max_force << '\n';
  }
} // namespace
