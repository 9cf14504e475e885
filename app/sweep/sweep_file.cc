// Sweep file reading (through the scene reader): the sweep file's sections, its parameters (lists,
// ranges, map values) and companions, checked at the lines of their keys, into a SweepPlan; the
// cases are counted and made on demand in sweep_plan.cc.
#include <algorithm>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "app/sweep/sweep_plan.h"
#include "app/sweep/sweep_values.h"
#include "io/scene_io.h"

namespace kimp::app
{
  using namespace kimp::io;
  namespace sv = sweep_values;
  using sv::fail_at;
  namespace
  {
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

    /// `key_path` checked (sv::check_key_path()), else an error at `line` naming `key`.
    void check_path(const std::string &key_path,
                    const std::string &file,
                    int                line,
                    const std::string &key)
    {
      try
      {
        sv::check_key_path(key_path);
      }
      catch (const std::invalid_argument &error)
      {
        fail_at(file, line, key, error.what());
      }
    }

    /// The `report:` section as read (kind is required: its default is only the example's).
    struct ReportFile
    {
      std::string kind = "gap_study";
      std::string gap  = "walls.left.gap";
      std::string title;
    };

    template <class Io>
    void visit(Io &io, ReportFile &report)
    {
      io.choice("kind",
                report.kind,
                sweep_report_kinds(),
                "charts and summary of scripts/sweep_charts.py (required)");
      io.text("gap", report.gap, "scene key path of the swept gap");
      io.text("title", report.title, "chart and summary title");
    }

    /// A sweep file as read: parameter values and companion overrides stay YAML text, since their
    /// keys and types are those of the base scene.
    struct SweepFile
    {
      std::string                                      scene;
      std::string                                      engine  = "lumped";
      SweepCombination                                 combine = SweepCombination::product;
      std::vector<std::pair<std::string, std::string>> parameters;
      std::vector<std::pair<std::string, std::string>> companions;
      std::optional<ReportFile>                        report;
    };

