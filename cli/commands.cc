// The command list of `kimp`; see commands.h.
#include "cli/commands.h"

namespace kimp::cli
{
  void register_commands(CLI::App &app)
  {
#ifdef KIMP_WITH_FEM
    register_mesh_command(app);
    register_fem_command(app);
    register_study_command(app);
#endif
    register_lumped_command(app);
    register_collide_command(app);
    register_fit_command(app);
    register_sweep_command(app);
    register_report_command(app);
    register_gui_command(app);
    register_export_opensees_command(app);
  }
} // namespace kimp::cli
