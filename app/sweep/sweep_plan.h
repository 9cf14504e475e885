// Sweep files of `kimp sweep`: a base scene, parameters varied by scene key path (lists
// or inclusive ranges, Cartesian product or zipped) and companion runs; each case (one scene text
// with a stable id: enumeration index + hash of the parameter values) is made on demand, so a
// plan keeps only its parameters, whatever its number of cases.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iterator>
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
   * An input iterator over the positions 0, 1, ... of a `Container` whose `operator[]` makes
   * its `Value` on demand (a value of a range, a case of a plan): nothing is expanded.
   */
  template <class Container, class Value>
  class IndexIterator
  {
  public:
    using iterator_category = std::input_iterator_tag;
    using value_type        = Value;
    using difference_type   = std::ptrdiff_t;
    using pointer           = void;
    using reference         = Value;

    IndexIterator(const Container *container, std::size_t index)
      : container_(container)
      , index_(index)
    {
    }
    Value          operator*() const { return (*container_)[index_]; }
    IndexIterator &operator++()
    {
      ++index_;
      return *this;
    }
    bool operator==(const IndexIterator &other) const { return index_ == other.index_; }
    bool operator!=(const IndexIterator &other) const { return index_ != other.index_; }

  private:
    const Container *container_ = nullptr;
    std::size_t      index_     = 0;
  };

  /**
   * The values of one parameter, in order: a list as written in the sweep file, or an inclusive
   * range {from, to, step} kept as its first value, step and count, each value formatted only
   * when asked for (a range of 10 M values takes a few bytes, not 10 M strings).
   */
  class SweepValues
  {
  public:
    SweepValues() = default;
    /// The listed values (scalar text, or the labels of map values).
    explicit SweepValues(std::vector<std::string> list)
      : list_(std::move(list))
    {
    }

    /**
     * The range from..to in steps of `step` (inclusive, robust to round-off: 10-45 cm step 0.5 cm
     * gives 71 values), each value formatted in the unit of `from` ("10.5 cm") or as a plain
     * number. Nothing is expanded.
     * @throws SweepError (named by `where`) for mismatched units, step <= 0, to < from, more than
     *         10 M values or a step below the resolution of `from`.
     */
    static SweepValues range(const std::string &from,
                             const std::string &to,
                             const std::string &step,
                             const std::string &where);

    std::size_t size() const { return is_range() ? range_count_ : list_.size(); }
    bool        empty() const { return size() == 0; }
    bool        is_range() const { return range_count_ > 0; }
    /// Value `i` (< size()) as text.
    std::string operator[](std::size_t i) const;
    /// Append a value to a list (not to a range).
    void push_back(std::string value);
    /// Every value as text (expands a range: for the results files, not for planning).
    std::vector<std::string> to_vector() const;

    /// Iterates the values by index; dereferencing formats the value.
    using const_iterator = IndexIterator<SweepValues, std::string>;
    const_iterator begin() const { return {this, 0}; }
    const_iterator end() const { return {this, size()}; }

  private:
    std::vector<std::string> list_;
    double                   range_from_  = 0.0; ///< SI
    double                   range_step_  = 0.0; ///< SI
    std::size_t              range_count_ = 0;   ///< > 0 for a range
    std::string              range_unit_;        ///< the unit of `from`, "" for plain numbers
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
    SweepValues              values;    ///< scalar text, or the label of a map value
    /// Per map value ({walls.left.gap: 10 cm, walls.right.gap: 20 cm, label: asym}) the
    /// (key path, YAML scalar) pairs it sets; empty for a parameter of scalar values (see
    /// settings()).
    std::vector<std::vector<std::pair<std::string, std::string>>> map_settings;
    int line = 0; ///< line of the key in the sweep file (1-based)

    /// The (key path, YAML scalar) pairs that value `v` sets: a scalar value sets every key path,
    /// a map value its own keys.
    std::vector<std::pair<std::string, std::string>> settings(std::size_t v) const;
    /// Whether some value of the parameter sets `key_path`.
    bool sets(const std::string &key_path) const;
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
   *                                # impact_parameters, adjacent_buildings, bumpers or
   *                                # directionality (scenes in plan: peaks against plan.angle)
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

  class SweepPlan;

  /**
   * The cases of a SweepPlan as a sequence that is never stored: size() and each case made on
   * demand (SweepPlan::case_at()), so that a plan of millions of cases takes the memory of its
   * parameters only.
   */
  class SweepCases
  {
  public:
    explicit SweepCases(const SweepPlan &plan)
      : plan_(&plan)
    {
    }
    std::size_t size() const;
    bool        empty() const { return size() == 0; }
    /// Case `index` with its scene text (SweepPlan::case_at()).
    SweepCase operator[](std::size_t index) const;

    /// Iterates the cases in enumeration order; dereferencing makes the case.
    using const_iterator = IndexIterator<SweepCases, SweepCase>;
    const_iterator begin() const { return {this, 0}; }
    const_iterator end() const { return {this, size()}; }

  private:
    const SweepPlan *plan_;
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

    /// Every case in enumeration order: each combination, followed by its companions. Made on
    /// demand, never stored (SweepCases).
    SweepCases cases() const { return SweepCases(*this); }
    /// The number of cases, companions included.
    std::size_t n_cases() const { return n_combinations_ * (1 + companions_.size()); }
    /**
     * Case `index` (< n_cases()) with its scene text: the base scene parsed again and the case's
     * values set (safe to call from several threads at once).
     * @throws SweepError at the sweep file's line when a key path cannot be followed.
     */
    SweepCase case_at(std::size_t index) const;
    /// Case `index` without its scene text (index, id, companion, values): cheap, no YAML.
    SweepCase case_info(std::size_t index) const;

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
    /// Calls `visit` with each variant in turn (one at a time: a range is not expanded).
    void for_each_variant(const std::function<void(const Variant &)> &visit) const;
    /// `check` of the variant's scene; its error becomes "FILE:LINE: key: <error>".
    void check_variant(const Variant &variant, const SceneChecker &check) const;
    /// Counts the cases (a zip of lists of unequal length, or too many combinations, is an error
    /// here, before anything is expanded), calls `check_count` and makes the first case as a
    /// check of the key paths.
    void count_cases(const CaseCountCheck &check_count);
    /// The choice of value of each parameter in combination `c`.
    std::vector<std::size_t> choices(std::size_t c) const;
    /// The case `index` without its scene text, and the choices of its combination.
    SweepCase case_header(std::size_t index, std::vector<std::size_t> &choice) const;

    std::string                    file_name_;
    std::string                    text_;
    std::string                    base_scene_text_;
    std::string                    base_scene_name_;
    std::string                    engine_      = "lumped";
    SweepCombination               combination_ = SweepCombination::product;
    std::vector<SweepParameter>    parameters_;
    std::vector<SweepCompanion>    companions_;
    std::optional<SweepReportSpec> report_;
    std::size_t                    n_combinations_ = 0;
  };

  inline std::size_t SweepCases::size() const
  {
    return plan_->n_cases();
  }

  inline SweepCase SweepCases::operator[](std::size_t index) const
  {
    return plan_->case_at(index);
  }

  /**
   * The values of SweepValues::range(from, to, step, where), expanded.
   * @throws SweepError as SweepValues::range().
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
