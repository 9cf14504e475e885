// What every scene Io shares: the error type, the admissible range of a quantity (io::Range), the
// failures of validate() (ValidationContext) and the file, line and failures of one scene file
// (SceneSource). See scene_io.h for the Io verbs and the loaders.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
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
  /// names file, line, key path, the bad value and what was expected; several errors stand one per
  /// line, in the order of their lines in the file.
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
   *   io.quantity("scale", s.scale, "", "factor (negative flips it)", Range::nonzero());
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
    /// != 0: any finite value but zero (a factor whose sign matters).
    static Range nonzero()
    {
      Range r;
      r.excludes_zero_ = true;
      return r;
    }

    /**
     * [`min`, `max`]: the values a real moat wall, building or record can have, with `what` in
     * the message ("must be in [1 cm, 10 m] (implausible outside for a wall thickness)"). For
     * geometry and material keys, so that a slip of the unit ("5 km") is refused, not meshed.
     */
    static Range plausible(double min, double max, const std::string &what)
    {
      return at_least(min).and_at_most(max).because("outside it implausible for " + what);
    }

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

    bool bounded() const { return min_ || max_ || excludes_zero_; }
    bool contains(double value) const
    {
      if (!bounded())
        return true;
      if (min_ && !(min_open_ ? value > *min_ : value >= *min_))
        return false;
      if (max_ && !(max_open_ ? value < *max_ : value <= *max_))
        return false;
      if (excludes_zero_ && value == 0.0)
        return false;
      return value == value; // NaN is outside every range
    }

    const std::optional<double> &min() const { return min_; }
    const std::optional<double> &max() const { return max_; }
    bool                         min_open() const { return min_open_; }
    bool                         max_open() const { return max_open_; }
    bool                         excludes_zero() const { return excludes_zero_; }
    const std::string           &note() const { return note_; }

    /// "> 0", ">= 1", "in (0, 1]", "in [0 %, 100 %)", "!= 0" with bounds in `unit` ("" if
    /// unbounded).
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
    bool                  min_open_      = false;
    bool                  max_open_      = false;
    bool                  excludes_zero_ = false;
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

    /**
     * Throws SceneError listing every failure as "FILE:LINE: key = value: expectation", one per
     * line, sorted by line. A key whose range the reader refused is reported once, with its range:
     * later failures of validate() at the same key follow from the same value.
     */
    void throw_if_failed(const ValidationContext &context) const;

    /// Range failures found while reading (full key paths); validate() appends to a copy.
    ValidationContext       &read_failures() { return read_failures_; }
    const ValidationContext &read_failures() const { return read_failures_; }

    /// Collect an unknown-key error at `line`; they are all thrown together, sorted by line,
    /// when the root map finishes.
    void add_unknown_key(int line, std::string message)
    {
      unknown_keys_.emplace_back(line, std::move(message));
    }
    /// Throws SceneError with every unknown-key error, one per line in file order (if any).
    void throw_if_unknown_keys() const;

  private:
    std::vector<std::pair<int, std::string>> unknown_keys_;
    ValidationContext                        read_failures_;
    std::string                              file_name_;
    std::map<std::string, int>               lines_;
  };

  namespace detail
  {
    /// `items` joined by `separator`.
    std::string join(const std::vector<std::string> &items, std::string_view separator);
    /// "integer in [1, 100]", "integer >= 0", "integer": bounds at or beyond the range of int are
    /// type limits, not scene rules, and are not printed.
    std::string integer_range_text(long long min, long long max);
    /// Reads the whole file; SceneError naming the file if it cannot.
    std::string read_text_file(const std::filesystem::path &file);
  } // namespace detail
} // namespace kimp::io
