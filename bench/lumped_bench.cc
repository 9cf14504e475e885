// Benchmarks of the lumped pounding engine: the Kobe-length 48 s case with moat walls at
// Δt = 2e-5 s (2.4 million steps; target < 60 ms on one core) with the fused and the reference
// time-loop kernels side by side, the sweep throughput, and accuracy against cost of the explicit
// central difference method and the implicit Newmark method.
#include <benchmark/benchmark.h>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <type_traits>
#include <utility>

#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/lumped_scenes.h"

namespace
{
  using namespace kimp::lumped;

  /// 48 s synthetic near-fault record sampled at 0.01 s (Kobe KJMA length and sampling).
  const GroundMotion &record_48s()
  {
    return kimp::testing::kobe_length_motion();
  }

  /// Thesis Table 4.3 configuration: 4-storey isolated building, modified Kelvin-Voigt walls
  /// (2500 kN/mm, the thesis COR, m_wall 500 t) at 15 cm on both sides.
  PoundingModel walled_building(const std::string &law = "modified_kelvin_voigt")
  {
    const double stiffness = law == "jankowski" ? 750e3 / std::pow(1e-3, 1.5) : 2.5e9;
    return PoundingModel(kimp::testing::walled_scene(law, stiffness, 0.15));
  }

  void set_counters(benchmark::State &state, const Response &r)
  {
    const double dof_steps  = static_cast<double>(r.n_steps) * static_cast<double>(r.n_dofs);
    state.counters["steps"] = static_cast<double>(r.n_steps);
    state.counters["s_per_dof_step"] =
      benchmark::Counter(dof_steps,
                         benchmark::Counter::kIsIterationInvariantRate |
                           benchmark::Counter::kInvert);
    state.counters["runs_per_s"] =
      benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["history_samples"] = static_cast<double>(r.history.time.size());
    state.counters["impacts"]         = static_cast<double>(r.n_impacts());
  }

  /// Time-loop kernel from a benchmark argument: 0 the automatic choice (the fused kernel for
  /// these models), 1 the block-tridiagonal reference kernel, 2 the any-size fused kernel.
  CdmKernel kernel_arg(const std::int64_t arg)
  {
    return arg == 0 ? CdmKernel::automatic : arg == 1 ? CdmKernel::reference : CdmKernel::any_size;
  }

  /// Central-difference options at time step `dt` with the kernel of benchmark argument
  /// `kernel` (kernel_arg()).
  CentralDifferenceOptions options_at(double dt, const std::int64_t kernel)
  {
    CentralDifferenceOptions opt;
    opt.dt     = dt;
    opt.kernel = kernel_arg(kernel);
    return opt;
  }

  /// Runs `model` under the 48 s record with `opt` in the benchmark loop.
  void run_model(benchmark::State               &state,
                 const PoundingModel            &model,
                 const CentralDifferenceOptions &opt)
  {
    const CentralDifference cdm(model, opt);
    Response                r;
    for (auto _ : state)
    {
      r = cdm.run(record_48s());
      benchmark::DoNotOptimize(r.peak_displacement.data());
    }
    set_counters(state, r);
  }

  /// Runs the walled 4-storey building under the 48 s record with `opt` in the benchmark loop.
  void run_walled_building(benchmark::State &state, const CentralDifferenceOptions &opt)
  {
    run_model(state, walled_building(), opt);
  }

