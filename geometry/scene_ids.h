// Numeric ids shared by geometry/ (gmsh physical groups) and fem/ (deal.II material and boundary
// ids). fem/ knows the scene only through these numbers.
#pragma once

#include <cstdint>

namespace kimp::geometry
{
  /// Material ids (2D physical groups).
  enum MaterialId : std::uint8_t
  {
    slab_material = 1,
    wall_material = 2,
    soil_material = 3
  };

  /// Boundary ids (1D physical groups). Interior bonded faces (wall-soil) carry none.
  /// 0 is never used: deal.II gives boundary faces without a group id 0, which means free
  /// (wall top and exposed back, soil top, slab top, bottom and back). The whole wall front face
  /// x = 0, y in [0, H] is wall_contact, not only the part the slab can reach.
  enum BoundaryId : std::uint8_t
  {
    fixed_base    = 1, ///< bottom of wall and backfill: u = 0
    soil_far_side = 2, ///< far vertical side of the backfill: rollers, u_x = 0
    slab_contact  = 3, ///< slab front face (slave side of the contact)
    wall_contact  = 4, ///< wall front face (master side of the contact)
    /// With a wall-soil contact interface (SceneGeometry::interface_contact) only: the wall's
    /// back face against the backfill, y in [0, H_b], and the backfill's front face on it, each
    /// with its own nodes at the same places.
    wall_back  = 5,
    soil_front = 6
  };
} // namespace kimp::geometry
