// `kimp mesh SCENE.yaml -o DIR`: the scene mesh per wall height.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/mesh_run.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{

  void register_mesh_command(CLI::App &app)
  {
    add_scene_command<app::FemScene>(app, {"mesh", fem_command_description("mesh")}, app::run_mesh);
  }
} // namespace kimp::cli
