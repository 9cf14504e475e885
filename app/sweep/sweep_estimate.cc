// Sweep cost estimate and step budget; see sweep_estimate.h.
#include "app/sweep/sweep_estimate.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_run.h"
#include "app/step_budget.h"
#include "base/logging.h"

namespace kimp::app
{
  std::string SweepEstimate::text() const
  {
    return fmt::format("{} cases x {} run(s) x ({}) = {:.3g} steps, ~{:.2g} s of one core (the "
                       "base scene's estimate; cases that change dt or the duration differ)",
                       n_cases,
                       runs_per_case,
                       base.text(),
                       total_steps,
                       seconds);
  }

  std::optional<SweepEstimate>
  estimate_sweep(std::size_t                                 n_cases,
                 const std::string                          &scene_text,
                 const std::string                          &scene_name,
                 const std::optional<std::filesystem::path> &records_dir)
  {
    try
    {
      const PlanLumpedScene read =
        io::load_scene_text<PlanLumpedScene>(scene_text,
                                             scene_name,
                                             std::filesystem::path(scene_name).parent_path());
      SweepEstimate e;
      e.n_cases = n_cases;
      if (read.plan)
      {
        // One run of the plan engine per case.
        e.runs_per_case = 1;
        e.base          = estimate_plan_case(
          read,
          load_plan_motion(read.base, *read.plan, records_dir, scene_name, scene_text));
        e.total_steps = static_cast<double>(n_cases) * e.base.n_steps;
        e.seconds     = static_cast<double>(n_cases) * e.base.seconds;
        return e;
      }
      const LumpedScene &scene = read.base;
      // Each of the scene's cases, and again without contacts with integration.companion.
      e.runs_per_case =
        std::max<std::size_t>(1, scene.cases.size()) * (scene.integration.companion ? 2 : 1);
      e.base = estimate_lumped_case(scene, load_ground_motion(scene.ground_motion, records_dir));
      const double runs = static_cast<double>(n_cases) * static_cast<double>(e.runs_per_case);
      e.total_steps     = runs * e.base.n_steps;
      e.seconds         = runs * e.base.seconds;
      return e;
    }
    catch (const std::exception &error)
    {
      base::logger().debug("no estimate of the sweep from its base scene: {}", error.what());
      return std::nullopt;
    }
  }

  void
  check_sweep_budget(const std::string &sweep_file, const SweepEstimate &estimate, double max_steps)
  {
    check_step_budget(
      sweep_file,
      estimate.text(),
      estimate.total_steps,
      max_steps,
      "of the sweep (--max-steps = {:.3g}; fewer values, a shorter duration, a "
      "larger dt, or a larger --max-steps or --accept-cost if the sweep is intended)");
  }
} // namespace kimp::app
