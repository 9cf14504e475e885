// The step budget of a run as a scene key: the most time steps a case may take before it is
// refused with its estimate, declared once for the FEM and the building scenes.
#pragma once

#include <string_view>

#include "io/scene_io.h"

namespace kimp::app
{
  /// The key `max_steps`: the largest number of time steps of a case (no unit, >= 1); `doc` says
  /// how the steps are counted and what the refusal reports.
  template <class Io>
  void visit_max_steps(Io &io, double &max_steps, std::string_view doc)
  {
    io.quantity("max_steps", max_steps, "", doc, io::Range::at_least(1.0));
  }
} // namespace kimp::app
