// `kimp mesh SCENE.yaml -o DIR`: the scene mesh per wall height.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/mesh_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::app;

  void register_mesh_command(CLI::App &app)
  {
    add_scene_command<FemScene>(app, "mesh", fem_command_description("mesh"), run_mesh);
  }
} // namespace kimp::cli