    template <class Io>
    void visit(Io &io, SweepFile &file)
    {
      io.text("scene", file.scene, "base scene file, relative to the sweep file");
      io.choice("engine",
                file.engine,
                {"lumped"},
                "scene type and runner of every case (lumped is the only engine with a sweep "
                "runner)");
      io.choice("combine",
                file.combine,
                {{"product", SweepCombination::product}, {"zip", SweepCombination::zip}},
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

    /// A sweep file read through the scene reader, with the lines of its keys.
    struct ReadSweepFile
    {
      SweepFile   file;
      SceneSource source;

      /// Line of a key path of the sweep file ("parameters.record[1]"), 1 if it was not written.
      int line(const std::string &key_path) const { return std::max(source.line_of(key_path), 1); }
    };

    ReadSweepFile read_sweep_file(const std::string &text, const std::string &file_name)
    {
      ReadSweepFile read{SweepFile(), SceneSource(file_name)};
      try
      {
        SceneReader reader = SceneReader::root(text, read.source);
        visit(reader, read.file);
        reader.finish();
      }
      catch (const SceneError &error)
      {
        throw SweepError(error.what());
      }
      if (!read.source.present("scene"))
        fail_at(file_name,
                1,
                "scene",
                "missing (expected the base scene file, relative to the sweep file)");
      return read;
    }

    /// One value of a parameter: a scalar, or a map of key paths (and a `label`) set together.
    void read_value(const YAML::Node    &value,
                    const std::string   &item_path,
                    const ReadSweepFile &read,
                    const std::string   &key,
                    SweepParameter      &p)
    {
      const std::string &file_name = read.source.file_name();
      if (!value.IsMap())
      {
        scalar_text(value, file_name, key, read.line(item_path));
        p.values.push_back(sv::value_text(value));
        return;
      }
      std::vector<std::pair<std::string, std::string>> setting;
      std::string                                      label;
      for (const auto &item : value)
      {
        const std::string path      = item.first.Scalar();
        const int         path_line = read.line(item_path + "." + path);
        const std::string item_text =
          scalar_text(item.second, file_name, key + "." + path, path_line);
        if (path == "label")
        {
          label = item_text;
          continue;
        }
        check_path(path, file_name, path_line, key);
        setting.emplace_back(path, sv::value_text(item.second));
      }
      if (setting.empty())
        fail_at(file_name, read.line(item_path), key, "a map value sets no key path");
      if (label.empty())
      {
        YAML::Emitter out;
        out << YAML::Flow << value;
        label = out.c_str();
      }
      p.values.push_back(label);
      p.map_settings.resize(p.values.size());
      p.map_settings.back() = std::move(setting);
    }

    /// A parameter: its key paths and values (a list, or a range {from, to, step}).
    SweepParameter read_parameter(const std::string   &name,
                                  const std::string   &values_text,
                                  const ReadSweepFile &read)
    {
      const std::string &file_name = read.source.file_name();
      SweepParameter     p;
      p.name                = name;
      const std::string key = "parameters." + p.name;
      p.line                = read.line(key);
      std::size_t begin     = 0;
      while (begin <= p.name.size())
      {
        const std::size_t end  = std::min(p.name.find(',', begin), p.name.size());
        std::string       path = p.name.substr(begin, end - begin);
        path.erase(0, path.find_first_not_of(' '));
        path.erase(path.find_last_not_of(' ') + 1);
        if (path.empty())
          fail_at(file_name, p.line, key, "empty key path (expected e.g. walls.left.gap)");
        check_path(path, file_name, p.line, key);
        p.key_paths.push_back(path);
        begin = end + 1;
      }
      const YAML::Node values = YAML::Load(values_text);
      if (values.IsSequence())
        for (std::size_t v = 0; v < values.size(); ++v)
          read_value(values[v], fmt::format("{}[{}]", key, v), read, key, p);
      else if (values.IsMap())
      {
        for (const auto &range_entry : values)
        {
          const std::string k = range_entry.first.Scalar();
          if (k != "from" && k != "to" && k != "step")
            fail_at(file_name,
                    read.line(key + "." + k),
                    key + "." + k,
                    "unknown key (a range has from, to and step)");
        }
        for (const char *k : {"from", "to", "step"})
          if (!values[k])
            fail_at(file_name,
                    p.line,
                    key,
                    std::string("range without '") + k + "' (expected {from, to, step})");
        const auto bound = [&](const char *k)
        { return scalar_text(values[k], file_name, key + "." + k, read.line(key + "." + k)); };
        // Kept as a range: its values are formatted one at a time when a case needs them.
        p.values = SweepValues::range(bound("from"),
                                      bound("to"),
                                      bound("step"),
                                      fmt::format("{}:{}: {}", file_name, p.line, key));
      }
      else
        fail_at(file_name, p.line, key, "expected a list of values or a range {from, to, step}");
      if (p.values.empty())
        fail_at(file_name, p.line, key, "no values (expected at least one)");
      return p;
    }

    SweepCompanion read_companion(const std::string   &name,
                                  const std::string   &overrides_text,
                                  const ReadSweepFile &read)
    {
      const std::string &file_name = read.source.file_name();
      SweepCompanion     c;
      c.name                = name;
      const std::string key = "companions." + c.name;
      c.line                = read.line(key);
      if (c.name.empty() || c.name.find_first_of(" ,\"") != std::string::npos)
        fail_at(file_name, c.line, key, "name must be non-empty without spaces, commas, quotes");
      const YAML::Node overrides = YAML::Load(overrides_text);
      if (!overrides.IsMap() || overrides.size() == 0)
        fail_at(file_name, c.line, key, "expected a non-empty map of key path -> value");
      for (const auto &o : overrides)
      {
        const std::string path = key + "." + o.first.Scalar();
        scalar_text(o.second, file_name, path, read.line(path));
        c.overrides.emplace_back(o.first.Scalar(), sv::value_text(o.second));
      }
      return c;
    }

  } // namespace

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
                                                "bumpers",
                                                "directionality"};
    return kinds;
  }

  std::filesystem::path SweepPlan::base_scene_path(const std::string           &text,
                                                   const std::filesystem::path &sweep_file)
  {
    const std::filesystem::path path(read_sweep_file(text, sweep_file.string()).file.scene);
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
      fail_at(file.string(),
              read_sweep_file(text, file.string()).line("scene"),
              "scene",
              error.what());
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

    const ReadSweepFile read = read_sweep_file(text, file_name);
    const SweepFile    &file = read.file;
    if (file.report)
    {
      SweepReportSpec spec;
      spec.line    = read.line("report");
      spec.kind    = file.report->kind;
      spec.gap_key = file.report->gap;
      spec.title   = file.report->title;
      if (!read.source.present("report.kind"))
        fail_at(file_name,
                spec.line,
                "report.kind",
                "missing (expected one of " + detail::join(sweep_report_kinds(), ", ") + ")");
      check_path(spec.gap_key, file_name, read.line("report.gap"), "report.gap");
      plan.report_ = std::move(spec);
    }
    plan.engine_      = file.engine;
    plan.combination_ = file.combine;

    if (file.parameters.empty())
      fail_at(file_name,
              read.line("parameters"),
              "parameters",
              "missing or empty (expected a map: scene key path -> list of values or "
              "{from, to, step})");
    for (const auto &[name, values_text] : file.parameters)
      plan.parameters_.push_back(read_parameter(name, values_text, read));
    for (const auto &[name, overrides_text] : file.companions)
      plan.companions_.push_back(read_companion(name, overrides_text, read));
    plan.count_cases(check_count);
    return plan;
  }
} // namespace kimp::app
