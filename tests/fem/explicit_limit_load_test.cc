// The explicit impact solver (fem/impact.h, central differences, mean-dilatation B-bar in the
// plastic soil cells) against the static solver (fem/static_plasticity.h, Q1 B-bar, full Newton)
// on the closed-form collapse loads of docs/physics.md §6, by a slow push of a heavy rigid slab:
// Prandtl's smooth strip footing on Tresca soil and Rankine's passive thrust of clay on a smooth
// wall. Each scene is the static test's (tests/fem/static_plasticity_test.cc) on the same grid,
// rotated so that the push is along +x (the rigid slab's direction). Numbers: docs/validation.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <gtest/gtest.h>
#include <memory>
#include <string>
#include <vector>

#include "fem/impact.h"
#include "fem/inelastic_laws.h"
#include "fem/static_plasticity.h"
#include "tests/fem/impact_test_support.h"
#include "tests/fem/static_plasticity_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;
  constexpr double pi = 3.14159265358979323846;
  constexpr double g  = 9.81;
  // Boundary ids of the static runs, the static test's (the impact runs use
  // geometry/scene_ids.h).
  constexpr unsigned int st_free = free_surface, st_push = wall, st_fixed = base,
                         st_roller = far_side;

  SoilParameters clay(double E, double nu, double c)
  {
    SoilParameters p;
    p.youngs_modulus = E;
    p.poisson_ratio  = nu;
    p.density        = 1700;
    p.cohesion       = c;
    p.friction_angle = 0;
    p.dilatancy      = 0;
    p.tension_cutoff = 1e9; // Tresca: no cut-off
    return p;
  }

  /** The mesh as ASCII MSH 2.2 at scratch(name) (rank 0 writes, all wait); edges of boundary 0
   *  are left out (free). */
  std::filesystem::path write_plane_mesh(const PlaneMesh &m, const std::string &name)
  {
    const auto file = scratch(name);
    if (rank() == 0)
    {
      std::size_t n_edges = 0;
      for (const auto &e : m.boundary_edges)
        n_edges += e.boundary != 0 ? 1 : 0;
      std::ofstream out(file);
      out.precision(17);
      out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << m.vertices.size() << '\n';
      for (std::size_t i = 0; i < m.vertices.size(); ++i)
        out << i + 1 << ' ' << m.vertices[i][0] << ' ' << m.vertices[i][1] << " 0\n";
      out << "$EndNodes\n$Elements\n" << n_edges + m.cells.size() << '\n';
      std::size_t k = 1;
      for (const auto &e : m.boundary_edges)
        if (e.boundary != 0)
          out << k++ << " 1 2 " << e.boundary << ' ' << e.boundary << ' ' << e.vertices[0] + 1
              << ' ' << e.vertices[1] + 1 << '\n';
      // PlaneMesh cells are lexicographic (deal.II); MSH quadrilaterals go round.
      for (const auto &c : m.cells)
        out << k++ << " 3 2 " << c.material << ' ' << c.material << ' ' << c.vertices[0] + 1 << ' '
            << c.vertices[1] + 1 << ' ' << c.vertices[3] + 1 << ' ' << c.vertices[2] + 1 << '\n';
      out << "$EndElements\n";
    }
    MPI_Barrier(MPI_COMM_WORLD);
    return file;
  }

  /** A soil body pushed in +x at x = 0 by a rigid slab of 1e11 kg/m moving at v (it loses
   *  < 0.1 % of its speed to the soil's resistance: a displacement-controlled push). */
  ImpactParameters push_parameters(const std::filesystem::path &mesh,
                                   const SoilParameters        &s,
                                   std::shared_ptr<MaterialLaw> law,
                                   double                       v,
                                   double                       travel,
                                   double                       y0,
                                   double                       y1)
  {
    ImpactParameters p;
    p.mesh_file = mesh;
    const Material m{s.youngs_modulus, s.poisson_ratio, s.density};
    for (const unsigned int id : {ids::slab_material, ids::wall_material, ids::soil_material})
      p.materials[id] = m;
    p.material_laws[ids::soil_material] = std::move(law);
    p.rigid_slab                        = true;
    p.slab_mass                         = 1e11;
    p.slab_face_y0                      = y0;
    p.slab_face_y1                      = y1;
    p.slab_front_x                      = 0;
    p.initial_velocity                  = v;
    p.end_time                          = travel / v;
    p.separation_hold_time              = p.end_time; // the slab never stops: run to the end
    p.output_interval                   = p.end_time / 1000;
    return p;
  }

  /** Mean contact force (N/m) of the samples whose slab displacement is in [a, b] (m). */
  double mean_force(const ImpactResult &r, double a, double b)
  {
    double sum = 0;
    int    n   = 0;
    for (std::size_t i = 0; i < r.history.time.size(); ++i)
      if (r.history.slab_displacement[i] >= a && r.history.slab_displacement[i] <= b)
      {
        sum += r.history.contact_force[i];
        ++n;
      }
    EXPECT_GT(n, 4);
    return n > 0 ? sum / n : 0;
  }

  /** Rank 0 begins the line of a push run: "<what> B-bar|plain Q1: N steps of dt ms, wall s; ". */
  void begin_run_line(const char *what, bool bbar, const ImpactResult &r)
  {
    if (rank() == 0)
      std::printf("%s %s: %zu steps of %.3g ms, %.2f s; ",
                  what,
                  bbar ? "B-bar" : "plain Q1",
                  static_cast<std::size_t>(r.summary.n_steps),
                  r.summary.dt * 1e3,
                  r.summary.wall_seconds);
  }

  /** The explicit push's load with B-bar (p_explicit[0]) and plain Q1 (p_explicit[1]) against the
   *  static solver's: rank 0 ends the line with both and their ratios; B-bar matches within 3 %,
   *  the plain Q1 element locks (more than 3 % above). */
  void expect_b_bar_matches_static_and_q1_locks(const std::vector<double> &p_explicit,
                                                double                     p_static)
  {
    if (rank() == 0)
      std::printf("explicit B-bar %.5g (%.4f of static), plain Q1 %.5g (%.4f of static)\n",
                  p_explicit[0] / 1e3,
                  p_explicit[0] / p_static,
                  p_explicit[1] / 1e3,
                  p_explicit[1] / p_static);
    EXPECT_LT(std::abs(p_explicit[0] / p_static - 1), 0.03);
    EXPECT_GT(p_explicit[1] / p_static, 1.03); // the plain Q1 element locks
  }

  /** Joins two graded coordinate lists sharing an end point. */
  std::vector<double> join(std::vector<double> a, const std::vector<double> &b)
  {
    a.insert(a.end(), b.begin() + 1, b.end());
    return a;
  }

  /** Prandtl's grid of the static test (level 1), rotated: depth x in [0, 3b] graded towards
   *  the surface x = 0, the full footing width y in [-4b, 4b] graded towards the edges y = +-b. */
  struct PrandtlGrid
  {
    std::vector<double> xs, ys;
  };
  PrandtlGrid prandtl_grid()
  {
    constexpr double b = 1;
    PrandtlGrid      grid;
    const auto       down = graded_coordinates(-3 * b, 0, 10, std::pow(1.0 / 8, 1.0 / 9));
    for (auto it = down.rbegin(); it != down.rend(); ++it)
      grid.xs.push_back(-*it);
    const auto half = join(graded_coordinates(0, b, 6, std::pow(1.0 / 4, 1.0 / 5)),
                           graded_coordinates(b, 4 * b, 8, std::pow(8.0, 1.0 / 7)));
    for (auto it = half.rbegin(); it != half.rend(); ++it)
      grid.ys.push_back(-*it);
    grid.ys.pop_back(); // 0 once
    grid.ys.insert(grid.ys.end(), half.begin(), half.end());
    return grid;
  }

  // Prandtl: smooth rigid strip footing of width 2b = 2 m on weightless Tresca soil
  // (c = 20 kPa, E = 10 MPa, nu = 0.45), the static test's grid and supports (rough base, the
  // sides held; the full width instead of the half model, whose symmetry roller the impact
  // solver has no boundary id for), pushed 4 cm at 1 cm/s (4 s, about 40 wave transits across
  // the 3 m depth; the slab's impedance stress rho c_p v = 2.5 kPa is 2.5 % of q_u and decays).
  // The explicit load (the mean over the last 4 mm) matches the static solver's within 3 %, both
  // near q_u = (2 + pi) c; with the plain Q1 strain the explicit solver locks (the load keeps
  // rising, more than 3 % above the static collapse load).
  TEST(ExplicitLimitLoad, PrandtlMatchesTheStaticSolver)
  {
    constexpr double     b = 1, delta = 0.04, v = 1e-2, tol = 1e-9;
    const SoilParameters s     = clay(10e6, 0.45, 20e3);
    const double         exact = (2 + pi) * s.cohesion * 2 * b;
    const auto           grid  = prandtl_grid();
    const double         depth = grid.xs.back(), side = grid.ys.back();

    StaticPlasticityParameters sp;
    sp.mesh               = tensor_product_mesh(grid.xs,
                                  grid.ys,
                                  0,
                                  [&](double x, double y)
                                  {
                                    return x < tol && std::abs(y) < b ? st_push :
                                                         x > depth - tol || std::abs(y) > side - tol ? st_fixed :
                                                                                                       st_free;
                                  });
    sp.laws[0]            = std::make_shared<MohrCoulombLaw>(s);
    sp.prescribed         = {{st_fixed, true, true, 0, 0}, {st_push, true, false, delta, 0}};
    sp.n_steps            = 8;
    const auto   st       = run_static_plasticity(sp);
    const double p_static = std::abs(st.steps.back().reactions[1][0]);

    const auto mesh =
      write_plane_mesh(tensor_product_mesh(grid.xs,
                                           grid.ys,
                                           ids::soil_material,
                                           [&](double x, double y)
                                           {
                                             const unsigned int contact = ids::wall_contact,
                                                                fixed   = ids::fixed_base;
                                             return x < tol && std::abs(y) < b ? contact :
                                                    x > depth - tol || std::abs(y) > side - tol ?
                                                                                 fixed :
                                                                                 0u;
                                           }),
                       "prandtl_push.msh");
    std::vector<double> p_explicit;
    for (const bool bbar : {true, false})
    {
      auto p = push_parameters(mesh, s, std::make_shared<MohrCoulombLaw>(s), v, delta, -b, b);
      p.mean_dilatation = bbar;
      const auto r      = run_impact(p, MPI_COMM_WORLD, nullptr);
      p_explicit.push_back(mean_force(r, 0.9 * delta, delta));
      begin_run_line("Prandtl", bbar, r);
      if (rank() == 0)
        std::printf("force at 1, 2, 3 cm: %.4g, %.4g, %.4g kN/m; mean over the last 10 %% %.5g "
                    "kN/m\n",
                    mean_force(r, 0.0095, 0.0105) / 1e3,
                    mean_force(r, 0.0195, 0.0205) / 1e3,
                    mean_force(r, 0.0295, 0.0305) / 1e3,
                    p_explicit.back() / 1e3);
    }
    if (rank() == 0)
      std::printf("Prandtl: exact %.5g kN/m; static %.5g (%.4f); ",
                  exact / 1e3,
                  p_static / 1e3,
                  p_static / exact);
    expect_b_bar_matches_static_and_q1_locks(p_explicit, p_static);
    EXPECT_LT(std::abs(p_static / exact - 1), 0.06);
  }

  // Rankine: smooth wall H = 2 m pushed into clay (phi = 0, c = 20 kPa, E = 5 MPa, nu = 0.45,
  // gravity with K0 = 1), rough base, far side on rollers, L = 3 H (the static test's scene), on
  // n = 8 cells over H. The rigid slab's plane cannot slide the heel node along the base as the
  // static test's wall does (the impact solver's base holds both components), and a slave node
  // on a fixed support would take an ever growing penalty force; so the base holds the heel, the
  // face's lowest edge is no contact face, and the static run holds the heel too (a transition
  // element, which lowers the n = 8 collapse load by ~8 % below P_p). The explicit run starts
  // from the geostatic state with the face free (the clay stands: gamma H / 2 = 17 kPa < c); the
  // rigid slab 2 cm away at 5 mm/s travels 10 cm in 20 s (about 400 transits of the 6 m
  // backfill; rho c_p v = 0.9 kPa, under 2 % of the mean passive pressure). Its plateau (mean
  // over the last 1 cm) matches the static thrust after an 8 cm push within 3 %.
  TEST(ExplicitLimitLoad, RankinePassiveThrustOfClayMatchesTheStaticSolver)
  {
    constexpr double     H = 2, L = 3 * H, v = 5e-3, travel = 0.1, push = 0.08, tol = 1e-9;
    constexpr unsigned   n     = 8;
    const SoilParameters s     = clay(5e6, 0.45, 20e3);
    const double         exact = 0.5 * s.density * g * H * H + 2 * s.cohesion * H;
    const auto   xs = graded_coordinates(0, L, 3 * n, 1.0), ys = graded_coordinates(0, H, n, 1.0);
    const double heel = 0.5 * H / n; // the lowest face edge's midpoint

    StaticPlasticityParameters sp;
    sp.mesh               = tensor_product_mesh(xs, ys, 0, backfill_sides(L, tol));
    sp.laws[0]            = std::make_shared<MohrCoulombLaw>(s);
    sp.densities[0]       = s.density;
    sp.gravity            = g;
    sp.initial_stress     = geostatic_stress(H, s.density * g, 1.0);
    sp.prescribed         = {{st_roller, true, false, 0, 0},
                             {st_push, true, false, push, 0},
                             {st_fixed, true, true, 0, 0}}; // last: the base governs the heel
    sp.n_steps            = 16;
    const auto   st       = run_static_plasticity(sp);
    const double p_static = std::abs(st.steps.back().reactions[1][0]);
    const double p_before = std::abs(st.steps[st.steps.size() - 3].reactions[1][0]);

    const auto mesh =
      write_plane_mesh(tensor_product_mesh(xs,
                                           ys,
                                           ids::soil_material,
                                           [&](double x, double y)
                                           {
                                             const unsigned int contact = ids::wall_contact,
                                                                fixed   = ids::fixed_base,
                                                                roller  = ids::soil_far_side;
                                             return x < tol && y > 2 * heel ? contact :
                                                    x > L - tol             ? roller :
                                                    y < tol                 ? fixed :
                                                                              0u;
                                           }),
                       "rankine_push.msh");
    std::vector<double> p_explicit;
    for (const bool bbar : {true, false})
    {
      auto p = push_parameters(mesh, s, std::make_shared<MohrCoulombLaw>(s), v, travel, 0, H);
      p.slab_front_x                                    = -0.02;
      p.geostatic.enabled                               = true;
      p.geostatic.gravity                               = g;
      p.geostatic.initial_stress_K0[ids::soil_material] = 1.0;
      p.mean_dilatation                                 = bbar;
      const auto r                                      = run_impact(p, MPI_COMM_WORLD, nullptr);
      p_explicit.push_back(mean_force(r, 0.09, 0.1));
      begin_run_line("Rankine clay", bbar, r);
      if (rank() == 0)
        std::printf("face after the geostatic step %.4g mm; force at slab travel 4, 6, 8 cm: "
                    "%.4g, %.4g, %.4g kN/m; mean over the last 1 cm %.5g kN/m\n",
                    r.summary.geostatic_wall_displacement * 1e3,
                    mean_force(r, 0.0395, 0.0405) / 1e3,
                    mean_force(r, 0.0595, 0.0605) / 1e3,
                    mean_force(r, 0.0795, 0.0805) / 1e3,
                    p_explicit.back() / 1e3);
    }
    if (rank() == 0)
      std::printf("Rankine clay, n = %u: exact %.5g kN/m; static %.5g (%.4f of exact; %.5g one "
                  "eighth of the push before); ",
                  n,
                  exact / 1e3,
                  p_static / 1e3,
                  p_static / exact,
                  p_before / 1e3);
    expect_b_bar_matches_static_and_q1_locks(p_explicit, p_static);
    EXPECT_LT(std::abs(p_static / exact - 1), 0.15);
    EXPECT_LT(std::abs(p_static / p_before - 1), 0.005); // the static load has plateaued
  }
} // namespace
