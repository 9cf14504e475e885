// The FEM engine's commands of `kimp-fem` in --help order; see commands.h.
#include "cli/commands.h"

namespace kimp::cli
{
  void register_fem_commands(CLI::App &app)
  {
    register_mesh_command(app);
    register_fem_command(app);
    register_study_command(app);
  }
} // namespace kimp::cli
