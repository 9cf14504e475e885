// The Coulomb friction coefficient of a contact as a scene key: its range, >= 0, declared once for
// the FEM's wall-soil interface and the moat wall face of a building in plan.
#pragma once

#include <string_view>

#include "io/scene_io.h"

namespace kimp::app
{
  /// The key `friction`: a Coulomb friction coefficient mu (no unit, >= 0); `doc` says of which
  /// contact.
  template <class Io, class Q>
  void visit_friction(Io &io, Q &friction, std::string_view doc)
  {
    io.quantity("friction", friction, "", doc, io::Range::non_negative());
  }
} // namespace kimp::app
