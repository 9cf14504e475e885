// Cost of the docs/physics.md §4 impact (H = 1.25 m) in kimp::fem: explicit vs implicit, rigid vs
// elastic slab, two mesh sizes. Fixed single iterations so that `mpirun -np N` stays collective.
#include <algorithm>
#include <benchmark/benchmark.h>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "fem/impact.h"
#include "fem/inelastic_laws.h"
#include "fem/mpi_session.h"
#include "geometry/scene_geometry.h"
#include "geometry/scene_ids.h"
#include "geometry/scene_mesh.h"
#include "tests/support/mpi_temp_dir.h"

namespace
{
  using kimp::fem::ImpactParameters;
  using kimp::fem::ImplicitOptions;

  ImpactParameters scene(double h_contact, bool rigid)
  {
    kimp::geometry::SceneGeometry g;
    g.h_contact = h_contact;
    g.h_max     = std::max(0.1, h_contact);
    g.mesh_slab = !rigid;
    int rank    = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    const auto file = kimp::testing::shared_temp_dir("fem_bench", MPI_COMM_WORLD) /
                      (std::to_string(h_contact) + (rigid ? "_rigid" : "") + ".msh");
    if (rank == 0)
      kimp::geometry::build_scene_mesh(g, file);
    MPI_Barrier(MPI_COMM_WORLD);
    ImpactParameters p;
    p.mesh_file                                = file;
    p.materials[kimp::geometry::slab_material] = {30e9, 0.2, 2400};
    p.materials[kimp::geometry::wall_material] = {30e9, 0.2, 2400};
    p.materials[kimp::geometry::soil_material] = {50e6, 0.3, 1900};
    p.rigid_slab                               = rigid;
    p.slab_mass                                = 2400 * g.slab_length * g.slab_thickness;
    p.slab_face_y0                             = g.slab_bottom();
    p.slab_face_y1                             = g.resolved_slab_top();
    p.slab_front_x                             = g.slab_front_x();
    return p;
  }

  void run(benchmark::State &state, ImpactParameters p)
  {
    kimp::fem::ImpactSummary s;
    for (auto _ : state)
      s = kimp::fem::run_impact(p, MPI_COMM_WORLD, nullptr).summary;
    state.counters["dofs"]         = s.n_dofs;
    state.counters["steps"]        = s.n_steps;
    state.counters["us_per_step"]  = 1e6 * s.wall_seconds / s.n_steps;
    state.counters["ranks"]        = s.n_ranks;
    state.counters["peak_kN_m"]    = s.peak_force / 1e3;
    state.counters["duration_ms"]  = s.contact_duration * 1e3;
    state.counters["cor"]          = s.apparent_cor;
    state.counters["impulse_Ns_m"] = s.impulse;
    state.counters["dt_us"]        = s.dt * 1e6;
    if (p.integrator == ImpactParameters::Integrator::implicit_newmark)
    {
      state.counters["newton"]   = s.n_newton;
      state.counters["halvings"] = s.n_step_halvings;
      state.counters["solves"]   = s.n_linear_solves;
      state.counters["setup_s"]  = s.linear_setup_seconds;
      state.counters["solver_s"] = s.linear_solver_seconds;
      state.counters["ms_per_solve"] =
        s.n_linear_solves > 0 ?
          1e3 * (s.linear_solver_seconds - s.linear_setup_seconds) / s.n_linear_solves :
          0.0;
    }
  }

  void ExplicitElasticSlab(benchmark::State &state)
  {
    run(state, scene(state.range(0) * 1e-4, false));
  }
  void ExplicitRigidSlab(benchmark::State &state)
  {
    run(state, scene(state.range(0) * 1e-4, true));
  }
  void ImplicitElasticSlab(benchmark::State &state)
  {
    auto p                           = scene(state.range(0) * 1e-4, false);
    p.integrator                     = ImpactParameters::Integrator::implicit_newmark;
    p.implicit_options.dt_factor     = static_cast<double>(state.range(1));
    p.implicit_options.linear_solver = state.range(2) == 0 ? ImplicitOptions::LinearSolver::direct :
                                                             ImplicitOptions::LinearSolver::cg_amg;
    run(state, p);
  }
  void ImplicitRigidSlab(benchmark::State &state)
  {
    auto p                       = scene(state.range(0) * 1e-4, true);
    p.integrator                 = ImpactParameters::Integrator::implicit_newmark;
    p.implicit_options.dt_factor = static_cast<double>(state.range(1));
    run(state, p);
  }

