// `kimp lumped SCENE.yaml -o DIR`: a pounding analysis of every case of a lumped scene.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/lumped/lumped_run.h"
#include "app/lumped/plan_run.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  void register_lumped_command(CLI::App &app)
  {
    CLI::App *subcommand = add_scene_command<app::PlanLumpedScene>(
      app,
      {"lumped",
       "pounding analysis of a shear building (isolated or fixed-base) with moat walls, "
       "neighbours and impact laws 1-7, or (with a plan section) a building in plan in a moat; "
       "writes DIR/lumped.h5, summary.json, peaks.csv"},
      [](const io::LoadedScene<app::PlanLumpedScene> &loaded,
         const io::OutputDir                         &output,
         const CLI::App                              &command)
      {
        if (loaded.scene.plan)
        {
          app::run_plan_lumped(loaded, output, given_records_dir(command));
          return;
        }
        // A planar scene: exactly the LoadedScene a planar-only reader gives (same resolved JSON).
        const io::LoadedScene<app::LumpedScene>  scene{loaded.scene.base,
                                                      loaded.file_name,
                                                      loaded.text,
                                                      io::to_json_text(loaded.scene.base)};
        const std::vector<app::LumpedCaseResult> results =
          app::run_lumped(scene, output, given_records_dir(command));
        std::string failed;
        std::size_t n_failed = 0;
        for (const app::LumpedCaseResult &r : results)
          if (!r.ok())
          {
            ++n_failed;
            failed += "\n  " + r.name + ": " + r.status;
          }
        if (n_failed == results.size())
          throw std::runtime_error(fmt::format("{} of {} cases failed, no results ({} status is "
                                               "in {}):{}",
                                               n_failed,
                                               n_failed,
                                               n_failed == 1 ? "its" : "their",
                                               (output.path() / "summary.json").string(),
                                               failed));
        if (n_failed > 0)
          throw std::runtime_error(std::to_string(n_failed) + " of " +
                                   std::to_string(results.size()) +
                                   " cases failed (the other results are written to " +
                                   output.path().string() + "):" + failed);
      });
    add_records_dir_option(*subcommand,
                           "directory of PEER records (overrides the scene's "
                           "ground_motion.records_dir and KIMP_RECORDS_DIR)");
  }
} // namespace kimp::cli
