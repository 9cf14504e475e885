// The moat wall around the base slab in plan (docs/physics.md "Pounding in plan", "Moat wall
// in plan"): a rigid polygon of wall faces moving with the ground, contact points on the slab's
// edges (the corners by default), a normal force from one of the impact laws 1-7 of the planar
// model per point and regularised Coulomb friction along the wall.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "lumped/laws/force_law.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/wall_backfill_law.h"
#include "lumped/plan/plan_building.h"

namespace kimp::lumped::plan
{
  /**
   * A rigid moat wall around the isolation level (level 0).
   *
   * Stiffness: `law.stiffness` (and a bumper law's `bumper_wall_stiffness`) is per metre of slab
   * edge, as the FEM gives it: the law of a slab edge of length ℓ facing a wall face has k·ℓ, the
   * planar wall's k_total. It is lumped at `points_per_edge` points of the edge with trapezoid
   * weights (2: the two corners, ½ each), every point with its own law (own history) whose force
   * is multiplied by its weight: an edge striking flat gives the planar force exactly, a corner
   * striking alone half of it. More points per edge spread the edge's stiffness along it (a
   * Winkler contact whose stiffness scales with the length in contact).
   *
   * | field           | unit | admissible       | meaning                                    |
   * |-----------------|------|------------------|--------------------------------------------|
   * | wall            | m    | simple polygon   | wall faces, enclosing level 0's outline     |
   * | law             | SI   | ForceLawSpec     | normal impact law, k per metre of edge     |
   * | mass            | kg   | > 0              | wall mass in m_eff = m_0·m_w/(m_0 + m_w)   |
   * | friction        | -    | >= 0             | Coulomb μ along the wall face              |
   * | stick_velocity  | m/s  | > 0              | v_s of the regularised friction law        |
   * | points_per_edge | -    | >= 2             | contact points per slab edge               |
   * | facing_cosine   | -    | (0, 1]           | an edge meets a wall face whose normal is  |
   * |                 |      |                  | within acos(this) of its own (default 0.5) |
   * | yielding        | SI   | PlanYieldingWall | faces with a yielding wall (convex wall    |
   * |                 |      |                  | polygon only)                              |
   */
  /**
   * A yielding wall face: the contact law of its points in series with a wall-and-backfill part
   * (lumped::WallBackfillLaw, docs/physics.md §2 "Yielding moat wall") on a DOF of its own, w,
   * the face's displacement along its normal away from the slab, relative to the ground:
   *   m·ẅ = −m·(n·ü_g) + Σ_c w_c·F_c − F(w, ẇ),   δ_c = n_c·q_0 − gap_c − w,
   * so the permanent set moves that face back (the next impact comes at a larger gap).
   * `params` are the whole face's (stiffness, capacity and dashpot of the face, not per metre);
   * params.mass is the DOF's mass m (> 0).
   */
  struct PlanYieldingWall
  {
    /// Wall face j: vertex j to j + 1 of `wall` ordered counter-clockwise (the contacts'
    /// `segment`).
    std::size_t        segment = 0;
    WallBackfillParams params;
  };

  struct PlanMoat
  {
    Polygon      wall;
    ForceLawSpec law;
    double       mass            = 500e3;
    double       friction        = 0.0;
    double       stick_velocity  = 1e-3;
    int          points_per_edge = 2;
    double       facing_cosine   = 0.5;
    /// Faces carrying a yielding wall (at most one entry per face; the others are rigid).
    std::vector<PlanYieldingWall> yielding;
  };

  /// The moat polygon at `gaps` (one per slab edge, or one for all; m) around level 0's outline
  /// (moat_polygon()).
  Polygon moat_around(const PlanBuilding &building, const std::vector<double> &gaps);

  /**
   * One contact point of the slab against one wall face, or (`point` = points_per_edge) a
   * re-entrant corner of the wall against a slab edge: then n_row and t_row are the edge's
   * normal and direction at the edge's point facing the corner, `segment` the corner's index. With
   * q_0 the DOFs of level 0: δ = n_row·q_0 − gap (interpenetration, > 0 in contact), s = s_rest +
   * t_row·q_0 its coordinate along the face (in contact only while s_lo <= s <= s_hi; a face ends
   * only at a re-entrant corner of the wall, at a convex one the limit is infinite: past it the
   * point is inside the corner block and meets both faces).
   */
  struct PlanContact
  {
    std::string        name; ///< "edge<e>_point<k>_wall<j>" or "edge<e>_wallcorner<j>"
    std::size_t        edge = 0, point = 0, segment = 0;
    Point              position;     ///< material point at rest, m
    Eigen::RowVector3d normal_row;   ///< dδ/dq_0 (wall normal away from the slab)
    Eigen::RowVector3d tangent_row;  ///< ds/dq_0 (along the face, wall vertex j to j + 1)
    double             gap    = 0.0; ///< clear gap at rest, m
    double             s_rest = 0.0, s_lo = 0.0, s_hi = 0.0; ///< m
    double             weight          = 0.0;                ///< share of the edge's law force
    double             effective_mass  = 0.0;                ///< the law's m_eff, kg
    double             tangential_mass = 0.0;                ///< 1/(t_row·M_0⁻¹·t_rowᵀ), kg
    std::shared_ptr<const ForceLaw> law;                     ///< prototype (k·ℓ of its edge)
  };

  /**
   * Check the moat against the building: the wall a simple polygon that encloses level 0's
   * outline with a clear gap everywhere (no slab vertex on or outside it, no edges crossing),
   * the friction and regularisation parameters, and the law (made once).
   * @throws std::invalid_argument "moat.<field>: ..." naming what is wrong.
   */
  void validate(const PlanMoat &moat, const PlanBuilding &building);

  /// The contact points of `moat` against level 0 of `building` (validated first).
  std::vector<PlanContact> moat_contacts(const PlanMoat &moat, const PlanBuilding &building);
} // namespace kimp::lumped::plan
