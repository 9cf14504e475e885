// Sweep execution: static round-robin over ranks, a thread pool per rank pulling case indices from
// an atomic counter, journal-based resume, and the merged HDF5/CSV table.
#include "app/sweep/sweep_engine.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "base/errors.h"
#include "base/logging.h"
#include "base/stopwatch.h"
#include "base/thread_pool.h"
#include "io/results_file.h"
#include "io/summary.h"
#include "io/table.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  namespace
  {
    using SteadyClock = std::chrono::steady_clock;

    using base::seconds_since;

    /// HDF5 object name from a column name ('/' separates groups).
    std::string dataset_name(std::string name)
    {
      std::replace(name.begin(), name.end(), '/', '_');
      if (name.empty() || name == "." || name == "..")
        name = "_" + name;
      return name;
    }

    /// Progress line "sweep: N/M cases (K resumed), R cases/s, ETA T s" every `interval` s.
    class SweepProgress
    {
    public:
      SweepProgress(std::size_t n_total, std::size_t n_done, std::size_t n_mine, double interval)
        : n_total_(n_total)
        , n_done_(n_done)
        , n_resumed_(n_done)
        , n_mine_(n_mine)
        , interval_(interval)
        , start_(SteadyClock::now())
        , last_(start_)
      {
      }

      void case_finished(std::size_t n_finished_here)
      {
        const auto now = SteadyClock::now();
        if (std::chrono::duration<double>(now - last_).count() < interval_ &&
            n_finished_here < n_mine_)
          return;
        last_                = now;
        const double elapsed = std::max(seconds_since(start_), 1e-9);
        const double rate    = static_cast<double>(n_finished_here) / elapsed;
        const double eta = rate > 0.0 ? static_cast<double>(n_mine_ - n_finished_here) / rate : 0.0;
        logger().info("sweep: {}/{} cases of this rank done ({}/{} in all incl. {} resumed), "
                      "{:.3g} cases/s, ETA {:.0f} s",
                      n_finished_here,
                      n_mine_,
                      n_done_ + n_finished_here,
                      n_total_,
                      n_resumed_,
                      rate,
                      eta);
      }

    private:
      std::size_t             n_total_;
      std::size_t             n_done_;
      std::size_t             n_resumed_;
      std::size_t             n_mine_;
      double                  interval_;
      SteadyClock::time_point start_;
      SteadyClock::time_point last_;
    };
  } // namespace

  namespace
  {
    /// The SI unit of a common dimension, or "" (the column is then text).
    std::string si_unit(const Dimension &d)
    {
      static const std::pair<Dimension, const char *> units[] = {{{0, 1, 0}, "m"},
                                                                 {{1, 0, 0}, "kg"},
                                                                 {{0, 0, 1}, "s"},
                                                                 {{1, 1, -2}, "N"},
                                                                 {{1, 0, -2}, "N/m"},
                                                                 {{1, 0, -1}, "N*s/m"},
                                                                 {{0, 1, -1}, "m/s"},
                                                                 {{0, 1, -2}, "m/s^2"},
                                                                 {{1, -1, -2}, "Pa"},
                                                                 {{1, -3, 0}, "kg/m^3"}};
      for (const auto &[dimension, unit] : units)
        if (dimension == d)
          return unit;
      return {};
    }

    /// "4 cm" -> {4, "cm"}; "0.7" -> {0.7, ""}; nullopt if the text does not start with a
    /// number or is no quantity.
    std::optional<std::pair<double, std::string>> number_and_unit(const std::string &text)
    {
      const char  *begin = text.c_str();
      char        *end   = nullptr;
      const double value = std::strtod(begin, &end);
      if (end == begin || !std::isfinite(value))
        return std::nullopt;
      std::string unit(end);
      unit.erase(0, unit.find_first_not_of(" \t"));
      unit.erase(unit.find_last_not_of(" \t") + 1);
      try
      {
        parse_unit(unit);
      }
      catch (const std::exception &)
      {
        return std::nullopt;
      }
      return std::pair{value, unit};
    }
  } // namespace

  double SweepParameterColumn::number(const std::string &value) const
  {
    const auto found = std::find(values.begin(), values.end(), value);
    return numeric && found != values.end() ? numbers[found - values.begin()] :
                                              std::numeric_limits<double>::quiet_NaN();
  }

  SweepParameterColumn sweep_parameter_column(const SweepParameter &parameter)
  {
    SweepParameterColumn column;
    for (const std::string &path : parameter.key_paths)
      column.name += (column.name.empty() ? "" : "+") + path;
    if (column.name.empty())
      column.name = parameter.name;
    column.values = parameter.values.to_vector();
    std::vector<std::pair<double, std::string>> parsed;
    for (const std::string &value : column.values)
    {
      const auto q = number_and_unit(value);
      if (!q)
        return column; // text
      parsed.push_back(*q);
    }
    if (parsed.empty())
      return column;
    const bool        one_unit = std::all_of(parsed.begin(),
                                      parsed.end(),
                                      [&](const auto &q) { return q.second == parsed[0].second; });
    const std::string unit     = parsed[0].second;
    if (one_unit && unit != "%")
    {
      column.unit = unit;
      for (const auto &q : parsed)
        column.numbers.push_back(q.first);
    }
    else
    {
      // Several units (or %): SI values, in the SI unit of their one dimension.
      std::optional<Dimension> dimension;
      for (const std::string &value : column.values)
      {
        const Quantity q = parse_quantity(value);
        if (dimension && *dimension != q.dimension)
          return column; // mixed dimensions: text
        dimension = q.dimension;
        column.numbers.push_back(q.value);
      }
      if (!dimension->dimensionless())
      {
        column.unit = si_unit(*dimension);
        if (column.unit.empty())
        {
          column.numbers.clear();
          return column;
        }
      }
    }
    column.numeric = true;
    return column;
  }

  std::vector<SweepParameterColumn> sweep_parameter_columns(const SweepPlan  &plan,
                                                            const SweepTable &table)
  {
    std::set<std::string> taken = {"index", "id", "companion", "status", "wall_time_s"};
    for (const std::string &metric : table.metric_names)
      taken.insert(csv_column(metric));
    std::vector<SweepParameterColumn> columns;
    for (const SweepParameter &p : plan.parameters())
    {
      SweepParameterColumn column = sweep_parameter_column(p);
      if (taken.count(csv_column(column.name, column.unit)) > 0)
        column.name = "parameter." + column.name;
      taken.insert(csv_column(column.name, column.unit));
      columns.push_back(std::move(column));
    }
    return columns;
  }

  std::pair<std::string, std::string> split_metric_unit(const std::string &metric)
  {
    const std::size_t open = metric.rfind(" [");
    if (open == std::string::npos || metric.empty() || metric.back() != ']')
      return {metric, "1"};
    std::string unit = metric.substr(open + 2, metric.size() - open - 3);
    return {metric.substr(0, open), unit.empty() ? "1" : unit};
  }

  namespace
  {
    /// The plan's cases finished before, by index: a journal entry is one when the case at its
    /// index has its id (entries of another plan are not); with `retry_failed` only the ok ones.
    std::unordered_set<std::size_t>
    finished_cases(const SweepPlan &plan, const JournalContents &journal, bool retry_failed)
    {
      const std::size_t               n_cases = plan.n_cases();
      std::unordered_set<std::size_t> finished;
      for (const JournalEntry &entry : journal.entries)
        if ((!retry_failed || entry.row.status == "ok") && entry.index < n_cases &&
            finished.count(entry.index) == 0 && plan.case_info(entry.index).id == entry.id)
          finished.insert(entry.index);
      return finished;
    }

    /// This rank's share of the plan: indices rank, rank + n_ranks, ...; none is stored (a plan
    /// may have millions): a finished case is skipped when its turn comes.
    struct RankShare
    {
      std::size_t  rank      = 0;
      std::size_t  n_ranks   = 1;
      std::size_t  n_of_rank = 0; ///< indices of this rank in the plan
      std::size_t  n_mine    = 0; ///< of them still to run
      unsigned int n_threads = 1;

      std::size_t index(std::size_t k) const { return rank + k * n_ranks; }
    };

    RankShare rank_share(std::size_t                            n_cases,
                         const std::unordered_set<std::size_t> &finished,
                         const SweepOptions                    &options)
    {
      RankShare share;
      share.n_ranks = static_cast<std::size_t>(options.n_ranks);
      share.rank    = static_cast<std::size_t>(options.rank);
      share.n_of_rank =
        n_cases > share.rank ? (n_cases - share.rank + share.n_ranks - 1) / share.n_ranks : 0;
      share.n_mine = share.n_of_rank;
      for (const std::size_t index : finished)
        share.n_mine -= index % share.n_ranks == share.rank ? 1 : 0;
      unsigned int n_threads = options.threads;
      if (n_threads == 0)
        n_threads = std::max(1U,
                             std::thread::hardware_concurrency() /
                               static_cast<unsigned int>(options.n_ranks));
      share.n_threads = static_cast<unsigned int>(
        std::max<std::size_t>(1, std::min<std::size_t>(n_threads, share.n_mine)));
      return share;
    }

    /// Case `index` run by `runner`, timed; an exception fails the case only.
    JournalEntry
    run_case(const SweepPlan &plan, const CaseRunner &runner, std::size_t index, int rank)
    {
      const SweepCase c = plan.case_info(index);
      JournalEntry    entry;
      entry.index      = c.index;
      entry.id         = c.id;
      entry.rank       = rank;
      const auto start = SteadyClock::now();
      try
      {
        // The scene is made now, case by case (a key path that cannot be followed fails the
        // case only).
        const SweepCase full = plan.case_at(index);
        entry.row            = runner(full.scene_text, full.scene_name);
      }
      catch (const std::exception &error)
      {
        entry.row = CaseRow{{}, "failed: " + base::error_text(error)};
      }
      catch (...)
      {
        entry.row = CaseRow{{}, "failed: unknown exception"};
      }
      entry.wall_time = seconds_since(start);
      if (entry.row.status != "ok")
        logger().warn("sweep: case {} {}", c.id, entry.row.status);
      return entry;
    }

    /// Runs this rank's unfinished cases on a pool of `share.n_threads` threads pulling indices
    /// from an atomic counter, each journaled as it ends; sets summary.n_run and n_failed.
    /// @throws the first journal write error (the other threads stop taking cases).
    void run_rank_cases(const SweepPlan                       &plan,
                        const CaseRunner                      &runner,
                        const std::filesystem::path           &dir,
                        const SweepOptions                    &options,
                        const std::unordered_set<std::size_t> &finished,
                        const RankShare                       &share,
                        SweepSummary                          &summary)
    {
      SweepJournal             out(SweepJournal::file_of(dir, options.rank));
      std::atomic<std::size_t> n_failed{0};
      std::mutex               progress_mutex;
      std::size_t              n_finished = 0;
      SweepProgress            progress(summary.n_cases,
                             summary.n_resumed,
                             share.n_mine,
                             options.rank == 0 ? options.progress_interval :
                                                            std::numeric_limits<double>::infinity());

      // A journal write error stops the other threads taking cases and is rethrown.
      const auto work = [&](std::size_t k)
      {
        const std::size_t index = share.index(k);
        if (finished.count(index) > 0)
          return true;
        const JournalEntry entry = run_case(plan, runner, index, options.rank);
        if (entry.row.status != "ok")
          ++n_failed;
        const std::lock_guard<std::mutex> lock(progress_mutex);
        out.append(entry);
        progress.case_finished(++n_finished);
        return true;
      };
      base::for_each_index(share.n_of_rank, share.n_threads, work);
      summary.n_run    = n_finished;
      summary.n_failed = n_failed;
    }

    /// Rank 0 after the barrier: merges every rank's journal into sweep.h5 and sweep.csv.
    void merge_sweep_results(const SweepPlan             &plan,
                             const std::filesystem::path &dir,
                             SweepSummary                &summary)
    {
      const SweepTable table = collect_sweep_table(plan, dir);
      summary.n_rows         = table.rows.size();
      write_sweep_results(plan, table, dir);
      if (summary.n_rows < summary.n_cases)
        logger().warn("sweep: {} of {} cases not finished (run the command again to complete)",
                      summary.n_cases - summary.n_rows,
                      summary.n_cases);
      logger().info("sweep: wrote {} rows to {} and {}",
                    summary.n_rows,
                    (dir / "sweep.h5").string(),
                    (dir / "sweep.csv").string());
    }
  } // namespace

  SweepSummary run_sweep(const SweepPlan             &plan,
                         const CaseRunner            &runner,
                         const std::filesystem::path &dir,
                         const SweepOptions          &options)
  {
    if (options.n_ranks < 1 || options.rank < 0 || options.rank >= options.n_ranks)
      throw std::invalid_argument(
        fmt::format("sweep rank {} of {} ranks (expected 0 <= rank < n_ranks)",
                    options.rank,
                    options.n_ranks));
    SweepSummary summary;
    summary.n_cases = plan.n_cases();

    const JournalContents journal = SweepJournal::read_all(dir);
    summary.n_torn_lines          = journal.n_torn_lines;
    if (journal.n_torn_lines > 0)
      logger().warn("sweep: ignored {} incomplete journal line(s) in {} (interrupted run)",
                    journal.n_torn_lines,
                    (dir / "journal").string());
    const std::unordered_set<std::size_t> finished =
      finished_cases(plan, journal, options.retry_failed);
    summary.n_resumed = finished.size();

    const RankShare share = rank_share(summary.n_cases, finished, options);
    logger().info("sweep: {} cases, {} already finished, {} to run on rank {} with {} thread(s)",
                  summary.n_cases,
                  summary.n_resumed,
                  share.n_mine,
                  options.rank,
                  share.n_threads);
    if (share.n_mine > 0)
      run_rank_cases(plan, runner, dir, options, finished, share, summary);

    if (options.barrier)
      options.barrier();
    if (options.rank == 0)
      merge_sweep_results(plan, dir, summary);
    return summary;
  }

  SweepTable collect_sweep_table(const SweepPlan &plan, const std::filesystem::path &dir)
  {
    const JournalContents                                 journal = SweepJournal::read_all(dir);
    std::unordered_map<std::string, const JournalEntry *> best;
    for (const JournalEntry &entry : journal.entries)
    {
      const auto found = best.find(entry.id);
      if (found == best.end())
        best.emplace(entry.id, &entry);
      else if (found->second->row.status != "ok" && entry.row.status == "ok")
        found->second = &entry;
    }

    SweepTable table;
    for (const SweepParameter &p : plan.parameters())
      table.parameter_names.push_back(p.name);
    std::map<std::string, std::size_t> metric_column;
    // Each journaled case looked up by its index (the plan's cases are not stored): an entry
    // belongs to this plan when the case at its index has its id.
    std::vector<std::pair<SweepCase, const JournalEntry *>> found;
    for (const auto &[id, entry] : best)
      if (entry->index < plan.n_cases())
        if (SweepCase c = plan.case_info(entry->index); c.id == id)
          found.emplace_back(std::move(c), entry);
    std::sort(found.begin(),
              found.end(),
              [](const auto &a, const auto &b) { return a.first.index < b.first.index; });
    for (auto &[c, entry_of_case] : found)
    {
      const JournalEntry &entry = *entry_of_case;
      SweepTableRow       row;
      row.index     = c.index;
      row.id        = std::move(c.id);
      row.companion = std::move(c.companion);
      row.values    = std::move(c.values);
      row.status    = entry.row.status;
      row.wall_time = entry.wall_time;
      for (const auto &[name, value] : entry.row.metrics)
      {
        auto column = metric_column.find(name);
        if (column == metric_column.end())
        {
          column = metric_column.emplace(name, table.metric_names.size()).first;
          table.metric_names.push_back(name);
        }
        if (row.metrics.size() <= column->second)
          row.metrics.resize(column->second + 1, std::numeric_limits<double>::quiet_NaN());
        row.metrics[column->second] = value;
      }
      table.rows.push_back(std::move(row));
    }
    for (SweepTableRow &row : table.rows)
      row.metrics.resize(table.metric_names.size(), std::numeric_limits<double>::quiet_NaN());
    return table;
  }

  namespace
  {
    /// sweep.csv: the CSV convention name_unit, with numbers only in numeric columns.
    Table sweep_csv_table(const std::vector<SweepParameterColumn> &parameter_columns,
                          const SweepTable                        &table)
    {
      Table csv;
      csv.integer("index").text("id").text("companion");
      for (const SweepParameterColumn &p : parameter_columns)
        if (p.numeric)
          csv.number(p.name, p.unit);
        else
          csv.text(p.name);
      csv.text("status");
      for (const std::string &metric : table.metric_names)
      {
        const auto [name, unit] = split_metric_unit(metric);
        csv.number(name, unit);
      }
      csv.number("wall_time", "s");
      for (const SweepTableRow &r : table.rows)
      {
        std::vector<Cell> row{static_cast<std::int64_t>(r.index), r.id, r.companion};
        for (std::size_t p = 0; p < parameter_columns.size(); ++p)
          if (parameter_columns[p].numeric)
            row.emplace_back(parameter_columns[p].number(r.values.at(p)));
          else
            row.emplace_back(r.values.at(p));
        row.emplace_back(r.status);
        for (const double m : r.metrics)
          row.emplace_back(m);
        row.emplace_back(r.wall_time);
        csv.add_row(std::move(row));
      }
      return csv;
    }

    /// sweep.h5 /sweep/metrics: one dataset per metric with its unit.
    void write_metrics(ResultsGroup &sweep, const SweepTable &table)
    {
      ResultsGroup metrics = sweep.group("metrics");
      for (std::size_t m = 0; m < table.metric_names.size(); ++m)
      {
        std::vector<double> values;
        for (const SweepTableRow &r : table.rows)
          values.push_back(r.metrics[m]);
        const auto [name, unit] = split_metric_unit(table.metric_names[m]);
        metrics.write(dataset_name(name), values, unit);
      }
    }

    /// sweep.h5 /sweep/parameters_si: the parameters whose every value is a quantity of one
    /// dimension, in SI.
    void write_parameters_si(ResultsGroup &sweep, const SweepTable &table)
    {
      ResultsGroup si = sweep.group("parameters_si");
      for (std::size_t p = 0; p < table.parameter_names.size(); ++p)
      {
        std::vector<double>      values;
        std::optional<Dimension> dimension;
        bool                     numeric = true;
        for (const SweepTableRow &r : table.rows)
        {
          try
          {
            const Quantity q = parse_quantity(r.values[p]);
            if (dimension && *dimension != q.dimension)
              numeric = false;
            dimension = q.dimension;
            values.push_back(q.value);
          }
          catch (const std::exception &)
          {
            numeric = false;
          }
          if (!numeric)
            break;
        }
        if (numeric && dimension)
          si.write(dataset_name(table.parameter_names[p]), values, to_string(*dimension));
      }
    }

    /// sweep.h5 /sweep: id, companion and status, and /sweep/parameters (the values as text).
    void write_text_columns(ResultsGroup &sweep, const SweepTable &table)
    {
      std::vector<std::string> ids, companions, statuses;
      for (const SweepTableRow &r : table.rows)
      {
        ids.push_back(r.id);
        companions.push_back(r.companion);
        statuses.push_back(r.status);
      }
      sweep.write("id", ids);
      sweep.write("companion", companions);
      sweep.write("status", statuses);
      ResultsGroup parameters = sweep.group("parameters");
      for (std::size_t p = 0; p < table.parameter_names.size(); ++p)
      {
        std::vector<std::string> values;
        for (const SweepTableRow &r : table.rows)
          values.push_back(r.values[p]);
        parameters.write(dataset_name(table.parameter_names[p]), values);
      }
    }

    /// The `columns` attribute of /sweep: the metric labels "name [unit]" as the journal has them.
    std::string column_labels(const SweepTable &table)
    {
      std::vector<std::string> labels{"index", "id", "companion"};
      labels.insert(labels.end(), table.parameter_names.begin(), table.parameter_names.end());
      labels.push_back("status");
      labels.insert(labels.end(), table.metric_names.begin(), table.metric_names.end());
      labels.push_back("wall_time [s]");
      std::string columns;
      for (const std::string &h : labels)
        columns += (columns.empty() ? "" : "\n") + h;
      return columns;
    }

    /// sweep.h5: numeric and text columns, meta and input through ResultsFile (temporary file,
    /// then rename).
    void write_sweep_h5(const SweepPlan                         &plan,
                        const SweepTable                        &table,
                        const std::vector<SweepParameterColumn> &parameter_columns,
                        const std::filesystem::path             &path)
    {
      ResultsFile               file(path, plan.text(), plan.to_json_text());
      ResultsGroup              sweep = file.root().group("sweep");
      std::vector<std::int64_t> index;
      std::vector<double>       wall_time;
      for (const SweepTableRow &r : table.rows)
      {
        index.push_back(static_cast<std::int64_t>(r.index));
        wall_time.push_back(r.wall_time);
      }
      sweep.write("index", index, "1");
      sweep.write("wall_time", wall_time, "s");
      write_metrics(sweep, table);
      write_parameters_si(sweep, table);
      std::vector<std::string> column_names;
      for (const SweepParameterColumn &p : parameter_columns)
        column_names.push_back(csv_column(p.name, p.unit));
      sweep.write("parameter_columns", column_names);
      sweep.set_attribute("n_cases", plan.n_cases());
      sweep.set_attribute("n_rows", table.rows.size());
      write_text_columns(sweep, table);
      sweep.set_attribute("columns", column_labels(table));
      file.commit();
    }
  } // namespace

  void write_sweep_results(const SweepPlan             &plan,
                           const SweepTable            &table,
                           const std::filesystem::path &dir)
  {
    const OutputDir                         output(dir);
    const std::vector<SweepParameterColumn> parameter_columns =
      sweep_parameter_columns(plan, table);
    sweep_csv_table(parameter_columns, table).write_csv(output.file("sweep.csv"));
    write_sweep_h5(plan, table, parameter_columns, output.file("sweep.h5"));
  }
} // namespace kimp::app
