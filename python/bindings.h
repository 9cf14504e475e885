// Shared pieces of the pybind11 extension kimp._kimp: the registration function of each part and
// the hand-over of C++ vectors to numpy without a copy.
#pragma once

#include <memory>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <string>
#include <utility>
#include <vector>

namespace kimp::python
{
  namespace py = pybind11;

  /**
   * A numpy array that owns `values` (moved into a capsule, freed with the array), row-major with
   * the given shape; an empty shape gives a 1-D array of all values. No copy of the data.
   */
  template <class T>
  py::array_t<T> to_numpy(std::vector<T> &&values, std::vector<py::ssize_t> shape = {})
  {
    if (values.empty())
      return py::array_t<T>(shape.empty() ? std::vector<py::ssize_t>{0} : shape);
    auto       *owner = new std::vector<T>(std::move(values));
    py::capsule capsule(owner, [](void *p) { delete static_cast<std::vector<T> *>(p); });
    if (shape.empty())
      shape = {static_cast<py::ssize_t>(owner->size())};
    return py::array_t<T>(shape, owner->data(), capsule);
  }

  /// Any array-like of numbers, as a contiguous array of double (converted if needed).
  using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

  /// A copy of a numpy array (any float-convertible input) as a std::vector<double>.
  inline std::vector<double> to_vector(const DoubleArray &array)
  {
    return std::vector<double>(array.data(), array.data() + array.size());
  }

  /// A scene read and validated once: its kind, name (the file name of its messages), text,
  /// resolved JSON (SI) and the scene struct (app::LumpedScene for kind "lumped", ...), so a run
  /// does not parse the text again.
  struct ParsedScene
  {
    std::string                 kind;
    std::string                 name;
    std::string                 text;
    std::string                 resolved;
    std::shared_ptr<const void> scene;

    template <class Scene>
    const Scene &as() const
    {
      return *std::static_pointer_cast<const Scene>(scene);
    }
  };

  void register_scene(py::module_ &m);
  void register_lumped(py::module_ &m);
  void register_laws(py::module_ &m);
  void register_fem(py::module_ &m);
} // namespace kimp::python
