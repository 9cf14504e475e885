// `kimp sweep`: reads the sweep file, checks every varied key against the scene schema, then runs
// the cases of this MPI rank on a thread pool and (rank 0) merges DIR/sweep.h5 and DIR/sweep.csv.
#include "app/sweep/sweep_run.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/helper_programs.h"
#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_scene.h"
#include "app/mpi_ranks.h"
#include "app/sweep/sweep_engine.h"
#include "app/sweep/sweep_estimate.h"
#include "app/sweep/sweep_lumped.h"
#include "app/sweep/sweep_report.h"
#include "base/logging.h"
#include "base/version.h"
#include "io/summary.h"

#include "report/report.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  namespace
  {
    /**
     * The d_SRSS table (report kinds gap_study, wall_location, adjacent_buildings, and bumpers
     * when the sweep varies the report's gap; needs companion metrics), then
     * scripts/sweep_charts.py: charts and summary.md.
     * @throws OutputError naming the script and its exit status when the charts fail
     */
    void write_report(const SweepPlan &plan, const OutputDir &output, const bool charts)
    {
      const SweepReportSpec &spec = *plan.report();
      // Bumper studies have the table (and d_req on their gap charts) when they sweep the gap.
      const bool gap_swept =
        std::any_of(plan.parameters().begin(),
                    plan.parameters().end(),
                    [&](const SweepParameter &p) { return p.sets(spec.gap_key); });
      if (spec.kind == "adjacent_buildings" || spec.kind == "gap_study" ||
          spec.kind == "wall_location" || (spec.kind == "bumpers" && gap_swept))
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
      // The tables are the sweep's result: a chart script that fails keeps them.
      output.keep_written();
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

    /// DIR/summary.json: what ran, and one entry per case in the shape of every command's
    /// summary (`cases`: name, status), with the parameter values as in the sweep file.
    void write_sweep_summary(const SweepPlan    &plan,
                             const SweepSummary &summary,
                             const OutputDir    &output,
                             int                 n_ranks,
                             double              wall_time)
    {
      const SweepTable       table = collect_sweep_table(plan, output.path());
      nlohmann::ordered_json j     = io::summary_preamble("sweep");
      j["sweep"]                   = plan.file_name();
      j["scene"]                   = plan.base_scene_name();
      j["n_ranks"]                 = n_ranks;
      j["wall_time"]               = wall_time;
      j["units"]                   = {{"wall_time", "s"}};
      j["n_cases"]                 = summary.n_cases;
      j["n_resumed"]               = summary.n_resumed;
      j["n_run"]                   = summary.n_run;
      j["n_failed"]                = summary.n_failed;
      j["n_rows"]                  = summary.n_rows;
      std::size_t n_not_ok         = 0;
      j["cases"]                   = nlohmann::ordered_json::array();
      for (const SweepTableRow &r : table.rows)
      {
        n_not_ok += r.status != "ok";
        nlohmann::ordered_json parameters = nlohmann::ordered_json::object();
        for (std::size_t p = 0; p < table.parameter_names.size(); ++p)
          parameters[table.parameter_names[p]] = r.values.at(p);
        j["cases"].push_back({{"name", r.id},
                              {"status", r.status},
                              {"index", r.index},
                              {"companion", r.companion},
                              {"parameters", parameters},
                              {"wall_time", r.wall_time}});
      }
      j["n_rows_not_ok"] = n_not_ok;
      write_text_atomic(output.file("summary.json"), j.dump(2) + "\n");
    }
  } // namespace

  std::size_t run_sweep_job(const SweepRunOptions &options)
  {
    const auto     start = std::chrono::steady_clock::now();
    const MpiRanks mpi;
    set_rank(mpi.rank());
    logger().info("{}: sweep {} on {} rank(s)", version_line(), options.sweep, mpi.size());

    std::optional<std::filesystem::path> records_dir;
    if (!options.records_dir.empty())
      records_dir = options.records_dir;
    // The reader refuses an engine other than lumped, at its line. The estimate is said (and a
    // sweep above the budget refused) before the cases are enumerated, which takes a while.
    const SweepPlan plan = SweepPlan::from_file(
      options.sweep,
      [&](std::size_t n_cases, const std::string &scene_text, const std::string &scene_name)
      {
        const auto estimate = estimate_sweep(n_cases, scene_text, scene_name, records_dir);
        if (!estimate)
        {
          logger().info("sweep: {} cases", n_cases);
          return;
        }
        logger().info("sweep estimate: {}", estimate->text());
        if (!options.accept_cost)
          check_sweep_budget(options.sweep, *estimate, options.max_steps);
        else if (!(estimate->total_steps <= options.max_steps))
          logger().warn("sweep: the estimate exceeds --max-steps = {:.3g}, going ahead "
                        "(--accept-cost)",
                        options.max_steps);
      });
    // Paths of the case scenes (k_table, record files) are relative to the base scene's file.
    const std::filesystem::path scene_directory =
      std::filesystem::path(plan.base_scene_name()).parent_path();
    plan.check_key_paths([&](const std::string &text, const std::string &name)
                         { read_scene_text<PlanLumpedScene>(text, name, scene_directory); });
    // Every record before the output directory is made: a misspelt one is an input error.
    plan.check_records(
      [&](const std::string &text, const std::string &name)
      {
        const PlanLumpedScene read = load_scene_text<PlanLumpedScene>(text, name, scene_directory);
        if (read.plan)
        {
          // Both components of a scene in plan (plan.second_record).
          load_plan_motion(read.base, *read.plan, records_dir, name, text);
          return;
        }
        const LumpedScene &scene = read.base;
        load_ground_motion_at(scene.ground_motion, records_dir, name, text, "ground_motion");
        for (std::size_t i = 0; i < scene.cases.size(); ++i)
          if (!scene.cases[i].record.empty() && scene.cases[i].record != scene.ground_motion.record)
          {
            GroundMotionScene own = scene.ground_motion;
            own.record            = scene.cases[i].record;
            load_ground_motion_at(own, records_dir, name, text, "cases[" + std::to_string(i) + "]");
          }
      });
    if (options.check)
      return plan.n_cases();
    const OutputDir output(options.output);

    SweepOptions sweep_options;
    sweep_options.threads      = options.threads;
    sweep_options.rank         = mpi.rank();
    sweep_options.n_ranks      = mpi.size();
    sweep_options.retry_failed = options.retry_failed;
    sweep_options.barrier      = mpi.barrier();
    const SweepSummary summary =
      run_sweep(plan,
                make_lumped_case_runner(records_dir, !options.no_shared_runs, scene_directory),
                output.path(),
                sweep_options);
    if (mpi.rank() == 0)
      logger().info("sweep: {} cases, {} resumed, {} run here ({} failed), {} rows",
                    summary.n_cases,
                    summary.n_resumed,
                    summary.n_run,
                    summary.n_failed,
                    summary.n_rows);
    if (mpi.rank() == 0)
    {
      write_sweep_summary(
        plan,
        summary,
        output,
        mpi.size(),
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      if (plan.report())
        write_report(plan, output, !options.no_charts);
      else
        logger().info("no report: section in {}: no charts or summary", options.sweep);
      // The results are complete by now: a report that cannot be written is only a warning.
      try
      {
        logger().info("HTML report: {}", kimp::report::write_report(output.path()).string());
      }
      catch (const std::exception &error)
      {
        logger().warn("no HTML report: {}", error.what());
      }
    }
    return plan.n_cases();
  }

} // namespace kimp::app
