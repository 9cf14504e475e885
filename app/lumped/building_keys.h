// Scene keys of a building scene that stand in several sections, each kind declared once with its
// display unit and range: a viscous damping ratio, the gap of a moat wall, a mass and a stiffness.
#pragma once

#include <string_view>

#include "io/scene_io.h"

namespace kimp::app
{
  /// The values a viscous damping ratio ζ may take: 0 <= ζ < 1 (underdamped).
  inline io::Range damping_ratio_range()
  {
    return io::Range::at_least(0.0).and_less(1.0);
  }

  /// A damping ratio key (shown in %, damping_ratio_range()); `doc` says whose damping it is.
  template <class Io, class Q>
  void visit_damping_ratio(Io &io, std::string_view key, Q &ratio, std::string_view doc)
  {
    io.quantity(key, ratio, "%", doc, damping_ratio_range());
  }

  /// The values the clear gap of a moat wall may take: 0 < gap <= 10 m.
  inline io::Range moat_gap_range()
  {
    return io::Range::positive().and_at_most(10.0).because("a moat gap is not wider");
  }

  /// A moat gap key (shown in cm, moat_gap_range()); `doc` says which walls it sets.
  template <class Io, class Q>
  void visit_moat_gap(Io &io, std::string_view key, Q &gap, std::string_view doc)
  {
    io.quantity(key, gap, "cm", doc, moat_gap_range());
  }

  /// A mass key: a floor, a wall, a body of a collision (shown in t, > 0); `doc` says whose.
  template <class Io, class Q>
  void visit_mass(Io &io, std::string_view key, Q &mass, std::string_view doc)
  {
    io.quantity(key, mass, "t", doc, io::Range::positive());
  }

  /// A lateral stiffness key: a storey, an isolator, a flexible wall, a plan element (shown in
  /// MN/m, > 0, or `range` where zero is admitted: a post-yield branch, an element stiff along one
  /// axis only); `doc` says whose.
  template <class Io, class Q>
  void visit_stiffness(Io              &io,
                       std::string_view key,
                       Q               &stiffness,
                       std::string_view doc,
                       const io::Range &range = io::Range::positive())
  {
    io.quantity(key, stiffness, "MN/m", doc, range);
  }
} // namespace kimp::app
