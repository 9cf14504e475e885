// Scene keys of the moat wall a building hits, each declared once with its display unit and
// range: the width of the building side that hits it (the length that turns a per-metre
// stiffness or force into the whole wall's) and the wall's height.
#pragma once

#include <string_view>

#include "io/scene_io.h"

namespace kimp::app
{
  /// The key `width`: the wall length the building side hits (m, > 0), k_total = k per metre x
  /// width; `doc` says what it scales.
  template <class Io>
  void visit_building_width(Io &io, double &width, std::string_view doc)
  {
    io.quantity("width", width, "m", doc, io::Range::positive());
  }

  /// A height of the moat wall (m, > 0); `doc` says what it sets.
  template <class Io, class Q>
  void visit_wall_height(Io &io, std::string_view key, Q &height, std::string_view doc)
  {
    io.quantity(key, height, "m", doc, io::Range::positive());
  }
} // namespace kimp::app
