// The coefficient of restitution as a scene key: its range, (0, 1], declared once for every scene
// and flag that takes a COR or a list of them.
#pragma once

#include <string_view>

#include "io/scene_io.h"

namespace kimp::app
{
  /// The values a coefficient of restitution may take: 0 < e <= 1.
  inline io::Range cor_range()
  {
    return io::Range::greater(0.0).and_at_most(1.0);
  }

  /// The key `cor`: a coefficient of restitution (no unit, cor_range()); `doc` says whose.
  template <class Io, class Q>
  void visit_cor(Io &io, Q &cor, std::string_view doc)
  {
    io.quantity("cor", cor, "", doc, cor_range());
  }
} // namespace kimp::app
