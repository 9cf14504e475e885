// Scene key paths in a YAML tree, value ranges and paths of a sweep's values; see sweep_values.h
// and sweep_plan.h.
#include "app/sweep/sweep_values.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <optional>
#include <stdexcept>
#include <vector>

#include "app/lumped/ground_motion_scene.h"
#include "app/sweep/sweep_plan.h"
#include "io/scene_io.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::io;
  namespace
  {
    /// One step of a key path: a map key, or a list index.
    struct PathStep
    {
      std::string key;
      long        index = -1; ///< >= 0 for a list index
    };

    std::vector<PathStep> split_key_path(const std::string &key_path)
    {
      std::vector<PathStep> steps;
      std::size_t           i    = 0;
      const auto            fail = [&](const std::string &why)
      { throw std::invalid_argument("key path '" + key_path + "': " + why); };
      if (key_path.empty())
        fail("empty (expected e.g. walls.left.gap or cases[0].cor)");
      while (i < key_path.size())
      {
        if (key_path[i] == '[')
        {
          const std::size_t close = key_path.find(']', i);
          if (close == std::string::npos || close == i + 1)
            fail("unterminated or empty [index]");
          const std::string digits = key_path.substr(i + 1, close - i - 1);
          if (digits.find_first_not_of("0123456789") != std::string::npos)
            fail("index '" + digits + "' is not a non-negative integer");
          steps.push_back({"", std::stol(digits)});
          i = close + 1;
          if (i < key_path.size() && key_path[i] == '.')
            ++i;
          continue;
        }
        const std::size_t end = key_path.find_first_of(".[", i);
        const std::string key = key_path.substr(i, end - i);
        if (key.empty())
          fail("empty key between dots");
        steps.push_back({key, -1});
        if (end == std::string::npos)
          break;
        i = key_path[end] == '.' ? end + 1 : end;
        if (key_path[end] == '.' && i == key_path.size())
          fail("ends with a dot");
      }
      return steps;
    }

    /// The last key of a key path ("cases[1].record" -> "record").
    std::string last_key(const std::string &key_path)
    {
      const std::size_t dot = key_path.find_last_of('.');
      const std::string key = dot == std::string::npos ? key_path : key_path.substr(dot + 1);
      return key.substr(0, key.find('['));
    }

    std::string unit_of(const std::string &quantity_text)
    {
      const char *begin = quantity_text.c_str();
      char       *end   = nullptr;
      std::strtod(begin, &end);
      std::string       unit(end);
      const std::size_t first = unit.find_first_not_of(' ');
      return first == std::string::npos ? std::string() : unit.substr(first);
    }

  } // namespace

  namespace sweep_values
  {
    void check_key_path(const std::string &key_path)
    {
      split_key_path(key_path);
    }

    void set_node_value(YAML::Node &root, const std::string &key_path, const std::string &value)
    {
      const std::vector<PathStep> steps = split_key_path(key_path);
      if (!root.IsDefined() || root.IsNull())
        root = YAML::Node(YAML::NodeType::Map);
      YAML::Node node = root;
      for (std::size_t s = 0; s < steps.size(); ++s)
      {
        const PathStep &step = steps[s];
        const bool      last = s + 1 == steps.size();
        YAML::Node      child;
        if (step.index >= 0)
        {
          if (node.IsNull())
            node = YAML::Node(YAML::NodeType::Sequence);
          if (!node.IsSequence())
            throw std::invalid_argument("key path '" + key_path + "': [" +
                                        std::to_string(step.index) + "] applied to a non-list");
          const auto index = static_cast<std::size_t>(step.index);
          if (index > node.size())
            throw std::invalid_argument(fmt::format(
              "key path '{}': index {} beyond the list's {} items (at most one new item)",
              key_path,
              index,
              node.size()));
          if (index == node.size())
            node.push_back(last ? YAML::Node() : YAML::Node(YAML::NodeType::Map));
          child = node[index];
        }
        else
        {
          if (node.IsNull())
            node = YAML::Node(YAML::NodeType::Map);
          if (!node.IsMap())
            throw std::invalid_argument("key path '" + key_path + "': key '" + step.key +
                                        "' applied to a value that is not a map");
          if (!node[step.key])
            node[step.key] = last ? YAML::Node() : YAML::Node(YAML::NodeType::Map);
          child = node[step.key];
        }
        if (last)
        {
          if (child.IsMap() || child.IsSequence())
            throw std::invalid_argument("key path '" + key_path +
                                        "' names a section, not a single value");
          child = YAML::Load(value);
          return;
        }
        node.reset(child);
      }
    }

    YAML::Node load(const std::string &text, const std::string &name)
    {
      try
      {
        return YAML::Load(text);
      }
      catch (const YAML::Exception &error)
      {
        throw SweepError(
          fmt::format("{}:{}: invalid YAML: {}", name, error.mark.line + 1, error.msg));
      }
    }

    std::string emit(const YAML::Node &root)
    {
      YAML::Emitter out;
      out << root;
      return std::string(out.c_str()) + "\n";
    }

    std::string value_text(const YAML::Node &node)
    {
      YAML::Emitter out;
      out << node;
      return out.c_str();
    }

    bool is_record_key(const std::string &key_path)
    {
      const std::string key = last_key(key_path);
      return key == "record" || key == "records_dir" || key == "record_unit";
    }

    std::string
    resolved_value(const std::string &key_path, const std::string &value, const std::string &file)
    {
      const std::string key = last_key(key_path);
      if (key != "k_table" && key != "record" && key != "records_dir")
        return value;
      YAML::Node node;
      try
      {
        node = YAML::Load(value);
      }
      catch (const std::exception &)
      {
        return value;
      }
      if (!node.IsScalar())
        return value;
      const std::filesystem::path parent = std::filesystem::path(file).parent_path();
      std::error_code             ec;
      const std::filesystem::path directory =
        std::filesystem::absolute(parent.empty() ? std::filesystem::path(".") : parent, ec)
          .lexically_normal();
      if (ec)
        return value;
      const std::string written  = node.Scalar();
      const std::string resolved = key == "record" ? resolve_record_path(written, directory) :
                                                     resolve_scene_path(written, directory);
      if (resolved == written)
        return value;
      YAML::Emitter out;
      out << YAML::DoubleQuoted << resolved;
      return out.c_str();
    }

    void fail_at(const std::string &file, int line, const std::string &key, const std::string &what)
    {
      throw SweepError(fmt::format("{}:{}: {}: {}", file, line, key, what));
    }

    void set_values_at(YAML::Node                                             &root,
                       const std::vector<std::pair<std::string, std::string>> &settings,
                       const std::string                                      &file,
                       const int                                               line,
                       const std::string                                      &key)
    {
      for (const auto &[path, value] : settings)
      {
        try
        {
          set_node_value(root, path, resolved_value(path, value, file));
        }
        catch (const std::exception &error)
        {
          fail_at(file, line, key, error.what());
        }
      }
    }
  } // namespace sweep_values

  std::string set_yaml_value(const std::string &yaml_text,
                             const std::string &key_path,
                             const std::string &value_yaml)
  {
    YAML::Node root = YAML::Load(yaml_text);
    sweep_values::set_node_value(root, key_path, value_yaml);
    return sweep_values::emit(root);
  }

  std::optional<std::string> get_yaml_value(const std::string &yaml_text,
                                            const std::string &key_path)
  {
    const std::vector<PathStep> steps = split_key_path(key_path);
    YAML::Node                  node  = YAML::Load(yaml_text);
    for (const PathStep &step : steps)
    {
      if (step.index >= 0)
      {
        if (!node.IsSequence() || static_cast<std::size_t>(step.index) >= node.size())
          return std::nullopt;
        node.reset(node[static_cast<std::size_t>(step.index)]);
      }
      else
      {
        if (!node.IsMap() || !node[step.key])
          return std::nullopt;
        node.reset(node[step.key]);
      }
    }
    if (node.IsNull())
      return std::nullopt;
    if (!node.IsScalar())
      throw std::invalid_argument("key path '" + key_path +
                                  "' names a section, not a single value");
    return node.Scalar();
  }

  SweepValues SweepValues::range(const std::string &from,
                                 const std::string &to,
                                 const std::string &step,
                                 const std::string &where)
  {
    Quantity q_from, q_to, q_step;
    try
    {
      q_from = parse_quantity(from);
      q_to   = parse_quantity(to);
      q_step = parse_quantity(step);
    }
    catch (const std::exception &error)
    {
      throw SweepError(where + ": range: " + error.what());
    }
    if (q_to.dimension != q_from.dimension || q_step.dimension != q_from.dimension)
      throw SweepError(fmt::format("{}: range from = {}, to = {}, step = {}: units of different "
                                   "dimensions (expected one dimension for all three)",
                                   where,
                                   from,
                                   to,
                                   step));
    if (!(q_step.value > 0.0))
      throw SweepError(fmt::format("{}: range step = {} (must be > 0)", where, step));
    if (q_to.value < q_from.value)
      throw SweepError(fmt::format("{}: range to = {} (must be >= from = {})", where, to, from));
    // Round-off tolerance of one part in 1e9 of a step: 10..45 step 0.5 includes 45.
    constexpr double      tolerance  = 1e-9;
    const double          span       = (q_to.value - q_from.value) / q_step.value;
    constexpr std::size_t max_values = 10'000'000;
    // Checked in floating point before the cast: a tiny step gives a count beyond size_t
    // (1e21 values for 10..20 cm step 1e-20 cm), whose cast is undefined.
    const double n_values = std::floor(span + tolerance) + 1.0;
    if (!(n_values <= static_cast<double>(max_values)))
      throw SweepError(fmt::format("{}: range {} .. {} step {} gives {:.4g} values (expected at "
                                   "most {}: use a larger step)",
                                   where,
                                   from,
                                   to,
                                   step,
                                   n_values,
                                   max_values));
    const auto n_steps = static_cast<std::size_t>(n_values) - 1;
    if (n_steps > 0 && !(q_from.value + q_step.value != q_from.value))
      throw SweepError(fmt::format("{}: range step = {} is below the resolution of from = {} "
                                   "(expected a step that changes the value)",
                                   where,
                                   step,
                                   from));
    SweepValues values;
    values.range_from_  = q_from.value;
    values.range_step_  = q_step.value;
    values.range_count_ = n_steps + 1;
    values.range_unit_  = unit_of(from);
    return values;
  }

  std::string SweepValues::operator[](std::size_t i) const
  {
    if (!is_range())
      return list_.at(i);
    if (i >= range_count_)
      throw std::out_of_range(
        fmt::format("sweep value {} of a range of {} values", i, range_count_));
    return format_quantity(range_from_ + static_cast<double>(i) * range_step_, range_unit_);
  }

  void SweepValues::push_back(std::string value)
  {
    if (is_range())
      throw std::logic_error("SweepValues::push_back on a range");
    list_.push_back(std::move(value));
  }

  std::vector<std::string> SweepValues::to_vector() const
  {
    if (!is_range())
      return list_;
    std::vector<std::string> values;
    values.reserve(size());
    for (std::size_t i = 0; i < size(); ++i)
      values.push_back((*this)[i]);
    return values;
  }

  std::vector<std::string> expand_range(const std::string &from,
                                        const std::string &to,
                                        const std::string &step,
                                        const std::string &where)
  {
    return SweepValues::range(from, to, step, where).to_vector();
  }
} // namespace kimp::app
