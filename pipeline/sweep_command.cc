// `kimp sweep`: reads the sweep file, checks every varied key against the scene schema, then runs
// the cases of this MPI rank on a thread pool and (rank 0) merges DIR/sweep.h5 and DIR/sweep.csv.
#include "pipeline/sweep_command.h"

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <mpi.h>
#include <optional>
#include <string>

#include "pipeline/cli.h"
#include "pipeline/helper_programs.h"
#include "pipeline/logging.h"
#include "pipeline/lumped_scene.h"
#include "pipeline/summary.h"
#include "pipeline/sweep_engine.h"
#include "pipeline/sweep_lumped.h"
#include "pipeline/sweep_report.h"

namespace kimp::pipeline
{
  namespace
  {
    /// True when started by an MPI launcher (mpirun/srun), so that MPI is worth initializing.
    bool launched_by_mpi()
    {
      for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
        if (std::getenv(name) != nullptr)
          return true;
      return false;
    }

    /// MPI for the duration of the command, unless main() already initialized it.
    class MpiScope
    {
    public:
      MpiScope()
      {
        int initialized = 0;
        MPI_Initialized(&initialized);
        if (!initialized && launched_by_mpi())
        {
          int provided = 0;
          MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
          owned_      = true;
          initialized = 1;
        }
        if (initialized)
        {
          active_ = true;
          MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
          MPI_Comm_size(MPI_COMM_WORLD, &size_);
        }
      }
      MpiScope(const MpiScope &) = delete;
      ~MpiScope()
      {
        int finalized = 0;
        MPI_Finalized(&finalized);
        // While an exception unwinds, MPI_Finalize would wait for the other ranks; main()
        // reports the error and aborts the job instead.
        if (owned_ && !finalized && std::uncaught_exceptions() == 0)
          MPI_Finalize();
      }
      int  rank() const { return rank_; }
      int  size() const { return size_; }
      bool active() const { return active_; }

    private:
      bool owned_  = false;
      bool active_ = false;
      int  rank_   = 0;
      int  size_   = 1;
    };

    struct Options
    {
      std::string  sweep;
      std::string  output;
      std::string  records_dir;
      unsigned int threads      = 0;
      bool         retry_failed = false;
      bool         no_charts    = false;
    };

    /**
     * The d_SRSS table (report kinds gap_study, wall_location, adjacent_buildings, when the sweep
     * varies the report's gap and has companion metrics), then scripts/sweep_charts.py: charts
     * and summary.md.
     * @throws OutputError naming the script and its exit status when the charts fail
     */
    void write_report(const SweepPlan &plan, const OutputDir &output, const bool charts)
    {
      const SweepReportSpec &spec = *plan.report();
      if (spec.kind == "adjacent_buildings" || spec.kind == "gap_study" ||
          spec.kind == "wall_location")
      {
        const SweepTable table = collect_sweep_table(plan, output.path());
        try
        {
          const DsrssTable dsrss = dsrss_table(plan, table, spec.gap_key);
          write_dsrss_table(dsrss, output.file("dsrss_table.csv"));
          logger().info("d_SRSS table: {} configurations in {}",
                        dsrss.rows.size(),
                        output.file("dsrss_table.csv").string());
        }
        catch (const SweepError &error)
        {
          // E.g. every case failed, or no companion run: the summary says the table is missing.
          logger().warn("no d_SRSS table: {}", error.what());
        }
      }
      if (!charts)
        return;
      const ChartScriptRun run = run_chart_script("sweep_charts.py", output.path());
      if (run.script.empty())
        throw OutputError("charts: scripts/sweep_charts.py not found (set KIMP_DATA_DIR to the "
                          "kimp source tree, or pass --no-charts)");
      if (run.status != 0)
        throw OutputError(fmt::format("charts: {} exited with status {} (needs /usr/bin/python3 "
                                      "with matplotlib, numpy and h5py); see {}",
                                      run.script.string(),
                                      run.status,
                                      run.log.string()));
      logger().info("charts and summary written to {} and {}",
                    output.file("charts").string(),
                    output.file("summary.md").string());
    }

    void run(const Options &options)
    {
      if (options.sweep.empty())
        throw CLI::RequiredError("the sweep file SWEEP.yaml");
      if (options.output.empty())
        throw CLI::RequiredError("the output directory -o/--output DIR");
      const MpiScope mpi;
      set_rank(mpi.rank());
      logger().info("{}: sweep {} on {} rank(s)", version_line(), options.sweep, mpi.size());

      const SweepPlan plan = SweepPlan::from_file(options.sweep);
      if (plan.engine() != "lumped")
        throw SweepError(options.sweep + ": engine: '" + plan.engine() +
                         "' (expected lumped, the only engine with a sweep runner)");
      plan.check_key_paths([](const std::string &text, const std::string &name)
                           { read_scene_text<LumpedScene>(text, name); });
      const OutputDir output(options.output);

      std::optional<std::filesystem::path> records_dir;
      if (!options.records_dir.empty())
        records_dir = options.records_dir;
      SweepOptions sweep_options;
      sweep_options.threads      = options.threads;
      sweep_options.rank         = mpi.rank();
      sweep_options.n_ranks      = mpi.size();
      sweep_options.retry_failed = options.retry_failed;
      if (mpi.active() && mpi.size() > 1)
        sweep_options.barrier = []() { MPI_Barrier(MPI_COMM_WORLD); };
      const SweepSummary summary =
        run_sweep(plan, make_lumped_case_runner(records_dir), output.path(), sweep_options);
      if (mpi.rank() == 0)
        logger().info("sweep: {} cases, {} resumed, {} run here ({} failed), {} rows",
                      summary.n_cases,
                      summary.n_resumed,
                      summary.n_run,
                      summary.n_failed,
                      summary.n_rows);
      if (mpi.rank() == 0)
      {
        if (plan.report())
          write_report(plan, output, !options.no_charts);
        else
          logger().info("no report: section in {}: no charts or summary", options.sweep);
      }
    }
  } // namespace

  void register_sweep_command(CLI::App &app)
  {
    auto      options = std::make_shared<Options>();
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
    command->preparse_callback([options](std::size_t) { *options = Options{}; });
    command->callback([options]() { run(*options); });
  }
} // namespace kimp::pipeline
