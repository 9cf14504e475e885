// Physics tests of kimp::fem: closed forms (Timoshenko cantilever, colliding bars rho c A v / 2
// for 2 L / c), contact consistency, energy balance, penalty convergence, rigid vs elastic slab
// and MPI agreement. Inelastic impacts and refused input are in inelastic_impact_test.cc, the
// mesh study in convergence_test.cc (label slow).
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <random>
#include <string>

#include "fem/penalty_contact.h"
#include "tests/fem/impact_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  TEST(Cantilever, TipStiffnessMatchesTimoshenko)
  {
    constexpr double tolerance = 0.02;
    for (const double height : {1.25, 2.0})
    {
      const double thickness = 0.25;
      const double k_fe      = cantilever_tip_stiffness(height, thickness, concrete, 16);
      const double k_beam    = timoshenko_tip_stiffness(height, thickness, concrete);
      EXPECT_NEAR(k_fe / k_beam, 1.0, tolerance)
        << "H = " << height << " m, t = " << thickness << " m: FE " << k_fe << " N/m vs beam "
        << k_beam << " N/m";
      if (rank() == 0)
        std::cout << "cantilever H = " << height << " m: FE " << k_fe
                  << " N/m, FE/Timoshenko = " << k_fe / k_beam << '\n';
    }
  }

  TEST(Cantilever, MeshRefinementConvergesFromAbove)
  {
    // Q1 is too stiff on coarse meshes (shear locking): the stiffness decreases with refinement.
    const double k4  = cantilever_tip_stiffness(1.25, 0.25, concrete, 4);
    const double k8  = cantilever_tip_stiffness(1.25, 0.25, concrete, 8);
    const double k16 = cantilever_tip_stiffness(1.25, 0.25, concrete, 16);
    EXPECT_GT(k4, k8);
    EXPECT_GT(k8, k16);
    EXPECT_LT((k8 - k16) / k16, 0.02) << "k8 = " << k8 << ", k16 = " << k16;
  }

  TEST(PenaltyContact, ForcesAreEqualOppositeAndDeriveFromThePenaltyEnergy)
  {
    // Master: a vertical chain x = 0 (outward normal -x); slaves slightly penetrating from x < 0.
    std::mt19937                           rng(42);
    std::uniform_real_distribution<double> noise(-1e-5, 1e-5);
    std::vector<PenaltyContact::Node>      nodes;
    for (int j = 0; j <= 4; ++j)
      nodes.push_back({0.0, 0.1 * j});
    for (int j = 0; j < 3; ++j)
      nodes.push_back({5e-5, 0.05 + 0.13 * j}); // 50 um inside the master body
    std::vector<PenaltyContact::Segment> segments;
    for (unsigned int j = 0; j < 4; ++j)
      segments.push_back({j, j + 1, -1.0}); // t = +y: n = -(t_y, -t_x) = (-1, 0)
    std::vector<PenaltyContact::Slave> slaves;
    for (unsigned int j = 5; j < 8; ++j)
      slaves.push_back({j, 1e9, 0.0});
    const PenaltyContact contact(nodes, slaves, segments);

    constexpr double force_tolerance  = 1e-10;
    constexpr double energy_tolerance = 1e-6;
    for (int trial = 0; trial < 5; ++trial)
    {
      std::vector<double> u(contact.n_compact_dofs()), v(u.size(), 0.0);
      for (auto &x : u)
        x = noise(rng);
      const auto ev = contact.evaluate(u, v);
      double     fx = 0, fy = 0, scale = 0;
      for (std::size_t i = 0; i < nodes.size(); ++i)
      {
        fx += ev.force[2 * i];
        fy += ev.force[2 * i + 1];
        scale += std::abs(ev.force[2 * i]) + std::abs(ev.force[2 * i + 1]);
      }
      ASSERT_GT(ev.active.size(), 0u) << "trial " << trial;
      EXPECT_LT(std::hypot(fx, fy), force_tolerance * scale) << "trial " << trial;
      // Force = -d(penalty energy)/du by central differences.
      for (std::size_t k = 0; k < u.size(); ++k)
      {
        const double h  = 1e-9;
        auto         up = u, um = u;
        up[k] += h;
        um[k] -= h;
        const double dE =
          (contact.evaluate(up, v).penalty_energy - contact.evaluate(um, v).penalty_energy) /
          (2 * h);
        EXPECT_NEAR(-dE, ev.force[k], energy_tolerance * scale + 1e-3)
          << "trial " << trial << ", compact DoF " << k;
      }
    }
  }

  TEST(TwoEqualBars, ExplicitForceIsHalfImpedanceTimesVelocityForTwoLOverC)
  {
    constexpr double tolerance = 0.02;
    const double     L = 1.0, t = 0.1, v = 1.0;
    const auto       p        = bar_parameters(write_two_bars(L, t, 1e-4, 8, "bars.msh"));
    const auto       r        = run_impact(p, MPI_COMM_WORLD, nullptr);
    const double     c        = std::sqrt(bar_material.youngs_modulus / bar_material.density);
    const double     force    = bar_material.density * c * t * v / 2;
    const double     duration = 2 * L / c;
    if (rank() == 0)
      std::cout << "bars explicit: " << summary_line(r) << "\n  plateau " << plateau(r, 0.2, 0.8)
                << " N/m vs rho c A v / 2 = " << force << " N/m, duration vs 2L/c = " << duration
                << " s\n";
    EXPECT_NEAR(plateau(r, 0.2, 0.8) / force, 1.0, tolerance) << summary_line(r);
    EXPECT_NEAR(r.summary.peak_force / force, 1.0, tolerance) << summary_line(r);
    EXPECT_NEAR(r.summary.contact_duration / duration, 1.0, tolerance) << summary_line(r);
    // Momentum exchange: the impulse is m v = rho L t v and the striker stops.
    EXPECT_NEAR(r.summary.impulse / (bar_material.density * L * t * v), 1.0, tolerance);
    EXPECT_NEAR(r.summary.rebound_velocity / v, 0.0, tolerance);
    // The struck bar carries E_0 away as a free translation: nothing stored, the run ends.
    EXPECT_TRUE(r.summary.separated);
    EXPECT_LT(r.summary.stored_energy_share, p.stored_energy_fraction);
  }

  TEST(TwoEqualBars, ImplicitNewmarkDeviationIsSmall)
  {
    // Average acceleration at 4x the stable limit (5x the explicit step): period elongation
    // smears the wave front, the plateau and the momentum exchange stay close to rho c A v / 2
    // and m v (deviations printed next to the explicit ones). Both linear solvers give the same
    // Newton iterates.
    constexpr double plateau_tolerance = 0.10;
    constexpr double impulse_tolerance = 0.02;
    constexpr double solver_tolerance  = 1e-6; // Newton stops at a relative residual of 1e-10
    const double     L = 1.0, t = 0.1, v = 1.0;
    auto             p = bar_parameters(write_two_bars(L, t, 1e-4, 8, "bars_implicit.msh"));
    const auto       explicit_run    = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.integrator                     = ImpactParameters::Integrator::implicit_newmark;
    const auto direct                = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.implicit_options.linear_solver = ImplicitOptions::LinearSolver::cg_amg;
    const auto   cg                  = run_impact(p, MPI_COMM_WORLD, nullptr);
    const double c        = std::sqrt(bar_material.youngs_modulus / bar_material.density);
    const double force    = bar_material.density * c * t * v / 2;
    const double momentum = bar_material.density * L * t * v;
    const double duration = 2 * L / c;
    if (rank() == 0)
      for (const auto *r : {&explicit_run, &direct, &cg})
      {
        const auto &m = r->summary;
        std::cout << (r == &explicit_run ? "bars explicit:        " :
                      r == &direct       ? "bars implicit direct: " :
                                           "bars implicit cg_amg: ")
                  << "plateau " << plateau(*r, 0.2, 0.8) / force - 1 << ", peak "
                  << m.peak_force / force - 1 << ", duration " << m.contact_duration / duration - 1
                  << ", impulse " << m.impulse / momentum - 1 << " (relative to closed form), COR "
                  << m.apparent_cor << "; dt " << m.dt << " s, " << m.n_steps << " steps, Newton "
                  << m.n_newton << ", halvings " << m.n_step_halvings << ", linear solves "
                  << m.n_linear_solves << ", " << m.wall_seconds << " s\n";
      }
    for (const auto *r : {&direct, &cg})
    {
      EXPECT_NEAR(plateau(*r, 0.2, 0.8) / force, 1.0, plateau_tolerance) << summary_line(*r);
      EXPECT_NEAR(r->summary.impulse / momentum, 1.0, impulse_tolerance) << summary_line(*r);
      EXPECT_LT(r->summary.energy_error, 0.01) << summary_line(*r);
      EXPECT_TRUE(r->summary.separated);
    }
    EXPECT_NEAR(cg.summary.impulse / direct.summary.impulse, 1.0, solver_tolerance);
    EXPECT_NEAR(cg.summary.peak_force / direct.summary.peak_force, 1.0, solver_tolerance);
  }

  TEST(TwoEqualBars, SmoothingPreservesTheImpulse)
  {
    constexpr double tolerance = 1e-12;
    auto             p      = bar_parameters(write_two_bars(1.0, 0.1, 1e-4, 8, "bars_smooth.msh"));
    p.output_interval       = 0; // every step: the smoothed history can be integrated exactly
    p.contact_damping_ratio = 0; // raw force chatters; the smoothing must still keep the impulse
    const auto   r          = run_impact(p, MPI_COMM_WORLD, nullptr);
    const auto  &h          = r.history;
    const double sum =
      std::accumulate(h.smoothed_contact_force.begin(), h.smoothed_contact_force.end(), 0.0);
    EXPECT_NEAR(sum * r.summary.dt / r.summary.impulse, 1.0, tolerance)
      << "window " << r.summary.smoothing_window << " s";
    EXPECT_LE(r.summary.peak_force, r.summary.peak_force_raw);
  }

  // The stop sees the whole system. A bar of length L strikes a bar of length 2L clamped at its
  // far end: at 2L/c the striker has handed on all its momentum and rests against the face, the
  // force is zero and the whole E_0 travels in the struck bar as a compressive pulse (1D wave
  // solution), which reflects at the clamped end and comes back at 4L/c: the face then strikes
  // the resting striker, which leaves at -v (COR 1, impulse 2 m v). The slab's rule alone
  // (stored_energy_fraction 1) ends the run at 2L/c with COR 0 and the energy still stored; the
  // default rule waits for it. Cut before the pulse is back, the record is truncated with
  // stored share 1.
  TEST(StopRule, WaitsUntilWallAndSoilHaveGivenBackTheirEnergy)
  {
    constexpr double tolerance = 0.05;
    const double     L = 1.0, t = 0.1, v = 1.0, gap = 1e-4;
    const unsigned   n_t  = 8;
    const auto       mesh = write_blocks(
      {{-gap - L, -gap, 0, t, 80, n_t, ids::slab_material, 0, ids::slab_contact, 0, 0},
             {0, 2 * L, 0, t, 160, n_t, ids::wall_material, ids::wall_contact, ids::fixed_base, 0, 0}},
      "bars_clamped.msh");
    auto         p         = bar_parameters(mesh);
    const double c         = std::sqrt(bar_material.youngs_modulus / bar_material.density);
    const double m_v       = bar_material.density * L * t * v;
    p.end_time             = 8 * L / c;
    const auto whole       = run_impact(p, MPI_COMM_WORLD, nullptr);
    auto       slab_only_p = p;
    slab_only_p.stored_energy_fraction = 1;
    const auto slab_only               = run_impact(slab_only_p, MPI_COMM_WORLD, nullptr);
    auto       cut_p                   = p;
    cut_p.end_time                     = 3 * L / c;
    const auto cut                     = run_impact(cut_p, MPI_COMM_WORLD, nullptr);
    if (rank() == 0)
      for (const auto *r : {&whole, &slab_only, &cut})
        std::cout << (r == &whole     ? "stop rule, whole system: " :
                      r == &slab_only ? "stop rule, slab only:    " :
                                        "stop rule, cut at 3L/c:  ")
                  << "end " << r->history.time.back() * c / L << " L/c, COR "
                  << r->summary.apparent_cor << ", impulse / m v " << r->summary.impulse / m_v
                  << ", stored share " << r->summary.stored_energy_share << ", separated "
                  << r->summary.separated << ", truncated " << r->summary.truncated << '\n';
    EXPECT_TRUE(whole.summary.separated) << summary_line(whole);
    EXPECT_FALSE(whole.summary.truncated);
    EXPECT_NEAR(whole.summary.apparent_cor, 1.0, tolerance) << summary_line(whole);
    EXPECT_NEAR(whole.summary.impulse / m_v, 2.0, 2 * tolerance) << summary_line(whole);
    EXPECT_LE(whole.summary.stored_energy_share, p.stored_energy_fraction);
    EXPECT_GT(whole.history.time.back(), 5 * L / c);

    EXPECT_TRUE(slab_only.summary.separated);
    EXPECT_NEAR(slab_only.summary.apparent_cor, 0.0, tolerance) << summary_line(slab_only);
    EXPECT_NEAR(slab_only.summary.stored_energy_share, 1.0, tolerance);
    EXPECT_LT(slab_only.history.time.back(), 3 * L / c);

    EXPECT_FALSE(cut.summary.separated);
    EXPECT_TRUE(cut.summary.truncated);
    EXPECT_NEAR(cut.summary.stored_energy_share, 1.0, tolerance) << summary_line(cut);
  }

  TEST(StopRule, ParametersOutsideTheirRangeAreRefused)
  {
    auto p                   = bar_parameters(write_two_bars(1.0, 0.1, 1e-4, 4, "bars_stop.msh"));
    p.stored_energy_fraction = 0;
    EXPECT_THROW(
      {
        try
        {
          run_impact(p, MPI_COMM_WORLD, nullptr);
        }
        catch (const std::exception &e)
        {
          EXPECT_NE(std::string(e.what()).find("stored_energy_fraction"), std::string::npos)
            << e.what();
          throw;
        }
      },
      std::exception);
    p.stored_energy_fraction    = 0.05;
    p.rebound_velocity_fraction = 1.5;
    EXPECT_THROW(run_impact(p, MPI_COMM_WORLD, nullptr), std::exception);
  }

  TEST(EnergyBalance, DriftBelowOnePercentWithoutContactDamping)
  {
    constexpr double tolerance = 0.01;
    auto             bars = bar_parameters(write_two_bars(1.0, 0.1, 1e-4, 8, "bars_energy.msh"));
    bars.contact_damping_ratio  = 0;
    auto scene                  = scene_parameters(0.05, false, "scene_energy.msh");
    scene.contact_damping_ratio = 0;
    for (const auto &p : {bars, scene})
    {
      const auto r = run_impact(p, MPI_COMM_WORLD, nullptr);
      EXPECT_LT(r.summary.energy_error, tolerance) << summary_line(r);
      // Without damping all contact work is stored in the penalty springs.
      for (const double d : r.history.contact_dissipation)
        EXPECT_NEAR(d / (r.history.kinetic.front() + 1e-300), 0.0, tolerance);
      if (rank() == 0)
        std::cout << "energy: max |dE/E0| = " << r.summary.energy_error << '\n';
    }
  }

  TEST(EnergyBalance, ContactDampingDissipatesLittle)
  {
    // The default contact damping removes the penalty chatter at a small energy cost.
    constexpr double tolerance = 0.01;
    const auto       p         = scene_parameters(0.05, false, "scene_damped.msh");
    const auto       r         = run_impact(p, MPI_COMM_WORLD, nullptr);
    const double     e0        = r.history.kinetic.front();
    EXPECT_LT(r.summary.energy_error, tolerance) << summary_line(r);
    EXPECT_LT(r.history.contact_dissipation.back() / e0, tolerance) << summary_line(r);
    if (rank() == 0)
      std::cout << "contact damping dissipates " << r.history.contact_dissipation.back() / e0
                << " of E0\n";
  }

  TEST(Penalty, PenetrationFallsAsOneOverPenaltyAndResultsConverge)
  {
    constexpr double result_tolerance      = 0.01;
    constexpr double penetration_tolerance = 0.02;
    auto             p                     = scene_parameters(0.025, false, "scene_penalty.msh");
    p.penalty_factor                       = 1;
    const auto r1                          = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.penalty_factor                       = 10;
    const auto r10                         = run_impact(p, MPI_COMM_WORLD, nullptr);
    if (rank() == 0)
      std::cout << "penalty x1:  " << summary_line(r1) << "\npenalty x10: " << summary_line(r10)
                << '\n';
    EXPECT_NEAR(r1.summary.mean_penetration / r10.summary.mean_penetration,
                10.0,
                10.0 * penetration_tolerance)
      << "mean penetration " << r1.summary.mean_penetration << " m vs "
      << r10.summary.mean_penetration << " m";
    EXPECT_NEAR(r10.summary.peak_force / r1.summary.peak_force, 1.0, result_tolerance);
    EXPECT_NEAR(r10.summary.contact_duration / r1.summary.contact_duration, 1.0, result_tolerance);
    EXPECT_NEAR(r10.summary.impulse / r1.summary.impulse, 1.0, result_tolerance);
  }

  TEST(Penalty, StepRatioGivesTheStatedStepAndKeepsTheImpact)
  {
    // penalty_step_ratio r: the penalty whose springs, with their damping, leave the explicit
    // stable step at r times the cells' own 2 / omega_mesh. Undamped the root is closed-form:
    // 1 / sqrt(1 + (omega_p / omega_mesh)^2) = r.
    EXPECT_NEAR(penalty_omega_ratio_for_step(0.8, 0.0), std::sqrt(1 / (0.8 * 0.8) - 1), 1e-12);
    constexpr double step_tolerance             = 1e-5; // the reference's penalty is 1e-12
    constexpr double peak_tolerance             = 0.02; // the smoothed (first) peak
    constexpr double result_tolerance           = 0.02; // impulse, duration, COR
    constexpr double impulse_momentum_tolerance = 0.02; // |impulse / m (v_in + v_out) - 1|
    constexpr double ratio                      = 0.6;
    auto             p     = scene_parameters(0.025, false, "scene_step_ratio.msh");
    const auto       stiff = run_impact(p, MPI_COMM_WORLD, nullptr);
    // The cells' own limit: a vanishing penalty, stopped before the slab reaches the wall.
    auto cells            = p;
    cells.penalty_factor  = 1e-12;
    cells.end_time        = 1e-4;
    const double dt_cells = run_impact(cells, MPI_COMM_WORLD, nullptr).summary.dt_stable;
    p.penalty_step_ratio  = ratio;
    const auto scaled     = run_impact(p, MPI_COMM_WORLD, nullptr);
    if (rank() == 0)
      std::cout << "penalty factor 1:            " << summary_line(stiff) << "\npenalty_step_ratio "
                << ratio << " (factor " << scaled.summary.penalty_factor
                << "): " << summary_line(scaled) << "\ncells' own stable step " << dt_cells
                << " s, with the factor-1 penalty " << stiff.summary.dt_stable << " s, scaled "
                << scaled.summary.dt_stable << " s\n";
    EXPECT_NEAR(scaled.summary.dt_stable / dt_cells, ratio, ratio * step_tolerance);
    EXPECT_LT(stiff.summary.dt_stable / dt_cells, 0.6) << "the factor-1 penalty halves the step";
    EXPECT_EQ(stiff.summary.penalty_factor, 1.0);
    EXPECT_GT(scaled.summary.penalty_factor, 0.0);
    EXPECT_LT(scaled.summary.penalty_factor, 1.0);
    EXPECT_NEAR(scaled.summary.penalty_stiffness / stiff.summary.penalty_stiffness,
                scaled.summary.penalty_factor,
                1e-12);
    EXPECT_NEAR(scaled.summary.peak_force / stiff.summary.peak_force, 1.0, peak_tolerance);
    EXPECT_NEAR(scaled.summary.impulse / stiff.summary.impulse, 1.0, result_tolerance);
    EXPECT_NEAR(scaled.summary.contact_duration / stiff.summary.contact_duration,
                1.0,
                result_tolerance);
    EXPECT_NEAR(scaled.summary.apparent_cor / stiff.summary.apparent_cor, 1.0, result_tolerance);
    for (const ImpactResult *r : {&stiff, &scaled})
    {
      const double momentum = p.slab_mass * p.initial_velocity * (1 + r->summary.apparent_cor);
      EXPECT_NEAR(r->summary.impulse / momentum, 1.0, impulse_momentum_tolerance)
        << summary_line(*r);
    }
    p.penalty_step_ratio = 1; // no penalty at all would give the mesh's own step: refused
    EXPECT_ANY_THROW(run_impact(p, MPI_COMM_WORLD, nullptr));
  }

  TEST(Subcycling, ContactSubStepsTakeTheMeshStepAndKeepTheImpact)
  {
    // contact_subcycles 0 (automatic): the penalty springs advance in sub-steps, the mesh at
    // its own step min(0.95 x 2 / omega_mesh, 1.75 / omega_p) x cfl_safety instead of the
    // step of mesh and damped penalty together (about half the cells' own). The impact must
    // not see the difference: peak, impulse, duration and COR of the elastic and the rigid
    // slab as without sub-cycling, the impulse equal to the slab's momentum change.
    constexpr double peak_tolerance             = 0.02; // the smoothed (first) peak
    constexpr double result_tolerance           = 0.02; // impulse, duration, COR
    constexpr double impulse_momentum_tolerance = 0.02; // |impulse / m (v_in + v_out) - 1|
    constexpr double energy_error_bound         = 0.01; // max |dE / E0| of the sub-cycled run
    // The step over the step without: 1.79 elastic, 1.51 rigid (whose heavy slab leaves the
    // penalty's omega lower, so it halves the step less).
    constexpr double min_step_gain = 1.4;
    for (const bool rigid : {false, true})
    {
      auto p = scene_parameters(0.025, rigid, rigid ? "scene_sub_rigid.msh" : "scene_sub.msh");
      const auto reference = run_impact(p, MPI_COMM_WORLD, nullptr);
      // The cells' own limit: a vanishing penalty, stopped before the slab reaches the wall.
      auto cells            = p;
      cells.penalty_factor  = 1e-12;
      cells.end_time        = 1e-4;
      const double dt_cells = run_impact(cells, MPI_COMM_WORLD, nullptr).summary.dt_stable;
      p.contact_subcycles   = 0;
      const auto  sub       = run_impact(p, MPI_COMM_WORLD, nullptr);
      const auto &r = reference.summary, &s = sub.summary;
      if (rank() == 0)
        std::cout << (rigid ? "rigid" : "elastic")
                  << " slab, without sub-cycling: " << summary_line(reference) << "\n  sub-cycled ("
                  << s.contact_subcycles << " sub-steps): " << summary_line(sub)
                  << "\n  cells' own limit " << dt_cells << " s; dt " << r.dt << " -> " << s.dt
                  << " s (x" << s.dt / r.dt << "), limit " << r.dt_stable << " -> " << s.dt_stable
                  << " s\n";
      EXPECT_EQ(r.contact_subcycles, 1u);
      EXPECT_GE(s.contact_subcycles, 2u);
      EXPECT_NEAR(s.dt, p.explicit_options.cfl_safety * s.dt_stable, 1e-12 * s.dt);
      EXPECT_LE(s.dt_stable, 0.95 * dt_cells * (1 + 1e-5)); // the vanishing penalty damps 5e-7
      EXPECT_GT(s.dt_stable, 0.85 * dt_cells) << "the sub-cycled step is the mesh's";
      EXPECT_GT(s.dt / r.dt, min_step_gain);
      EXPECT_LE(s.dt / s.contact_subcycles, r.dt * (1 + 1e-12)) << "the contact's sub-step";
      EXPECT_NEAR(s.peak_force / r.peak_force, 1.0, peak_tolerance);
      EXPECT_NEAR(s.impulse / r.impulse, 1.0, result_tolerance);
      EXPECT_NEAR(s.contact_duration / r.contact_duration, 1.0, result_tolerance);
      EXPECT_NEAR(s.apparent_cor / r.apparent_cor, 1.0, result_tolerance);
      EXPECT_LT(s.energy_error, energy_error_bound);
      const double mass = p.slab_mass; // the meshed slab's too
      for (const ImpactSummary *m : {&r, &s})
        EXPECT_NEAR(m->impulse / (mass * p.initial_velocity * (1 + m->apparent_cor)),
                    1.0,
                    impulse_momentum_tolerance)
          << (m == &s ? "sub-cycled" : "reference");
    }
  }

  TEST(Subcycling, RefusedWithTheImplicitIntegratorAndAboveItsRange)
  {
    auto p              = scene_parameters(0.05, true, "scene_sub_refused.msh");
    p.end_time          = 1e-4;
    p.contact_subcycles = 65;
    EXPECT_ANY_THROW(run_impact(p, MPI_COMM_WORLD, nullptr));
    p.contact_subcycles = 2;
    p.integrator        = ImpactParameters::Integrator::implicit_newmark;
    EXPECT_ANY_THROW(run_impact(p, MPI_COMM_WORLD, nullptr));
  }

  TEST(SlabDamping, TakesTheStrikersVibrationAtItsRateAndKeepsItsMomentum)
  {
    // A bar of length 2 L strikes an equal bar of length L (nu = 0: exactly 1D). The struck bar
    // leaves at v after 2 L / c; the striker keeps half its momentum (mean velocity v / 2) and
    // E_0 / 4 as a free axial vibration. Its damping, mass-proportional relative to the plane
    // sections' motion, decays every axial mode's energy as exp(-alpha t), alpha = 2 zeta
    // omega_1 with omega_1 = pi c / (2 L), and leaves the momentum alone.
    constexpr double zeta = 0.02, L = 0.5, t = 0.1, v = 1.0, gap = 1e-4;
    constexpr double momentum_tolerance = 1e-9, energy_tolerance = 1e-3, rate_tolerance = 0.02;
    const auto       mesh = write_blocks(
      {{-gap - 2 * L, -gap, 0, t, 80, 4, ids::slab_material, 0, ids::slab_contact, 0, 0},
             {0, L, 0, t, 20, 4, ids::wall_material, ids::wall_contact, 0, 0, 0}},
      "bars_slab_damping.msh");
    auto p                      = bar_parameters(mesh);
    p.contact_damping_ratio     = 0;
    p.end_time                  = 12e-3;
    p.separation_hold_time      = p.end_time; // run on after the separation
    p.output_interval           = 1e-5;
    const ImpactResult undamped = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.slab_damping_ratio        = zeta;
    const ImpactResult damped   = run_impact(p, MPI_COMM_WORLD, nullptr);
    const double       c        = std::sqrt(bar_material.youngs_modulus / bar_material.density);
    const double       alpha    = 2 * zeta * M_PI * c / (2 * L);
    const double       e0       = undamped.history.kinetic.front();
    const auto        &h        = damped.history;
    ASSERT_EQ(h.slab_damping.size(), h.time.size());
    EXPECT_TRUE(undamped.history.slab_damping.empty());

    // Before the contact the slab moves as a whole: nothing to damp.
    const double t_contact = damped.summary.contact_start, t_apart = t_contact + 2 * L / c;
    for (std::size_t i = 0; i < h.time.size() && h.time[i] < t_contact; ++i)
      EXPECT_NEAR(h.slab_damping[i], 0.0, 1e-12 * e0) << "t = " << h.time[i];
    // The energy balance closes with the damping's work, and the slab's momentum does not
    // change once the contact has opened.
    EXPECT_LT(damped.summary.energy_error, energy_tolerance) << summary_line(damped);
    double v_apart = 0;
    for (std::size_t i = 0; i < h.time.size(); ++i)
      if (h.time[i] > t_apart + 0.2e-3)
      {
        if (v_apart == 0)
          v_apart = h.slab_velocity[i];
        EXPECT_NEAR(h.slab_velocity[i], v_apart, momentum_tolerance) << "t = " << h.time[i];
      }
    EXPECT_NEAR(v_apart / v, 0.5, 0.02);
    EXPECT_NEAR(undamped.summary.rebound_velocity / v, 0.5, 0.02);

    // The vibration left at t is what the damping still takes, so it takes E(t0) (1 -
    // exp(-alpha tau)) over [t0, t0 + tau]: two such increments 4 ms apart give alpha. tau is
    // four periods of omega_1 (the energy's ripple averaged); read over 1 ms the rate still
    // ripples by +-6 % with a 2 ms period (the modes' beat), over 4 ms by +-1.3 %.
    const double d_end  = h.slab_damping.back();
    const double period = 2 * L * 2 / c;
    const auto   taken  = [&](double t0)
    {
      const auto at = [&](double time)
      {
        std::size_t i = 0;
        while (i + 1 < h.time.size() && h.time[i] < time)
          ++i;
        return h.slab_damping[i];
      };
      return at(t0 + 4 * period) - at(t0);
    };
    const double t0 = t_apart + 0.5e-3, t1 = t0 + 4e-3;
    const double rate = std::log(taken(t0) / taken(t1)) / (t1 - t0);
    // The striker's vibration at the separation: E_0 / 4 undamped; the damping took some of
    // it during the contact, and takes all of it afterwards (exp(-alpha 12 ms) < 1e-3).
    EXPECT_NEAR(rate / alpha, 1.0, rate_tolerance);
    EXPECT_GT(d_end / e0, 0.2);
    EXPECT_LT(d_end / e0, 0.25 + energy_tolerance);
    if (rank() == 0)
      std::cout << "slab damping: alpha " << alpha << " 1/s, decay rate " << rate
                << " 1/s, dissipated " << d_end / e0 << " E_0, mean velocity after " << v_apart
                << " m/s, |dE/E0| " << damped.summary.energy_error << '\n';
  }

  TEST(SlabDamping, RefusedOutsideItsRangeOnARigidSlabAndWithTheImplicitIntegrator)
  {
    auto p               = scene_parameters(0.05, false, "scene_slab_damping_refused.msh");
    p.end_time           = 1e-4;
    p.slab_damping_ratio = 1.5;
    EXPECT_ANY_THROW(run_impact(p, MPI_COMM_WORLD, nullptr));
    p.slab_damping_ratio = -0.1;
    EXPECT_ANY_THROW(run_impact(p, MPI_COMM_WORLD, nullptr));
    p.slab_damping_ratio = 0.05;
    p.integrator         = ImpactParameters::Integrator::implicit_newmark;
    EXPECT_ANY_THROW(run_impact(p, MPI_COMM_WORLD, nullptr));
    auto rigid               = scene_parameters(0.05, true, "scene_slab_damping_rigid.msh");
    rigid.end_time           = 1e-4;
    rigid.slab_damping_ratio = 0.05;
    EXPECT_ANY_THROW(run_impact(rigid, MPI_COMM_WORLD, nullptr));
  }

  TEST(Scene, RigidSlabDoublesPeakForceAndKeepsImpulseAndLocalStiffness)
  {
    // A rigid slab has no axial wave: the force is not capped by rho c A v / 2, so the peak is
    // about twice as high and the contact shorter; the momentum exchange (impulse) is the same,
    // and so is the secant stiffness F / delta at the peak, a property of the wall's local
    // compliance (values printed).
    const auto rigid =
      run_impact(scene_parameters(0.05, true, "scene_rigid.msh"), MPI_COMM_WORLD, nullptr);
    const auto elastic =
      run_impact(scene_parameters(0.05, false, "scene_elastic.msh"), MPI_COMM_WORLD, nullptr);
    const auto secant = [](const ImpactResult &r)
    {
      const auto &h = r.history;
      const auto  it =
        std::max_element(h.smoothed_contact_force.begin(), h.smoothed_contact_force.end());
      const auto i = static_cast<std::size_t>(it - h.smoothed_contact_force.begin());
      return *it / std::max(h.indentation[i], 1e-12);
    };
    if (rank() == 0)
      std::cout << "rigid:   " << summary_line(rigid) << ", F/delta " << secant(rigid)
                << " N/m^2\nelastic: " << summary_line(elastic) << ", F/delta " << secant(elastic)
                << " N/m^2\n";
    EXPECT_GT(rigid.summary.peak_force, 1.5 * elastic.summary.peak_force);
    EXPECT_NEAR(secant(rigid) / secant(elastic), 1.0, 0.1);
    EXPECT_LT(rigid.summary.contact_duration, elastic.summary.contact_duration);
    EXPECT_NEAR(rigid.summary.impulse / elastic.summary.impulse, 1.0, 0.05);
    EXPECT_TRUE(rigid.summary.separated);
    EXPECT_TRUE(elastic.summary.separated);
  }

  TEST(Scene, ImplicitNewmarkMatchesExplicitForRigidAndElasticSlab)
  {
    // The accuracy-vs-cost comparison: integral results agree within a few per cent.
    constexpr double tolerance = 0.03;
    for (const bool rigid : {true, false})
    {
      auto       p = scene_parameters(0.05, rigid, rigid ? "scene_ir.msh" : "scene_ie.msh");
      const auto explicit_run = run_impact(p, MPI_COMM_WORLD, nullptr);
      p.integrator            = ImpactParameters::Integrator::implicit_newmark;
      const auto implicit_run = run_impact(p, MPI_COMM_WORLD, nullptr);
      if (rank() == 0)
        std::cout << (rigid ? "rigid" : "elastic") << " explicit: " << summary_line(explicit_run)
                  << "\n"
                  << (rigid ? "rigid" : "elastic") << " implicit: " << summary_line(implicit_run)
                  << ", Newton " << implicit_run.summary.n_newton << '\n';
      const auto &e = explicit_run.summary, &i = implicit_run.summary;
      EXPECT_NEAR(i.impulse / e.impulse, 1.0, tolerance) << "rigid " << rigid;
      EXPECT_NEAR(i.contact_duration / e.contact_duration, 1.0, tolerance) << "rigid " << rigid;
      EXPECT_NEAR(i.apparent_cor, e.apparent_cor, tolerance) << "rigid " << rigid;
      EXPECT_LT(i.energy_error, 0.01) << "rigid " << rigid;
    }
  }

  TEST(Scene, ImplicitNewtonConvergesOnTheDefaultMesh)
  {
    // The default 2.5 cm contact mesh, where a full Newton step jumps between active sets:
    // the line search on the incremental potential (and step halving where Newton still
    // fails) gives a run whose integral results match the explicit ones.
    constexpr double tolerance = 0.03;
    auto             p         = scene_parameters(0.025, false, "scene_default_implicit.msh", 0.1);
    const auto       explicit_run = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.integrator                  = ImpactParameters::Integrator::implicit_newmark;
    const auto  implicit_run      = run_impact(p, MPI_COMM_WORLD, nullptr);
    const auto &e = explicit_run.summary, &i = implicit_run.summary;
    if (rank() == 0)
      std::cout << "2.5 cm explicit: " << summary_line(explicit_run)
                << "\n2.5 cm implicit: " << summary_line(implicit_run) << ", Newton " << i.n_newton
                << ", halvings " << i.n_step_halvings << ", linear solves " << i.n_linear_solves
                << " (" << i.linear_solver_seconds << " s, setup " << i.linear_setup_seconds
                << " s)\n";
    EXPECT_NEAR(i.impulse / e.impulse, 1.0, tolerance);
    EXPECT_NEAR(i.contact_duration / e.contact_duration, 1.0, tolerance);
    EXPECT_NEAR(i.apparent_cor, e.apparent_cor, tolerance);
    EXPECT_LT(i.energy_error, 0.01);
    EXPECT_TRUE(i.separated);
  }

  TEST(Scene, ImplicitStepHalvingRecoversAndItsFloorIsANumericalError)
  {
    // One Newton iteration per attempt does not converge the first contact steps of the scene
    // (active set and node-to-segment geometry change): the step is retried at dt / 2, dt / 4,
    // dt / 8 and at that floor the run stops with a NumericalError naming time and step. With
    // three iterations the halvings recover and the momentum exchange is unchanged.
    constexpr double impulse_tolerance       = 0.02;
    auto             p                       = scene_parameters(0.05, false, "scene_halving.msh");
    p.integrator                             = ImpactParameters::Integrator::implicit_newmark;
    const auto reference                     = run_impact(p, MPI_COMM_WORLD, nullptr);
    p.implicit_options.newton_max_iterations = 1;
    p.implicit_options.max_halvings          = 3;
    try
    {
      run_impact(p, MPI_COMM_WORLD, nullptr);
      FAIL() << "no NumericalError with one Newton iteration per step";
    }
    catch (const NumericalError &e)
    {
      EXPECT_NE(std::string(e.what()).find("halved 3 times"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("the floor"), std::string::npos) << e.what();
      EXPECT_GT(e.time, 0.0);
      EXPECT_GT(e.step, 0u);
      if (rank() == 0)
        std::cout << "floor: " << e.what() << '\n';
    }
    p.implicit_options.newton_max_iterations = 3;
    p.implicit_options.max_halvings          = 6;
    const auto halved                        = run_impact(p, MPI_COMM_WORLD, nullptr);
    if (rank() == 0)
      std::cout << "halving: " << halved.summary.n_step_halvings << " halvings, "
                << summary_line(halved) << "\nreference: " << summary_line(reference) << '\n';
    EXPECT_GT(halved.summary.n_step_halvings, 0u);
    EXPECT_NEAR(halved.summary.contact_duration / reference.summary.contact_duration,
                1.0,
                impulse_tolerance);
    EXPECT_NEAR(halved.summary.impulse / reference.summary.impulse, 1.0, impulse_tolerance);
    EXPECT_TRUE(halved.summary.separated);
  }

  TEST(Progress, CallbackSeesIncreasingTimeUpToTheEnd)
  {
    auto p = bar_parameters(write_two_bars(1.0, 0.1, 1e-4, 4, "bars_progress.msh"));
    std::vector<std::pair<double, double>> calls;
    p.progress          = [&calls](double t, double t_end) { calls.emplace_back(t, t_end); };
    p.progress_interval = 50;
    for (const auto integrator : {ImpactParameters::Integrator::explicit_central_difference,
                                  ImpactParameters::Integrator::implicit_newmark})
    {
      calls.clear();
      p.integrator = integrator;
      const auto r = run_impact(p, MPI_COMM_WORLD, nullptr);
      if (rank() != 0)
      {
        EXPECT_TRUE(calls.empty()) << "progress is reported on rank 0 only";
        continue;
      }
      ASSERT_EQ(calls.size(), r.summary.n_steps / p.progress_interval + 1)
        << r.summary.n_steps << " steps";
      for (std::size_t k = 1; k < calls.size(); ++k)
        EXPECT_GT(calls[k].first, calls[k - 1].first) << "call " << k;
      EXPECT_NEAR(calls.back().first, r.summary.n_steps * r.summary.dt, 1e-12);
      EXPECT_EQ(calls.back().second, p.end_time);
    }
  }

  TEST(Output, FieldFilesAndMeshInfoDescribeTheRun)
  {
    const double L = 1.0, t = 0.1;
    const auto   mesh = write_two_bars(L, t, 1e-4, 4, "bars_vtu.msh");
    auto         p    = bar_parameters(mesh);
    p.vtu_dir         = scratch("vtu");
    p.vtu_interval    = 1e-4;
    if (rank() == 0)
      std::filesystem::create_directories(p.vtu_dir);
    MPI_Barrier(MPI_COMM_WORLD);
    const auto r = run_impact(p, MPI_COMM_WORLD, nullptr);
    const auto n_expected =
      static_cast<std::size_t>(r.summary.n_steps / std::lround(p.vtu_interval / r.summary.dt)) + 1;
    std::size_t n_pvtu = 0;
    for (const auto &entry : std::filesystem::directory_iterator(p.vtu_dir))
      n_pvtu += entry.path().extension() == ".pvtu";
    EXPECT_EQ(n_pvtu, n_expected);
    EXPECT_TRUE(std::filesystem::exists(p.vtu_dir / "impact.pvd"));

    constexpr double tolerance = 1e-12;
    const auto       info      = read_mesh_info(mesh);
    EXPECT_NEAR(info.area_by_material.at(kimp::geometry::slab_material), L * t, tolerance);
    EXPECT_NEAR(info.area_by_material.at(kimp::geometry::wall_material), L * t, tolerance);
    EXPECT_NEAR(info.length_by_boundary.at(kimp::geometry::slab_contact), t, tolerance);
    EXPECT_NEAR(info.length_by_boundary.at(kimp::geometry::wall_contact), t, tolerance);
    EXPECT_EQ(info.n_cells, 2u * 40u * 4u);
  }

  TEST(Mpi, DistributedRunMatchesSerialRun)
  {
    // Run on MPI_COMM_WORLD (1 or 2 ranks under ctest) and on MPI_COMM_SELF on every rank.
    constexpr double tolerance = 1e-10;
    auto             p         = scene_parameters(0.05, false, "scene_mpi.msh");
    p.end_time                 = 0.004; // the first axial-wave round trip and its force dips
    const auto  runs           = run_on_world_and_self(p);
    const auto &world = runs.world, &self = runs.self;
    ASSERT_EQ(world.history.time.size(), self.history.time.size());
    const auto [max_force, max_difference] = force_history_difference(world, self);
    ASSERT_GT(max_force, 0);
    for (std::size_t i = 0; i < world.history.time.size(); ++i)
    {
      EXPECT_NEAR(world.history.contact_force[i],
                  self.history.contact_force[i],
                  tolerance * max_force)
        << "sample " << i << ", t = " << world.history.time[i];
      EXPECT_NEAR(world.history.slab_velocity[i], self.history.slab_velocity[i], tolerance)
        << "sample " << i;
    }
    if (rank() == 0)
      std::cout << "MPI: " << world.summary.n_ranks << " ranks vs 1, " << world.history.time.size()
                << " samples, max |dF| / max F = " << max_difference / max_force << '\n';
  }

  /** The run of @p p on all ranks and on one: the same step and force history (relative
   *  @p tolerance); returns both for the caller's own checks. */
  auto same_on_every_partition(const ImpactParameters &p, double tolerance)
  {
    const auto runs = run_on_world_and_self(p);
    EXPECT_NEAR(runs.world.summary.dt / runs.self.summary.dt, 1.0, 1e-12);
    const auto [max_force, max_difference] = force_history_difference(runs.world, runs.self);
    EXPECT_GT(max_force, 0);
    EXPECT_LT(max_difference, tolerance * max_force);
    return runs;
  }

  TEST(Mpi, ScaledPenaltyIsTheSameOnEveryPartition)
  {
    // penalty_step_ratio takes the cells' largest omega and the slaves' masses over all ranks:
    // 1 or 2 ranks choose the same factor and step as one rank alone.
    auto p               = scene_parameters(0.05, false, "scene_mpi_step_ratio.msh");
    p.end_time           = 0.002;
    p.penalty_step_ratio = 0.7;
    const auto runs      = same_on_every_partition(p, 1e-10);
    EXPECT_NEAR(runs.world.summary.penalty_factor / runs.self.summary.penalty_factor, 1.0, 1e-12);
  }

  TEST(Mpi, SlabDampingTakesTheSameEnergyOnEveryPartition)
  {
    // The plane sections' motion is a sum over every rank's slab nodes: 1 or 2 ranks give the
    // same force history and dissipation as one rank alone.
    auto p               = scene_parameters(0.05, false, "scene_mpi_slab_damping.msh");
    p.end_time           = 0.004;
    p.slab_damping_ratio = 0.05;
    const auto runs      = same_on_every_partition(p, 1e-10);
    ASSERT_FALSE(runs.self.history.slab_damping.empty());
    EXPECT_GT(runs.self.history.slab_damping.back(), 0);
    EXPECT_NEAR(runs.world.history.slab_damping.back(),
                runs.self.history.slab_damping.back(),
                1e-10 * runs.self.history.kinetic.front());
  }

  TEST(Mpi, SubcycledContactIsTheSameOnEveryPartition)
  {
    // The contact nodes' sub-steps run on the gathered compact state, the same on every rank:
    // 1 or 2 ranks give the same step, sub-steps and force history as one rank alone.
    auto p              = scene_parameters(0.05, false, "scene_mpi_subcycles.msh");
    p.end_time          = 0.002;
    p.contact_subcycles = 0;
    const auto runs     = same_on_every_partition(p, 1e-10);
    EXPECT_EQ(runs.world.summary.contact_subcycles, runs.self.summary.contact_subcycles);
    EXPECT_GE(runs.world.summary.contact_subcycles, 2u);
  }

  TEST(Mpi, FramesGatherTheWholeMeshOnRankZeroAsOnOneRank)
  {
    // The deformed-mesh frames of the report's animation: gathered from 1 or 2 ranks they equal
    // a run on one rank; frame 0 is undeformed; every cell is counter-clockwise.
    auto p           = scene_parameters(0.05, false, "scene_mpi_frames.msh");
    p.end_time       = 0.004;
    p.frame_interval = 1e-3;
    const auto world = run_impact(p, MPI_COMM_WORLD, nullptr);
    const auto self  = run_impact(p, MPI_COMM_SELF, nullptr);
    if (rank() != 0)
    {
      EXPECT_TRUE(world.frames.time.empty()) << "frames are gathered on rank 0 only";
      return;
    }
    const ImpactFrames &f = world.frames, &g = self.frames;
    const std::size_t   n_cells = f.material.size(), n_vertices = f.vertices.size() / 2;
    EXPECT_EQ(n_cells, world.summary.n_cells);
    ASSERT_EQ(f.cells.size(), 4 * n_cells);
    // The same frames on every partition: one every frame_interval, and dense ones around the
    // force peak (the elastic slab's force chatters at first touch, which must not end them), so
    // that the frame nearest the peak of the force history is within 0.15 ms of it.
    ASSERT_EQ(f.time, g.time);
    const auto   every = std::lround(p.frame_interval / world.summary.dt);
    const double dt    = world.summary.dt;
    for (long k = 0; k * every <= static_cast<long>(world.summary.n_steps); ++k)
      EXPECT_TRUE(std::any_of(f.time.begin(),
                              f.time.end(),
                              [&](double t) { return std::abs(t - k * every * dt) < 1e-3 * dt; }))
        << "no frame at step " << k * every;
    const auto &h = world.history;
    const auto  i_peak =
      std::max_element(h.contact_force.begin(), h.contact_force.end()) - h.contact_force.begin();
    const double t_peak  = h.time[static_cast<std::size_t>(i_peak)];
    double       nearest = f.time.front();
    for (const double t : f.time)
      if (std::abs(t - t_peak) < std::abs(nearest - t_peak))
        nearest = t;
    EXPECT_LT(std::abs(nearest - t_peak), 0.15e-3) << "peak at " << t_peak << " s";
    ASSERT_EQ(f.displacement.size(), f.time.size() * 2 * n_vertices);
    ASSERT_EQ(f.von_mises_stress.size(), f.time.size() * n_cells);
    EXPECT_TRUE(f.damage.empty()) << "linear laws have no damage field";
    for (std::size_t c = 0; c < n_cells; ++c)
    {
      double area2 = 0; // shoelace: positive for counter-clockwise vertices
      for (int k = 0; k < 4; ++k)
      {
        const auto a = static_cast<std::size_t>(f.cells[4 * c + k]);
        const auto b = static_cast<std::size_t>(f.cells[4 * c + (k + 1) % 4]);
        area2 +=
          f.vertices[2 * a] * f.vertices[2 * b + 1] - f.vertices[2 * b] * f.vertices[2 * a + 1];
      }
      EXPECT_GT(area2, 0) << "cell " << c;
    }
    double u_max = 0, s_max = 0;
    for (std::size_t i = 0; i < 2 * n_vertices; ++i)
      EXPECT_EQ(f.displacement[i], 0.0) << "frame 0 is the undeformed mesh";
    for (const double u : g.displacement)
      u_max = std::max(u_max, std::abs(u));
    for (const double s : g.von_mises_stress)
      s_max = std::max(s_max, s);
    ASSERT_GT(u_max, 0);
    ASSERT_GT(s_max, 0);
    ASSERT_EQ(g.displacement.size(), f.displacement.size());
    for (std::size_t i = 0; i < f.displacement.size(); ++i)
      ASSERT_NEAR(f.displacement[i], g.displacement[i], 1e-10 * u_max) << "value " << i;
    for (std::size_t i = 0; i < f.von_mises_stress.size(); ++i)
      ASSERT_NEAR(f.von_mises_stress[i], g.von_mises_stress[i], 1e-8 * s_max) << "value " << i;
    // The contact pressure: the same contact nodes (mesh vertices on the slab front) and
    // pressures, to the tolerance of the displacements it comes from.
    const std::size_t n_contact = f.contact_vertices.size();
    ASSERT_GT(n_contact, 1u);
    ASSERT_EQ(f.contact_vertices, g.contact_vertices);
    ASSERT_EQ(f.contact_length, g.contact_length);
    ASSERT_EQ(f.contact_pressure.size(), f.time.size() * n_contact);
    ASSERT_EQ(g.contact_pressure.size(), f.contact_pressure.size());
    for (const double v : f.contact_vertices)
      ASSERT_LT(v, static_cast<double>(n_vertices));
    double p_max = 0;
    for (const double x : g.contact_pressure)
      p_max = std::max(p_max, x);
    ASSERT_GT(p_max, 0);
    for (std::size_t i = 0; i < f.contact_pressure.size(); ++i)
      ASSERT_NEAR(f.contact_pressure[i], g.contact_pressure[i], 1e-8 * p_max) << "value " << i;
    std::cout << "frames: " << f.time.size() << " of " << n_cells << " cells and " << n_vertices
              << " vertices on " << world.summary.n_ranks << " ranks, max |u| " << u_max
              << " m, max von Mises " << s_max << " Pa, max contact pressure " << p_max << " Pa on "
              << n_contact << " nodes\n";
  }

  TEST(Mpi, DistributedImplicitRunMatchesSerialRun)
  {
    // Implicit, direct solver: the KLU factorization and the Woodbury contact update on 1 or 2
    // ranks give the same Newton iterates up to round-off and the Newton tolerance.
    constexpr double tolerance = 1e-8;
    auto             p         = scene_parameters(0.05, false, "scene_mpi_implicit.msh");
    p.end_time                 = 0.004;
    p.integrator               = ImpactParameters::Integrator::implicit_newmark;
    expect_same_force_history(run_on_world_and_self(p), tolerance, "MPI implicit");
  }
} // namespace
