// Cost of the contact laws (one set_trial + commit in contact) and of the two-body collision lab
// at the thesis' set-up (280 t vs 300 t at 1 m/s, Δt = 2e-4 s and 1e-5 s).
#include <benchmark/benchmark.h>
#include <cmath>
#include <string>

#include "lumped/collision/cimp_calibration.h"
#include "lumped/collision/two_body.h"
#include "lumped/laws/bumper_law.h"
#include "lumped/laws/force_law_factory.h"

namespace
{
  kimp::lumped::ForceLawSpec bench_spec(const std::string &law)
  {
    kimp::lumped::ForceLawSpec s;
    s.law            = law;
    s.cor            = kimp::lumped::thesis_cor;
    s.effective_mass = 144.8e3;
    s.stiffness = law == "linear" || law.find("kelvin") != std::string::npos ? 2.5e9 : 2.3717e10;
    if (law == "bumper")
    {
      s.stiffness = kimp::lumped::bumper_stiffness(0.0225, 55835e3, 0.05, 2.65, 4);
      s.bumper_ultimate_deformation = 0.0375;
      s.bumper_wall_stiffness       = 1.5e9;
    }
    return s;
  }

  /// One contact (approach and restitution) sampled in 1000 steps, repeated: ns per law call.
  void BM_SetTrialCommit(benchmark::State &state, const std::string &law_name)
  {
    const auto          law = kimp::lumped::make_force_law(bench_spec(law_name));
    constexpr int       n   = 1000;
    constexpr double    pi  = 3.14159265358979323846;
    std::vector<double> delta(n + 2), rate(n + 2);
    for (int i = 0; i < n + 2; ++i)
    {
      delta[i] = 5e-3 * std::sin(pi * (i - 0.5) / n);
      rate[i]  = 5e-3 * pi / n * std::cos(pi * (i - 0.5) / n) / 1e-5;
    }
    for (auto _ : state)
    {
      for (int i = 0; i < n + 2; ++i)
      {
        benchmark::DoNotOptimize(law->set_trial(delta[i], rate[i]));
        law->commit();
      }
      law->revert_to_start();
    }
    state.SetItemsProcessed(state.iterations() * (n + 2));
  }

  void BM_TwoBodyCollision(benchmark::State &state, const std::string &law_name, double dt)
  {
    const auto                 law = kimp::lumped::make_force_law(bench_spec(law_name));
    kimp::lumped::TwoBodySetup setup;
    setup.time_step      = dt;
    setup.record_history = false;
    std::size_t steps    = 0;
    for (auto _ : state)
    {
      const auto r = kimp::lumped::simulate_two_body(*law, setup);
      steps += r.n_steps;
      benchmark::DoNotOptimize(r.effective_cor);
    }
    state.SetItemsProcessed(static_cast<int64_t>(steps));
  }

  void BM_CalibrationThesisGrid(benchmark::State &state)
  {
    const kimp::lumped::CalibrationOptions options; // 14 COR x 5 v x 10 masses, Δt = 2e-5 s
    for (auto _ : state)
      benchmark::DoNotOptimize(kimp::lumped::calibrate_impact_coefficient(options).c);
  }
} // namespace

BENCHMARK_CAPTURE(BM_SetTrialCommit, linear, std::string("linear"));
BENCHMARK_CAPTURE(BM_SetTrialCommit, kelvin_voigt, std::string("kelvin_voigt"));
BENCHMARK_CAPTURE(BM_SetTrialCommit, modified_kelvin_voigt, std::string("modified_kelvin_voigt"));
BENCHMARK_CAPTURE(BM_SetTrialCommit, jankowski, std::string("jankowski"));
BENCHMARK_CAPTURE(BM_SetTrialCommit, hertzdamp, std::string("hertzdamp"));
BENCHMARK_CAPTURE(BM_SetTrialCommit, hysteretic, std::string("hysteretic"));
BENCHMARK_CAPTURE(BM_SetTrialCommit, bumper, std::string("bumper"));
BENCHMARK_CAPTURE(BM_TwoBodyCollision, kelvin_voigt_2e4, std::string("kelvin_voigt"), 2e-4);
BENCHMARK_CAPTURE(BM_TwoBodyCollision, hysteretic_2e4, std::string("hysteretic"), 2e-4);
BENCHMARK_CAPTURE(BM_TwoBodyCollision, hysteretic_1e5, std::string("hysteretic"), 1e-5);
BENCHMARK(BM_CalibrationThesisGrid)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
