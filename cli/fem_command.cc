// `kimp fem SCENE.yaml -o DIR`: the FEM slab-wall impact per wall height.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/fem_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::app;

  void register_fem_command(CLI::App &app)
  {
    add_scene_command<FemScene>(app, "fem", fem_command_description("fem"), run_fem);
  }
} // namespace kimp::cli
