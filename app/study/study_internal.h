// Stages of `kimp study` shared by its translation units (not a public API): the per-height FEM
// and fits, the building runs and extra studies (compute), and the files they produce (writers).
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/study/study_run.h"

namespace kimp::app::study_internal
{
  using Clock = std::chrono::steady_clock;

  /// s since `start`.
  double seconds_since(Clock::time_point start);

  /// The row of thesis Table 2.1 at `wall_height` (m), if there is one.
  std::optional<ThesisStiffness> thesis_row(double wall_height);

  /// k of a fit in kN/mm^n per metre (or NaN).
  double per_metre(const std::optional<fit::FitResult> &fit);
  /// Lower or upper end of the 95 % interval of k in kN/mm^n per metre (or NaN).
  double per_metre_bound(const std::optional<fit::FitResult> &fit, bool upper);
  /// Numerical error of k (fidelity ladder) in kN/mm^n per metre; NaN if not estimated.
  double numerical_error(const StudyHeight &h, double exponent);
  /// Contact element size of the FEM level used for `h`, m.
  double used_h_contact(const StudyScene &scene, const StudyHeight &h);
  /// Penalty factor of the FEM level used for `h`.
  double used_penalty(const StudyScene &scene, const StudyHeight &h);
  /// Every value times `factor`.
  std::vector<double> scale(std::vector<double> values, double factor);
  /// "{:.6g}", or "" for NaN and infinities.
  std::string number(double value);

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
  /// Per record: the building without walls, then with walls for every height and law.
  std::vector<StudyBuildingRun> run_building(const StudyScene               &scene,
                                             const std::vector<StudyHeight> &heights);
  /// The accuracy, stability and sensitivity studies the scene asks for.
  StudyExtras
  run_extras(const StudyScene &scene, const StudyResult &result, const io::OutputDir &output);

  // writers: study_files.cc
  /// DIR/k_table.csv and (fidelity: auto) DIR/fidelity_levels.csv.
  void write_k_table_csv(const io::OutputDir            &output,
                         const StudyScene               &scene,
                         const std::vector<StudyHeight> &heights,
                         const std::vector<StudyHeight> &velocity_cases = {});
  /// DIR/building_response.csv.
  void write_building_csv(const io::OutputDir &output, const std::vector<StudyBuildingRun> &runs);
  /// DIR/study.h5: /fem, /fit, /k_table, extras, /fidelity, /building.
  void write_study_h5(const io::LoadedScene<StudyScene> &loaded,
                      const StudyResult                 &result,
                      const io::OutputDir               &output);
  /// The content of DIR/summary.json.
  nlohmann::ordered_json summary_json(const StudyScene &scene, const StudyResult &result);

  // writers: study_report.cc
  /// The content of DIR/report.md (`charts`: link the charts).
  std::string report_markdown(const StudyScene &scene, const StudyResult &result, bool charts);
  /// Draw the charts; false (with a warning) if they could not be drawn.
  bool draw_charts(const io::OutputDir &output);
} // namespace kimp::app::study_internal
