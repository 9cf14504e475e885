// The compiled part of the Python module kimp (kimp._kimp): scenes, lumped runs, laws, collisions,
// ground motions, fits and (FEM build) FEM runs and studies; the package kimp/ wraps it. Only
// this file calls the parts' register_*() functions; the parts call nothing here.
#include <pybind11/pybind11.h>
#include <stdexcept>
#include <string>

#include "base/logging.h"
#include "io/scene_io.h"
#include "io/units.h"

#include "python/bindings.h"

PYBIND11_MODULE(_kimp, m)
{
  namespace py = pybind11;
  m.doc()      = "kimp's engines (lumped pounding, impact laws, fitter, FEM) for the package kimp";
  // Scene errors keep the CLI's message; kimp.SceneError (kimp/_scene.py) adds file, line, key.
  py::register_exception<kimp::io::SceneError>(m, "SceneError", PyExc_ValueError);
  py::register_exception<kimp::io::UnitError>(m, "UnitError", PyExc_ValueError);
  kimp::python::register_scene(m);
  kimp::python::register_lumped(m);
  kimp::python::register_laws(m);
  kimp::python::register_fem(m);
  m.def(
    "set_verbosity",
    [](const std::string &level)
    {
      using kimp::base::Verbosity;
      if (level == "quiet")
        kimp::base::set_verbosity(Verbosity::quiet);
      else if (level == "normal")
        kimp::base::set_verbosity(Verbosity::normal);
      else if (level == "verbose")
        kimp::base::set_verbosity(Verbosity::verbose);
      else
        throw std::invalid_argument("verbosity '" + level +
                                    "' is not one of quiet, normal, verbose");
    },
    py::arg("level"),
    "What the engines log on stderr: 'quiet' (warnings and errors), 'normal' (also the "
    "progress of each run, as the CLI without -q), 'verbose' (also debug lines).");
#ifdef KIMP_WITH_FEM
  m.attr("with_fem") = true;
#else
  m.attr("with_fem") = false;
#endif
}
