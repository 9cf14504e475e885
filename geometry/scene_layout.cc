// Grid lines of the scene blocks from the graded size fields (see header and graded_spacing.h).
#include "geometry/scene_layout.h"

#include <algorithm>
#include <stdexcept>

#include "geometry/graded_spacing.h"

namespace kimp::geometry
{
  SceneLayout SceneLayout::build(const SceneGeometry &geometry)
  {
    geometry.validate();

    const double h_c      = geometry.h_contact;
    const double h_max    = geometry.h_max;
    const double grading  = geometry.grading;
    const double height   = geometry.wall_height;
    const double t_w      = geometry.wall_thickness;
    const double y_top    = geometry.resolved_slab_top();
    const double y_bottom = geometry.slab_bottom();

    SceneLayout layout;

    // Vertical lines of wall and soil: one axis with the wall as fine zone, so the sizes grow
    // smoothly into the soil starting from the wall's own element size.
    const double        x_end = geometry.with_backfill ? t_w + geometry.backfill_width : t_w;
    const GradedSpacing horizontal(0.0, t_w, h_c, h_max, grading);
    const auto          x_lines = horizontal.nodes(0.0, x_end, {t_w});
    const auto          wall_end =
      std::find(x_lines.begin(), x_lines.end(), t_w); // t_w is a breakpoint, hence a node
    if (wall_end == x_lines.end())
      throw std::logic_error("SceneLayout: wall back face is not a grid line");
    layout.wall_x.assign(x_lines.begin(), wall_end + 1);
    if (geometry.with_backfill)
      layout.soil_x.assign(wall_end, x_lines.end());

    // Horizontal lines of wall and soil: fine in the band the slab front can touch, with grid
    // lines at the band edges so that the slab's nodes face wall nodes, unless forcing them breaks
    // the grading (band edges within about h_max of H_b or the wall ends; see GradedSpacing).
    // The wall's rows are at most wall_aspect_max times its (uniform) column width; the slab's
    // rows keep h_max.
    const double        wall_width = layout.wall_x[1] - layout.wall_x[0];
    const double        h_rows     = geometry.wall_aspect_max ?
                                       std::min(h_max, std::max(h_c, *geometry.wall_aspect_max * wall_width)) :
                                       h_max;
    const GradedSpacing vertical(y_bottom, y_top, h_c, h_max, grading);
    const GradedSpacing wall_vertical(y_bottom, y_top, h_c, h_rows, grading);
    std::vector<double> forced;
    if (geometry.with_backfill)
      forced.push_back(geometry.resolved_backfill_height());
    std::vector<double> with_band = forced;
    with_band.insert(with_band.end(), {y_bottom, y_top});
    layout.wall_y = wall_vertical.nodes(0.0, height, with_band);
    if (max_neighbour_ratio(layout.wall_y) > grading * (1.0 + 1e-12))
      layout.wall_y = wall_vertical.nodes(0.0, height, forced);
    if (geometry.with_backfill)
    {
      const double h_b = geometry.resolved_backfill_height();
      const auto   top = std::find(layout.wall_y.begin(), layout.wall_y.end(), h_b);
      if (top == layout.wall_y.end())
        throw std::logic_error("SceneLayout: backfill top is not a wall grid line");
      layout.soil_y.assign(layout.wall_y.begin(), top + 1);
    }

    // Slab: coarse toward the far end. The fine zone is one h_contact deep (not the face line
    // alone), so that the front column itself is no wider than h_contact.
    const double        x_front = geometry.slab_front_x();
    const GradedSpacing along_slab(x_front - h_c, x_front, h_c, h_max, grading);
    layout.slab_x = along_slab.nodes(x_front - geometry.slab_length, x_front);
    layout.slab_y = vertical.nodes(y_bottom, y_top);

    return layout;
  }
} // namespace kimp::geometry
