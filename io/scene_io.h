// Scene files: YAML -> plain struct with SI members -> validate() -> use (docs/architecture.md
// "Scenes and errors"). One `template <class Io> void visit(Io &, Scene &)` per struct serves
// reading (SceneReader), the annotated default listing (DefaultsPrinter) and the resolved JSON dump
// (JsonWriter).
#pragma once

#include <algorithm>
#include <climits>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace kimp::io
{
  /// Case-insensitive Levenshtein distance of two names, for "did you mean" hints.
  std::size_t edit_distance(std::string_view a, std::string_view b);

  /**
   * Line (1-based) of `key_path` ("ground_motion.record", "records[1].record") in the YAML
   * `yaml_text`, else of its nearest written ancestor, else 0 (also for unreadable text).
   */
  int key_line(const std::string &yaml_text, const std::string &key_path);

  /**
   * A path written in a scene file, resolved against the scene file's `directory`: absolute paths,
   * "" and paths of a scene without a directory (text, or a file in the working directory) stay as
   * they are; a relative path becomes `directory`/path (lexically normalised).
   */
  std::string resolve_scene_path(const std::string &path, const std::filesystem::path &directory);

  /// Any error in a scene file: YAML syntax, unit, unknown key, type or validation. The message
  /// names file, line, key path, the bad value and what was expected.
  class SceneError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * Admissible interval of a quantity, given with its declaration so that the reader enforces it,
   * the default listing and the schema print it, and validate() keeps only rules linking several
   * keys. Bounds are SI. A value outside (or NaN) is reported as
   * "FILE:LINE: key = value: must be > 0" like a validate() failure.
   * @code
   *   io.quantity("K1", s.K1, "MN/m", "initial stiffness", Range::positive());
   *   io.quantity("cor", s.cor, "", "restitution", Range::greater(0).and_at_most(1)); // (0, 1]
   * @endcode
   */
  class Range
  {
  public:
    /// No bound: every finite value.
    Range() = default;

    static Range greater(double bound) { return Range().lower(bound, true); }
    static Range at_least(double bound) { return Range().lower(bound, false); }
    static Range less(double bound) { return Range().upper(bound, true); }
    static Range at_most(double bound) { return Range().upper(bound, false); }
    /// > 0
    static Range positive() { return greater(0.0); }
    /// >= 0
    static Range non_negative() { return at_least(0.0); }

    /// This range with an upper bound: < `bound` (and_less) or <= `bound` (and_at_most).
    Range and_less(double bound) const { return upper(bound, true); }
    Range and_at_most(double bound) const { return upper(bound, false); }
    /// This range with a reason appended to the message: "must be > 0 (toward the wall)".
    Range because(std::string note) const
    {
      Range r = *this;
      r.note_ = std::move(note);
      return r;
    }

    bool bounded() const { return min_ || max_; }
    bool contains(double value) const
    {
      if (!bounded())
        return true;
      if (min_ && !(min_open_ ? value > *min_ : value >= *min_))
        return false;
      if (max_ && !(max_open_ ? value < *max_ : value <= *max_))
        return false;
      return value == value; // NaN is outside every range
    }

    const std::optional<double> &min() const { return min_; }
    const std::optional<double> &max() const { return max_; }
    bool                         min_open() const { return min_open_; }
    bool                         max_open() const { return max_open_; }
    const std::string           &note() const { return note_; }

    /// "> 0", ">= 1", "in (0, 1]", "in [0 %, 100 %)" with bounds in `unit` ("" if unbounded).
    std::string text(std::string_view unit) const;
    /// "must be " + text(unit), plus " (note)" if given: the validation message.
    std::string expectation(std::string_view unit) const;

  private:
    Range lower(double bound, bool open) const
    {
      Range r     = *this;
      r.min_      = bound;
      r.min_open_ = open;
      return r;
    }
    Range upper(double bound, bool open) const
    {
      Range r     = *this;
      r.max_      = bound;
      r.max_open_ = open;
      return r;
    }

    std::optional<double> min_;
    std::optional<double> max_;
    bool                  min_open_ = false;
    bool                  max_open_ = false;
    std::string           note_;
  };

  /**
   * Collects violated rules of a scene's `validate()`. Key paths are written as in the file,
   * e.g. "isolator.K2" or "cases[1].gap"; the value as the user would write it
   * (format_quantity(value, "MN/m")). A validator of a nested struct can use keys relative to it
   * inside a `section()` scope:
   * @code
   *   const auto scope = ctx.section("isolator"); // or "cases[2]"
   *   validate(scene.isolator, ctx);               // its ctx.fail("K2", ...) reports isolator.K2
   * @endcode
   */
  class ValidationContext
  {
  public:
    struct Failure
    {
      std::string key_path;
      std::string value_text;
      std::string expectation;
    };

    /// Record that `key_path = value_text` violates `expectation` (e.g. "must be < K1").
    void fail(std::string key_path, std::string value_text, std::string expectation);
    /// fail() unless `condition`; returns `condition`.
    bool
    check(bool condition, std::string key_path, std::string value_text, std::string expectation);

    const std::vector<Failure> &failures() const { return failures_; }

    /// Directory of the scene file being validated ("" for a scene given as text): relative
    /// paths in the scene (impact.k_table, a record file) are relative to it.
    const std::filesystem::path &directory() const { return directory_; }
    void set_directory(std::filesystem::path directory) { directory_ = std::move(directory); }
    /// resolve_scene_path() of `path` against directory().
    std::string resolve_path(const std::string &path) const
    {
      return resolve_scene_path(path, directory_);
    }

    /// Prefixes key paths with "<key>." until destroyed (scopes nest).
    class Section
    {
    public:
      Section(const Section &) = delete;
      ~Section() { context_->prefix_.resize(previous_size_); }

    private:
      friend class ValidationContext;
      Section(ValidationContext &context, std::string_view key)
        : context_(&context)
        , previous_size_(context.prefix_.size())
      {
        context.prefix_ += std::string(key) + ".";
      }
      ValidationContext *context_;
      std::size_t        previous_size_;
    };

    /// Key paths of fail()/check() are relative to `key` while the returned scope lives.
    [[nodiscard]] Section section(std::string_view key) { return Section(*this, key); }

  private:
    std::vector<Failure>  failures_;
    std::string           prefix_;
    std::filesystem::path directory_;
  };

  /// File name and the line of every key path present in a scene file (1-based).
  class SceneSource
  {
  public:
    explicit SceneSource(std::string file_name);

    const std::string &file_name() const { return file_name_; }
    void               record(const std::string &key_path, int line);
    /// True if `key_path` was written in the file (false: the default was kept).
    bool present(const std::string &key_path) const;
    /// Line of `key_path`, else of its nearest written ancestor, else 0.
    int line_of(const std::string &key_path) const;
    /// "FILE:LINE" (or "FILE" when no line is known) for `key_path`.
    std::string location(const std::string &key_path) const;

    /// Throws SceneError listing every failure as "FILE:LINE: key = value: expectation".
    void throw_if_failed(const ValidationContext &context) const;

    /// Range failures found while reading (full key paths); validate() appends to a copy.
    ValidationContext       &read_failures() { return read_failures_; }
    const ValidationContext &read_failures() const { return read_failures_; }

    /// Collect an unknown-key error; they are all thrown together when the root map finishes.
    void add_unknown_key(std::string message) { unknown_keys_.push_back(std::move(message)); }
    const std::vector<std::string> &unknown_keys() const { return unknown_keys_; }

  private:
    std::vector<std::string>   unknown_keys_;
    ValidationContext          read_failures_;
    std::string                file_name_;
    std::map<std::string, int> lines_;
  };

  namespace detail
  {
    /// One value of a map_of(): a std::string is kept as YAML text (raw()), any other T is a
    /// section visited through its visit().
    template <class Io, class T>
    void visit_map_value(Io &io, const std::string &name, T &value, std::string_view doc)
    {
      if constexpr (std::is_same_v<T, std::string>)
        io.raw(name, value, doc);
      else
        io.section(name, value, doc);
    }
  } // namespace detail

  /// Verbs shared by every Io: integer types and enum/string choices map onto the
  /// non-template `integer_value` and `choice_index` of the Io.
  template <class Derived>
  class IoVerbs
  {
  public:
    /// Integer `key` in [min, max] and in the range of Int (so an unsigned key is >= 0).
    template <class Int>
    std::enable_if_t<std::is_integral_v<Int> && !std::is_same_v<Int, bool>>
    integer(std::string_view key,
            Int             &value,
            std::string_view doc,
            long long        min = LLONG_MIN,
            long long        max = LLONG_MAX)
    {
      min = std::max<long long>(min, static_cast<long long>(std::numeric_limits<Int>::lowest()));
      if constexpr (std::is_signed_v<Int> || sizeof(Int) < sizeof(long long))
        max = std::min<long long>(max, static_cast<long long>(std::numeric_limits<Int>::max()));
      long long v = static_cast<long long>(value);
      self().integer_value(key, v, doc, min, max);
      value = static_cast<Int>(v);
    }

    /// One of `options`.
    void choice(std::string_view                key,
                std::string                    &value,
                const std::vector<std::string> &options,
                std::string_view                doc)
    {
      std::size_t index = index_of(options, [&](const std::string &o) { return o == value; });
      self().choice_index(key, index, options, doc);
      value = options.at(index);
    }

    /// An enum class through its string table, e.g. {{"linear", Kind::linear}, ...}.
    template <class E>
    std::enable_if_t<std::is_enum_v<E>> choice(std::string_view                              key,
                                               E                                            &value,
                                               const std::vector<std::pair<std::string, E>> &table,
                                               std::string_view                              doc)
    {
      std::vector<std::string> names;
      for (const auto &entry : table)
        names.push_back(entry.first);
      std::size_t index = index_of(table, [&](const auto &entry) { return entry.second == value; });
      self().choice_index(key, index, names, doc);
      value = table.at(index).second;
    }

  private:
    Derived &self() { return static_cast<Derived &>(*this); }

    template <class Container, class Predicate>
    static std::size_t index_of(const Container &container, Predicate predicate)
    {
      for (std::size_t i = 0; i < container.size(); ++i)
        if (predicate(container[i]))
          return i;
      throw std::logic_error("scene default is not one of its own choices");
    }
  };

  /**
   * Io that reads one YAML map into a struct. Keys missing from the file keep the struct's
   * defaults; every key present is recorded with its line in the SceneSource; finish() rejects
   * keys that no verb asked for. Errors throw SceneError.
   */
  class SceneReader : public IoVerbs<SceneReader>
  {
  public:
    /// Reader of the document root of `text` (an empty document reads as an empty map).
    static SceneReader root(const std::string &text, SceneSource &source);

    SceneReader(SceneReader &&) noexcept;
    SceneReader &operator=(SceneReader &&) noexcept;
    ~SceneReader();

    /// Quantity with a unit, stored in SI; `unit` is the display unit (e.g. "MN/m"). A value
    /// written in the file outside `range` is recorded as a failure in the SceneSource (reported
    /// with validate()'s); a default outside it is not checked.
    void quantity(std::string_view key,
                  double          &value,
                  std::string_view unit,
                  std::string_view doc,
                  const Range     &range = {});
    /// Optional quantity: absent keeps the default, `null` clears it.
    void quantity(std::string_view       key,
                  std::optional<double> &value,
                  std::string_view       unit,
                  std::string_view       doc,
                  const Range           &range = {});
    /// List of quantities; `range` applies to every item (failures at "key[i]").
    void quantity_list(std::string_view     key,
                       std::vector<double> &values,
                       std::string_view     unit,
                       std::string_view     doc,
                       const Range         &range = {});
    void flag(std::string_view key, bool &value, std::string_view doc);
    void text(std::string_view key, std::string &value, std::string_view doc);

    template <class T>
    void section(std::string_view key, T &value, std::string_view /*doc*/)
    {
      if (std::optional<SceneReader> sub = open_section(key, false))
      {
        visit(*sub, value);
        sub->finish();
      }
    }

    /// Optional section: absent keeps the default, `null` clears it, a map fills a default T.
    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view /*doc*/)
    {
      if (!has_key(key))
        return;
      std::optional<SceneReader> sub = open_section(key, true);
      if (!sub)
      {
        value.reset();
        return;
      }
      value.emplace();
      visit(*sub, *value);
      sub->finish();
    }

    /// List of sections (`- key: value` items), replacing the default list when present.
    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view /*doc*/)
    {
      const std::optional<std::size_t> n = open_list(key);
      if (!n)
        return;
      values.clear();
      for (std::size_t i = 0; i < *n; ++i)
      {
        SceneReader item = list_item(key, i);
        T           value;
        visit(item, value);
        item.finish();
        values.push_back(std::move(value));
      }
    }

    /**
     * Any YAML value (scalar, list or map) kept as one line of flow-style YAML text, for a caller
     * that interprets it itself (e.g. a sweep's list of values or {from, to, step}); `null` gives
     * "~". The lines of its items are recorded in the SceneSource as "key[i]" and "key.sub".
     */
    void raw(std::string_view key, std::string &yaml_text, std::string_view doc);

    /**
     * Map whose keys the file chooses (e.g. scene key paths), in file order, replacing the default
     * entries when present. A std::string value is read with raw(), any other T as a section.
     */
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      std::optional<SceneReader> sub = open_map(key);
      if (!sub)
        return;
      entries.clear();
      for (const std::string &name : sub->keys())
      {
        T value;
        detail::visit_map_value(*sub, name, value, doc);
        entries.emplace_back(name, std::move(value));
      }
      sub->finish();
    }

    /// Rejects every key of this map that no verb asked for (thrown, with those of all nested
    /// maps, when the root reader finishes).
    void finish();

    void integer_value(std::string_view key,
                       long long       &value,
                       std::string_view doc,
                       long long        min,
                       long long        max);
    void choice_index(std::string_view                key,
                      std::size_t                    &index,
                      const std::vector<std::string> &options,
                      std::string_view                doc);

  private:
    struct State;
    explicit SceneReader(std::unique_ptr<State> state);

    bool                       has_key(std::string_view key) const;
    std::optional<SceneReader> open_section(std::string_view key, bool null_means_absent);
    std::optional<std::size_t> open_list(std::string_view key);
    SceneReader                list_item(std::string_view key, std::size_t index);
    std::optional<SceneReader> open_map(std::string_view key);
    std::vector<std::string>   keys() const;

    std::unique_ptr<State> state_;
  };

  /**
   * Io that writes an annotated YAML scene of the current values (the defaults when given a
   * default-constructed struct): every key, its value in the display unit and a comment with
   * meaning, unit and admissible range. Reading the output back gives the same values.
   */
  class DefaultsPrinter : public IoVerbs<DefaultsPrinter>
  {
  public:
    explicit DefaultsPrinter(std::ostream &out);

    void quantity(std::string_view key,
                  double          &value,
                  std::string_view unit,
                  std::string_view doc,
                  const Range     &range = {});
    void quantity(std::string_view       key,
                  std::optional<double> &value,
                  std::string_view       unit,
                  std::string_view       doc,
                  const Range           &range = {});
    void quantity_list(std::string_view     key,
                       std::vector<double> &values,
                       std::string_view     unit,
                       std::string_view     doc,
                       const Range         &range = {});
    void flag(std::string_view key, bool &value, std::string_view doc);
    void text(std::string_view key, std::string &value, std::string_view doc);

    template <class T>
    void section(std::string_view key, T &value, std::string_view doc)
    {
      line(key, "", doc);
      DefaultsPrinter sub = child(lead_ + "  ", "");
      visit(sub, value);
    }

    /// An absent optional section is listed commented out, with the defaults of T.
    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view doc)
    {
      if (value)
      {
        section(key, *value, std::string(doc) + " (optional)");
        return;
      }
      line(key, "", std::string(doc) + " (optional; absent by default, example below)", "# ");
      DefaultsPrinter sub = child(lead_ + "#   ", "");
      T               example;
      visit(sub, example);
    }

    /// A list prints its default items; an empty list prints `[]` and one commented example item.
    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view doc)
    {
      if (values.empty())
      {
        line(key, "[]", std::string(doc) + " (list; example item below)");
        DefaultsPrinter sub = child(lead_ + "#     ", lead_ + "#   - ");
        T               example;
        visit(sub, example);
        return;
      }
      line(key, "", std::string(doc) + " (list)");
      for (T &item : values)
      {
        DefaultsPrinter sub = child(lead_ + "    ", lead_ + "  - ");
        visit(sub, item);
      }
    }

    /// The YAML text as written (flow style), `null` when empty; no comment when `doc` is empty.
    void raw(std::string_view key, std::string &yaml_text, std::string_view doc);

    /// Every entry under `key` (`{}` when there is none).
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      if (entries.empty())
      {
        line(key, "{}", std::string(doc) + " (map)");
        return;
      }
      line(key, "", std::string(doc) + " (map)");
      DefaultsPrinter sub = child(lead_ + "  ", "");
      for (auto &[name, value] : entries)
        detail::visit_map_value(sub, name, value, ""); // the map's comment says what they are
    }

    void integer_value(std::string_view key,
                       long long       &value,
                       std::string_view doc,
                       long long        min,
                       long long        max);
    void choice_index(std::string_view                key,
                      std::size_t                    &index,
                      const std::vector<std::string> &options,
                      std::string_view                doc);

  private:
    DefaultsPrinter child(std::string lead, std::string first_lead) const;
    void            line(std::string_view key,
                         std::string_view value,
                         std::string_view comment,
                         std::string_view extra_lead = "");

    std::ostream *out_;
    std::string   lead_;       ///< text before every key of this map (indentation, "# ")
    std::string   first_lead_; ///< lead of the first key of a list item ("  - "), then lead_
  };

  /// Io that builds a JSON object of the current values in SI (quantities as plain numbers).
  class JsonWriter : public IoVerbs<JsonWriter>
  {
  public:
    JsonWriter();
    JsonWriter(JsonWriter &&) noexcept;
    ~JsonWriter();

    /// The JSON text of everything written so far.
    std::string dump(int indent = 2) const;

    void quantity(std::string_view key,
                  double          &value,
                  std::string_view unit,
                  std::string_view doc,
                  const Range     &range = {});
    void quantity(std::string_view       key,
                  std::optional<double> &value,
                  std::string_view       unit,
                  std::string_view       doc,
                  const Range           &range = {});
    void quantity_list(std::string_view     key,
                       std::vector<double> &values,
                       std::string_view     unit,
                       std::string_view     doc,
                       const Range         &range = {});
    void flag(std::string_view key, bool &value, std::string_view doc);
    void text(std::string_view key, std::string &value, std::string_view doc);

    template <class T>
    void section(std::string_view key, T &value, std::string_view /*doc*/)
    {
      JsonWriter sub = object(key);
      visit(sub, value);
    }

    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view doc)
    {
      if (value)
        section(key, *value, doc);
      else
        null(key);
    }

    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view /*doc*/)
    {
      empty_array(key);
      for (T &item : values)
      {
        JsonWriter sub = array_item(key);
        visit(sub, item);
      }
    }

    /// The YAML value as JSON (scalars as strings).
    void raw(std::string_view key, std::string &yaml_text, std::string_view doc);

    /// An object of the entries, in order.
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      JsonWriter sub = object(key);
      for (auto &[name, value] : entries)
        detail::visit_map_value(sub, name, value, doc);
    }

    void integer_value(std::string_view key,
                       long long       &value,
                       std::string_view doc,
                       long long        min,
                       long long        max);
    void choice_index(std::string_view                key,
                      std::size_t                    &index,
                      const std::vector<std::string> &options,
                      std::string_view                doc);

  private:
    JsonWriter(std::shared_ptr<nlohmann::ordered_json> root, nlohmann::ordered_json *node);

    JsonWriter object(std::string_view key);
    void       null(std::string_view key);
    void       empty_array(std::string_view key);
    JsonWriter array_item(std::string_view key);

    std::shared_ptr<nlohmann::ordered_json> root_; ///< owns the document
    nlohmann::ordered_json                 *node_; ///< the object this writer fills
  };

  template <class T>
  std::string to_json_text(const T &value, int indent = 2);

  /**
   * Io that describes the keys a visit() walks, as JSON for form generators: an array of
   * {key, path, type, unit, default, range, doc} entries in file order. Types: "quantity" (default
   * as the file would write it, e.g. "15 cm", and `default_si`), "quantity_list", "optional
   * quantity", "integer" (range {min, max}), "flag", "text", "choice" (with `options`), "section"
   * and "optional section" (with `keys`), "list" (with `item`: the keys of one item, and
   * `default`: the default items as resolved JSON). A quantity's range is
   * {min, min_open, max, max_open} in SI plus `text` in the display unit.
   */
  class SchemaWriter : public IoVerbs<SchemaWriter>
  {
  public:
    SchemaWriter();
    SchemaWriter(SchemaWriter &&) noexcept;
    ~SchemaWriter();

    /// The JSON text of the schema: {"keys": [...]}.
    std::string dump(int indent = 2) const;

    void quantity(std::string_view key,
                  double          &value,
                  std::string_view unit,
                  std::string_view doc,
                  const Range     &range = {});
    void quantity(std::string_view       key,
                  std::optional<double> &value,
                  std::string_view       unit,
                  std::string_view       doc,
                  const Range           &range = {});
    void quantity_list(std::string_view     key,
                       std::vector<double> &values,
                       std::string_view     unit,
                       std::string_view     doc,
                       const Range         &range = {});
    void flag(std::string_view key, bool &value, std::string_view doc);
    void text(std::string_view key, std::string &value, std::string_view doc);

    template <class T>
    void section(std::string_view key, T &value, std::string_view doc)
    {
      SchemaWriter sub = nested(key, "section", doc, "keys", "");
      visit(sub, value);
    }

    /// Its `default` is the resolved JSON of the default value, or null when absent.
    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view doc)
    {
      SchemaWriter sub =
        nested(key, "optional section", doc, "keys", value ? to_json_text(*value, -1) : "null");
      T example = value ? *value : T();
      visit(sub, example);
    }

    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view doc)
    {
      std::string items;
      for (const T &item : values)
        items += (items.empty() ? "" : ",") + to_json_text(item, -1);
      SchemaWriter sub = nested(key, "list", doc, "item", "[" + items + "]");
      T            example;
      visit(sub, example);
    }

    /// Type "yaml", its default the YAML text.
    void raw(std::string_view key, std::string &yaml_text, std::string_view doc);

    /// Type "map" with `value`: the entry of one value, keyed "<name>".
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      std::string items;
      for (const auto &[name, value] : entries)
        items += (items.empty() ? "" : ",") + json_string(name) + ":" + map_value_json(value);
      SchemaWriter sub = nested(key, "map", doc, "value", "{" + items + "}");
      T            example;
      detail::visit_map_value(sub, "<name>", example, doc);
    }

    void integer_value(std::string_view key,
                       long long       &value,
                       std::string_view doc,
                       long long        min,
                       long long        max);
    void choice_index(std::string_view                key,
                      std::size_t                    &index,
                      const std::vector<std::string> &options,
                      std::string_view                doc);

  private:
    /// `text` as a JSON string literal.
    static std::string json_string(const std::string &text);
    /// JSON of a raw YAML text (scalars as strings).
    static std::string yaml_json(const std::string &yaml_text);
    template <class T>
    static std::string map_value_json(const T &value)
    {
      if constexpr (std::is_same_v<T, std::string>)
        return yaml_json(value);
      else
        return to_json_text(value, -1);
    }

    struct State;
    explicit SchemaWriter(std::unique_ptr<State> state);

    /// Appends an entry of `type` (with `default_json` as its default unless empty) and returns a
    /// writer of its `member` array.
    SchemaWriter nested(std::string_view   key,
                        std::string_view   type,
                        std::string_view   doc,
                        std::string_view   member,
                        const std::string &default_json);

    std::unique_ptr<State> state_;
  };

  namespace detail
  {
    template <class T, class = void>
    struct HasMemberValidate : std::false_type
    {
    };
    template <class T>
    struct HasMemberValidate<T,
                             std::void_t<decltype(std::declval<const T &>().validate(
                               std::declval<ValidationContext &>()))>> : std::true_type
    {
    };
    template <class T, class = void>
    struct HasFreeValidate : std::false_type
    {
    };
    template <class T>
    struct HasFreeValidate<T,
                           std::void_t<decltype(validate(std::declval<const T &>(),
                                                         std::declval<ValidationContext &>()))>>
      : std::true_type
    {
    };

    template <class T, class = void>
    struct HasResolvePaths : std::false_type
    {
    };
    template <class T>
    struct HasResolvePaths<
      T,
      std::void_t<decltype(resolve_paths(std::declval<T &>(),
                                         std::declval<const std::filesystem::path &>()))>>
      : std::true_type
    {
    };

    /// Reads the whole file; SceneError naming the file if it cannot.
    std::string read_text_file(const std::filesystem::path &file);
  } // namespace detail

  /// A loaded scene with what the results file needs: the text verbatim and the resolved values.
  template <class T>
  struct LoadedScene
  {
    T           scene;
    std::string file_name;     ///< as given (used in messages)
    std::string text;          ///< the file verbatim, for /input/scene
    std::string resolved_json; ///< every value after defaults, SI, for /input/resolved
  };

  /// JSON text of `value` (SI numbers) through its visit().
  template <class T>
  std::string to_json_text(const T &value, int indent)
  {
    T          copy = value;
    JsonWriter writer;
    visit(writer, copy);
    return writer.dump(indent);
  }

  /// Annotated YAML of the default T: every key, default, unit and meaning; `title` heads it.
  template <class T>
  std::string default_scene_text(std::string_view title)
  {
    std::ostringstream out;
    out << "# " << title << "\n"
        << "# Every key with its default. Quantities are strings with units (\"2500 kN/mm\", "
           "\"15 cm\", \"5 %\");\n"
        << "# any unit of the same dimension is accepted. Keys left out keep these defaults.\n";
    T               defaults;
    DefaultsPrinter printer(out);
    visit(printer, defaults);
    return out.str();
  }

  /// JSON schema of T (see SchemaWriter): every key with type, unit, default, range and doc.
  template <class T>
  std::string schema_text()
  {
    T            defaults;
    SchemaWriter writer;
    visit(writer, defaults);
    return writer.dump(2) + "\n";
  }

  // Scene structs give every member a default initializer (docs/architecture.md "Scenes and
  // errors"), so they are default-initialized (`T scene;`): value-initialization `T{}` of such
  // aggregates trips a false -Wmaybe-uninitialized of GCC 12 at -O3.

  /**
   * Parse, visit, then validate (free `validate(const T&, ValidationContext&)` found by ADL, or a
   * member `validate(ValidationContext&) const`). `name` is used in error messages. Paths in
   * the scene are relative to `directory` (the scene file's directory): validate() sees them as
   * written (ValidationContext::directory() resolves them), then a free
   * `resolve_paths(T&, const std::filesystem::path&)`, if T has one, rewrites them resolved, so
   * that the scene returned (and its resolved JSON) works from any working directory.
   * @throws SceneError naming file, line, key path, value and expectation.
   */
  template <class T>
  LoadedScene<T>
  read_scene_text(std::string text, std::string name, const std::filesystem::path &directory = {})
  {
    SceneSource source(name);
    T           scene;
    SceneReader reader = SceneReader::root(text, source);
    visit(reader, scene);
    reader.finish();

    ValidationContext context = source.read_failures();
    context.set_directory(directory);
    if constexpr (detail::HasMemberValidate<T>::value)
      scene.validate(context);
    else if constexpr (detail::HasFreeValidate<T>::value)
      validate(static_cast<const T &>(scene), context);
    source.throw_if_failed(context);
    if constexpr (detail::HasResolvePaths<T>::value)
      resolve_paths(scene, directory);

    std::string resolved = to_json_text(scene);
    return {std::move(scene), std::move(name), std::move(text), std::move(resolved)};
  }

  /// read_scene_text() of a file.
  template <class T>
  LoadedScene<T> read_scene(const std::filesystem::path &file)
  {
    return read_scene_text<T>(detail::read_text_file(file), file.string(), file.parent_path());
  }

  /// The validated scene of `file` (see read_scene_text()).
  template <class T>
  T load_scene(const std::filesystem::path &file)
  {
    return read_scene<T>(file).scene;
  }

  /// The validated scene of `text`, named `name` in messages (see read_scene_text()).
  template <class T>
  T load_scene_text(std::string text, std::string name, const std::filesystem::path &directory = {})
  {
    return read_scene_text<T>(std::move(text), std::move(name), directory).scene;
  }
} // namespace kimp::io