  /**
   * The reinforced moat wall of docs/validation.md on contact elements of h_contact: geostatic
   * medium_dense_sand Mohr-Coulomb, concrete damage from f_cm = 38 MPa with the wall's and the
   * slab's bars, elastic slab at 1 m/s.
   */
  ImpactParameters moat_wall(double h_contact)
  {
    using namespace kimp::fem;
    namespace ids                       = kimp::geometry;
    auto                 p              = scene(h_contact, false);
    const SoilParameters sp             = soil_preset("medium_dense_sand");
    p.materials[ids::soil_material]     = {sp.youngs_modulus, sp.poisson_ratio, sp.density};
    p.material_laws[ids::soil_material] = std::make_shared<const MohrCoulombLaw>(sp);
    const auto              cp          = ConcreteParameters::from_f_cm(38e6);
    ReinforcementParameters wall, slab;
    wall.ratio_x                        = 0.002;
    wall.ratio_y                        = 0.008;
    slab.ratio_x                        = 0.005;
    p.materials[ids::wall_material]     = {cp.youngs_modulus, cp.poisson_ratio, 2400};
    p.materials[ids::slab_material]     = {cp.youngs_modulus, cp.poisson_ratio, 2400};
    p.material_laws[ids::wall_material] = std::make_shared<const ConcreteDamageLaw>(cp, wall);
    p.material_laws[ids::slab_material] = std::make_shared<const ConcreteDamageLaw>(cp, slab);
    p.geostatic.enabled                 = true;
    p.geostatic.initial_stress_K0[ids::soil_material] = 1 - std::sin(sp.friction_angle);
    p.initial_velocity                                = 1.0;
    return p;
  }

  /** moat_wall() for a fixed 40 ms with (range 1 = 1) or without the soil's mean-dilatation
   *  B-bar: its cost per step (CPU time of the run; docs/performance.md). */
  void ExplicitInelasticMeanDilatation(benchmark::State &state)
  {
    auto p                 = moat_wall(state.range(0) * 1e-4);
    p.end_time             = 0.04;
    p.separation_hold_time = p.end_time;
    p.mean_dilatation      = state.range(1) != 0;
    run(state, p);
  }

  /** moat_wall() for a fixed 300 ms: the wall face's displacement at the end (mm) and its change
   *  over the last 50 ms (mm), the permanent displacement and whether it has settled
   *  (docs/validation.md). */
  void ImpactPermanentDisplacement(benchmark::State &state)
  {
    auto p                 = moat_wall(state.range(0) * 1e-4);
    p.end_time             = 0.3;
    p.separation_hold_time = p.end_time;
    p.output_interval      = 1e-4;
    kimp::fem::ImpactResult r;
    for (auto _ : state)
      r = kimp::fem::run_impact(p, MPI_COMM_WORLD, nullptr);
    const auto &w = r.history.wall_displacement;
    const auto &t = r.history.time;
    std::size_t k = 0;
    while (k + 1 < t.size() && t[k] < t.back() - 0.05)
      ++k;
    state.counters["dofs"]              = r.summary.n_dofs;
    state.counters["steps"]             = r.summary.n_steps;
    state.counters["wall_end_mm"]       = r.summary.wall_residual_displacement * 1e3;
    state.counters["wall_last_50ms_mm"] = (w.back() - w[k]) * 1e3;
    state.counters["wall_max_mm"]       = *std::max_element(w.begin(), w.end()) * 1e3;
    state.counters["permanent_ind_mm"]  = r.summary.permanent_indentation * 1e3;
    state.counters["peak_kN_m"]         = r.summary.peak_force / 1e3;
    state.counters["cor"]               = r.summary.apparent_cor;
  }
} // namespace

// Arguments: contact element size in 0.1 mm; B-bar on (1) or off (0).
BENCHMARK(ExplicitInelasticMeanDilatation)
  ->Args({500, 1})
  ->Args({500, 0})
  ->Args({250, 1})
  ->Args({250, 0})
  ->Iterations(1)
  ->Unit(benchmark::kSecond);
// Argument: contact element size in 0.1 mm (the three ladder levels).
BENCHMARK(ImpactPermanentDisplacement)
  ->Arg(500)
  ->Arg(250)
  ->Arg(125)
  ->Iterations(1)
  ->Unit(benchmark::kSecond);
// Argument: contact element size in 0.1 mm (250 = 2.5 cm, the default scene).
BENCHMARK(ExplicitElasticSlab)->Arg(250)->Arg(125)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(ExplicitRigidSlab)->Arg(250)->Iterations(1)->Unit(benchmark::kSecond);
// Arguments: contact element size in 0.1 mm, dt as a multiple of the explicit limit, linear
// solver (0: direct KLU + Woodbury contact update, 1: CG + ML AMG).
BENCHMARK(ImplicitElasticSlab)
  ->Args({500, 4, 0})
  ->Args({250, 4, 0})
  ->Args({125, 4, 0})
  ->Args({500, 4, 1})
  ->Args({250, 4, 1})
  ->Args({125, 4, 1})
  ->Iterations(1)
  ->Unit(benchmark::kSecond);
BENCHMARK(ImplicitRigidSlab)->Args({250, 4})->Iterations(1)->Unit(benchmark::kSecond);

int main(int argc, char **argv)
{
  kimp::fem::MpiSession mpi(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  kimp::testing::remove_shared_temp_dir("fem_bench", MPI_COMM_WORLD);
  return 0;
}
