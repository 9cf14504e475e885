// `kimp fit FEM.h5 -o DIR`: impact laws fitted to FEM force histories.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/laws/fit_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  void register_fit_command(CLI::App &app)
  {
    auto      options = std::make_shared<app::FitCommandOptions>();
    CLI::App *command = app.add_subcommand(
      "fit",
      "fit impact laws (Kelvin-Voigt, Jankowski, free-exponent Hertz) to FEM force histories");
    auto file = std::make_shared<std::string>();
    auto out  = std::make_shared<std::string>();
    command->add_option("fem_file", *file, "results file of `kimp fem` (/fem/<case>)")
      ->type_name("FEM.h5")
      ->required();
    add_output_option(*command, *out)->required();
    // --cor, --width, --raw-force, --force-only-contact, --separation-fraction, ...: the keys of
    // the study's `fit:` section, declared once (fit::FitConfig's visit()).
    const auto config = add_key_options<fit::FitConfig>(*command);
    command->preparse_callback(
      [options, file, out](std::size_t)
      {
        *options = app::FitCommandOptions{};
        file->clear();
        out->clear();
      });
    command->callback(
      [options, file, out, config]()
      {
        options->config   = config();
        options->fem_file = *file;
        options->output   = *out;
        base::logger().info("{}: fit {}", base::version_line(), *file);
        const int failures = app::run_fit_command(*options);
        if (failures > 0)
          base::logger().warn("fit: {} fit(s) failed or with a warning (see the status column of "
                              "fit_table.csv)",
                              failures);
      });
  }
} // namespace kimp::cli
