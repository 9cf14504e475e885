// Scene file reading (yaml-cpp): every verb of SceneReader, key lines, unknown keys with a
// "did you mean", range failures; see scene_reader.h.
#include "io/scene_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <variant>
#include <yaml-cpp/yaml.h>

#include "base/format.h"
#include "io/units.h"

namespace kimp::io
{
  using detail::integer_range_text;
  using detail::join;

  namespace
  {

    /// The value as the user wrote it, for messages.
    std::string describe(const YAML::Node &node)
    {
      if (!node.IsDefined() || node.IsNull())
        return "(empty)";
      if (node.IsScalar())
        return "'" + base::excerpt(node.Scalar()) + "'";
      if (node.IsSequence())
        return "a list";
      return "a map";
    }

    int line_of(const YAML::Node &node)
    {
      return node.Mark().is_null() ? 0 : node.Mark().line + 1;
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
  } // namespace

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
                                         base::excerpt(full_path(key)),
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

    /// A range failure (or a subnormal value) of the value at `path`, reported with validate()'s.
    void check_range(const std::string &path, const Key &key, double value, const std::string &text)
    {
      if (!key.range.contains(value))
        source->read_failures().fail(path,
                                     format_quantity(value, key.unit),
                                     key.range.expectation(key.unit));
      else if (!is_normal_or_zero(value))
        source->read_failures().fail(path, text, subnormal_expectation);
    }

    void read(const Entry &entry, const Key &key, double *value)
    {
      const std::string expected =
        fmt::format("a quantity like '{}'", format_quantity(*value, key.unit));
      const std::string &text = scalar(entry, expected);
      try
      {
        *value = parse_quantity_as(text, key.unit);
      }
      catch (const UnitError &error)
      {
        fail(entry, error.what());
      }
      check_range(full_path(key.key), key, *value, text);
    }

    void read(const Entry &entry, const Key &key, std::optional<double> *value)
    {
      if (entry.value.IsNull())
      {
        value->reset();
        return;
      }
      double v = value->value_or(parse_unit(key.unit).value);
      read(entry, key, &v);
      *value = v;
    }

    void read(const Entry &entry, const Key &key, std::vector<double> *values)
    {
      if (entry.value.IsNull())
      {
        values->clear();
        return;
      }
      if (!entry.value.IsSequence())
        fail(entry,
             fmt::format("{} is not a list: expected a list of quantities like [\"{}\", ...]",
                         describe(entry.value),
                         format_quantity(parse_unit(key.unit).value, key.unit)));
      std::vector<double> parsed;
      for (std::size_t i = 0; i < entry.value.size(); ++i)
      {
        const YAML::Node  item      = entry.value[i];
        const std::string item_path = full_path(key.key) + fmt::format("[{}]", i);
        const int         item_line = line_of(item) > 0 ? line_of(item) : entry.line;
        try
        {
          if (!item.IsScalar())
            throw UnitError(fmt::format("{} is not a quantity", describe(item)));
          parsed.push_back(parse_quantity_as(item.Scalar(), key.unit));
        }
        catch (const UnitError &error)
        {
          throw SceneError(
            fmt::format("{}:{}: {}: {}", source->file_name(), item_line, item_path, error.what()));
        }
        if (!key.range.contains(parsed.back()) || !is_normal_or_zero(parsed.back()))
        {
          // Items are recorded only here, so that validate()'s messages about items stay as they
          // were; the item was written, so its failure is not marked "(default)".
          source->record(item_path, item_line);
          check_range(item_path, key, parsed.back(), format_quantity(parsed.back(), key.unit));
        }
      }
      *values = std::move(parsed);
    }

    void read(const Entry &entry, const Key & /*key*/, bool *value)
    {
      const std::string &text = scalar(entry, "true or false");
      if (!YAML::convert<bool>::decode(entry.value, *value))
        fail(entry, fmt::format("'{}' is not true or false", base::excerpt(text)));
    }

    void read(const Entry &entry, const Key &key, Member::Text member)
    {
      if (entry.value.IsNull())
        fail(entry, "missing value: expected a text");
      *member.value = scalar(entry, "a text");
      if (key.range.bounded())
        check_text_range(full_path(key.key), key, *member.value);
    }

