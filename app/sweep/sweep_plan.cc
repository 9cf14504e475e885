// Sweep file reading (through the scene reader) and case enumeration; key paths are set on a copy
// of the base scene's YAML tree, so every scene key can be varied without the sweep knowing the
// schema.
#include "app/sweep/sweep_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "app/ground_motion_scene.h"
#include "base/hash.h"
#include "io/scene_io.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::base;
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

    /// Set the scalar at `key_path` inside `root` (modified in place).
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

    /// The last key of a key path ("cases[1].record" -> "record").
    std::string last_key(const std::string &key_path)
    {
      const std::size_t dot = key_path.find_last_of('.');
      const std::string key = dot == std::string::npos ? key_path : key_path.substr(dot + 1);
      return key.substr(0, key.find('['));
    }

    /// True for the keys that select a ground motion's record.
    bool is_record_key(const std::string &key_path)
    {
      const std::string key = last_key(key_path);
      return key == "record" || key == "records_dir" || key == "record_unit";
    }

    /**
     * A value of the sweep file `file` for `key_path`, with a relative path in it
     * (impact.k_table, a record file, records_dir) made absolute against the sweep file's
     * directory: the case scenes are read relative to the base scene, which may live elsewhere.
     */
    std::string
    sweep_value(const std::string &key_path, const std::string &value, const std::string &file)
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

    std::string emit(const YAML::Node &root)
    {
      YAML::Emitter out;
      out << root;
      return std::string(out.c_str()) + "\n";
    }

    int line_of(const YAML::Node &node)
    {
      return node.Mark().line + 1;
    }

    [[noreturn]] void
    fail_at(const std::string &file, int line, const std::string &key, const std::string &what)
    {
      throw SweepError(fmt::format("{}:{}: {}: {}", file, line, key, what));
    }

    /// The scalar of `node`; else an error at `line` (where the scene reader recorded it).
    std::string
    scalar_text(const YAML::Node &node, const std::string &file, const std::string &key, int line)
    {
      if (node.IsNull())
        return "null";
      if (!node.IsScalar())
        fail_at(file, line, key, "expected a single value (quantity, number, word)");
      return node.Scalar();
    }

    std::string scalar_text(const YAML::Node &node, const std::string &file, const std::string &key)
    {
      return scalar_text(node, file, key, line_of(node));
    }

    /// Text of a value as it must be written back into YAML (strings that look like numbers or
    /// flags keep their quotes).
    std::string yaml_value_text(const YAML::Node &node)
    {
      YAML::Emitter out;
      out << node;
      return out.c_str();
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

    std::string kind_list()
    {
      std::string list;
      for (const std::string &kind : sweep_report_kinds())
        list += (list.empty() ? "" : ", ") + kind;
      return list;
    }

    void load_root(const std::string &text, const std::string &name, YAML::Node &root)
    {
      try
      {
        root = YAML::Load(text);
      }
      catch (const YAML::Exception &error)
      {
        throw SweepError(
          fmt::format("{}:{}: invalid YAML: {}", name, error.mark.line + 1, error.msg));
      }
    }

    /// The `report:` section as read; kind and gap are checked by SweepPlan::parse().
    struct ReportFile
    {
      std::string kind;
      std::string gap = "walls.left.gap";
      std::string title;
    };

    template <class Io>
    void visit(Io &io, ReportFile &report)
    {
      io.text("kind",
              report.kind,
              "charts and summary of scripts/sweep_charts.py: one of " + kind_list());
      io.text("gap", report.gap, "scene key path of the swept gap");
      io.text("title", report.title, "chart and summary title");
    }

    /// A sweep file as read: parameter values and companion overrides stay YAML text, since their
    /// keys and types are those of the base scene.
    struct SweepFile
    {
      std::string                                      scene;
      std::string                                      engine  = "lumped";
      std::string                                      combine = "product";
      std::vector<std::pair<std::string, std::string>> parameters;
      std::vector<std::pair<std::string, std::string>> companions;
      std::optional<ReportFile>                        report;
    };

    template <class Io>
    void visit(Io &io, SweepFile &file)
    {
      io.text("scene", file.scene, "base scene file, relative to the sweep file");
      io.text("engine", file.engine, "scene type and runner of every case");
      io.text("combine",
              file.combine,
              "product (Cartesian, first parameter slowest) or zip (i-th values together)");
      io.map_of("parameters",
                file.parameters,
                "scene key path(s), comma separated -> list of values, {from, to, step} or list "
                "of maps {key path: value, ..., label: name}");
      io.map_of("companions",
                file.companions,
                "extra run of every case: name -> {key path: value, ...}");
      io.optional_section("report", file.report, "charts and summary of the sweep");
    }

    /// The example printed by `kimp sweep --print-defaults` (a valid sweep file).
    SweepFile example_sweep_file()
    {
      SweepFile file;
      file.scene      = "scene.yaml";
      file.parameters = {{"walls.left.gap, walls.right.gap",
                          "{from: 10 cm, to: 45 cm, step: 5 cm}"},
                         {"impact.cor", "[0.5, 0.7, 0.9]"}};
      file.companions = {{"no_contact", "{walls.left.present: false, walls.right.present: false}"}};
      return file;
    }

    /// Specific messages for a malformed `report:`, before the scene reader's generic ones.
    void check_report_shape(const YAML::Node &root, const std::string &file)
    {
      const YAML::Node report = root["report"];
      if (!report)
        return;
      int line = line_of(report);
      for (const auto &entry : root)
        if (entry.first.Scalar() == "report")
          line = line_of(entry.first);
      if (!report.IsMap())
        fail_at(file,
                line,
                "report",
                "expected a map {kind: ..., gap: scene key path, title: ...}");
      for (const auto &entry : report)
      {
        const std::string key = entry.first.Scalar();
        if (key != "kind" && key != "gap" && key != "title")
          fail_at(file,
                  line_of(entry.first),
                  "report." + key,
                  "unknown key (expected kind, gap or title)");
      }
    }
  } // namespace

  std::string set_yaml_value(const std::string &yaml_text,
                             const std::string &key_path,
                             const std::string &value_yaml)
  {
    YAML::Node root = YAML::Load(yaml_text);
    set_node_value(root, key_path, value_yaml);
    return emit(root);
  }

  std::string sweep_file_defaults_text()
  {
    std::ostringstream out;
    out << "# kimp sweep file (an example: parameters and companions have no defaults)\n"
        << "# Parameter and companion keys are key paths of the base scene; values are written as "
           "in the scene.\n";
    SweepFile           file = example_sweep_file();
    io::DefaultsPrinter printer(out);
    visit(printer, file);
    return out.str();
  }

  std::string sweep_file_schema_text()
  {
    SweepFile        file = example_sweep_file();
    io::SchemaWriter writer;
    visit(writer, file);
    return writer.dump(2) + "\n";
  }

  const std::vector<std::string> &sweep_report_kinds()
  {
    static const std::vector<std::string> kinds{"gap_study",
                                                "isolation_flexibility",
                                                "wall_location",
                                                "impact_parameters",
                                                "adjacent_buildings",
                                                "bumpers"};
    return kinds;
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

  std::vector<std::string> expand_range(const std::string &from,
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
    const std::string        unit = unit_of(from);
    std::vector<std::string> values;
    values.reserve(n_steps + 1);
    for (std::size_t i = 0; i <= n_steps; ++i)
    {
      const double v = q_from.value + static_cast<double>(i) * q_step.value;
      values.push_back(format_quantity(v, unit));
    }
    return values;
  }

  std::filesystem::path SweepPlan::base_scene_path(const std::string           &text,
                                                   const std::filesystem::path &sweep_file)
  {
    YAML::Node root;
    load_root(text, sweep_file.string(), root);
    if (!root.IsMap() || !root["scene"])
      throw SweepError(sweep_file.string() +
                       ":1: scene: missing (expected the base scene file, relative to the "
                       "sweep file)");
    const std::string           scene = scalar_text(root["scene"], sweep_file.string(), "scene");
    const std::filesystem::path path(scene);
    return path.is_absolute() ? path : sweep_file.parent_path() / path;
  }

  SweepPlan SweepPlan::from_file(const std::filesystem::path &file,
                                 const CaseCountCheck        &check_count)
  {
    std::string text;
    try
    {
      text = detail::read_text_file(file);
    }
    catch (const SceneError &error)
    {
      throw SweepError(error.what());
    }
    const std::filesystem::path scene = base_scene_path(text, file);
    std::string                 scene_text;
    try
    {
      scene_text = detail::read_text_file(scene);
    }
    catch (const SceneError &error)
    {
      YAML::Node root = YAML::Load(text);
      fail_at(file.string(), line_of(root["scene"]), "scene", error.what());
    }
    return parse(text, file.string(), scene_text, scene.string(), check_count);
  }

  SweepPlan SweepPlan::parse(const std::string    &text,
                             const std::string    &file_name,
                             const std::string    &base_scene_text,
                             const std::string    &base_scene_name,
                             const CaseCountCheck &check_count)
  {
    SweepPlan plan;
    plan.file_name_       = file_name;
    plan.text_            = text;
    plan.base_scene_text_ = base_scene_text;
    plan.base_scene_name_ = base_scene_name;

    YAML::Node root;
    load_root(text, file_name, root);
    if (!root.IsMap())
      throw SweepError(file_name + ":1: expected a map with keys scene, parameters, combine, "
                                   "companions, engine");
    check_report_shape(root, file_name);

    SceneSource source(file_name);
    SweepFile   file;
    try
    {
      SceneReader reader = SceneReader::root(text, source);
      visit(reader, file);
      reader.finish();
    }
    catch (const SceneError &error)
    {
      throw SweepError(error.what());
    }
    // Line of a key path of the sweep file ("parameters.record[1]"), 1 if it was not written.
    const auto line = [&](const std::string &key_path)
    { return std::max(source.line_of(key_path), 1); };

    if (file.report)
    {
      SweepReportSpec spec;
      spec.line                             = line("report");
      spec.kind                             = file.report->kind;
      spec.gap_key                          = file.report->gap;
      spec.title                            = file.report->title;
      const std::vector<std::string> &kinds = sweep_report_kinds();
      if (!source.present("report.kind"))
        fail_at(file_name,
                spec.line,
                "report.kind",
                "missing (expected one of " + kind_list() + ")");
      if (std::find(kinds.begin(), kinds.end(), spec.kind) == kinds.end())
        fail_at(file_name,
                line("report.kind"),
                "report.kind",
                "'" + spec.kind + "' (expected one of " + kind_list() + ")");
      try
      {
        split_key_path(spec.gap_key);
      }
      catch (const std::invalid_argument &error)
      {
        fail_at(file_name, line("report.gap"), "report.gap", error.what());
      }
      plan.report_ = std::move(spec);
    }
    plan.engine_ = file.engine;
    if (file.combine == "product")
      plan.combination_ = SweepCombination::product;
    else if (file.combine == "zip")
      plan.combination_ = SweepCombination::zip;
    else
      fail_at(file_name,
              line("combine"),
              "combine",
              "'" + file.combine + "' (expected product or zip)");

    if (file.parameters.empty())
      fail_at(file_name,
              line("parameters"),
              "parameters",
              "missing or empty (expected a map: scene key path -> list of values or "
              "{from, to, step})");
    for (const auto &[name, values_text] : file.parameters)
    {
      SweepParameter p;
      p.name                = name;
      const std::string key = "parameters." + p.name;
      p.line                = line(key);
      std::size_t begin     = 0;
      while (begin <= p.name.size())
      {
        const std::size_t end  = std::min(p.name.find(',', begin), p.name.size());
        std::string       path = p.name.substr(begin, end - begin);
        path.erase(0, path.find_first_not_of(' '));
        path.erase(path.find_last_not_of(' ') + 1);
        if (path.empty())
          fail_at(file_name, p.line, key, "empty key path (expected e.g. walls.left.gap)");
        try
        {
          split_key_path(path);
        }
        catch (const std::invalid_argument &error)
        {
          fail_at(file_name, p.line, key, error.what());
        }
        p.key_paths.push_back(path);
        begin = end + 1;
      }
      const YAML::Node values = YAML::Load(values_text);
      if (values.IsSequence())
      {
        for (std::size_t v = 0; v < values.size(); ++v)
        {
          const YAML::Node  value     = values[v];
          const std::string item_path = fmt::format("{}[{}]", key, v);
          if (!value.IsMap())
          {
            scalar_text(value, file_name, key, line(item_path));
            p.values.push_back(yaml_value_text(value));
            continue;
          }
          // A map sets several keys together; `label` names it in the results.
          std::vector<std::pair<std::string, std::string>> setting;
          std::string                                      label;
          for (const auto &item : value)
          {
            const std::string path      = item.first.Scalar();
            const int         path_line = line(item_path + "." + path);
            const std::string item_text =
              scalar_text(item.second, file_name, key + "." + path, path_line);
            if (path == "label")
            {
              label = item_text;
              continue;
            }
            try
            {
              split_key_path(path);
            }
            catch (const std::invalid_argument &error)
            {
              fail_at(file_name, path_line, key, error.what());
            }
            setting.emplace_back(path, yaml_value_text(item.second));
          }
          if (setting.empty())
            fail_at(file_name, line(item_path), key, "a map value sets no key path");
          if (label.empty())
          {
            YAML::Emitter out;
            out << YAML::Flow << value;
            label = out.c_str();
          }
          p.values.push_back(label);
          p.settings.resize(p.values.size());
          p.settings.back() = std::move(setting);
        }
      }
      else if (values.IsMap())
      {
        for (const auto &range_entry : values)
        {
          const std::string k = range_entry.first.Scalar();
          if (k != "from" && k != "to" && k != "step")
            fail_at(file_name,
                    line(key + "." + k),
                    key + "." + k,
                    "unknown key (a range has from, to and step)");
        }
        for (const char *k : {"from", "to", "step"})
          if (!values[k])
            fail_at(file_name,
                    p.line,
                    key,
                    std::string("range without '") + k + "' (expected {from, to, step})");
        p.values =
          expand_range(scalar_text(values["from"], file_name, key + ".from", line(key + ".from")),
                       scalar_text(values["to"], file_name, key + ".to", line(key + ".to")),
                       scalar_text(values["step"], file_name, key + ".step", line(key + ".step")),
                       fmt::format("{}:{}: {}", file_name, p.line, key));
      }
      else
        fail_at(file_name, p.line, key, "expected a list of values or a range {from, to, step}");
      if (p.values.empty())
        fail_at(file_name, p.line, key, "no values (expected at least one)");
      p.settings.resize(p.values.size());
      for (std::size_t v = 0; v < p.values.size(); ++v)
        if (p.settings[v].empty())
          for (const std::string &path : p.key_paths)
            p.settings[v].emplace_back(path, p.values[v]);
      plan.parameters_.push_back(std::move(p));
    }

    for (const auto &[name, overrides_text] : file.companions)
    {
      SweepCompanion c;
      c.name                = name;
      const std::string key = "companions." + c.name;
      c.line                = line(key);
      if (c.name.empty() || c.name.find_first_of(" ,\"") != std::string::npos)
        fail_at(file_name, c.line, key, "name must be non-empty without spaces, commas, quotes");
      const YAML::Node overrides = YAML::Load(overrides_text);
      if (!overrides.IsMap() || overrides.size() == 0)
        fail_at(file_name, c.line, key, "expected a non-empty map of key path -> value");
      for (const auto &o : overrides)
      {
        const std::string path = key + "." + o.first.Scalar();
        scalar_text(o.second, file_name, path, line(path));
        c.overrides.emplace_back(o.first.Scalar(), yaml_value_text(o.second));
      }
      plan.companions_.push_back(std::move(c));
    }

    // Enumerate combinations.
    std::size_t n_combinations = 1;
    if (plan.combination_ == SweepCombination::zip)
    {
      n_combinations = plan.parameters_.front().values.size();
      for (const SweepParameter &p : plan.parameters_)
        if (p.values.size() != n_combinations)
          fail_at(file_name,
                  p.line,
                  "parameters." + p.name,
                  fmt::format("{} values, but {} has {} (combine: zip needs equal lengths)",
                              p.values.size(),
                              plan.parameters_.front().name,
                              n_combinations));
    }
    else
    {
      constexpr std::size_t max_cases = 10'000'000;
      for (const SweepParameter &p : plan.parameters_)
      {
        n_combinations *= p.values.size();
        if (n_combinations > max_cases)
          fail_at(file_name,
                  p.line,
                  "parameters",
                  fmt::format("more than {} combinations", max_cases));
      }
    }

    if (check_count)
      check_count(n_combinations * (1 + plan.companions_.size()), base_scene_text, base_scene_name);
    YAML::Node base;
    load_root(base_scene_text, base_scene_name, base);
    std::size_t index = 0;
    for (std::size_t c = 0; c < n_combinations; ++c)
    {
      std::vector<std::string> values(plan.parameters_.size());
      std::vector<std::size_t> choice(plan.parameters_.size());
      std::size_t              rest = c;
      for (std::size_t i = plan.parameters_.size(); i-- > 0;)
      {
        const SweepParameter &p = plan.parameters_[i];
        if (plan.combination_ == SweepCombination::zip)
          choice[i] = c;
        else
        {
          choice[i] = rest % p.values.size();
          rest /= p.values.size();
        }
        values[i] = p.values[choice[i]];
      }
      YAML::Node  scene = YAML::Clone(base);
      std::string signature;
      for (std::size_t i = 0; i < plan.parameters_.size(); ++i)
      {
        const SweepParameter &p = plan.parameters_[i];
        signature += p.name + "=" + values[i] + "\n";
        for (const auto &[path, value] : p.settings[choice[i]])
        {
          try
          {
            set_node_value(scene, path, sweep_value(path, value, file_name));
          }
          catch (const std::exception &error)
          {
            fail_at(file_name, p.line, "parameters." + p.name, error.what());
          }
          if (path != p.name || value != values[i])
            signature += "  " + path + "=" + value + "\n";
        }
      }

      const auto add_case = [&](const YAML::Node &case_scene, const std::string &companion)
      {
        SweepCase sc;
        sc.index     = index++;
        sc.companion = companion;
        sc.values    = values;
        const std::uint64_t hash =
          stable_hash(signature + (companion.empty() ? "" : "companion=" + companion + "\n"));
        sc.id         = fmt::format("{}-{:016x}", sc.index, hash);
        sc.scene_text = emit(case_scene);
        sc.scene_name = fmt::format("{} case {}", file_name, sc.id);
        plan.cases_.push_back(std::move(sc));
      };
      add_case(scene, "");
      for (const SweepCompanion &companion : plan.companions_)
      {
        YAML::Node variant = YAML::Clone(scene);
        for (const auto &[path, value] : companion.overrides)
        {
          try
          {
            set_node_value(variant, path, sweep_value(path, value, file_name));
          }
          catch (const std::exception &error)
          {
            fail_at(file_name, companion.line, "companions." + companion.name, error.what());
          }
        }
        add_case(variant, companion.name);
      }
    }
    return plan;
  }

  void SweepPlan::check_key_paths(const SceneChecker &check) const
  {
    YAML::Node base;
    load_root(base_scene_text_, base_scene_name_, base);
    for (const SweepParameter &p : parameters_)
      for (std::size_t v = 0; v < p.values.size(); ++v)
      {
        const std::string &value = p.values[v];
        YAML::Node         scene = YAML::Clone(base);
        for (const auto &[path, text] : p.settings[v])
          set_node_value(scene, path, sweep_value(path, text, file_name_));
        try
        {
          check(emit(scene), base_scene_name_ + " (" + p.name + " = " + value + ")");
        }
        catch (const std::exception &error)
        {
          fail_at(file_name_, p.line, "parameters." + p.name + " = " + value, error.what());
        }
      }
    for (const SweepCompanion &c : companions_)
    {
      YAML::Node scene = YAML::Clone(base);
      for (const auto &[path, value] : c.overrides)
        set_node_value(scene, path, sweep_value(path, value, file_name_));
      try
      {
        check(emit(scene), base_scene_name_ + " (companion " + c.name + ")");
      }
      catch (const std::exception &error)
      {
        fail_at(file_name_, c.line, "companions." + c.name, error.what());
      }
    }
  }

  void SweepPlan::check_records(const SceneChecker &check) const
  {
    YAML::Node base;
    load_root(base_scene_text_, base_scene_name_, base);
    bool set_here = false;
    for (const SweepParameter &p : parameters_)
      for (std::size_t v = 0; v < p.values.size(); ++v)
      {
        if (std::none_of(p.settings[v].begin(),
                         p.settings[v].end(),
                         [](const auto &setting) { return is_record_key(setting.first); }))
          continue;
        set_here         = true;
        YAML::Node scene = YAML::Clone(base);
        for (const auto &[path, text] : p.settings[v])
          set_node_value(scene, path, sweep_value(path, text, file_name_));
        try
        {
          check(emit(scene), base_scene_name_ + " (" + p.name + " = " + p.values[v] + ")");
        }
        catch (const std::exception &error)
        {
          fail_at(file_name_, p.line, "parameters." + p.name + " = " + p.values[v], error.what());
        }
      }
    for (const SweepCompanion &c : companions_)
    {
      if (std::none_of(c.overrides.begin(),
                       c.overrides.end(),
                       [](const auto &setting) { return is_record_key(setting.first); }))
        continue;
      set_here         = true;
      YAML::Node scene = YAML::Clone(base);
      for (const auto &[path, value] : c.overrides)
        set_node_value(scene, path, sweep_value(path, value, file_name_));
      try
      {
        check(emit(scene), base_scene_name_ + " (companion " + c.name + ")");
      }
      catch (const std::exception &error)
      {
        fail_at(file_name_, c.line, "companions." + c.name, error.what());
      }
    }
    // The base scene's own records, reported at its lines, when nothing above replaced them.
    if (!set_here)
      check(base_scene_text_, base_scene_name_);
  }

  std::string SweepPlan::to_json_text() const
  {
    nlohmann::ordered_json json;
    json["file"]       = file_name_;
    json["scene"]      = base_scene_name_;
    json["engine"]     = engine_;
    json["combine"]    = combination_ == SweepCombination::product ? "product" : "zip";
    json["parameters"] = nlohmann::ordered_json::array();
    for (const SweepParameter &p : parameters_)
    {
      // Per value the key paths it sets (map values set their own keys, e.g. gap and separation).
      nlohmann::ordered_json settings = nlohmann::ordered_json::array();
      for (const auto &setting : p.settings)
      {
        nlohmann::ordered_json keys = nlohmann::ordered_json::object();
        for (const auto &[path, value] : setting)
          keys[path] = value;
        settings.push_back(keys);
      }
      json["parameters"].push_back({{"name", p.name},
                                    {"key_paths", p.key_paths},
                                    {"values", p.values},
                                    {"settings", settings}});
    }
    json["companions"] = nlohmann::ordered_json::array();
    for (const SweepCompanion &c : companions_)
    {
      nlohmann::ordered_json overrides = nlohmann::ordered_json::object();
      for (const auto &[path, value] : c.overrides)
        overrides[path] = value;
      json["companions"].push_back({{"name", c.name}, {"overrides", overrides}});
    }
    if (report_)
      json["report"] = {{"kind", report_->kind},
                        {"gap", report_->gap_key},
                        {"title", report_->title}};
    json["n_cases"] = cases_.size();
    return json.dump(2);
  }
} // namespace kimp::app
