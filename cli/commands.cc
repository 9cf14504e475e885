// The command list of `kimp`; see commands.h.
#include "cli/commands.h"

#include <stdexcept>
#include <string>

namespace kimp::cli
{
  void register_commands(CLI::App &app)
  {
    register_lumped_command(app);
    register_collide_command(app);
    register_fit_command(app);
    register_sweep_command(app);
    register_report_command(app);
    register_gui_command(app);
    register_export_opensees_command(app);
  }

  const std::vector<FemCommandInfo> &fem_command_infos()
  {
    static const std::vector<FemCommandInfo> infos = {
      {"mesh",
       "mesh the FEM impact scene of every wall height: DIR/mesh/H<H>.msh with PNG and VTU "
       "previews, summary.json"},
      {"fem",
       "run the FEM slab-wall impact for every wall height (also under mpirun): DIR/fem.h5, "
       "summary.json, fem_histories.csv"},
      {"study",
       "the wall-height study: FEM per height -> fitted k (Kelvin-Voigt, Jankowski) -> k table "
       "beside thesis Table 2.1 -> building pounding runs -> CSV, study.h5, charts, report.md"}};
    return infos;
  }

  const char *fem_command_description(std::string_view name)
  {
    for (const FemCommandInfo &info : fem_command_infos())
      if (name == info.name)
        return info.description;
    throw std::out_of_range("no FEM command named " + std::string(name));
  }
} // namespace kimp::cli
