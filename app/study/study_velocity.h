// The k(H, v) axis of `kimp study` (not a public API): FEM cases per wall height and impact
// velocity, the material-model choice of fidelity: auto, the k table in memory and the
// consistent-k building runs with their files (docs/physics.md §4 "Consistent k").
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/laws/k_table.h"
#include "app/study/study_fem.h"
#include "app/study/study_run.h"
#include "io/results_file.h"

namespace kimp::app::study_internal
{
  /// The velocities of the k(H, v) table: fem.velocities and fem.slab.velocity, increasing, m/s.
  std::vector<double> study_velocities(const StudyScene &scene);

  /// Name of a velocity case: "H1.25_v0.5" (m, m/s).
  std::string velocity_case_name(double wall_height, double velocity);

  /**
   * The linear-elastic counterpart of `scene`: both material models elastic with the elastic
   * constants the inelastic laws use (E_ci from f_cm for damage-plasticity concrete, the preset's
   * E, ν, ρ for the soil), so that only the inelasticity differs.
   */
  FemScene linear_fem_scene(const FemScene &scene);

  /// `scene` itself (inelastic = true) or its linear counterpart.
  FemScene material_fem_scene(const FemScene &scene, bool inelastic);

  /// Suffix of the FEM cache names of a case run linear although the scene is inelastic.
  std::string material_suffix(const FemScene &scene, bool inelastic);

  /**
   * fidelity: auto on a scene with inelastic materials: run the cheapest ladder level linear and
   * inelastic; keep linear if both k differ by less than the ladder tolerance, else inelastic.
   * Sets h.inelastic and h.material_reason. An elastic scene is left linear without a run.
   * If @p inelastic_cheap_fits is given, it receives the inelastic fits of the cheap level (when
   * run), so that the fidelity ladder reuses them instead of fitting (and logging) them again.
   */
  void choose_material_model(const StudyScene         &scene,
                             double                    wall_height,
                             const io::OutputDir      &output,
                             StudyHeight              &h,
                             std::optional<StudyFits> *inelastic_cheap_fits = nullptr);

  /**
   * For an inelastic case: fit the linear counterpart of `level_scene` (the FEM level the case
   * used) into the `linear` fit of each of h's study laws. `case_name` names its cache files.
   */
  void add_linear_counterpart(const FemScene      &level_scene,
                              const StudyFitScene &fit,
                              double               wall_height,
                              const io::OutputDir &output,
                              const std::string   &case_name,
                              StudyHeight         &h);

  /**
   * The FEM cases of `reference` (a height at the reference velocity, its level and material
   * chosen) at every other velocity of study_velocities(), fitted; their numerical error is the
   * reference's relative error times their k.
   */
  std::vector<StudyHeight> run_velocity_cases(const StudyScene    &scene,
                                              const StudyHeight   &reference,
                                              const io::OutputDir &output);

  /// Rank `rank` of `n_ranks` computes its share of the velocity cases into the FEM cache (the
  /// reference heights must be in the cache: compute_heights_on_ranks() and a barrier first).
  void compute_velocity_cases_on_ranks(const StudyScene    &scene,
                                       const io::OutputDir &output,
                                       int                  rank,
                                       int                  n_ranks);

  /// The study's k table in memory (every height and velocity with both fits), as read_k_table()
  /// would read it back from k_table.csv.
  KTable study_k_table(const StudyScene &scene, const StudyResult &result);

  /// Every height and velocity, sorted by height, then velocity (the rows of k_table.csv).
  std::vector<const StudyHeight *> k_table_cases(const StudyResult &result);

  /// The k(H, v) table and the linear k beside it in the log.
  void log_velocity_table(const StudyResult &result);

  /// Consistent k of every building run with walls (scene.consistent_k).
  std::vector<ConsistentKRun> run_consistent_k(const StudyScene &scene, const StudyResult &result);

  /// DIR/consistent_k.csv and DIR/consistent_k_iterations.csv (if any run).
  void write_consistent_k_csv(const io::OutputDir &output, const StudyResult &result);

  /// study.h5: /k_table_velocity (every height and velocity), /fem/<H>_v<v>,
  /// /fit_velocity/<case>/<law> and /consistent_k/<record>/<law>.
  void
  write_velocity_h5(io::ResultsGroup &root, const StudyScene &scene, const StudyResult &result);

  /// summary.json: "k_table_velocity" and "consistent_k".
  void add_velocity_summary(nlohmann::ordered_json &j,
                            const StudyScene       &scene,
                            const StudyResult      &result);

  /// report.md section of k(H, v) with the linear k beside (empty for a linear study at one
  /// velocity).
  std::string
  velocity_report_markdown(const StudyScene &scene, const StudyResult &result, bool charts);

  /// report.md section of the consistent-k iterations (empty if none ran).
  std::string consistent_k_report_markdown(const StudyScene &scene, const StudyResult &result);
} // namespace kimp::app::study_internal
