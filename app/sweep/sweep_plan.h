// Sweep files of `kimp sweep`: a base scene, parameters varied by scene key path (lists
// or inclusive ranges, Cartesian product or zipped) and companion runs, expanded into one scene
// text per case with a stable id (enumeration index + hash of the parameter values).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "io/scene_source.h"

namespace kimp::app
{
  /// A malformed sweep file; the message is "FILE:LINE: key: what is wrong (what was expected)",
  /// one line per error (a sweep file is read like a scene file).
  class SweepError : public io::SceneError
  {
  public:
    using io::SceneError::SceneError;
  };

  /// How the value lists of several parameters are combined into cases.
  enum class SweepCombination
  {
    product, ///< Cartesian product; the first parameter varies slowest
    zip      ///< i-th values together; every list has the same length
  };

  /**
   * One varied parameter: the scene key paths it sets (usually one, e.g. "walls.left.gap",
   * "cases[0].cor"; several paths receive the same value) and its values as YAML scalar text
   * ("10 cm", "0.7", "kobe").
   */
  struct SweepParameter
  {
    std::string              name;      ///< as written in the sweep file
    std::vector<std::string> key_paths; ///< `name` split at commas
    std::vector<std::string> values;    ///< scalar text, or the label of a map value
    /// Per value: the (key path, YAML scalar) pairs it sets; a scalar value sets every key path,
    /// a map value ({walls.left.gap: 10 cm, walls.right.gap: 20 cm, label: asym}) its own keys.
    std::vector<std::vector<std::pair<std::string, std::string>>> settings;
    int line = 0; ///< line of the key in the sweep file (1-based)
  };

  /// A companion run added to every case: the same scene with fixed overrides (key path, value).
  struct SweepCompanion
  {
    std::string                                      name;
    std::vector<std::pair<std::string, std::string>> overrides;
    int                                              line = 0;
  };

  /**
   * The optional `report:` section: which charts scripts/sweep_charts.py draws and how the summary
   * reads the rows.
   * @code
   *   report:
   *     kind: adjacent_buildings   # gap_study, isolation_flexibility, wall_location,
   *                                # impact_parameters, adjacent_buildings or bumpers
   *     gap: walls.left.gap        # scene key path of the swept gap (default walls.left.gap)
   *     title: "Study 5: ..."      # optional chart and summary title
   * @endcode
   */
  struct SweepReportSpec
  {
    std::string kind;
    std::string gap_key = "walls.left.gap";
    std::string title;
    int         line = 0; ///< line of `report:` in the sweep file (1-based)
  };

  /// An annotated example sweep file (every key with its meaning), for `kimp sweep
  /// --print-defaults`; it reads back as a valid sweep.
  std::string sweep_file_defaults_text();

  /// The keys of a sweep file as JSON (io::SchemaWriter), for `kimp sweep --print-schema`.
  std::string sweep_file_schema_text();

  /// The report kinds scripts/sweep_charts.py knows (studies 1-6 of data/studies).
  const std::vector<std::string> &sweep_report_kinds();

  /// One run of the sweep.
  struct SweepCase
  {
    std::size_t index = 0;           ///< position in the enumeration (companions follow their case)
    std::string id;                  ///< "<index>-<16 hex digits>", stable across runs
    std::string companion;           ///< "" for the main run
    std::vector<std::string> values; ///< one per parameter, as in the sweep file
    std::string              scene_text; ///< the base scene with the values set (YAML)
    std::string              scene_name; ///< for messages: "SWEEP.yaml case <id>"
  };

  /// Loads a scene text (throws SceneError when it is invalid); used to check key paths early.
  using SceneChecker = std::function<void(const std::string &text, const std::string &name)>;

  /// Called by SweepPlan::parse() once the cases are counted (companions included), before they
  /// are enumerated, which takes a while for many cases: a cost estimate and a budget.
  using CaseCountCheck = std::function<void(std::size_t        n_cases,
                                            const std::string &base_scene_text,
                                            const std::string &base_scene_name)>;

  /**
   * A parsed sweep file:
   * @code
   *   scene: ../scenes/isolated_4storey.yaml   # base scene, relative to the sweep file
   *   engine: lumped                           # which scene type / runner (default lumped)
   *   combine: product                         # or zip
   *   parameters:                              # key path(s) -> list or inclusive range
   *     walls.left.gap, walls.right.gap: {from: "10 cm", to: "45 cm", step: "0.5 cm"}
   *     ground_motion.record: [kobe, sylmar_olive_view]
   *     motion:                                # map values set several keys at once
   *       - {label: kobe_48s, ground_motion.record: RSN1106_KOBE_KJM000, ground_motion.duration: 48
   * s}
   *       - {label: converter, ground_motion.record: SCS142}
   *   companions:                              # extra run per case with fixed overrides
   *     no_contact: {walls.left.present: false, walls.right.present: false}
   * @endcode
   */
  class SweepPlan
  {
  public:
    /// Parse `text` (named `file_name` in messages); `base_scene_text` is the scene YAML that the
    /// key paths apply to (read by from_file() from `scene:`).
    static SweepPlan parse(const std::string    &text,
                           const std::string    &file_name,
                           const std::string    &base_scene_text,
                           const std::string    &base_scene_name,
                           const CaseCountCheck &check_count = {});

