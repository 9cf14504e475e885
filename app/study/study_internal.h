// Stages of `kimp study` shared by its translation units (not a public API): the per-height FEM
// and fits, the building runs and extra studies (compute), and the files they produce (writers).
#pragma once

#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/lumped/lumped_run.h"
#include "app/study/study_run.h"
#include "app/table_cells.h"
#include "base/format.h"
#include "base/logging.h"
#include "base/stopwatch.h"
#include "fit/fitter.h"
#include "io/output_dir.h"
#include "io/results_file.h"
#include "io/summary.h"
#include "io/table.h"

namespace kimp::app
{
  struct StudyFits;
} // namespace kimp::app

namespace kimp::app::study_internal
{
  // The names of base, io and fit every stage is written against.
  using base::logger;
  using fit::FitResult;
  using fit::stiffness_display_unit;
  using fit::stiffness_si_unit;
  using fit::stiffness_to_kn_per_mm;
  using io::Cell;
  using io::OutputDir;
  using io::ResultsFile;
  using io::ResultsGroup;
  using io::Table;
  using io::write_csv_atomic;

  using Clock = std::chrono::steady_clock;

  /// The value of a quantity that was not computed (written as "" in the CSV files).
  inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

  using base::seconds_since;

  /// The row of thesis Table 2.1 at `wall_height` (m), if there is one.
  std::optional<ThesisStiffness> thesis_row(double wall_height);

  /// k of a fit in kN/mm^n per metre (or NaN).
  double per_metre(const std::optional<fit::FitResult> &fit);
  /// Lower or upper end of the 95 % interval of k in kN/mm^n per metre (or NaN).
  double per_metre_bound(const std::optional<fit::FitResult> &fit, bool upper);
  /// Numerical error of the k of `law` (fidelity ladder) in kN/mm^n per metre; NaN if not
  /// estimated.
  double numerical_error(const StudyHeight &h, const StudyLaw &law);
  /// k of `law` in thesis Table 2.1 at `row` in kN/mm^n per metre (NaN: no row or no value).
  double thesis_k(const std::optional<ThesisStiffness> &row, const StudyLaw &law);
  /// Contact element size of the FEM level used for `h`, m.
  double used_h_contact(const StudyScene &scene, const StudyHeight &h);
  /// Penalty factor of the FEM level used for `h`.
  double used_penalty(const StudyScene &scene, const StudyHeight &h);
  /// The fitted laws of `fits` and their statuses into `h` (its fit_seconds is the caller's).
  void set_fits(StudyHeight &h, StudyFits fits);
  /// 1 for true, 0 for false (the flag columns of the HDF5 tables).
  inline double flag(bool value)
  {
    return value ? 1.0 : 0.0;
  }

  /// summary.json's object of `law` at `h`: status and, when fitted, k per metre with its 95 %
  /// interval and unit and the numerical error; with `width` (m) also k_total and the fit's
  /// normalised RMS.
  nlohmann::ordered_json
  law_json(const StudyHeight &h, const StudyLawFit &law, std::optional<double> width = {});

  /// Adds the columns `law`, `law`_lower and `law`_upper: k per metre and its 95 % interval.
  void add_k_columns(Table &t, const StudyLaw &law);
  /// Appends the cells of add_k_columns() for `fit` (NaN without a fit).
  void add_k_cells(std::vector<Cell> &row, const std::optional<FitResult> &fit);

  /// The runs by (record, law), the keys in order; with `only_ok`, only the runs whose status
  /// is "ok" (a study.h5 table per record and law).
  template <class Run>
  std::map<std::pair<std::string, std::string>, std::vector<const Run *>>
  by_record_and_law(const std::vector<Run> &runs, bool only_ok)
  {
    std::map<std::pair<std::string, std::string>, std::vector<const Run *>> groups;
    for (const Run &r : runs)
      if (!only_ok || r.status == "ok")
        groups[{r.record, r.law}].push_back(&r);
    return groups;
  }

  /// The header and rule of a Markdown table with a group of columns per study law: `lead` (its
  /// `lead_columns` column titles, "| H (m) | v (m/s) |"), the `law_columns` titles `titles(law)`
  /// of each law (" k_KV kN/mm/m | error KV |"), then "status".
  std::string law_table_header(const std::string                                  &lead,
                               std::size_t                                         lead_columns,
                               std::size_t                                         law_columns,
                               const std::function<std::string(const StudyLaw &)> &titles);

  /// Every value times `factor`.
  std::vector<double> scale(std::vector<double> values, double factor);
  /// A CSV cell: the shortest text that reads back to the same double, "" for NaN and infinities.
  std::string number(double value);
  /// A report cell: base::sig() (4 significant figures), "" for NaN and infinities.
  std::string readable(double value);

