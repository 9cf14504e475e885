// `kimp collide [SCENE.yaml] -o DIR [--calibrate]`: effective COR of the impact laws.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/collide_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::app;

  void register_collide_command(CLI::App &app)
  {
    struct Options
    {
      std::string scene;
      std::string output;
      bool        print_defaults = false;
      bool        print_schema   = false;
      bool        calibrate      = false;
    };
    auto      options = std::make_shared<Options>();
    CLI::App *command = app.add_subcommand(
      "collide",
      "effective COR of every impact law against its nominal COR (two bodies, thesis set-up "
      "280 t / 300 t at 1 m/s, dt 2e-4 s); --calibrate redoes the C_imp calibration (eq. 2.23)");
    command
      ->add_option("scene", options->scene, "scene file (YAML, optional); see --print-defaults")
      ->type_name("SCENE.yaml");
    command->add_option("-o,--output", options->output, "output directory (created if missing)")
      ->type_name("DIR");
    command->add_flag("--print-defaults",
                      options->print_defaults,
                      "print the annotated default scene and exit");
    command->add_flag("--calibrate",
                      options->calibrate,
                      "also recalibrate C_imp = c(1-COR^2)/(COR^p1 m_eff^p2 v^p3) and compare "
                      "with 1.55/0.7076/0.0025/0.9755");
    add_print_schema_flag(*command, options->print_schema);
    command->preparse_callback([options](std::size_t) { *options = Options{}; });
    command->callback(
      [options]()
      {
        if (options->print_defaults)
          throw PrintDefaults(default_scene_text<CollideScene>("kimp collide scene (defaults)"));
        if (options->print_schema)
          throw PrintDefaults(schema_text<CollideScene>());
        if (options->output.empty())
          throw CLI::RequiredError("the output directory -o/--output DIR");
        logger().info("{}: collide {}", version_line(), options->scene);
        const LoadedScene<CollideScene> scene = options->scene.empty() ?
                                                  read_scene_text<CollideScene>("", "(defaults)") :
                                                  read_scene<CollideScene>(options->scene);
        logger().debug("resolved scene (SI):\n{}", scene.resolved_json);
        const OutputDir output(options->output);
        run_collide(scene, output, options->calibrate);
      });
  }
} // namespace kimp::cli