    /// Read the sweep file and its base scene (path relative to the sweep file).
    /// @throws SweepError for a malformed file or a missing scene.
    static SweepPlan from_file(const std::filesystem::path &file,
                               const CaseCountCheck        &check_count = {});

    /// The `scene:` entry of a sweep text, resolved against `sweep_file`'s directory.
    static std::filesystem::path base_scene_path(const std::string           &text,
                                                 const std::filesystem::path &sweep_file);

    /// Every case in enumeration order: each combination, followed by its companions.
    const std::vector<SweepCase> &cases() const { return cases_; }

    const std::vector<SweepParameter> &parameters() const { return parameters_; }
    const std::vector<SweepCompanion> &companions() const { return companions_; }
    /// The `report:` section, if the sweep file has one.
    const std::optional<SweepReportSpec> &report() const { return report_; }
    SweepCombination                      combination() const { return combination_; }
    const std::string                    &engine() const { return engine_; }
    const std::string                    &file_name() const { return file_name_; }
    const std::string                    &text() const { return text_; }

    /**
     * Load every value of every parameter (one at a time on the base scene) and each companion
     * with `check`, so that an unknown key path or a bad value is reported against the sweep
     * file's line before anything runs.
     * @throws SweepError "FILE:LINE: key = value: <scene error>".
     */
    void check_key_paths(const SceneChecker &check) const;

    /**
     * Load the ground motions before anything runs, with `check` (which loads a scene text's
     * records): each parameter value and companion that sets a record key (record,
     * records_dir, record_unit), reported as check_key_paths() does; when the sweep file sets no
     * record, the base scene itself, whose errors name its own file, line and key.
     * @throws SweepError for a value or companion; what `check` throws for the base scene.
     */
    void check_records(const SceneChecker &check) const;

    /// The base scene file (the `scene:` entry resolved against the sweep file's directory).
    const std::string &base_scene_name() const { return base_scene_name_; }

    /// The plan as JSON text (parameters, values, companions, number of cases).
    std::string to_json_text() const;

  private:
    /// A scene the sweep's settings give on their own: one parameter value or one companion,
    /// set on the base scene.
    struct Variant
    {
      std::string label; ///< "walls.left.gap = 10 cm", "companion no_contact"
      std::string key;   ///< the sweep file's key blamed for its errors
      int         line = 0;
      std::vector<std::pair<std::string, std::string>> settings; ///< (key path, YAML value)
    };
    std::vector<Variant> variants() const;
    /// `check` of the variant's scene; its error becomes "FILE:LINE: key: <error>".
    void check_variant(const Variant &variant, const SceneChecker &check) const;
    /// Fills cases_ from the parameters and companions.
    void enumerate_cases(const CaseCountCheck &check_count);

    std::string                    file_name_;
    std::string                    text_;
    std::string                    base_scene_text_;
    std::string                    base_scene_name_;
    std::string                    engine_      = "lumped";
    SweepCombination               combination_ = SweepCombination::product;
    std::vector<SweepParameter>    parameters_;
    std::vector<SweepCompanion>    companions_;
    std::optional<SweepReportSpec> report_;
    std::vector<SweepCase>         cases_;
  };

  /**
   * Inclusive range from..to in steps of `step`, robust to round-off (10-45 cm step 0.5 cm gives
   * 71 values); values are formatted in the unit of `from` ("10.5 cm"), or as plain numbers.
   * @throws SweepError (named by `where`) for mismatched units, step <= 0 or to < from.
   */
  std::vector<std::string> expand_range(const std::string &from,
                                        const std::string &to,
                                        const std::string &step,
                                        const std::string &where);

  /**
   * `yaml_text` with the scalar at `key_path` ("a.b[2].c") set to `value_yaml` (a YAML scalar).
   * Missing map keys are created (the scene reader then rejects unknown ones); a list index may be
   * at most the list's length (one new item).
   * @throws std::invalid_argument naming the path when it cannot be followed.
   */
  std::string set_yaml_value(const std::string &yaml_text,
                             const std::string &key_path,
                             const std::string &value_yaml);

  /**
   * The scalar text at `key_path` ("a.b[2].c") of `yaml_text`, or nullopt when the path does not
   * exist or ends at a null.
   * @throws std::invalid_argument for a malformed key path or one ending at a section.
   */
  std::optional<std::string> get_yaml_value(const std::string &yaml_text,
                                            const std::string &key_path);

} // namespace kimp::app
