// Accuracy against cost of the time-step policies of `kimp lumped` on a scene's cases: fixed
// steps (central differences and Newmark), `dt: stable` and the variable-step `dt: auto`, against
// the Δt → 0 reference (Richardson on fixed central-difference steps). Prints a Markdown table
// (docs/performance.md "Accuracy against cost"). Not a Google Benchmark: it counts steps.
//   dt_auto_bench SCENE.yaml [CASE-SUBSTRING] [--newmark]
//   dt_auto_bench SCENE.yaml [CASE-SUBSTRING] --time [REPEATS]
// The second form times `dt: stable` and `dt: auto` per case instead (no companion): the least
// wall and thread CPU time of REPEATS (default 20) interleaved runs of each, and their ratio.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_run.h"
#include "app/lumped/lumped_scene.h"

namespace
{
  using namespace kimp::app;

  /// The peaks compared: largest contact force, base and roof |ü + ü_g| and |u|.
  struct Peaks
  {
    double force = 0, base_acc = 0, roof_acc = 0, base_u = 0, roof_u = 0;
    double steps = 0;
  };

  Peaks peaks_of(const LumpedCaseResult &r, std::size_t roof)
  {
    Peaks p;
    for (const auto &c : r.response.contacts)
      p.force = std::max(p.force, c.peak_force);
    p.base_acc = r.response.peak_absolute_acceleration[0];
    p.roof_acc = r.response.peak_absolute_acceleration[roof];
    p.base_u   = r.response.peak_displacement[0];
    p.roof_u   = r.response.peak_displacement[roof];
    p.steps    = static_cast<double>(r.response.n_steps) +
              (r.adaptive ? static_cast<double>(r.adaptive->estimate_steps) : 0.0);
    return p;
  }

  Peaks run(const std::string                &name,
            LumpedScene                       scene,
            const kimp::lumped::GroundMotion &motion,
            double                            base_scale,
            const std::string                &dt,
            bool                              newmark,
            LumpedCaseResult                 *out = nullptr)
  {
    scene.integration.dt        = dt;
    scene.integration.companion = false;
    scene.integration.method    = newmark ? IntegrationMethod::newmark : IntegrationMethod::cdm;
    scene.integration.max_steps = 1e12;
    const LumpedCaseResult r    = run_lumped_case(name, scene, motion, base_scale);
    if (!r.ok())
    {
      std::fprintf(stderr, "%s dt %s: %s\n", name.c_str(), dt.c_str(), r.status.c_str());
      std::exit(1);
    }
    const std::size_t roof = scene.building.kind == BuildingKind::isolated ?
                               scene.building.n_storeys :
                               scene.building.n_storeys - 1;
    if (out)
      *out = r;
    return peaks_of(r, roof);
  }

  double cpu_seconds()
  {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }

  std::string load_average()
  {
    std::ifstream in("/proc/loadavg");
    std::string   a, b, c;
    in >> a >> b >> c;
    return a + " " + b + " " + c;
  }

  /// Least wall and CPU time (s) of `repeats` runs of `stable` and `auto`, interleaved.
  void time_policies(const std::string                &name,
                     const LumpedScene                &scene,
                     const kimp::lumped::GroundMotion &motion,
                     const double                      base_scale,
                     const int                         repeats)
  {
    double      wall[2] = {1e300, 1e300}, cpu[2] = {1e300, 1e300}, steps[2] = {0, 0};
    const char *policy[2] = {"stable", "auto"};
    // The result is not copied out (a copy of the histories is no part of run_lumped_case).
    for (int k = 0; k < repeats; ++k)
      for (int p = 0; p < 2; ++p)
      {
        const auto   w0 = std::chrono::steady_clock::now();
        const double c0 = cpu_seconds();
        steps[p]        = run(name, scene, motion, base_scale, policy[p], false).steps;
        const double c1 = cpu_seconds();
        const auto   w1 = std::chrono::steady_clock::now();
        wall[p]         = std::min(wall[p], std::chrono::duration<double>(w1 - w0).count());
        cpu[p]          = std::min(cpu[p], c1 - c0);
      }
    std::printf("| %s | %.0f | %.3f ms | %.3f ms | %.0f | %.3f ms | %.3f ms | %.2f | %.2f | %.0f / "
                "%.0f ns |\n",
                name.c_str(),
                steps[0],
                1e3 * wall[0],
                1e3 * cpu[0],
                steps[1],
                1e3 * wall[1],
                1e3 * cpu[1],
                wall[1] / wall[0],
                cpu[1] / cpu[0],
                1e9 * cpu[0] / steps[0],
                1e9 * cpu[1] / steps[1]);
    std::fflush(stdout);
  }

