// `kimp fem SCENE.yaml -o DIR`: the FEM slab-wall impact per wall height.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/fem_run.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{

  void register_fem_command(CLI::App &app)
  {
    add_scene_command<app::FemScene>(app, {"fem", fem_command_description("fem")}, app::run_fem);
  }
} // namespace kimp::cli
