// Benchmarks of the 3D (plan) lumped engine against the planar one: the Kobe-length 48 s record at
// Δt = 2e-5 s (2.4 million steps), the thesis' 4-storey isolated building (5 levels) with the
// Table 4.3 walls (modified Kelvin-Voigt, 2500 kN/mm, 15 cm): planar (5 DOFs, walls on two sides)
// and in plan (15 DOFs, moat all round), symmetric along x and eccentric at 30°. The target is a
// cost per DOF-step of the plan run at most 3 times the planar one (counter s_per_dof_step).
#include <benchmark/benchmark.h>
#include <cmath>

#include "lumped/integrators/central_difference.h"
#include "tests/lumped/plan_scenes.h"

namespace
{
  using namespace kimp::lumped;

  constexpr double dt = 2e-5;

  /// 48 s synthetic near-fault record sampled at 0.01 s (Kobe KJMA length and sampling).
  const GroundMotion &record_48s()
  {
    return kimp::testing::kobe_length_motion();
  }

  void set_counters(benchmark::State &state,
                    const long        n_steps,
                    const std::size_t n_dofs,
                    const std::size_t impacts)
  {
    state.counters["steps"] = static_cast<double>(n_steps);
    state.counters["s_per_dof_step"] =
      benchmark::Counter(static_cast<double>(n_steps) * static_cast<double>(n_dofs),
                         benchmark::Counter::kIsIterationInvariantRate |
                           benchmark::Counter::kInvert);
    state.counters["impacts"] = static_cast<double>(impacts);
  }

  void BM_PlanarTable43(benchmark::State &state)
  {
    CentralDifferenceOptions opt;
    opt.dt = dt;
    const CentralDifference cdm(
      PoundingModel(kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, 0.15)),
      opt);
    Response r;
    for (auto _ : state)
      benchmark::DoNotOptimize(r = cdm.run(record_48s()));
    set_counters(state, r.n_steps, r.n_dofs, r.n_impacts());
  }
  BENCHMARK(BM_PlanarTable43)->Unit(benchmark::kMillisecond);

  /// The plan run: arg 0 symmetric along x, arg 1 masses 5 % of the plan off centre, at 30°.
  void BM_PlanTable43(benchmark::State &state)
  {
    plan::PlanScene scene;
    scene.building       = kimp::testing::plan_reference_building();
    const bool eccentric = state.range(0) == 1;
    if (eccentric)
      for (plan::PlanLevel &l : scene.building.levels)
        l.mass_eccentricity = plan::Point(0.05, 0.05) * kimp::testing::plan_width;
    scene.moat =
      kimp::testing::plan_moat(scene.building, "modified_kelvin_voigt", 2.5e9, 0.15, 0.3);
    plan::PlanOptions opt;
    opt.dt = dt;
    const plan::PlanCentralDifference cdm(plan::PlanModel(scene), opt);
    const plan::PlanGroundMotion      g =
      plan::along_angle(record_48s(), eccentric ? 30.0 * 3.14159265358979323846 / 180.0 : 0.0);
    plan::PlanResponse r;
    for (auto _ : state)
      benchmark::DoNotOptimize(r = cdm.run(g));
    set_counters(state, r.n_steps, cdm.model().n_dofs(), r.n_impacts());
  }
  BENCHMARK(BM_PlanTable43)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
} // namespace

BENCHMARK_MAIN();
