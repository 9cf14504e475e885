// FEM runs and wall-height studies for Python (FEM build only): `kimp fem` and `kimp study` into a
// directory, with the GIL released. MPI (and p4est) start once, at the first FEM use.
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <pybind11/stl.h>
#include <string>

#include "python/bindings.h"
#ifdef KIMP_WITH_FEM
#  include "app/fem/fem_run.h"
#  include "app/fem/fem_scene.h"
#  include "app/fem/pushover_run.h"
#  include "app/session.h"
#  include "app/study/study_run.h"
#  include "app/study/study_scene.h"
#  include "io/scene_io.h"
#  include "io/summary.h"
#endif

namespace kimp::python
{
#ifdef KIMP_WITH_FEM
  namespace
  {
    std::unique_ptr<app::Session> &session_slot()
    {
      static std::unique_ptr<app::Session> session;
      return session;
    }

    /// The process's session (a singleton process, no mpirun needed), created on first use and
    /// ended by Python's atexit, before the interpreter unloads the module. Called with the GIL
    /// held; MPI starts with it released, so other Python threads run meanwhile.
    void ensure_session()
    {
      static std::once_flag once;
      bool                  created = false;
      {
        py::gil_scoped_release release;
        std::call_once(once,
                       [&created]
                       {
                         static int    argc   = 1;
                         static char   name[] = "kimp";
                         static char  *args[] = {name, nullptr};
                         static char **argv   = args;
                         session_slot()       = std::make_unique<app::Session>(argc, argv);
                         created              = true;
                       });
      }
      if (created)
        py::module_::import("atexit").attr("register")(
          py::cpp_function([] { session_slot().reset(); }));
    }

    std::filesystem::path directory(const std::optional<std::string> &text)
    {
      return text ? std::filesystem::path(*text) : std::filesystem::path();
    }

    /// `m.<python_name>(text, name, output, directory=None)`: the scene text read as the CLI reads
    /// it, then `run(scene, output)` with the GIL released.
    template <class Scene, class Run>
    void def_scene_run(py::module_ &m, const char *python_name, Run run, const char *doc)
    {
      m.def(
        python_name,
        [run](const std::string                &text,
              const std::string                &name,
              const std::string                &output,
              const std::optional<std::string> &scene_directory)
        {
          ensure_session();
          py::gil_scoped_release release;
          run(io::read_scene_text<Scene>(text, name, directory(scene_directory)), output);
        },
        py::arg("text"),
        py::arg("name"),
        py::arg("output"),
        py::arg("directory") = py::none(),
        doc);
    }
  } // namespace

  void register_fem(py::module_ &m)
  {
    def_scene_run<app::FemScene>(
      m,
      "run_fem",
      [](const io::LoadedScene<app::FemScene> &scene, const std::string &output)
      { app::run_fem(scene, io::OutputDir(output)); },
      "`kimp fem` of a scene text into the directory `output` (fem.h5, summary.json, ...).");
    def_scene_run<app::FemScene>(
      m,
      "run_fem_pushover",
      [](const io::LoadedScene<app::FemScene> &scene, const std::string &output)
      { app::run_fem_pushover(scene, io::OutputDir(output)); },
      "`kimp fem --pushover` of a scene text into the directory `output` (pushover.h5, "
      "pushover.csv, pushover_summary.csv, charts/).");
    def_scene_run<app::StudyScene>(
      m,
      "run_study",
      [](const io::LoadedScene<app::StudyScene> &scene, const std::string &output)
      { app::run_study_job(scene, output); },
      "`kimp study` of a scene text into the directory `output` (study.h5, k_table.csv, ...).");
  }
#else
  void register_fem(py::module_ &) {}
#endif
} // namespace kimp::python
