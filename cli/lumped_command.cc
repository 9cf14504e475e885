// `kimp lumped SCENE.yaml -o DIR`: a pounding analysis of every case of a lumped scene.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/lumped_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::app;

  void register_lumped_command(CLI::App &app)
  {
    auto      records_dir = std::make_shared<CLI::Option *>(nullptr);
    CLI::App *command     = add_scene_command<LumpedScene>(
      app,
      {"lumped",
           "pounding analysis of a shear building (isolated or fixed-base) with moat walls, "
               "neighbours and impact laws 1-7; writes DIR/lumped.h5, summary.json, peaks.csv"},
      [records_dir](const LoadedScene<LumpedScene> &scene, const OutputDir &output)
      {
        std::optional<std::filesystem::path> override_dir;
        if (*records_dir && (*records_dir)->count() > 0)
          override_dir = (*records_dir)->as<std::string>();
        const std::vector<LumpedCaseResult> results = run_lumped(scene, output, override_dir);
        std::string                         failed;
        std::size_t                         n_failed = 0;
        for (const LumpedCaseResult &r : results)
          if (!r.ok())
          {
            ++n_failed;
            failed += "\n  " + r.name + ": " + r.status;
          }
        if (n_failed == results.size())
          throw std::runtime_error(fmt::format("{} of {} cases failed, no results ({} status is "
                                                   "in {}):{}",
                                               n_failed,
                                               n_failed,
                                               n_failed == 1 ? "its" : "their",
                                               (output.path() / "summary.json").string(),
                                               failed));
        if (n_failed > 0)
          throw std::runtime_error(std::to_string(n_failed) + " of " +
                                   std::to_string(results.size()) +
                                   " cases failed (the other results are written to " +
                                   output.path().string() + "):" + failed);
      });
    *records_dir = command->add_option("--records-dir",
                                       "directory of PEER records (overrides the scene's "
                                       "ground_motion.records_dir and KIMP_RECORDS_DIR)");
    (*records_dir)->type_name("DIR");
  }
} // namespace kimp::cli