    /// The range of a quantity typed as text (IoVerbs::quantity_text): a text that reads as a
    /// number with a unit is held to it, and refused when subnormal; a word ("auto") or a text
    /// that is no quantity is left to validate(), which knows the words and the dimension.
    void check_text_range(const std::string &path, const Key &key, const std::string &text)
    {
      double value = 0.0;
      try
      {
        const Quantity quantity = parse_quantity(text);
        // A wrong dimension is validate()'s to explain ("'auto' or a time"); a display unit that
        // is no unit (N/m^n) leaves the dimension to it as well.
        std::optional<Quantity> unit;
        try
        {
          unit = parse_unit(key.unit);
        }
        catch (const UnitError &)
        {
        }
        if (unit && quantity.dimension != unit->dimension)
          return;
        value = quantity.value;
      }
      catch (const UnitError &)
      {
        return;
      }
      if (!key.range.contains(value))
        source->read_failures().fail(path, text, key.range.expectation(key.unit));
      else if (!is_normal_or_zero(value))
        source->read_failures().fail(path, text, subnormal_expectation);
    }

    void read(const Entry &entry, const Key &key, Member::Yaml member)
    {
      *member.text = flow_text(entry.value);
      record_item_lines(*source, full_path(key.key), entry.value);
    }

    void read(const Entry &entry, const Key & /*key*/, Member::Integer member)
    {
      const std::string  expected = integer_range_text(member.min, member.max);
      const std::string &text     = scalar(entry, expected);
      std::string_view   digits(text);
      if (!digits.empty() && digits.front() == '+')
        digits.remove_prefix(1);
      long long parsed = 0;
      const auto [end, error] =
        std::from_chars(digits.data(), digits.data() + digits.size(), parsed);
      if (digits.empty() || error != std::errc() || end != digits.data() + digits.size())
        fail(entry,
             fmt::format("'{}' is not an integer: expected an {}", base::excerpt(text), expected));
      if (parsed < member.min || parsed > member.max)
        fail(entry, fmt::format("{} is out of range: expected an {}", parsed, expected));
      *member.value = parsed;
    }

    void read(const Entry &entry, const Key & /*key*/, Member::Choice member)
    {
      const std::vector<std::string> &options  = *member.options;
      const std::string               expected = "one of: " + join(options, ", ");
      const std::string              &text     = scalar(entry, expected);
      const auto                      it       = std::find(options.begin(), options.end(), text);
      if (it == options.end())
        fail(entry, fmt::format("'{}' is not {}", base::excerpt(text), expected));
      *member.index = static_cast<std::size_t>(it - options.begin());
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

  void SceneReader::value(const Key &key, Member::Ref member)
  {
    if (const State::Entry *entry = state_->find(key.key))
      std::visit([&](auto m) { state_->read(*entry, key, m); }, member);
  }

  bool SceneReader::has_key(std::string_view key) const
  {
    for (const auto &e : state_->entries)
      if (e.key == key)
        return true;
    return false;
  }

  std::optional<SceneReader> SceneReader::open_section(std::string_view key,
                                                       std::string_view /*doc*/)
  {
    return open_map(key, false, false);
  }

  std::optional<SceneReader>
  SceneReader::open_map(std::string_view key, bool null_means_absent, bool file_named_keys)
  {
    const State::Entry *entry = state_->find(key);
    if (entry == nullptr || (entry->value.IsNull() && null_means_absent))
      return std::nullopt;
    if (!entry->value.IsNull() && !entry->value.IsMap())
      state_->fail(*entry,
                   describe(entry->value) +
                     (file_named_keys ? " is not a map: expected a map of 'name: value' lines" :
                                        " is not a section: expected indented 'key: value' lines"));
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

  std::vector<std::string> SceneReader::keys() const
  {
    std::vector<std::string> names;
    for (const auto &e : state_->entries)
      names.push_back(e.key);
    return names;
  }

  void SceneReader::finish()
  {
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
      state_->source->add_unknown_key(e.line,
                                      fmt::format("{}:{}: unknown key '{}'{} (known: {}){}",
                                                  state_->source->file_name(),
                                                  e.line,
                                                  base::excerpt(e.key),
                                                  state_->path.empty() ? "" : " in " + state_->path,
                                                  state_->known.empty() ? "none" :
                                                                          join(state_->known, ", "),
                                                  suggestion));
    }
    if (state_->is_root)
      state_->source->throw_if_unknown_keys();
  }
} // namespace kimp::io
