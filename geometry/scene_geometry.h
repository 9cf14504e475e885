// Parameters of the plane-strain impact scene of docs/physics.md §4: slab, cantilever moat wall and
// backfill block (x horizontal, slab moving +x; y up; ground at y = 0; wall contact face x = 0).
#pragma once

#include <optional>

namespace kimp::geometry
{
  /**
   * The scene: three axis-aligned rectangles (all lengths in m).
   *
   * | region   | x range                              | y range                       |
   * |----------|--------------------------------------|-------------------------------|
   * | slab     | [−gap − slab_length, −gap]           | [top − slab_thickness, top]   |
   * | wall     | [0, wall_thickness]                  | [0, wall_height]              |
   * | backfill | [wall_thickness, wall_thickness + B] | [0, H_b]                      |
   *
   * with top = slab_top (default: the wall top), B = backfill_width and H_b = backfill_height
   * (default: the wall height). The backfill is bonded to the wall on x = wall_thickness,
   * y in [0, H_b]. Mesh sizes: h_contact at the contact (wall face in the slab's band and slab
   * front), growing away from it by at most the factor `grading` per element up to h_max.
   *
   * Plain aggregate: fill it, then call validate() before meshing.
   */
  struct SceneGeometry
  {
    double wall_height    = 1.25; ///< H, m
    double wall_thickness = 0.25; ///< t_w, m

    bool                  with_backfill  = true; ///< false: bare cantilever wall
    double                backfill_width = 2.0;  ///< B, m
    std::optional<double> backfill_height;       ///< H_b, m; default wall_height; 0 < H_b <= H

    double                slab_length    = 8.0;  ///< L, m
    double                slab_thickness = 0.20; ///< t_s, m
    std::optional<double> slab_top;              ///< y of the slab top, m; default wall_height

    double gap = 0.5e-3; ///< initial clear distance between slab front and wall face, m

    bool mesh_slab = true; ///< false: rigid slab, no slab cells are written
    /**
     * false: wall and backfill share the nodes of their interface (bonded). true: the backfill
     * has its own interface nodes, and the faces are tagged wall_back and soil_front
     * (scene_ids.h) for a contact interface.
     */
    bool interface_contact = false;

    double h_contact = 0.025; ///< element size at the contact, m
    double h_max     = 0.10;  ///< largest element size away from the contact, m
    double grading   = 1.15;  ///< largest size ratio of neighbouring elements, >= 1
    /**
     * Largest height/width of the wall's cells (and so of the backfill's rows beside them,
     * which share the wall's horizontal grid lines), >= 1; unset: the rows grow to h_max.
     * Plain Q1 cells much taller than wide lock in bending (parasitic shear), and a cracked,
     * reinforced wall on them resists about twice its section's capacity (docs/validation.md
     * "What the dynamic FEM's wall resists").
     */
    std::optional<double> wall_aspect_max;

    /** H_b in m: backfill_height if given, else wall_height. */
    double resolved_backfill_height() const;

    /** y of the slab top in m: slab_top if given, else wall_height. */
    double resolved_slab_top() const;

    /** y of the slab bottom in m: resolved_slab_top() − slab_thickness. */
    double slab_bottom() const;

    /** x of the slab contact face in m: −gap. The wall contact face is x = 0. */
    double slab_front_x() const { return -gap; }

    /**
     * Checks every parameter and the cross-field rules (positive sizes, slab between the ground
     * and the wall top, no overlap (gap > 0), backfill not above the wall, h_contact <= h_max,
     * h_contact not larger than the wall or slab thickness, grading >= 1, wall_aspect_max >= 1).
     * @throws std::invalid_argument whose message names the parameter (`geometry.<name>`), its
     *         value with unit and the admissible range.
     */
    void validate() const;
  };

  /**
   * The mesh ladder: @p geometry with h_contact and h_max divided by 2^level (grading and
   * wall_aspect_max kept), so every element size halves per level.
   * @param[in] level >= 0; 0 returns @p geometry unchanged.
   * @throws std::invalid_argument if level < 0 or level > 10.
   */
  SceneGeometry refined(const SceneGeometry &geometry, int level);
} // namespace kimp::geometry
