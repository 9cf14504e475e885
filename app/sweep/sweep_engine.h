// Runs the cases of a SweepPlan over MPI ranks (static round-robin by case index) and a thread
// pool, journals each finished case (resume skips them), and merges all journals into DIR/sweep.h5
// and DIR/sweep.csv, one row per case sorted by index.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/sweep/sweep_journal.h"
#include "app/sweep/sweep_plan.h"

namespace kimp::app
{
  /**
   * Runs one case: loads the scene text (read_scene_text<Scene>), runs it and returns its metrics.
   * Called concurrently from several threads; an exception marks the case "failed: <what>".
   */
  using CaseRunner =
    std::function<CaseRow(const std::string &scene_yaml_text, const std::string &scene_name)>;

  /// How run_sweep() distributes and reports.
  struct SweepOptions
  {
    unsigned int threads      = 0; ///< per rank; 0 = hardware concurrency / n_ranks (>= 1)
    int          rank         = 0;
    int          n_ranks      = 1;
    bool         retry_failed = false; ///< rerun cases journaled as failed
    /// Called by every rank after its cases, before rank 0 merges (MPI_Barrier under MPI).
    std::function<void()> barrier;
    double                progress_interval = 2.0; ///< s between progress lines (rank 0)
  };

  /// What one call of run_sweep() did.
  struct SweepSummary
  {
    std::size_t n_cases      = 0; ///< in the plan
    std::size_t n_resumed    = 0; ///< found finished in the journals, skipped
    std::size_t n_run        = 0; ///< run by this rank now
    std::size_t n_failed     = 0; ///< of n_run
    std::size_t n_torn_lines = 0; ///< journal lines ignored
    std::size_t n_rows       = 0; ///< rows merged (rank 0), < n_cases if some are missing
  };

  /// One merged row.
  struct SweepTableRow
  {
    std::size_t              index = 0;
    std::string              id;
    std::string              companion;
    std::vector<std::string> values; ///< one per parameter
    std::string              status;
    std::vector<double>      metrics; ///< aligned with SweepTable::metric_names (NaN if absent)
    double                   wall_time = 0.0; ///< s
  };

  /// All finished cases of a sweep directory.
  struct SweepTable
  {
    std::vector<std::string>   parameter_names;
    std::vector<std::string>   metric_names; ///< in order of first appearance
    std::vector<SweepTableRow> rows;         ///< sorted by index, one per case id
  };

  /**
   * Run the cases of `plan` assigned to `options.rank` that no journal in `dir` lists as finished,
   * on `options.threads` threads, appending each to DIR/journal/rank-<rank>.jsonl. Then all
   * ranks meet at options.barrier and rank 0 merges (collect_sweep_table, write_sweep_results).
   * @throws OutputError if the journal or results cannot be written (a failing case does not
   *         throw: it is recorded with status "failed: <what>").
   */
  SweepSummary run_sweep(const SweepPlan             &plan,
                         const CaseRunner            &runner,
                         const std::filesystem::path &dir,
                         const SweepOptions          &options);

  /// Merge the journals of `dir` for the cases of `plan`: sorted by index, one row per case id
  /// (an "ok" entry wins over a failed one, else the first), entries of other plans ignored.
  SweepTable collect_sweep_table(const SweepPlan &plan, const std::filesystem::path &dir);

  /**
   * DIR/sweep.csv (index, id, companion, parameters..., status, metrics..., wall_time_s; header
   * convention name_unit, parameters as sweep_parameter_column() says) and
   * DIR/sweep.h5: /meta, /input/{scene = sweep file, resolved = plan JSON}, and /sweep with one
   * dataset per column (strings for id, companion, status and parameter texts; parameters that are
   * all quantities of one dimension also as SI numbers under /sweep/parameters_si; the CSV column
   * of each parameter, in plan order, in /sweep/parameter_columns). Both files are written under
   * temporary names and renamed.
   */
  void write_sweep_results(const SweepPlan             &plan,
                           const SweepTable            &table,
                           const std::filesystem::path &dir);

  /**
   * How a parameter is written in sweep.csv and dsrss_table.csv. Its column is named by its key
   * paths joined with '+' ("walls.left.gap+walls.right.gap"). When every value is a number with
   * one unit, the column holds the numbers in that unit (`..._cm`: 4, 6, 8); "%" values and bare
   * numbers are dimensionless fractions (no suffix: 0.02); numbers in several units of one
   * dimension are SI (`_m`, `_N_per_m`, ...). Other values (records, labels) are a text column.
   */
  struct SweepParameterColumn
  {
    std::string              name; ///< CSV column name before the unit suffix
    std::string              unit; ///< unit of the numbers ("" dimensionless or text)
    bool                     numeric = false;
    std::vector<std::string> values;  ///< the parameter's value texts
    std::vector<double>      numbers; ///< per value, in `unit` (numeric columns)

    /// The number of the value text `value` (NaN if unknown), or -- for a text column -- none.
    double number(const std::string &value) const;
  };

  /// The column of `parameter` (see SweepParameterColumn).
  SweepParameterColumn sweep_parameter_column(const SweepParameter &parameter);

  /**
   * The columns of the plan's parameters in sweep.csv, in plan order: sweep_parameter_column(),
   * named "parameter.<key paths>" where the CSV column would repeat another one (a metric of the
   * same name, e.g. the parameter and the metric `building.n_storeys`). dsrss_table.csv uses the
   * same names.
   */
  std::vector<SweepParameterColumn> sweep_parameter_columns(const SweepPlan  &plan,
                                                            const SweepTable &table);

  /// "name [unit]" -> {"name", "unit"}; a name without brackets has unit "1".
  std::pair<std::string, std::string> split_metric_unit(const std::string &metric);
} // namespace kimp::app