  double err(double x, double ref)
  {
    return ref != 0.0 ? 100.0 * (x - ref) / ref : 0.0;
  }

  Peaks richardson(const Peaks &coarse, const Peaks &fine)
  {
    // First order in Δt (the backward law velocity): 2·P(h/2) − P(h).
    const auto r = [](double a, double b) { return 2.0 * b - a; };
    return {r(coarse.force, fine.force),
            r(coarse.base_acc, fine.base_acc),
            r(coarse.roof_acc, fine.roof_acc),
            r(coarse.base_u, fine.base_u),
            r(coarse.roof_u, fine.roof_u),
            0.0};
  }
} // namespace

int main(int argc, char **argv)
{
  if (argc < 2)
  {
    std::fprintf(
      stderr,
      "usage: dt_auto_bench SCENE.yaml [CASE-SUBSTRING] [--newmark | --time [REPEATS]]\n");
    return 2;
  }
  const std::string                filter  = argc > 2 ? argv[2] : "";
  const bool                       newmark = argc > 3 && std::strcmp(argv[3], "--newmark") == 0;
  const bool                       timing  = argc > 3 && std::strcmp(argv[3], "--time") == 0;
  const LumpedScene                scene   = kimp::io::load_scene<LumpedScene>(argv[1]);
  const kimp::lumped::GroundMotion motion  = load_ground_motion(scene.ground_motion);
  if (timing)
  {
    const int repeats = argc > 4 ? std::max(1, std::atoi(argv[4])) : 20;
    std::printf("load average before: %s\n", load_average().c_str());
    std::printf("| case | stable steps | stable wall | stable CPU | auto steps | auto wall | auto "
                "CPU | wall auto/stable | CPU auto/stable | CPU per step stable / auto |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto &[name, resolved] : resolve_cases(scene))
      if (filter.empty() || name.find(filter) != std::string::npos)
        time_policies(name, resolved, motion, scene.ground_motion.scale, repeats);
    std::printf("load average after: %s\n", load_average().c_str());
    return 0;
  }
  std::printf(
    "| case | policy | steps | cost vs stable | peak force | base acc. | roof acc. | base "
    "displ. | roof displ. |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const auto &[name, resolved] : resolve_cases(scene))
  {
    if (!filter.empty() && name.find(filter) == std::string::npos)
      continue;
    const double     s   = scene.ground_motion.scale;
    const Peaks      p2  = run(name, resolved, motion, s, "1e-5 s", false);
    const Peaks      p1  = run(name, resolved, motion, s, "5e-6 s", false);
    const Peaks      ref = richardson(p2, p1);
    LumpedCaseResult var;
    const Peaks      stable = run(name, resolved, motion, s, "stable", false);
    const Peaks      autov  = run(name, resolved, motion, s, "auto", false, &var);
    const auto       line   = [&](const char *policy, const Peaks &p)
    {
      std::printf(
        "| %s | %s | %.0f | %.2f | %+.3f %% | %+.3f %% | %+.3f %% | %+.3f %% | %+.3f %% |\n",
        name.c_str(),
        policy,
        p.steps,
        p.steps / stable.steps,
        err(p.force, ref.force),
        err(p.base_acc, ref.base_acc),
        err(p.roof_acc, ref.roof_acc),
        err(p.base_u, ref.base_u),
        err(p.roof_u, ref.roof_u));
    };
    std::printf("| %s | reference (Richardson 1e-5/5e-6 s) | | | %.6g N | %.6g | %.6g | %.6g m | "
                "%.6g m |\n",
                name.c_str(),
                ref.force,
                ref.base_acc,
                ref.roof_acc,
                ref.base_u,
                ref.roof_u);
    line("fixed 5e-6 s", p1);
    line("fixed 1e-5 s", p2);
    line("fixed 2e-4 s", run(name, resolved, motion, s, "2e-4 s", false));
    line("stable (old auto)", stable);
    line("auto (variable)", autov);
    if (newmark)
    {
      line("newmark 5e-3 s", run(name, resolved, motion, s, "5e-3 s", true));
      line("newmark 1e-3 s", run(name, resolved, motion, s, "1e-3 s", true));
    }
    if (var.adaptive)
      std::printf("|   | %s | | | | | | | |\n", var.adaptive->text().c_str());
    std::fflush(stdout);
  }
  return 0;
}
