// `kimp fit FEM.h5 -o DIR`: impact laws fitted to FEM force histories.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/fit_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "io/units.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::app;

  void register_fit_command(CLI::App &app)
  {
    auto      options = std::make_shared<FitCommandOptions>();
    CLI::App *command = app.add_subcommand(
      "fit",
      "fit impact laws (Kelvin-Voigt, Jankowski, free-exponent Hertz) to FEM force histories");
    auto file = std::make_shared<std::string>();
    auto out  = std::make_shared<std::string>();
    command->add_option("fem_file", *file, "results file of `kimp fem` (/fem/<case>)")
      ->type_name("FEM.h5")
      ->required();
    command->add_option("-o,--output", *out, "output directory (created if missing)")
      ->type_name("DIR")
      ->required();
    command->add_option("--cor", options->cor, "COR of the fixed-COR fits, (0, 1]")
      ->capture_default_str();
    // A length with its unit like every quantity of kimp ("27.78 m", "2778 cm"); a bare number
    // is metres, as before units were accepted.
    command
      ->add_option_function<std::string>(
        "--width",
        [options](const std::string &text)
        {
          std::size_t used = 0;
          try
          {
            options->width = std::stod(text, &used);
          }
          catch (const std::exception &)
          {
            used = 0;
          }
          if (used != text.size() || used == 0)
          {
            try
            {
              options->width = parse_quantity_as(text, "m");
            }
            catch (const std::exception &error)
            {
              throw CLI::ValidationError("--width", error.what());
            }
          }
          if (!(options->width > 0.0))
            throw CLI::ValidationError("--width", "must be > 0, got '" + text + "'");
        },
        "building side W, a length such as '27.78 m' (a bare number is metres): k_total = k·W")
      ->type_name("LENGTH")
      ->default_str(format_quantity(FitCommandOptions{}.width, "m"));
    command->add_flag("--raw-force", options->raw_force, "fit the raw, not the smoothed, force");
    command
      ->add_option("--displacement-weight",
                   options->displacement_weight,
                   "weight of the slab-displacement misfit (0: force only)")
      ->capture_default_str();
    command->preparse_callback(
      [options, file, out](std::size_t)
      {
        *options = FitCommandOptions{};
        file->clear();
        out->clear();
      });
    command->callback(
      [options, file, out]()
      {
        options->fem_file = *file;
        options->output   = *out;
        logger().info("{}: fit {}", version_line(), *file);
        const int failures = run_fit_command(*options);
        if (failures > 0)
          logger().warn("fit: {} fit(s) failed (see fit_table.csv)", failures);
      });
  }
} // namespace kimp::cli