  // compute: study_heights.cc
  /// FEM (fixed level, or the fidelity ladder) and both fits of one wall height.
  StudyHeight run_height(const StudyScene &scene, double wall_height, const io::OutputDir &output);
  /// Rank `rank` of `n_ranks` computes its share of the heights into the FEM cache.
  void compute_heights_on_ranks(const StudyScene    &scene,
                                const io::OutputDir &output,
                                int                  rank,
                                int                  n_ranks);
  /// The k table in the log, beside thesis Table 2.1.
  void log_k_table(const StudyScene &scene, const std::vector<StudyHeight> &heights);

  // compute: study_building.cc
  /// The study's records with the labels of the building runs (a repeated record gets "_2",
  /// "_3", ...).
  std::vector<std::pair<std::string, GroundMotionScene>> labelled_records(const StudyScene &scene);
  /// The wall gap of a record whose run without walls has the peak isolation displacement
  /// `base_displacement` (walls.gap, or that peak less walls.gap_reduction), m.
  double wall_gap(const StudyScene &scene, double base_displacement);
  /// The laws a height's fits give the building runs, with the fit each takes its k from
  /// (Kelvin-Voigt; Jankowski's for jankowski and hysteretic).
  std::vector<std::pair<std::string, const std::optional<fit::FitResult> *>>
  building_laws(const StudyHeight &h);
  /// `base` with both walls present at `gap` (m) and the impact law `law` of total stiffness
  /// `k_total` (N/m^n, the law's own exponent) at COR `cor`.
  LumpedScene walled_scene(const LumpedScene &base,
                           double             gap,
                           const std::string &law,
                           double             k_total,
                           double             cor);
  /// Per record: the building without walls, then with walls for every height and law. With
  /// `yielding` every height also gets a run against its yielding wall element: instead of the
  /// laws with inelastic materials, beside them in a linear study (the estimate element); these
  /// runs share a pool of threads with the laws' runs (run_yielding_wall_cases()).
  std::vector<StudyBuildingRun> run_building(const StudyScene                     &scene,
                                             const std::vector<StudyHeight>       &heights,
                                             const std::vector<StudyYieldingWall> &yielding = {});
  /// Peaks, status and (with `without_walls`) amplification of one building run into `run`.
  void fill_building_peaks(StudyBuildingRun       &run,
                           const LumpedCaseResult &result,
                           unsigned int            top_dof,
                           const lumped::Response *without_walls);
  /// The accuracy, stability and sensitivity studies the scene asks for.
  StudyExtras
  run_extras(const StudyScene &scene, const StudyResult &result, const io::OutputDir &output);

  // compute: study_flexible_wall.cc (walls.flexible)
  /// The wall SDOF of every height from its FE model (a failure is a row with its status).
  std::vector<StudyWallSdof> compute_wall_sdofs(const StudyScene               &scene,
                                                const std::vector<StudyHeight> &heights,
                                                const io::OutputDir            &output);
  /// The runs of run_building() with walls, against each height's flexible wall instead.
  std::vector<StudyBuildingRun>
  run_flexible_wall_building(const StudyScene                    &scene,
                             const std::vector<StudyHeight>      &heights,
                             const std::vector<StudyWallSdof>    &sdofs,
                             const std::vector<StudyBuildingRun> &rigid);

  // compute and writers: study_yielding_wall.cc (inelastic materials)
  /// The element of every height from the scene (yielding_wall_inputs(); a failure is a row).
  std::vector<StudyYieldingWall>
  derive_study_yielding_walls(const StudyScene &scene, const std::vector<StudyHeight> &heights);
  /// What a record's walled runs share with its run without walls.
  struct RecordRun
  {
    const std::string          &label;
    double                      scale = 1.0; ///< the record's base scale
    double                      gap   = 0.0; ///< m
    const lumped::GroundMotion &motion;
    const LumpedScene          &base;          ///< the building without walls
    const lumped::Response     &without_walls; ///< its response
  };
  /// A record's run without walls, kept for its walled runs (record() refers to it).
  struct RecordContext
  {
    std::string          label;
    double               scale = 1.0; ///< the record's base scale
    double               gap   = 0.0; ///< m
    lumped::GroundMotion motion;
    LumpedScene          base;          ///< the building without walls
    lumped::Response     without_walls; ///< its response

