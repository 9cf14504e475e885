// Cost of the docs/physics.md §4 impact (H = 1.25 m) in kimp::fem: explicit vs implicit, rigid vs
// elastic slab, two mesh sizes. Fixed single iterations so that `mpirun -np N` stays collective.
#include <benchmark/benchmark.h>
#include <filesystem>
#include <string>

#include "fem/impact.h"
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
} // namespace

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
  return 0;
}
