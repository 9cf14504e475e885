// The commands of `kimp`: one register_<name>_command() per cli/<name>_command.cc. Each adds its
// subcommand (options, help) to the app and calls kimp::app when it runs.
#pragma once

namespace CLI
{
  class App;
}

namespace kimp::cli
{
  void register_lumped_command(CLI::App &app);
  void register_collide_command(CLI::App &app);
  void register_fit_command(CLI::App &app);
  void register_sweep_command(CLI::App &app);
  void register_report_command(CLI::App &app);
  void register_gui_command(CLI::App &app);
  void register_export_opensees_command(CLI::App &app);
#ifdef KIMP_WITH_FEM
  void register_mesh_command(CLI::App &app);
  void register_fem_command(CLI::App &app);
  void register_study_command(CLI::App &app);
#endif

  /// Every command of this build (the FEM ones only with KIMP_WITH_FEM), in `kimp --help` order.
  void register_commands(CLI::App &app);
} // namespace kimp::cli
