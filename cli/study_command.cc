// `kimp study [SCENE.yaml] -o DIR`: the wall-height study (main job).
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/study/study_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::app;

  void register_study_command(CLI::App &app)
  {
    struct Options
    {
      std::string scene;
      std::string output;
      bool        print_defaults = false;
      bool        print_schema   = false;
      std::string records_dir;
    };
    auto      options = std::make_shared<Options>();
    CLI::App *command = app.add_subcommand("study", fem_command_description("study"));
    command->add_option("scene", options->scene, "study scene (YAML; none: the default study)")
      ->type_name("SCENE.yaml");
    command->add_option("-o,--output", options->output, "output directory (created if missing)")
      ->type_name("DIR");
    command->add_flag("--print-defaults",
                      options->print_defaults,
                      "print the annotated default study scene and exit");
    command
      ->add_option("--records-dir",
                   options->records_dir,
                   "directory of the PEER records (overrides the scene's records_dir, those of "
                   "its records and KIMP_RECORDS_DIR)")
      ->type_name("DIR");
    add_print_schema_flag(*command, options->print_schema);
    command->preparse_callback([options](std::size_t) { *options = Options{}; });
    command->callback(
      [options]()
      {
        if (options->print_defaults)
          throw PrintDefaults(default_scene_text<StudyScene>("kimp study scene (defaults)"));
        if (options->print_schema)
          throw PrintDefaults(schema_text<StudyScene>());
        if (options->output.empty())
          throw CLI::RequiredError("the output directory -o/--output DIR");
        logger().info("{}: study {}",
                      version_line(),
                      options->scene.empty() ? "(default scene)" : options->scene);
        LoadedScene<StudyScene> scene = options->scene.empty() ?
                                          read_scene_text<StudyScene>("", "(default study scene)") :
                                          read_scene<StudyScene>(options->scene);
        if (!options->records_dir.empty())
        {
          // The flag wins over every records directory of the scene.
          scene.scene.records_dir = options->records_dir;
          for (GroundMotionScene &record : scene.scene.records)
            record.records_dir = options->records_dir;
          scene.resolved_json = to_json_text(scene.scene);
        }
        run_study_job(scene, options->output);
      });
  }
} // namespace kimp::cli
