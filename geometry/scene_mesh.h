// Meshing of the docs/physics.md §4 scene: structured bilinear quadrilaterals written as ASCII
// MSH 4.1 with the numeric physical groups of geometry/scene_ids.h (readable by deal.II
// GridIn::read_msh).
#pragma once

#include <cstddef>
#include <filesystem>
#include <iosfwd>

#include "geometry/scene_geometry.h"

namespace kimp::geometry
{
  /** What build_scene_mesh() wrote (lengths in m). */
  struct MeshStatistics
  {
    std::size_t n_nodes      = 0;
    std::size_t n_cells      = 0; ///< all quads
    std::size_t n_slab_cells = 0; ///< material slab_material (0 for a rigid slab)
    std::size_t n_wall_cells = 0; ///< material wall_material
    std::size_t n_soil_cells = 0; ///< material soil_material (0 without backfill)

    std::size_t n_slab_contact_faces = 0; ///< boundary slab_contact (0 for a rigid slab)
    std::size_t n_wall_contact_faces = 0; ///< boundary wall_contact

    double min_cell_size = 0; ///< shortest cell edge
    double max_cell_size = 0; ///< longest cell edge
    /** Longest edge of the cells touching a contact face (wall face within the slab's band, slab
     *  front): the resolution of the contact, <= h_contact. */
    double contact_cell_size = 0;

    double max_neighbour_ratio = 1; ///< largest size ratio of neighbouring cells (<= grading)
    double max_aspect_ratio    = 1; ///< largest longest/shortest edge ratio of one cell
    /** Smallest sine of a cell corner angle over all cells (1: rectangles; <= 0: invalid). */
    double min_scaled_jacobian = 1;
  };

  /** One-line summary of @p statistics for logs. */
  std::ostream &operator<<(std::ostream &out, const MeshStatistics &statistics);

  /**
   * Builds the scene mesh and writes it to @p msh_file (parent directories created, an existing
   * file replaced).
   *
   * The mesh: three structured blocks of bilinear 4-node quadrilaterals (SceneLayout grid lines),
   * nodes numbered counter-clockwise, wall and soil sharing the nodes of their bonded interface.
   * Physical groups (numeric tags of scene_ids.h, with names):
   * - 2D: slab_material (only if geometry.mesh_slab), wall_material, soil_material (only with
   *   backfill);
   * - 1D: fixed_base (bottom of wall and backfill), soil_far_side (backfill x = t_w + B; only
   *   with backfill), slab_contact (slab front face x = −gap; only if mesh_slab), wall_contact
   *   (the whole wall front face x = 0, y in [0, H]); with geometry.interface_contact also
   *   wall_back (x = t_w, y in [0, H_b], wall nodes) and soil_front (the same line, the soil's
   *   own nodes: the interface is then not bonded).
   * No other face is tagged: the bonded interface carries no group (deal.II does not read ids on
   * internal faces) and the free edges (wall top, exposed wall back above H_b, soil top, slab top,
   * bottom and back) get deal.II's default boundary id 0. Every entity has exactly one physical
   * group. Format: MSH 4.1 ASCII, only elements of physical groups (no points, no unused nodes).
   * The file is checked complete (it ends with a section end and is synced to disk: gmsh reports
   * no write error). Writing under a temporary name and renaming is the caller's (app's
   * write_scene_mesh() through io::TemporaryFile).
   *
   * Not thread safe (gmsh is a global singleton; see GmshSession). Does not print.
   * @throws std::invalid_argument from geometry.validate(); std::runtime_error if the file cannot
   *         be written.
   */
  MeshStatistics build_scene_mesh(const SceneGeometry         &geometry,
                                  const std::filesystem::path &msh_file);
} // namespace kimp::geometry
