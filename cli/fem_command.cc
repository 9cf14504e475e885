// `kimp fem SCENE.yaml -o DIR`: the FEM slab-wall impact per wall height.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/fem_estimate.h"
#include "app/fem/fem_run.h"
#include "app/fem/pushover_run.h"
#include "base/logging.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{

  void register_fem_command(CLI::App &app)
  {
    CLI::App *command = add_scene_command<app::FemScene>(
      app,
      {"fem", fem_command_description("fem")},
      [](const io::LoadedScene<app::FemScene> &scene,
         const io::OutputDir                  &output,
         const CLI::App                       &cmd)
      {
        if (cmd.get_option("--pushover")->count() > 0)
          app::run_fem_pushover(scene, output);
        else
          app::run_fem(scene, output);
      },
      [](const app::FemScene &scene, bool accept)
      {
        const app::FemCost cost = app::estimate_fem_scene(scene);
        base::logger().info("fem estimate: {}", cost.text());
        app::check_cost("kimp fem", cost, {}, true, accept);
      });
    command->add_flag("--pushover",
                      "instead of the impact: the static pushover of wall and backfill per wall "
                      "height (section pushover; pushover.h5, pushover.csv, "
                      "pushover_summary.csv, charts/pushover.svg)");
  }
} // namespace kimp::cli
