// The structured (tensor-product) grid lines of the scene: graded 1D node lists per axis and
// region, refined toward the contact (docs/physics.md §4 scene, sizes of SceneGeometry).
#pragma once

#include <vector>

#include "geometry/scene_geometry.h"

namespace kimp::geometry
{
  /**
   * Grid-line coordinates (m, strictly increasing) of the three structured blocks. Each block's
   * mesh is the tensor product of its x and y lists, so all quads are rectangles.
   *
   * - wall_y has sizes <= h_contact in the slab's band [slab_bottom, slab top], growing away
   *   from it, a node at H_b, and nodes at the band edges unless forcing them would break the
   *   grading (then the band is still fine but its edges may fall inside elements); in the
   *   default scene the band is divided exactly as slab_y. Its sizes are at most
   *   wall_aspect_max × the wall's column width where that is set (and at least h_contact).
   *   soil_y is the prefix of wall_y up to H_b, which makes the bonded wall-soil interface
   *   conforming.
   * - wall_x is uniform (size <= h_contact); soil_x starts at wall_thickness and grows from the
   *   wall's size to h_max (empty without backfill).
   * - slab_x grows from h_contact at the front x = −gap to h_max toward the far end; slab_y is
   *   uniform (size <= h_contact).
   */
  struct SceneLayout
  {
    std::vector<double> slab_x, slab_y;
    std::vector<double> wall_x, wall_y;
    std::vector<double> soil_x, soil_y;

    /**
     * Grid of @p geometry (validated first; throws std::invalid_argument as validate()).
     * The slab lists are filled even for a rigid slab (mesh_slab = false).
     */
    static SceneLayout build(const SceneGeometry &geometry);
  };
} // namespace kimp::geometry
