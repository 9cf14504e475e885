// `kimp report DIR [-o FILE]`: one self-contained HTML file with the interactive charts and the
// animation of a result directory. Parses the command's options and calls kimp::report.
#include <CLI/CLI.hpp>
#include <iostream>

#include "base/logging.h"
#include "base/version.h"
#include "cli/commands.h"

#include "report/report.h"

namespace kimp::cli
{
  void register_report_command(CLI::App &app)
  {
    struct Options
    {
      std::string dir;
      std::string output;
      bool        json = false;
    };
    auto      options = std::make_shared<Options>();
    CLI::App *command = app.add_subcommand(
      "report",
      "write DIR/report.html: interactive charts, tables and animation of a result directory of "
      "lumped, collide, fem, fit, study or sweep (one file, opens offline)");
    command->add_option("dir", options->dir, "result directory")->type_name("DIR")->required();
    command->add_option("-o,--output", options->output, "HTML file (default DIR/report.html)")
      ->type_name("FILE");
    command->add_flag("--json", options->json, "print the report's data as JSON instead");
    command->preparse_callback([options](std::size_t) { *options = Options{}; });
    command->callback(
      [options]()
      {
        if (options->json)
        {
          std::cout << report::report_data(options->dir).dump(1) << '\n';
          return;
        }
        const auto path = report::write_report(options->dir, options->output);
        base::logger().info("{}: report written to {}", base::version_line(), path.string());
      });
  }
} // namespace kimp::cli
