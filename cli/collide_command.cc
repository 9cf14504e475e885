// `kimp collide [SCENE.yaml] -o DIR [--calibrate]`: effective COR of the impact laws.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/lumped/collide_run.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  void register_collide_command(CLI::App &app)
  {
    add_scene_command<app::CollideScene>(
      app,
      {"collide",
       "effective COR of every impact law against its nominal COR (two bodies, thesis set-up "
       "280 t / 300 t at 1 m/s, dt 2e-4 s); --calibrate redoes the C_imp calibration (eq. 2.23)",
       "defaults"},
      [](const io::LoadedScene<app::CollideScene> &scene,
         const io::OutputDir                      &output,
         const CLI::App                           &command)
      { app::run_collide(scene, output, command.count("--calibrate") > 0); })
      ->add_flag("--calibrate",
                 "also recalibrate C_imp = c(1-COR^2)/(COR^p1 m_eff^p2 v^p3) "
                 "and compare with 1.55/0.7076/0.0025/0.9755");
  }
} // namespace kimp::cli
