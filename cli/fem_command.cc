// `kimp fem SCENE.yaml -o DIR`: the FEM slab-wall impact per wall height.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/fem_estimate.h"
#include "app/fem/fem_run.h"
#include "base/logging.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{

  void register_fem_command(CLI::App &app)
  {
    add_scene_command<app::FemScene>(app,
                                     {"fem", fem_command_description("fem")},
                                     app::run_fem,
                                     [](const app::FemScene &scene, bool accept)
                                     {
                                       const app::FemCost cost = app::estimate_fem_scene(scene);
                                       base::logger().info("fem estimate: {}", cost.text());
                                       app::check_cost("kimp fem", cost, {}, true, accept);
                                     });
  }
} // namespace kimp::cli
