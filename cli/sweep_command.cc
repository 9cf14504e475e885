// `kimp sweep SWEEP.yaml -o DIR`: distributed, resumable parameter sweeps.
// Parses the command's options and calls kimp::app.
#include <CLI/CLI.hpp>
#include <memory>
#include <utility>

#include "app/sweep/sweep_plan.h"
#include "app/sweep/sweep_run.h"
#include "cli/cli.h"
#include "cli/commands.h"

namespace kimp::cli
{
  void register_sweep_command(CLI::App &app)
  {
    auto      options = std::make_shared<app::SweepRunOptions>();
    auto      prints  = std::make_shared<std::pair<bool, bool>>(); // --print-defaults, -schema
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
    add_output_option(*command, options->output);
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
    command->add_flag("--no-shared-runs",
                      options->no_shared_runs,
                      "run every case from t = 0 instead of from a shared contact-free run "
                      "(the same results, bit for bit; for timing comparisons)");
    command->add_option("--records-dir", options->records_dir, "directory of the PEER records")
      ->type_name("DIR");
    command
      ->add_option("--max-steps",
                   options->max_steps,
                   "step budget over all runs: a sweep whose estimate (cases x the base scene's "
                   "steps) exceeds it is refused before planning (default 1e11)")
      ->type_name("N")
      ->check(CLI::PositiveNumber);
    command->add_flag("--check",
                      options->check,
                      "plan the sweep and check it (cost, every value and record on the base "
                      "scene), print \"SWEEP.yaml: valid, N cases\" and exit without running");
    command->add_flag("--print-defaults",
                      prints->first,
                      "print an annotated example sweep file (every key with its meaning) and "
                      "exit");
    command->add_flag("--print-schema",
                      prints->second,
                      "print the sweep file's keys as JSON (type, default, meaning) and exit");
    command->preparse_callback(
      [options, prints](std::size_t)
      {
        *options = app::SweepRunOptions{};
        *prints  = {false, false};
      });
    command->callback(
      [options, prints]()
      {
        if (prints->first)
          throw PrintDefaults(app::sweep_file_defaults_text());
        if (prints->second)
          throw PrintDefaults(app::sweep_file_schema_text());
        if (options->sweep.empty())
          throw CLI::RequiredError("the sweep file SWEEP.yaml (or --print-defaults)");
        if (options->output.empty() && !options->check)
          throw CLI::RequiredError("the output directory -o/--output DIR");
        const std::size_t n_cases = app::run_sweep_job(*options);
        if (options->check)
          throw PrintDefaults(options->sweep + ": valid, " + std::to_string(n_cases) + " cases\n");
      });
  }
} // namespace kimp::cli
