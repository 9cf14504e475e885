// The commands of `kimp`: one register_<name>_command() per cli/<name>_command.cc. Each adds its
// subcommand (options, help) to the app and calls kimp::app when it runs.
#pragma once

#include <string_view>
#include <vector>

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

  /// mesh, fem and study (in `kimp --help` order), run by the FEM executable `kimp-fem`.
  void register_fem_commands(CLI::App &app);
#endif

  /// Every command that the lean `kimp` executable runs itself (no deal.II, gmsh or MPI_Init),
  /// in `kimp --help` order. A new command that does not need the FEM engine goes here.
  void register_commands(CLI::App &app);

  /// Name and one-line help of a command of the FEM engine. The lean `kimp` lists these in its
  /// --help and execs `kimp-fem` (beside it) with the same arguments when one is chosen.
  struct FemCommandInfo
  {
    const char *name;
    const char *description;
  };

  /// mesh, fem and study, in `kimp --help` order.
  const std::vector<FemCommandInfo> &fem_command_infos();

  /// The help line of FEM command `name` (mesh, fem or study); std::out_of_range otherwise.
  const char *fem_command_description(std::string_view name);
} // namespace kimp::cli