    RecordRun record() const { return {label, scale, gap, motion, base, without_walls}; }
  };
  /// One building run against a height's yielding walls: its row, and whether it ran (false:
  /// skipped) with its variable-step errors (dt: auto).
  struct YieldingWallCase
  {
    StudyBuildingRun                          run;
    bool                                      ran = false;
    std::optional<lumped::AdaptiveStepReport> adaptive;
  };
  YieldingWallCase run_yielding_wall_case(const StudyScene                     &scene,
                                          const RecordRun                      &record,
                                          const StudyHeight                    &h,
                                          const std::vector<StudyYieldingWall> &yielding);
  /**
   * run_yielding_wall_case() of every record of `records` and height of `heights`, record by
   * record (index: record × heights.size() + height), on base::for_each_index() with
   * hardware_concurrency() threads; the caller runs `beside` (a linear study's runs of the laws)
   * first, so both share the cores.
   * A case that throws is a row with its status; an exception of `beside` is rethrown after the
   * pool has stopped.
   */
  std::vector<YieldingWallCase>
  run_yielding_wall_cases(const StudyScene                     &scene,
                          const std::vector<RecordContext>     &records,
                          const std::vector<StudyHeight>       &heights,
                          const std::vector<StudyYieldingWall> &yielding,
                          const std::function<void()>          &beside);
  /// One line per yielding-wall study: failed walls and the largest resistance / capacity; `what`
  /// names the runs ("yielding walls").
  void log_yielding_walls(const std::vector<StudyBuildingRun> &runs, const std::string &what);
  /// DIR/yielding_wall_element.csv (per height) and DIR/yielding_wall.csv (per height and record).
  void write_yielding_wall_csv(const io::OutputDir &output, const StudyResult &result);
  /// What a study's yielding wall runs are: "inelastic" (the walls of every building run, instead
  /// of the laws) or "linear" (the estimate element, run beside the laws' impact springs).
  std::string yielding_wall_route(const StudyScene &scene);
  /// study.h5 /yielding_wall/element, /yielding_wall/runs (SI; the group's attribute `route`) and
  /// /yielding_wall/pushover/<H> (the curve each pushover-derived element was fitted to).
  void write_yielding_wall_h5(io::ResultsGroup  &root,
                              const StudyScene  &scene,
                              const StudyResult &result);
  /// summary.json "yielding_wall" (SI): its route, runs, failed walls, and per run the wall's
  /// values.
  nlohmann::ordered_json yielding_wall_json(const StudyScene &scene, const StudyResult &result);
  /// The report.md section (empty without yielding walls).
  std::string yielding_wall_markdown(const StudyScene &scene, const StudyResult &result);

  // writers: study_flexible_wall_files.cc
  /// DIR/wall_sdof.csv and DIR/flexible_wall.csv (rigid beside flexible, per run).
  void write_flexible_wall_csv(const io::OutputDir &output, const StudyResult &result);
  /// study.h5 /wall_sdof and /flexible_wall/<record>/<law>.
  void write_flexible_wall_h5(io::ResultsGroup &root, const StudyResult &result);
  /// summary.json "flexible_wall".
  nlohmann::ordered_json flexible_wall_json(const StudyResult &result);
  /// The report.md section (empty without flexible-wall results).
  std::string flexible_wall_markdown(const StudyScene &scene, const StudyResult &result);

  // writers: study_files.cc
  /// The k table of `cases` (one row each): k_table.csv, study.h5 /k_table and report.md.
  io::Table k_table(const StudyScene &scene, const std::vector<const StudyHeight *> &cases);
  /// DIR/k_table.csv and (fidelity: auto) DIR/fidelity_levels.csv.
  void write_k_table_csv(const io::OutputDir            &output,
                         const StudyScene               &scene,
                         const std::vector<StudyHeight> &heights,
                         const std::vector<StudyHeight> &velocity_cases = {});
  /// DIR/building_response.csv.
  void write_building_csv(const io::OutputDir &output, const std::vector<StudyBuildingRun> &runs);
  /// The fits of `h` into `g`: groups kelvin_voigt and jankowski, each with its status and
  /// (when fitted) its result for a building `width` wide (m).
  void write_study_fits(io::ResultsGroup &g, const StudyHeight &h, double width);
  /// DIR/study.h5: /fem, /fit, /k_table, extras, /fidelity, /building.
  void write_study_h5(const io::LoadedScene<StudyScene> &loaded,
                      const StudyResult                 &result,
                      const io::OutputDir               &output);
  /// Wall time of the study's stages that ran, in order (FEM, fits, building runs, flexible
  /// walls, extra studies, charts, then "files and the rest" = total minus the others), s.
  std::vector<std::pair<std::string, double>> cost_by_stage(const StudyResult &result);
  /// "FEM 11.4 s, fits 2.02 s, ..., total 49.2 s" of cost_by_stage().
  std::string cost_text(const StudyResult &result);
  /// The content of DIR/summary.json.
  nlohmann::ordered_json summary_json(const StudyScene &scene, const StudyResult &result);

  // writers: study_report.cc
  /// The k table of `heights` as Markdown (report.md and the log): k [95 % CI] ± numerical,
  /// thesis Table 2.1, totals, the FEM level.
  std::string k_table_markdown(const StudyScene &scene, const std::vector<StudyHeight> &heights);
  /// The content of DIR/report.md (`charts`: link the charts).
  std::string report_markdown(const StudyScene &scene, const StudyResult &result, bool charts);
  /// Draw the charts; false (with a warning) if they could not be drawn.
  bool draw_charts(const io::OutputDir &output);
} // namespace kimp::app::study_internal
