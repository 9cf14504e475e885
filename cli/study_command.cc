// `kimp study [SCENE.yaml] -o DIR`: the wall-height study (main job).
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fem/fem_estimate.h"
#include "app/study/study_fem.h"
#include "app/study/study_run.h"
#include "base/logging.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  void register_study_command(CLI::App &app)
  {
    CLI::App *subcommand = add_scene_command_at<app::StudyScene>(
      app,
      {"study", fem_command_description("study"), "default study scene"},
      [](io::LoadedScene<app::StudyScene> &scene,
         const std::filesystem::path      &output,
         const CLI::App                   &command)
      {
        if (const auto dir = given_records_dir(command))
        {
          // The flag wins over every records directory of the scene.
          scene.scene.records_dir = *dir;
          for (app::GroundMotionScene &record : scene.scene.records)
            record.records_dir = *dir;
          scene.resolved_json = io::to_json_text(scene.scene);
        }
        // On every rank: rank 0 creates the output directory (run_study_job).
        app::run_study_job(scene, output);
      },
      [](const app::StudyScene &scene, bool accept)
      {
        const app::FemCost cost = app::estimate_study_fem(scene);
        base::logger().info("study estimate (FEM): {}", cost.text());
        app::check_cost("kimp study", cost, {}, true, accept);
      });
    add_records_dir_option(*subcommand,
                           "directory of the PEER records (overrides the scene's records_dir, "
                           "those of its records and KIMP_RECORDS_DIR)");
  }
} // namespace kimp::cli