  /// The performance target: 48 s, Δt = 2e-5 s; arg 0: decimated output every 0.01 s (1) or
  /// none (0); arg 1: kernel (0 fused, 1 reference), side by side.
  void BM_CdmWalls48s(benchmark::State &state)
  {
    CentralDifferenceOptions opt = options_at(2e-5, state.range(1));
    opt.output_interval          = state.range(0) ? 0.01 : 0.0;
    run_walled_building(state, opt);
  }
  BENCHMARK(BM_CdmWalls48s)
    ->ArgNames({"history", "reference"})
    ->ArgsProduct({{1, 0}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

  /// The isolated building between moat walls at 15 cm and fixed-base neighbours of `left` and
  /// `right` storeys at 20 cm (modified Kelvin-Voigt everywhere): 5 + left + right DOFs.
  PoundingModel building_between_neighbours(const int left, const int right)
  {
    PoundingScene scene = kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, 0.15);
    for (const auto &[storeys, side] :
         {std::pair{left, &scene.left_neighbour}, std::pair{right, &scene.right_neighbour}})
    {
      AdjacentBuilding nb;
      nb.building   = reference_fixed_base_building(storeys);
      nb.separation = 0.20;
      nb.law        = force_law_factory(kimp::testing::contact_law("modified_kelvin_voigt", 2.5e9));
      *side         = nb;
    }
    return PoundingModel(scene);
  }

  /// Any model size: the building between two neighbours (arg 0, 1: their storeys; 4 + 4 is
  /// data/scenes/isolated_between_neighbours.yaml, 13 DOFs; 6 + 7: 18 DOFs), 20 s of the record
  /// at Δt = 2e-5 s (10^6 steps), histories every 0.01 s; arg 2: kernel (0 automatic, i.e. the
  /// any-size kernel, 1 reference). s_per_dof_step against BM_CdmWalls48s (5 DOFs).
  void BM_CdmNeighbours(benchmark::State &state)
  {
    CentralDifferenceOptions opt = options_at(2e-5, state.range(2));
    opt.duration                 = 20.0;
    run_model(state,
              building_between_neighbours(static_cast<int>(state.range(0)),
                                          static_cast<int>(state.range(1))),
              opt);
  }
  BENCHMARK(BM_CdmNeighbours)
    ->ArgNames({"left", "right", "reference"})
    ->Args({4, 4, 0})
    ->Args({6, 6, 0})
    ->Args({6, 7, 0})
    ->Args({6, 7, 1})
    ->Args({12, 12, 0})
    ->Unit(benchmark::kMillisecond);

  /// A tall building alone (arg: storeys of the fixed-base building; one dense block), 20 s at
  /// Δt = 2e-5 s, no histories; arg 1: kernel (0 automatic, i.e. the reference kernel beyond 16
  /// DOFs per block, 1 reference, 2 any-size): where the dense any-size kernel stops paying
  /// against the reference kernel's Thomas solve.
  void BM_CdmTallBuilding(benchmark::State &state)
  {
    CentralDifferenceOptions opt = options_at(2e-5, state.range(1));
    opt.duration                 = 20.0;
    opt.output_interval          = 0.0;
    PoundingScene scene;
    scene.building = reference_fixed_base_building(static_cast<int>(state.range(0)));
    run_model(state, PoundingModel(scene), opt);
  }
  BENCHMARK(BM_CdmTallBuilding)
    ->ArgNames({"storeys", "kernel"})
    ->ArgsProduct({{20, 40, 80}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

  /// The fused kernel's vector width (arg: doubles per register, 2 SSE2, 4 AVX2, 8 AVX-512F;
  /// capped at what the processor has): the 48 s target case with histories.
  void BM_CdmWalls48sLanes(benchmark::State &state)
  {
    CentralDifferenceOptions opt;
    opt.dt           = 2e-5;
    opt.vector_lanes = static_cast<int>(state.range(0));
    run_walled_building(state, opt);
  }
  BENCHMARK(BM_CdmWalls48sLanes)
    ->ArgName("lanes")
    ->Arg(2)
    ->Arg(4)
    ->Arg(8)
    ->Unit(benchmark::kMillisecond);

  /// Sweep throughput at the thesis' coarser step Δt = 2e-4 s: one run of the first arg seconds
  /// of the record (20 s: 100 000 steps, 48 s: 240 000 steps) with histories every 0.01 s;
  /// arg 1: kernel (0 fused, 1 reference).
  void BM_CdmSweepRun(benchmark::State &state)
  {
    CentralDifferenceOptions opt = options_at(2e-4, state.range(1));
    opt.duration                 = static_cast<double>(state.range(0));
    run_walled_building(state, opt);
  }
  BENCHMARK(BM_CdmSweepRun)
    ->ArgNames({"seconds", "reference"})
    ->ArgsProduct({{20, 48}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

  /// The same 48 s case driven through CentralDifferenceStepper::step() one step at a time
  /// (cost of the stepping interface against run(), which advances in blocks).
  void BM_CdmSingleSteps(benchmark::State &state)
  {
    CentralDifferenceOptions opt;
    opt.dt = 2e-4;
    const CentralDifference  cdm(walled_building(), opt);
    CentralDifferenceStepper stepper(cdm);
    Response                 r;
    for (auto _ : state)
    {
      stepper.init(record_48s());
      while (!stepper.finished())
        stepper.step();
      r = stepper.response();
      benchmark::DoNotOptimize(r.peak_displacement.data());
    }
    set_counters(state, r);
  }
  BENCHMARK(BM_CdmSingleSteps)->Unit(benchmark::kMillisecond);

  struct Reference
  {
    double peak_force      = 0.0;
    double peak_base_accel = 0.0;
  };

  double max_force(const Response &r)
  {
    double f = 0.0;
    for (const ContactResult &c : r.contacts)
      f = std::max(f, c.peak_force);
    return f;
  }

  /// Reference peaks: central differences at Δt = 2.5e-6 s on the first 20 s of the record.
  const Reference &reference(const std::string &law)
  {
    static std::map<std::string, Reference> cache;
    auto                                    it = cache.find(law);
    if (it == cache.end())
    {
      CentralDifferenceOptions opt;
      opt.dt              = 2.5e-6;
      opt.duration        = 20.0;
      opt.output_interval = 0.0;
      const Response r    = CentralDifference(walled_building(law), opt).run(record_48s());
      it = cache.emplace(law, Reference{max_force(r), r.peak_absolute_acceleration[0]}).first;
    }
    return it->second;
  }

  /// Accuracy against cost: arg 0 = law (0 modified KV, 1 Jankowski), arg 1 = Δt in µs.
  template <bool implicit>
  void BM_AccuracyVsCost(benchmark::State &state)
  {
    const std::string   law   = state.range(0) == 0 ? "modified_kelvin_voigt" : "jankowski";
    const double        dt    = static_cast<double>(state.range(1)) * 1e-6;
    const Reference    &ref   = reference(law);
    const PoundingModel model = walled_building(law);
    Response            r;
    for (auto _ : state)
    {
      using Integrator = std::conditional_t<implicit, NewmarkIntegrator, CentralDifference>;
      using Options    = std::conditional_t<implicit, NewmarkOptions, CentralDifferenceOptions>;
      Options opt;
      opt.dt              = dt;
      opt.duration        = 20.0;
      opt.output_interval = 0.0;
      r                   = Integrator(model, opt).run(record_48s());
      benchmark::DoNotOptimize(r.peak_displacement.data());
    }
    state.counters["dt_us"]          = static_cast<double>(state.range(1));
    state.counters["err_peak_force"] = std::abs(max_force(r) - ref.peak_force) / ref.peak_force;
    state.counters["err_base_accel"] =
      std::abs(r.peak_absolute_acceleration[0] - ref.peak_base_accel) / ref.peak_base_accel;
    state.counters["energy_error"] = r.energy.max_relative_error;
  }
  BENCHMARK_TEMPLATE(BM_AccuracyVsCost, false)
    ->ArgsProduct({{0, 1}, {200, 100, 50, 20, 10}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
  BENCHMARK_TEMPLATE(BM_AccuracyVsCost, true)
    ->ArgsProduct({{0, 1}, {5000, 2000, 1000, 500, 200, 100}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
} // namespace

BENCHMARK_MAIN();
