// `kimp sweep SWEEP.yaml -o DIR`: distributed, resumable parameter sweeps.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>

#include "app/sweep/sweep_run.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::app;

  void register_sweep_command(CLI::App &app)
  {
    auto      options = std::make_shared<SweepRunOptions>();
    CLI::App *command = app.add_subcommand(
      "sweep",
      "parameter sweep over scene keys: cases over MPI ranks and threads, resumable "
      "(finished cases are journaled in DIR/journal), results in DIR/sweep.h5 and DIR/sweep.csv");
    command
      ->add_option("sweep",
                   options->sweep,
                   "sweep file (YAML): scene, parameters, combine, "
                   "companions")
      ->type_name("SWEEP.yaml");
    command->add_option("-o,--output", options->output, "output directory (created if missing)")
      ->type_name("DIR");
    command
      ->add_option("-t,--threads",
                   options->threads,
                   "threads per rank (default: hardware threads / ranks)")
      ->type_name("N");
    command->add_flag("--retry-failed",
                      options->retry_failed,
                      "rerun cases recorded as failed instead of keeping their failure");
    command->add_flag("--no-charts",
                      options->no_charts,
                      "do not run scripts/sweep_charts.py (charts/ and summary.md)");
    command->add_option("--records-dir", options->records_dir, "directory of the PEER records")
      ->type_name("DIR");
    command->preparse_callback([options](std::size_t) { *options = SweepRunOptions{}; });
    command->callback(
      [options]()
      {
        if (options->sweep.empty())
          throw CLI::RequiredError("the sweep file SWEEP.yaml");
        if (options->output.empty())
          throw CLI::RequiredError("the output directory -o/--output DIR");
        run_sweep_job(*options);
      });
  }
} // namespace kimp::cli
