// `kimp study [SCENE.yaml] -o DIR`: the wall-height study (main job).
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/study/study_run.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  using namespace kimp::io;
  using namespace kimp::app;

  void register_study_command(CLI::App &app)
  {
    auto      records_dir = std::make_shared<CLI::Option *>(nullptr);
    CLI::App *command     = add_scene_command_at<StudyScene>(
      app,
      {"study", fem_command_description("study"), "default study scene"},
      [records_dir](LoadedScene<StudyScene> &scene, const std::filesystem::path &output)
      {
        if ((*records_dir)->count() > 0)
        {
          // The flag wins over every records directory of the scene.
          const std::string dir   = (*records_dir)->as<std::string>();
          scene.scene.records_dir = dir;
          for (GroundMotionScene &record : scene.scene.records)
            record.records_dir = dir;
          scene.resolved_json = to_json_text(scene.scene);
        }
        // On every rank: rank 0 creates the output directory (run_study_job).
        run_study_job(scene, output);
      });
    *records_dir = command
                     ->add_option("--records-dir",
                                  "directory of the PEER records (overrides the scene's "
                                  "records_dir, those of its records and KIMP_RECORDS_DIR)")
                     ->type_name("DIR");
  }
} // namespace kimp::cli
