// Scene errors, ranges, validation failures and the lines of a scene file; see scene_source.h.
#include "io/scene_source.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <fmt/format.h>
#include <fstream>
#include <set>
#include <sstream>
#include <yaml-cpp/yaml.h>

#include "base/format.h"
#include "io/units.h"

namespace kimp::io
{
  namespace
  {
    /// A zero bound needs no unit ("> 0"); a percent bound keeps it ("< 100 %", "> 0 %").
    std::string bound_text(double bound, std::string_view unit)
    {
      return bound == 0.0 && unit != "%" ? std::string("0") : format_quantity(bound, unit);
    }
  } // namespace

  std::string detail::join(const std::vector<std::string> &items, std::string_view separator)
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

  std::string detail::integer_range_text(long long min, long long max)
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

  // ---------------------------------------------------------------------------------------------

  std::string Range::text(std::string_view unit) const
  {
    std::string text;
    if (min_ && max_)
      text = fmt::format("in {}{}, {}{}",
                         min_open_ ? '(' : '[',
                         bound_text(*min_, unit),
                         bound_text(*max_, unit),
                         max_open_ ? ')' : ']');
    else if (min_)
      text = (min_open_ ? "> " : ">= ") + bound_text(*min_, unit);
    else if (max_)
      text = (max_open_ ? "< " : "<= ") + bound_text(*max_, unit);
    if (excludes_zero_)
      text += text.empty() ? "!= 0" : " and != 0";
    return text;
  }

  std::string Range::expectation(std::string_view unit) const
  {
    return "must be " + text(unit) + (note_.empty() ? "" : " (" + note_ + ")");
  }
  // ---------------------------------------------------------------------------------------------

  void
  ValidationContext::fail(std::string key_path, std::string value_text, std::string expectation)
  {
    // A value is quoted at most base::quoted_value_limit characters long (a 1 MB value in a
    // file would otherwise be the whole message).
    failures_.push_back({prefix_ + key_path, base::excerpt(value_text), std::move(expectation)});
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
    std::set<std::string> refused_while_reading;
    for (const auto &f : read_failures_.failures())
      refused_while_reading.insert(f.key_path);
    struct Line
    {
      int         line;
      std::string text;
    };
    std::vector<Line>     lines;
    std::set<std::string> reported;
    for (std::size_t i = 0; i < context.failures().size(); ++i)
    {
      const auto &f = context.failures()[i];
      // The copy of read_failures_ comes first: a later failure at a refused key repeats it.
      const bool read = i < read_failures_.failures().size();
      if (!read && refused_while_reading.count(f.key_path) > 0)
        continue;
      std::string text = fmt::format("{}: {} = {}{}: {}",
                                     location(f.key_path),
                                     f.key_path,
                                     f.value_text,
                                     present(f.key_path) ? "" : " (default)",
                                     f.expectation);
      if (reported.insert(text).second)
        lines.push_back({line_of(f.key_path), std::move(text)});
    }
    // In file order; failures of defaults without a line last.
    std::stable_sort(lines.begin(),
                     lines.end(),
                     [](const Line &a, const Line &b)
                     { return (a.line > 0 ? a.line : INT_MAX) < (b.line > 0 ? b.line : INT_MAX); });
    std::vector<std::string> texts;
    for (Line &l : lines)
      texts.push_back(std::move(l.text));
    throw SceneError(detail::join(texts, "\n"));
  }

  void SceneSource::throw_if_unknown_keys() const
  {
    if (unknown_keys_.empty())
      return;
    std::vector<std::pair<int, std::string>> sorted = unknown_keys_;
    std::stable_sort(sorted.begin(),
                     sorted.end(),
                     [](const auto &a, const auto &b) { return a.first < b.first; });
    std::vector<std::string> texts;
    for (auto &entry : sorted)
      texts.push_back(std::move(entry.second));
    throw SceneError(detail::join(texts, "\n"));
  }

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
