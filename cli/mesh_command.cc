// `kimp mesh SCENE.yaml -o DIR`: the scene mesh per wall height.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/fem_estimate.h"
#include "app/fem/mesh_run.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{

  void register_mesh_command(CLI::App &app)
  {
    // Meshing costs nodes, not steps: only the DoF limit applies.
    add_scene_command<app::FemScene>(app,
                                     {"mesh", fem_command_description("mesh")},
                                     app::run_mesh,
                                     [](const app::FemScene &scene, bool accept)
                                     {
                                       const app::FemCost cost = app::estimate_fem_scene(scene);
                                       app::check_cost("kimp mesh", cost, {}, false, accept);
                                     });
  }
} // namespace kimp::cli
