// Scene file reading (yaml-cpp) with key ranges, annotated defaults, resolved JSON and the key
// schema; see scene_io.h.
#include "io/scene_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <yaml-cpp/yaml.h>

#include "io/units.h"

namespace kimp::io
{
  namespace
  {
    std::string join(const std::vector<std::string> &items, std::string_view separator)
    {
      std::string text;
      for (const auto &item : items)
      {
        if (!text.empty())
          text += separator;
        text += item;
      }
      return text;
    }

  } // namespace

  std::size_t edit_distance(std::string_view a, std::string_view b)
  {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
      row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
      std::size_t diagonal = row[0];
      row[0]               = i;
      for (std::size_t j = 1; j <= b.size(); ++j)
      {
        const std::size_t above = row[j];
        const bool        same  = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                          std::tolower(static_cast<unsigned char>(b[j - 1]));
        row[j]   = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
        diagonal = above;
      }
    }
    return row[b.size()];
  }

  std::string resolve_scene_path(const std::string &path, const std::filesystem::path &directory)
  {
    if (path.empty() || directory.empty() || std::filesystem::path(path).is_absolute())
      return path;
    return (directory / path).lexically_normal().string();
  }

  int key_line(const std::string &yaml_text, const std::string &key_path)
  {
    try
    {
      YAML::Node  node = YAML::Load(yaml_text);
      int         line = 0;
      std::size_t i    = 0;
      while (i < key_path.size())
      {
        if (key_path[i] == '.')
          ++i;
        if (key_path[i] == '[')
        {
          const std::size_t close = key_path.find(']', i);
          const std::size_t index = std::stoul(key_path.substr(i + 1, close - i - 1));
          if (!node.IsSequence() || index >= node.size())
            return line;
          node.reset(node[index]);
          line = node.Mark().is_null() ? line : node.Mark().line + 1;
          i    = close + 1;
          continue;
        }
        const std::size_t end = std::min(key_path.find_first_of(".[", i), key_path.size());
        const std::string key = key_path.substr(i, end - i);
        if (!node.IsMap())
          return line;
        bool found = false;
        for (auto it = node.begin(); it != node.end() && !found; ++it)
          if (it->first.IsScalar() && it->first.Scalar() == key)
          {
            line = it->first.Mark().line + 1;
            node.reset(it->second);
            found = true;
          }
        if (!found)
          return line;
        i = end;
      }
      return line;
    }
    catch (const std::exception &)
    {
      return 0;
    }
  }

  namespace
  {

    /// The value as the user wrote it, for messages.
    std::string describe(const YAML::Node &node)
    {
      if (!node.IsDefined() || node.IsNull())
        return "(empty)";
      if (node.IsScalar())
        return "'" + node.Scalar() + "'";
      if (node.IsSequence())
        return "a list";
      return "a map";
    }

    int line_of(const YAML::Node &node)
    {
      return node.Mark().is_null() ? 0 : node.Mark().line + 1;
    }

    std::string yaml_quote(std::string_view text)
    {
      std::string quoted = "\"";
      for (const char c : text)
      {
        switch (c)
        {
          case '"':
            quoted += "\\\"";
            break;
          case '\\':
            quoted += "\\\\";
            break;
          case '\n':
            quoted += "\\n";
            break;
          case '\t':
            quoted += "\\t";
            break;
          default:
            quoted += c;
        }
      }
      return quoted + "\"";
    }

    std::string unit_comment(std::string_view unit)
    {
      return unit.empty() ? std::string("dimensionless") : std::string(unit);
    }

    /// Bounds at or beyond the range of int are type limits, not scene rules: not printed.
    std::string range_text(long long min, long long max)
    {
      if (min <= INT_MIN)
        min = LLONG_MIN;
      if (max >= INT_MAX)
        max = LLONG_MAX;
      if (min != LLONG_MIN && max != LLONG_MAX)
        return fmt::format("integer in [{}, {}]", min, max);
      if (min != LLONG_MIN)
        return fmt::format("integer >= {}", min);
      if (max != LLONG_MAX)
        return fmt::format("integer <= {}", max);
      return "integer";
    }

    /// A zero bound needs no unit ("> 0"); a percent bound keeps it ("< 100 %", "> 0 %").
    std::string bound_text(double bound, std::string_view unit)
    {
      return bound == 0.0 && unit != "%" ? std::string("0") : format_quantity(bound, unit);
    }

    /// One line of flow-style YAML for `node` (a raw() value).
    std::string flow_text(const YAML::Node &node)
    {
      YAML::Emitter out;
      out << YAML::Flow << node;
      return out.c_str();
    }

    /// Records the line of every item of `node` under `path` ("path[i]", "path.key").
    void record_item_lines(SceneSource &source, const std::string &path, const YAML::Node &node)
    {
      if (node.IsSequence())
        for (std::size_t i = 0; i < node.size(); ++i)
        {
          const std::string item_path = path + fmt::format("[{}]", i);
          if (line_of(node[i]) > 0)
            source.record(item_path, line_of(node[i]));
          record_item_lines(source, item_path, node[i]);
        }
      else if (node.IsMap())
        for (auto it = node.begin(); it != node.end(); ++it)
        {
          if (!it->first.IsScalar())
            continue;
          const std::string item_path = path + "." + it->first.Scalar();
          source.record(item_path, line_of(it->first));
          record_item_lines(source, item_path, it->second);
        }
    }

    /// JSON of a YAML value; scalars stay strings (their type is the caller's to decide).
    nlohmann::ordered_json yaml_to_json(const YAML::Node &node)
    {
      if (!node.IsDefined() || node.IsNull())
        return nullptr;
      if (node.IsScalar())
        return node.Scalar();
      nlohmann::ordered_json json =
        node.IsSequence() ? nlohmann::ordered_json::array() : nlohmann::ordered_json::object();
      for (auto it = node.begin(); it != node.end(); ++it)
        if (node.IsSequence())
          json.push_back(yaml_to_json(*it));
        else
          json[it->first.as<std::string>()] = yaml_to_json(it->second);
      return json;
    }

    nlohmann::ordered_json yaml_text_to_json(const std::string &yaml_text)
    {
      return yaml_text.empty() ? nlohmann::ordered_json(nullptr) :
                                 yaml_to_json(YAML::Load(yaml_text));
    }

    /// Line (1-based) of the marker that starts the second document of a YAML stream: the
    /// second "---" when the text opens with one, else the first (or the node's own line).
    int second_document_line(const std::string &text, const YAML::Node &second)
    {
      std::istringstream lines(text);
      std::string        line;
      int                number = 0, markers = 0;
      bool               opens_with_marker = false, content_seen = false;
      while (std::getline(lines, line))
      {
        ++number;
        if (!line.empty() && line.back() == '\r')
          line.pop_back();
        const bool marker =
          line.rfind("---", 0) == 0 && (line.size() == 3 || line[3] == ' ' || line[3] == '\t');
        if (marker)
        {
          if (!content_seen && markers == 0)
            opens_with_marker = true;
          ++markers;
          if (markers == (opens_with_marker ? 2 : 1))
            return number;
        }
        const std::size_t first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line[first] != '#')
          content_seen = true;
      }
      return std::max(1, line_of(second));
    }

    /// Subnormal doubles (|x| < 2.2e-308, e.g. a gap of 1e-320 m) are not physical inputs and
    /// pass every "> 0" test while losing precision: they are refused with the range checks.
    bool is_normal_or_zero(double value)
    {
      return value == 0.0 || std::isnormal(value);
    }

    const char *const subnormal_expectation =
      "must be 0 or a normal number (|value| >= 2.2e-308 in SI units; a subnormal value is not "
      "a physical input)";

    /// Unit and range of a quantity's comment: "MN/m", "MN/m, > 0".
    std::string unit_range_comment(std::string_view unit, const Range &range)
    {
      return range.bounded() ? unit_comment(unit) + ", " + range.text(unit) : unit_comment(unit);
    }
  } // namespace

  // ---------------------------------------------------------------------------------------------

  std::string Range::text(std::string_view unit) const
  {
    if (min_ && max_)
      return fmt::format("in {}{}, {}{}",
                         min_open_ ? '(' : '[',
                         bound_text(*min_, unit),
                         bound_text(*max_, unit),
                         max_open_ ? ')' : ']');
    if (min_)
      return (min_open_ ? "> " : ">= ") + bound_text(*min_, unit);
    if (max_)
      return (max_open_ ? "< " : "<= ") + bound_text(*max_, unit);
    return "";
  }

  std::string Range::expectation(std::string_view unit) const
  {
    return "must be " + text(unit) + (note_.empty() ? "" : " (" + note_ + ")");
  }

  // ---------------------------------------------------------------------------------------------

  void
  ValidationContext::fail(std::string key_path, std::string value_text, std::string expectation)
  {
    failures_.push_back({prefix_ + key_path, std::move(value_text), std::move(expectation)});
  }

  bool ValidationContext::check(bool        condition,
                                std::string key_path,
                                std::string value_text,
                                std::string expectation)
  {
    if (!condition)
      fail(std::move(key_path), std::move(value_text), std::move(expectation));
    return condition;
  }

  // ---------------------------------------------------------------------------------------------

  SceneSource::SceneSource(std::string file_name)
    : file_name_(std::move(file_name))
  {
  }

  void SceneSource::record(const std::string &key_path, int line)
  {
    lines_.emplace(key_path, line);
  }

  bool SceneSource::present(const std::string &key_path) const
  {
    return lines_.count(key_path) > 0;
  }

  int SceneSource::line_of(const std::string &key_path) const
  {
    std::string path = key_path;
    while (!path.empty())
    {
      if (const auto it = lines_.find(path); it != lines_.end())
        return it->second;
      const std::size_t cut = path.find_last_of(".[");
      path.resize(cut == std::string::npos ? 0 : cut);
    }
    return 0;
  }

  std::string SceneSource::location(const std::string &key_path) const
  {
    const int line = line_of(key_path);
    return line > 0 ? fmt::format("{}:{}", file_name_, line) : file_name_;
  }

  void SceneSource::throw_if_failed(const ValidationContext &context) const
  {
    if (context.failures().empty())
      return;
    std::vector<std::string> lines;
    for (const auto &f : context.failures())
      lines.push_back(fmt::format("{}: {} = {}{}: {}",
                                  location(f.key_path),
                                  f.key_path,
                                  f.value_text,
                                  present(f.key_path) ? "" : " (default)",
                                  f.expectation));
    throw SceneError(join(lines, "\n"));
  }

  // ---------------------------------------------------------------------------------------------

  struct SceneReader::State
  {
    struct Entry
    {
      std::string key;
      YAML::Node  value;
      int         line = 0;
      bool        used = false;
    };

    SceneSource             *source = nullptr;
    std::string              path; ///< "" at the root, else "isolator", "cases[1]", ...
    int                      line = 0;
    std::vector<Entry>       entries;
    std::vector<std::string> known;
    bool                     is_root = false;

    State(SceneSource &scene_source, std::string map_path, const YAML::Node &map, int map_line)
      : source(&scene_source)
      , path(std::move(map_path))
      , line(map_line)
    {
      if (!map.IsDefined() || map.IsNull())
        return;
      for (auto it = map.begin(); it != map.end(); ++it)
      {
        const int key_line = line_of(it->first);
        if (!it->first.IsScalar())
          throw SceneError(fmt::format("{}:{}: {}: keys must be plain names, got {}",
                                       source->file_name(),
                                       key_line,
                                       path.empty() ? "top level" : path,
                                       describe(it->first)));
        const std::string key = it->first.Scalar();
        for (const auto &e : entries)
          if (e.key == key)
            throw SceneError(fmt::format("{}:{}: duplicate key '{}' (first at line {})",
                                         source->file_name(),
                                         key_line,
                                         full_path(key),
                                         e.line));
        entries.push_back({key, it->second, key_line, false});
        source->record(full_path(key), key_line);
      }
    }

    std::string full_path(std::string_view key) const
    {
      return path.empty() ? std::string(key) : path + "." + std::string(key);
    }

    Entry *find(std::string_view key)
    {
      if (std::find(known.begin(), known.end(), key) == known.end())
        known.emplace_back(key);
      for (auto &e : entries)
        if (e.key == key)
        {
          e.used = true;
          return &e;
        }
      return nullptr;
    }

    [[noreturn]] void fail(const Entry &entry, const std::string &message) const
    {
      throw SceneError(fmt::format("{}:{}: {}: {}",
                                   source->file_name(),
                                   entry.line,
                                   full_path(entry.key),
                                   message));
    }

    /// The scalar text of `entry`, or an error naming what was expected.
    const std::string &scalar(const Entry &entry, std::string_view expected) const
    {
      if (!entry.value.IsScalar())
        fail(entry,
             fmt::format("{} is not a single value: expected {}", describe(entry.value), expected));
      return entry.value.Scalar();
    }
  };

  SceneReader::SceneReader(std::unique_ptr<State> state)
    : state_(std::move(state))
  {
  }

  SceneReader::SceneReader(SceneReader &&) noexcept            = default;
  SceneReader &SceneReader::operator=(SceneReader &&) noexcept = default;
  SceneReader::~SceneReader()                                  = default;

  SceneReader SceneReader::root(const std::string &text, SceneSource &source)
  {
    YAML::Node document;
    try
    {
      // Every document is parsed so that a second one is refused rather than silently ignored.
      const std::vector<YAML::Node> documents = YAML::LoadAll(text);
      if (documents.size() > 1)
        throw SceneError(fmt::format("{}:{}: a second YAML document starts here (expected one "
                                     "scene per file; remove the '---' line and what follows, "
                                     "or split the file)",
                                     source.file_name(),
                                     second_document_line(text, documents[1])));
      if (!documents.empty())
        document = documents.front();
    }
    catch (const YAML::ParserException &error)
    {
      throw SceneError(fmt::format("{}:{}:{}: YAML syntax error: {}",
                                   source.file_name(),
                                   error.mark.line + 1,
                                   error.mark.column + 1,
                                   error.msg));
    }
    if (document.IsDefined() && !document.IsNull() && !document.IsMap())
      throw SceneError(fmt::format("{}:{}: expected a map of 'key: value' lines at the top level, "
                                   "got {}",
                                   source.file_name(),
                                   line_of(document),
                                   describe(document)));
    auto state     = std::make_unique<State>(source, "", document, 1);
    state->is_root = true;
    return SceneReader(std::move(state));
  }

  void SceneReader::quantity(std::string_view key,
                             double          &value,
                             std::string_view unit,
                             std::string_view /*doc*/,
                             const Range &range)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    const std::string expected = fmt::format("a quantity like '{}'", format_quantity(value, unit));
    try
    {
      value = parse_quantity_as(state_->scalar(*entry, expected), unit);
    }
    catch (const UnitError &error)
    {
      state_->fail(*entry, error.what());
    }
    if (!range.contains(value))
      state_->source->read_failures().fail(state_->full_path(key),
                                           format_quantity(value, unit),
                                           range.expectation(unit));
    else if (!is_normal_or_zero(value))
      state_->source->read_failures().fail(state_->full_path(key),
                                           state_->scalar(*entry, ""),
                                           subnormal_expectation);
  }

  void SceneReader::quantity(std::string_view       key,
                             std::optional<double> &value,
                             std::string_view       unit,
                             std::string_view       doc,
                             const Range           &range)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    if (entry->value.IsNull())
    {
      value.reset();
      return;
    }
    double v = value.value_or(parse_unit(unit).value);
    quantity(key, v, unit, doc, range);
    value = v;
  }

  void SceneReader::quantity_list(std::string_view     key,
                                  std::vector<double> &values,
                                  std::string_view     unit,
                                  std::string_view /*doc*/,
                                  const Range &range)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    if (entry->value.IsNull())
    {
      values.clear();
      return;
    }
    if (!entry->value.IsSequence())
      state_->fail(*entry,
                   fmt::format("{} is not a list: expected a list of quantities like "
                               "[\"{}\", ...]",
                               describe(entry->value),
                               format_quantity(parse_unit(unit).value, unit)));
    std::vector<double> parsed;
    for (std::size_t i = 0; i < entry->value.size(); ++i)
    {
      const YAML::Node  item      = entry->value[i];
      const std::string item_path = state_->full_path(key) + fmt::format("[{}]", i);
      try
      {
        if (!item.IsScalar())
          throw UnitError(fmt::format("{} is not a quantity", describe(item)));
        parsed.push_back(parse_quantity_as(item.Scalar(), unit));
      }
      catch (const UnitError &error)
      {
        throw SceneError(fmt::format("{}:{}: {}: {}",
                                     state_->source->file_name(),
                                     line_of(item) > 0 ? line_of(item) : entry->line,
                                     item_path,
                                     error.what()));
      }
    }
    for (std::size_t i = 0; i < parsed.size(); ++i)
      if (!range.contains(parsed[i]) || !is_normal_or_zero(parsed[i]))
      {
        // Items are recorded only here, so that validate()'s messages about items stay as they
        // were; the item was written, so its failure is not marked "(default)".
        const std::string item_path = state_->full_path(key) + fmt::format("[{}]", i);
        const int         item_line = line_of(entry->value[i]);
        state_->source->record(item_path, item_line > 0 ? item_line : entry->line);
        state_->source->read_failures().fail(item_path,
                                             format_quantity(parsed[i], unit),
                                             range.contains(parsed[i]) ?
                                               std::string(subnormal_expectation) :
                                               range.expectation(unit));
      }
    values = std::move(parsed);
  }

  void SceneReader::flag(std::string_view key, bool &value, std::string_view /*doc*/)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    const std::string &text   = state_->scalar(*entry, "true or false");
    bool               parsed = false;
    if (!YAML::convert<bool>::decode(entry->value, parsed))
      state_->fail(*entry, fmt::format("'{}' is not true or false", text));
    value = parsed;
  }

  void SceneReader::text(std::string_view key, std::string &value, std::string_view /*doc*/)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    if (entry->value.IsNull())
      state_->fail(*entry, "missing value: expected a text");
    value = state_->scalar(*entry, "a text");
  }

  void SceneReader::integer_value(std::string_view key,
                                  long long       &value,
                                  std::string_view /*doc*/,
                                  long long min,
                                  long long max)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    const std::string &text = state_->scalar(*entry, range_text(min, max));
    std::string_view   digits(text);
    if (!digits.empty() && digits.front() == '+')
      digits.remove_prefix(1);
    long long parsed        = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), parsed);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size())
      state_->fail(*entry,
                   fmt::format("'{}' is not an integer: expected an {}",
                               text,
                               range_text(min, max)));
    if (parsed < min || parsed > max)
      state_->fail(*entry,
                   fmt::format("{} is out of range: expected an {}", parsed, range_text(min, max)));
    value = parsed;
  }

  void SceneReader::choice_index(std::string_view                key,
                                 std::size_t                    &index,
                                 const std::vector<std::string> &options,
                                 std::string_view /*doc*/)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    const std::string  expected = "one of: " + join(options, ", ");
    const std::string &text     = state_->scalar(*entry, expected);
    const auto         it       = std::find(options.begin(), options.end(), text);
    if (it == options.end())
      state_->fail(*entry, fmt::format("'{}' is not {}", text, expected));
    index = static_cast<std::size_t>(it - options.begin());
  }

  bool SceneReader::has_key(std::string_view key) const
  {
    for (const auto &e : state_->entries)
      if (e.key == key)
        return true;
    return false;
  }

  std::optional<SceneReader> SceneReader::open_section(std::string_view key, bool null_means_absent)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return std::nullopt;
    if (entry->value.IsNull() && null_means_absent)
      return std::nullopt;
    if (!entry->value.IsNull() && !entry->value.IsMap())
      state_->fail(*entry,
                   fmt::format("{} is not a section: expected indented 'key: value' lines",
                               describe(entry->value)));
    return SceneReader(
      std::make_unique<State>(*state_->source, state_->full_path(key), entry->value, entry->line));
  }

  std::optional<std::size_t> SceneReader::open_list(std::string_view key)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return std::nullopt;
    if (entry->value.IsNull())
      return 0;
    if (!entry->value.IsSequence())
      state_->fail(*entry,
                   fmt::format("{} is not a list: expected items starting with '- '",
                               describe(entry->value)));
    return entry->value.size();
  }

  SceneReader SceneReader::list_item(std::string_view key, std::size_t index)
  {
    const State::Entry *entry = state_->find(key);
    const YAML::Node    item  = entry->value[index];
    const std::string   path  = state_->full_path(key) + fmt::format("[{}]", index);
    const int           line  = line_of(item) > 0 ? line_of(item) : entry->line;
    state_->source->record(path, line);
    if (!item.IsNull() && !item.IsMap())
      throw SceneError(fmt::format("{}:{}: {}: {} is not a section: expected 'key: value' lines",
                                   state_->source->file_name(),
                                   line,
                                   path,
                                   describe(item)));
    return SceneReader(std::make_unique<State>(*state_->source, path, item, line));
  }

  void SceneReader::raw(std::string_view key, std::string &yaml_text, std::string_view /*doc*/)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return;
    yaml_text = flow_text(entry->value);
    record_item_lines(*state_->source, state_->full_path(key), entry->value);
  }

  std::optional<SceneReader> SceneReader::open_map(std::string_view key)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr)
      return std::nullopt;
    if (!entry->value.IsNull() && !entry->value.IsMap())
      state_->fail(*entry,
                   fmt::format("{} is not a map: expected a map of 'name: value' lines",
                               describe(entry->value)));
    return SceneReader(
      std::make_unique<State>(*state_->source, state_->full_path(key), entry->value, entry->line));
  }

  std::vector<std::string> SceneReader::keys() const
  {
    std::vector<std::string> names;
    for (const auto &e : state_->entries)
      names.push_back(e.key);
    return names;
  }

  void SceneReader::finish()
  {
    std::vector<std::string> errors;
    for (const auto &e : state_->entries)
    {
      if (e.used)
        continue;
      std::string suggestion;
      std::size_t best = 3; // more than two edits away is not a typo
      for (const auto &k : state_->known)
        if (const std::size_t d = edit_distance(e.key, k); d < best)
        {
          best       = d;
          suggestion = fmt::format("; did you mean '{}'?", k);
        }
      errors.push_back(fmt::format("{}:{}: unknown key '{}'{} (known: {}){}",
                                   state_->source->file_name(),
                                   e.line,
                                   e.key,
                                   state_->path.empty() ? "" : " in " + state_->path,
                                   state_->known.empty() ? "none" : join(state_->known, ", "),
                                   suggestion));
    }
    for (auto &e : errors)
      state_->source->add_unknown_key(std::move(e));
    if (state_->is_root && !state_->source->unknown_keys().empty())
      throw SceneError(join(state_->source->unknown_keys(), "\n"));
  }

  // ---------------------------------------------------------------------------------------------

  DefaultsPrinter::DefaultsPrinter(std::ostream &out)
    : out_(&out)
  {
  }

  DefaultsPrinter DefaultsPrinter::child(std::string lead, std::string first_lead) const
  {
    DefaultsPrinter sub(*out_);
    sub.lead_       = std::move(lead);
    sub.first_lead_ = std::move(first_lead);
    return sub;
  }

  void DefaultsPrinter::line(std::string_view key,
                             std::string_view value,
                             std::string_view comment,
                             std::string_view extra_lead)
  {
    const std::string lead = first_lead_.empty() ? lead_ : first_lead_;
    first_lead_.clear();
    *out_ << lead << extra_lead << key << ':';
    if (!value.empty())
      *out_ << ' ' << value;
    *out_ << "  # " << comment << '\n';
  }

  void DefaultsPrinter::quantity(std::string_view key,
                                 double          &value,
                                 std::string_view unit,
                                 std::string_view doc,
                                 const Range     &range)
  {
    line(key,
         yaml_quote(format_quantity(value, unit)),
         fmt::format("{} [{}]", doc, unit_range_comment(unit, range)));
  }

  void DefaultsPrinter::quantity(std::string_view       key,
                                 std::optional<double> &value,
                                 std::string_view       unit,
                                 std::string_view       doc,
                                 const Range           &range)
  {
    line(key,
         value ? yaml_quote(format_quantity(*value, unit)) : std::string("null"),
         fmt::format("{} [{}] (optional: null = not set)", doc, unit_range_comment(unit, range)));
  }

  void DefaultsPrinter::quantity_list(std::string_view     key,
                                      std::vector<double> &values,
                                      std::string_view     unit,
                                      std::string_view     doc,
                                      const Range         &range)
  {
    std::vector<std::string> items;
    for (const double v : values)
      items.push_back(yaml_quote(format_quantity(v, unit)));
    line(key,
         "[" + join(items, ", ") + "]",
         fmt::format("{} [{}, list{}]",
                     doc,
                     unit_comment(unit),
                     range.bounded() ? ", each " + range.text(unit) : std::string()));
  }

  void DefaultsPrinter::flag(std::string_view key, bool &value, std::string_view doc)
  {
    line(key, value ? "true" : "false", fmt::format("{} (true or false)", doc));
  }

  void DefaultsPrinter::text(std::string_view key, std::string &value, std::string_view doc)
  {
    line(key, yaml_quote(value), doc);
  }

  void DefaultsPrinter::raw(std::string_view key, std::string &yaml_text, std::string_view doc)
  {
    const std::string value = yaml_text.empty() ? std::string("null") : yaml_text;
    if (!doc.empty())
    {
      line(key, value, doc);
      return;
    }
    *out_ << (first_lead_.empty() ? lead_ : first_lead_) << key << ": " << value << '\n';
    first_lead_.clear();
  }

  void DefaultsPrinter::integer_value(std::string_view key,
                                      long long       &value,
                                      std::string_view doc,
                                      long long        min,
                                      long long        max)
  {
    line(key, std::to_string(value), fmt::format("{} ({})", doc, range_text(min, max)));
  }

  void DefaultsPrinter::choice_index(std::string_view                key,
                                     std::size_t                    &index,
                                     const std::vector<std::string> &options,
                                     std::string_view                doc)
  {
    line(key,
         yaml_quote(options.at(index)),
         fmt::format("{} (one of: {})", doc, join(options, ", ")));
  }

  // ---------------------------------------------------------------------------------------------

  JsonWriter::JsonWriter()
    : root_(std::make_shared<nlohmann::ordered_json>(nlohmann::ordered_json::object()))
    , node_(root_.get())
  {
  }

  JsonWriter::JsonWriter(std::shared_ptr<nlohmann::ordered_json> root, nlohmann::ordered_json *node)
    : root_(std::move(root))
    , node_(node)
  {
  }

  JsonWriter::JsonWriter(JsonWriter &&) noexcept = default;
  JsonWriter::~JsonWriter()                      = default;

  std::string JsonWriter::dump(int indent) const
  {
    // Scene text may hold bytes that are not UTF-8 (a mistyped or binary file): replaced
    // (U+FFFD) rather than thrown, so a bad scene is refused by its reader, not by the JSON writer.
    return root_->dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  }

  void JsonWriter::quantity(std::string_view key,
                            double          &value,
                            std::string_view /*unit*/,
                            std::string_view /*doc*/,
                            const Range & /*range*/)
  {
    (*node_)[std::string(key)] = value;
  }

  void JsonWriter::quantity(std::string_view       key,
                            std::optional<double> &value,
                            std::string_view /*unit*/,
                            std::string_view /*doc*/,
                            const Range & /*range*/)
  {
    (*node_)[std::string(key)] =
      value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
  }

  void JsonWriter::quantity_list(std::string_view     key,
                                 std::vector<double> &values,
                                 std::string_view /*unit*/,
                                 std::string_view /*doc*/,
                                 const Range & /*range*/)
  {
    (*node_)[std::string(key)] = values;
  }

  void JsonWriter::flag(std::string_view key, bool &value, std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = value;
  }

  void JsonWriter::text(std::string_view key, std::string &value, std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = value;
  }

  void JsonWriter::raw(std::string_view key, std::string &yaml_text, std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = yaml_text_to_json(yaml_text);
  }

  void JsonWriter::integer_value(std::string_view key,
                                 long long       &value,
                                 std::string_view /*doc*/,
                                 long long /*min*/,
                                 long long /*max*/)
  {
    (*node_)[std::string(key)] = value;
  }

  void JsonWriter::choice_index(std::string_view                key,
                                std::size_t                    &index,
                                const std::vector<std::string> &options,
                                std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = options.at(index);
  }

  JsonWriter JsonWriter::object(std::string_view key)
  {
    nlohmann::ordered_json &child = (*node_)[std::string(key)];
    child                         = nlohmann::ordered_json::object();
    return JsonWriter(root_, &child);
  }

  void JsonWriter::null(std::string_view key)
  {
    (*node_)[std::string(key)] = nullptr;
  }

  void JsonWriter::empty_array(std::string_view key)
  {
    (*node_)[std::string(key)] = nlohmann::ordered_json::array();
  }

  JsonWriter JsonWriter::array_item(std::string_view key)
  {
    nlohmann::ordered_json &array = (*node_)[std::string(key)];
    array.push_back(nlohmann::ordered_json::object());
    return JsonWriter(root_, &array.back());
  }

  // ---------------------------------------------------------------------------------------------

  struct SchemaWriter::State
  {
    std::shared_ptr<nlohmann::ordered_json> root;  ///< {"keys": [...]}
    nlohmann::ordered_json                 *array; ///< the entries this writer appends to
    std::string                             path;  ///< key path of this map ("" at the root)

    std::string full_path(std::string_view key) const
    {
      return path.empty() ? std::string(key) : path + "." + std::string(key);
    }

    /// Appends {key, path, type, ...} and returns it for the caller to complete.
    nlohmann::ordered_json &add(std::string_view key, std::string_view type, std::string_view doc)
    {
      nlohmann::ordered_json entry = nlohmann::ordered_json::object();
      entry["key"]                 = std::string(key);
      entry["path"]                = full_path(key);
      entry["type"]                = std::string(type);
      entry["doc"]                 = std::string(doc);
      array->push_back(std::move(entry));
      return array->back();
    }
  };

  namespace
  {
    nlohmann::ordered_json range_json(const Range &range, std::string_view unit)
    {
      if (!range.bounded())
        return nullptr;
      nlohmann::ordered_json json = nlohmann::ordered_json::object();
      if (range.min())
      {
        json["min"]      = *range.min();
        json["min_open"] = range.min_open();
      }
      if (range.max())
      {
        json["max"]      = *range.max();
        json["max_open"] = range.max_open();
      }
      json["text"] = range.text(unit);
      return json;
    }
  } // namespace

  SchemaWriter::SchemaWriter()
    : state_(std::make_unique<State>())
  {
    state_->root = std::make_shared<nlohmann::ordered_json>(nlohmann::ordered_json::object());
    (*state_->root)["keys"] = nlohmann::ordered_json::array();
    state_->array           = &(*state_->root)["keys"];
  }

  SchemaWriter::SchemaWriter(std::unique_ptr<State> state)
    : state_(std::move(state))
  {
  }

  SchemaWriter::SchemaWriter(SchemaWriter &&) noexcept = default;
  SchemaWriter::~SchemaWriter()                        = default;

  std::string SchemaWriter::dump(int indent) const
  {
    return state_->root->dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  }

  void SchemaWriter::quantity(std::string_view key,
                              double          &value,
                              std::string_view unit,
                              std::string_view doc,
                              const Range     &range)
  {
    nlohmann::ordered_json &entry = state_->add(key, "quantity", doc);
    entry["unit"]                 = std::string(unit);
    entry["default"]              = format_quantity(value, unit);
    entry["default_si"]           = value;
    entry["range"]                = range_json(range, unit);
  }

  void SchemaWriter::quantity(std::string_view       key,
                              std::optional<double> &value,
                              std::string_view       unit,
                              std::string_view       doc,
                              const Range           &range)
  {
    nlohmann::ordered_json &entry = state_->add(key, "optional quantity", doc);
    entry["unit"]                 = std::string(unit);
    entry["default"]    = value ? nlohmann::ordered_json(format_quantity(*value, unit)) : nullptr;
    entry["default_si"] = value ? nlohmann::ordered_json(*value) : nullptr;
    entry["range"]      = range_json(range, unit);
  }

  void SchemaWriter::quantity_list(std::string_view     key,
                                   std::vector<double> &values,
                                   std::string_view     unit,
                                   std::string_view     doc,
                                   const Range         &range)
  {
    nlohmann::ordered_json &entry = state_->add(key, "quantity_list", doc);
    entry["unit"]                 = std::string(unit);
    std::vector<std::string> texts;
    for (const double v : values)
      texts.push_back(format_quantity(v, unit));
    entry["default"]    = texts;
    entry["default_si"] = values;
    entry["range"]      = range_json(range, unit);
  }

  void SchemaWriter::flag(std::string_view key, bool &value, std::string_view doc)
  {
    state_->add(key, "flag", doc)["default"] = value;
  }

  void SchemaWriter::text(std::string_view key, std::string &value, std::string_view doc)
  {
    state_->add(key, "text", doc)["default"] = value;
  }

  void SchemaWriter::raw(std::string_view key, std::string &yaml_text, std::string_view doc)
  {
    state_->add(key, "yaml", doc)["default"] = yaml_text;
  }

  std::string SchemaWriter::json_string(const std::string &text)
  {
    return nlohmann::ordered_json(text).dump(-1,
                                             ' ',
                                             false,
                                             nlohmann::ordered_json::error_handler_t::replace);
  }

  std::string SchemaWriter::yaml_json(const std::string &yaml_text)
  {
    return yaml_text_to_json(yaml_text).dump(-1,
                                             ' ',
                                             false,
                                             nlohmann::ordered_json::error_handler_t::replace);
  }

  void SchemaWriter::integer_value(std::string_view key,
                                   long long       &value,
                                   std::string_view doc,
                                   long long        min,
                                   long long        max)
  {
    nlohmann::ordered_json &entry = state_->add(key, "integer", doc);
    entry["default"]              = value;
    nlohmann::ordered_json range  = nlohmann::ordered_json::object();
    // Bounds at or beyond the range of int are type limits, as in the default listing.
    if (min > INT_MIN)
      range["min"] = min;
    if (max < INT_MAX)
      range["max"] = max;
    range["text"]  = range_text(min, max);
    entry["range"] = range;
  }

  void SchemaWriter::choice_index(std::string_view                key,
                                  std::size_t                    &index,
                                  const std::vector<std::string> &options,
                                  std::string_view                doc)
  {
    nlohmann::ordered_json &entry = state_->add(key, "choice", doc);
    entry["default"]              = options.at(index);
    entry["options"]              = options;
  }

  SchemaWriter SchemaWriter::nested(std::string_view   key,
                                    std::string_view   type,
                                    std::string_view   doc,
                                    std::string_view   member,
                                    const std::string &default_json)
  {
    nlohmann::ordered_json &entry = state_->add(key, type, doc);
    if (!default_json.empty())
      entry["default"] = nlohmann::ordered_json::parse(default_json);
    // The entry is complete before the child writer points into it (ordered_json objects
    // reallocate when a key is added).
    nlohmann::ordered_json &keys = entry[std::string(member)];
    keys                         = nlohmann::ordered_json::array();
    auto sub                     = std::make_unique<State>();
    sub->root                    = state_->root;
    sub->array                   = &keys;
    sub->path = state_->full_path(key) + (member == "item" ? std::string("[]") : std::string());
    return SchemaWriter(std::move(sub));
  }

  // ---------------------------------------------------------------------------------------------

  std::string detail::read_text_file(const std::filesystem::path &file)
  {
    // A directory opens as an empty stream on Linux and would read as the default scene; a
    // device or a pipe may never end: only a regular file (or a link to one) is a scene.
    std::error_code                    ec;
    const std::filesystem::file_status status = std::filesystem::status(file, ec);
    if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
      throw SceneError(fmt::format("{}: is {} (expected a scene file: a regular YAML file)",
                                   file.string(),
                                   std::filesystem::is_directory(status) ? "a directory" :
                                   std::filesystem::is_fifo(status)      ? "a pipe" :
                                   std::filesystem::is_character_file(status) ||
                                       std::filesystem::is_block_file(status) ?
                                                                      "a device" :
                                                                      "not a regular file"));
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw SceneError(fmt::format("{}: cannot open scene file (does it exist and is it readable?)",
                                   file.string()));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad())
      throw SceneError(fmt::format("{}: error while reading the scene file", file.string()));
    return text.str();
  }
} // namespace kimp::io
