// Scenes for Python: validation through the CLI's reader (io::read_scene_text), the schema and the
// annotated defaults of every scene kind, and unit parsing (io/units.h).
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <pybind11/stl.h>
#include <stdexcept>
#include <string>

#include "app/lumped/collide_run.h"
#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_scene.h"
#include "io/scene_io.h"
#include "io/units.h"

#include "python/bindings.h"
#ifdef KIMP_WITH_FEM
#  include "app/fem/fem_scene.h"
#  include "app/study/study_scene.h"
#endif

namespace kimp::python
{
  namespace
  {
    /// A scene's resolved JSON as its command writes it.
    template <class Scene>
    std::string resolved_json(io::LoadedScene<Scene> &loaded)
    {
      return std::move(loaded.resolved_json);
    }

    /// `kimp lumped`: a scene without `plan` resolves as the planar scene it is (no `plan: null`).
    std::string resolved_json(io::LoadedScene<app::PlanLumpedScene> &loaded)
    {
      return loaded.scene.plan ? std::move(loaded.resolved_json) :
                                 io::to_json_text(loaded.scene.base);
    }

    /// What Python needs of one scene kind.
    struct SceneKind
    {
      std::function<
        ParsedScene(const std::string &, const std::string &, const std::optional<std::string> &)>
                                   validate;
      std::function<std::string()> schema;
      std::function<std::string()> defaults;
    };

    template <class Scene>
    SceneKind scene_kind(const char *title)
    {
      return {[](const std::string                &text,
                 const std::string                &name,
                 const std::optional<std::string> &given_directory)
              {
                // Paths in the scene are relative to `given_directory`, else (a scene read from
                // a file, which Scene.from_yaml names by its path) to the file's directory, as
                // on the command line.
                std::error_code             ec;
                const std::filesystem::path file(name);
                const std::filesystem::path directory =
                  given_directory ? std::filesystem::path(*given_directory) :
                  std::filesystem::is_regular_file(file, ec) ? file.parent_path() :
                                                               std::filesystem::path();
                io::LoadedScene<Scene> loaded   = io::read_scene_text<Scene>(text, name, directory);
                std::string            resolved = resolved_json(loaded);
                return ParsedScene{"",
                                   name,
                                   text,
                                   std::move(resolved),
                                   std::make_shared<const Scene>(std::move(loaded.scene))};
              },
              [] { return io::schema_text<Scene>(); },
              [title] { return io::default_scene_text<Scene>(title); }};
    }

    const std::map<std::string, SceneKind> &scene_kinds()
    {
      static const std::map<std::string, SceneKind> kinds = {
        {"lumped", scene_kind<app::PlanLumpedScene>("kimp lumped scene")},
        {"collide", scene_kind<app::CollideScene>("kimp collide scene")},
#ifdef KIMP_WITH_FEM
        {"fem", scene_kind<app::FemScene>("kimp fem scene")},
        {"study", scene_kind<app::StudyScene>("kimp study scene")},
#endif
      };
      return kinds;
    }

    const SceneKind &find_kind(const std::string &kind)
    {
      const auto &kinds = scene_kinds();
      const auto  it    = kinds.find(kind);
      if (it == kinds.end())
      {
        std::string known;
        for (const auto &[name, unused] : kinds)
          known += (known.empty() ? "" : ", ") + name;
        throw std::invalid_argument("unknown scene kind '" + kind + "' (known: " + known + ")");
      }
      return it->second;
    }
  } // namespace

  void register_scene(py::module_ &m)
  {
    py::class_<ParsedScene>(m, "ParsedScene")
      .def_readonly("kind", &ParsedScene::kind)
      .def_readonly("name", &ParsedScene::name)
      .def_readonly("resolved", &ParsedScene::resolved);
    m.def("scene_kinds",
          []
          {
            std::vector<std::string> names;
            for (const auto &[name, unused] : scene_kinds())
              names.push_back(name);
            return names;
          });
    m.def(
      "validate_scene",
      [](const std::string                &kind,
         const std::string                &text,
         const std::string                &name,
         const std::optional<std::string> &directory)
      {
        ParsedScene parsed = find_kind(kind).validate(text, name, directory);
        parsed.kind        = kind;
        return parsed;
      },
      py::arg("kind"),
      py::arg("text"),
      py::arg("name"),
      py::arg("directory") = py::none(),
      "Read and validate a scene as the CLI does (a ParsedScene); its relative paths are "
      "resolved against `directory` (default: the directory of the file `name`, if it is one). "
      "Raises SceneError with the CLI's message.");
    m.def(
      "read_text_file",
      [](const std::string &path) { return io::detail::read_text_file(path); },
      py::arg("path"),
      "The whole file; SceneError with the CLI's message if it cannot be read.");
    m.def(
      "scene_schema",
      [](const std::string &kind) { return find_kind(kind).schema(); },
      py::arg("kind"));
    m.def(
      "default_scene",
      [](const std::string &kind) { return find_kind(kind).defaults(); },
      py::arg("kind"));
    m.def(
      "si_unit",
      [](const std::string &unit)
      {
        std::string text = io::to_string(io::parse_unit(unit).dimension);
        for (char &c : text)
          if (c == ' ')
            c = '*';
        return text;
      },
      py::arg("unit"),
      "The SI unit of the dimension of `unit` in the scene grammar, e.g. 'kg*s^-2' for 'MN/m'.");
    m.def("parse_quantity",
          &io::parse_quantity_as,
          py::arg("text"),
          py::arg("expected_unit"),
          "SI value of a quantity text such as '600 MN/m' of the dimension of `expected_unit`.");
    m.def("format_quantity",
          &io::format_quantity,
          py::arg("value"),
          py::arg("display_unit"),
          "Text of an SI value in `display_unit` (15 significant digits).");
  }
} // namespace kimp::python
