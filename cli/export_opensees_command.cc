// `kimp export-opensees [STUDY_DIR | k_table.csv] -o DIR`: the fitted impact laws as OpenSees
// input (Tcl and OpenSeesPy). Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/export/opensees_export.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  void register_export_opensees_command(CLI::App &app)
  {
    CLI::App *command = app.add_subcommand(
      "export-opensees",
      "write the fitted impact laws as OpenSees uniaxial materials (ViscoelasticGap, "
      "ElasticPPGap, JankowskiImpact, Hertzdamp, ImpactMaterial) in Tcl and OpenSeesPy, units N, "
      "m, s");
    auto source = std::make_shared<std::string>();
    auto out    = std::make_shared<std::string>();
    command
      ->add_option("source",
                   *source,
                   "output directory of `kimp study` or its k_table.csv (omit to give --k-kv "
                   "and/or --k-hertz)")
      ->type_name("STUDY_DIR|k_table.csv");
    add_output_option(*command, *out)->required();
    auto lumped_scene = std::make_shared<std::string>();
    command
      ->add_option("--lumped-scene",
                   *lumped_scene,
                   "a `kimp lumped` scene: also write its yielding walls as nodes, materials and "
                   "elements (opensees_walls.tcl, .py)")
      ->type_name("SCENE.yaml");
    // --wall-height, --k-kv, --k-hertz, --cor, --effective-mass, ...: app::ExportOpenSeesSettings.
    const auto settings = add_key_options<app::ExportOpenSeesSettings>(*command);
    command->preparse_callback(
      [source, out, lumped_scene](std::size_t)
      {
        source->clear();
        out->clear();
        lumped_scene->clear();
      });
    command->callback(
      [source, out, settings, lumped_scene]()
      {
        app::ExportOpenSeesOptions options;
        options.lumped_scene = *lumped_scene;
        options.source       = *source;
        options.output       = *out;
        options.settings     = settings();
        base::logger().info("{}: export-opensees {}", base::version_line(), *source);
        app::run_export_opensees(options);
      });
  }
} // namespace kimp::cli
