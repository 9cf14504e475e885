// The yielding moat walls of a `kimp lumped` scene as OpenSees input (docs/physics.md §2
// "Yielding moat wall"): per wall a node with the wall's mass, the wall-and-backfill part
// (ElasticPPGap "damage", HyperbolicGapMaterial, or for a curve envelope one ElasticPPGap
// "damage" per kink of the curve, all in parallel with a Viscous dashpot) in a zeroLength element
// to a fixed ground node, and the contact part (one of the impact materials of
// opensees_impact.tcl) in a zeroLength element from the building's node: the series arrangement.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lumped/laws/wall_backfill_law.h"

namespace kimp::app
{
  struct LumpedScene;

  /// One yielding wall to export, SI.
  struct OpenSeesWall
  {
    std::string                name; ///< "left_wall", "right_wall"
    bool                       right = false;
    double                     mass  = 0.0; ///< the wall DOF's mass, kg
    double                     gap   = 0.0; ///< clear gap of the contact part, m
    lumped::WallBackfillParams part;
  };

  /// A number of the OpenSees files (Tcl and Python): 10 significant figures.
  std::string opensees_number(double value);

  /// One ElasticPPGap spring of a curve envelope's parallel arrangement, SI (positive values; the
  /// files write the yield force negative).
  struct OpenSeesGapSpring
  {
    double stiffness   = 0.0; ///< E_i = s_i − s_{i+1}, N/m
    double yield_force = 0.0; ///< F_y,i = E_i·w_{i+1}, N
  };

  /**
   * The parallel (Iwan) decomposition of the curve envelope of `part`: the segment slopes
   * s_0 > s_1 > ... > s_{n−1}, s_n = 0 past the last point; spring i has E_i = s_i − s_{i+1} and
   * yields at the curve's point w_{i+1} (F_y,i = E_i·w_{i+1}). The sum of the springs is the
   * envelope exactly (ΣE_i = k, ΣF_y,i = the last force). A kink whose slope does not fall (a
   * collinear point, a flat last segment, a rise within the law's round-off allowance of 1e-9
   * of the first slope) gets no spring. @throws std::invalid_argument for a part whose envelope
   * is not a curve.
   */
  std::vector<OpenSeesGapSpring> opensees_curve_springs(const lumped::WallBackfillParams &part);

  /// The yielding walls of `scene` (left first; none: empty).
  std::vector<OpenSeesWall> opensees_walls(const LumpedScene &scene);

  /// Tcl (`python` false) or OpenSeesPy commands of `walls`: material tags from `first_tag`
  /// (per wall the gap materials, one or one per spring of opensees_curve_springs(), then the
  /// dashpot and the Parallel), node tags from `first_node` (two per wall), element tags from
  /// `first_element` (two per wall). The building's node and the contact material are variables
  /// the user sets (kimpBuildingNode, kimpImpactMaterial).
  std::string opensees_walls_text(const std::vector<OpenSeesWall> &walls,
                                  bool                             python,
                                  int                              first_tag     = 11,
                                  int                              first_node    = 1001,
                                  int                              first_element = 1001);

  /**
   * Reads the lumped scene `scene_file` and writes `tcl_file` and `python_file` for its yielding
   * walls (atomic writes). @throws io::SceneError for a bad scene, std::invalid_argument for a
   * scene without a yielding wall.
   */
  void write_opensees_walls(const std::filesystem::path &scene_file,
                            const std::filesystem::path &tcl_file,
                            const std::filesystem::path &python_file);
} // namespace kimp::app
