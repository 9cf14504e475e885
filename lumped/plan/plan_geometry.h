// Plan geometry of the 3D lumped model (docs/physics.md "Pounding in plan"): simple polygons in
// the horizontal plane (x, y), their area, centroid and polar moment, the small-rotation
// kinematics of a rigid diaphragm, and the moat polygon offset from a slab outline.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace kimp::lumped::plan
{
  /// A point or vector in plan, m.
  using Point = Eigen::Vector2d;

  /// A simple polygon, vertices in order (either orientation), m; the last joins the first.
  using Polygon = std::vector<Point>;

  /// A rectangle of `width` (along x) by `depth` (along y), m, centred at `centre`,
  /// counter-clockwise from the corner (−width/2, −depth/2).
  Polygon rectangle(double width, double depth, const Point &centre = Point::Zero());

  /// Signed area (> 0 counter-clockwise), m².
  double signed_area(const Polygon &polygon);

  /// Centroid of the area, m.
  Point centroid(const Polygon &polygon);

  /// Polar moment of area about `point`, ∫ |x − point|² dA, m⁴ (a uniform slab of mass m has the
  /// polar inertia m·J/A about that point).
  double polar_moment(const Polygon &polygon, const Point &point);

  /**
   * Check that a polygon is usable: at least 3 vertices, finite, no zero-length edge, not
   * self-intersecting, non-zero area.
   * @throws std::invalid_argument "<where>: <what is wrong>" naming the vertices or edges.
   */
  void validate_polygon(const Polygon &polygon, const std::string &where);

  /// The polygon counter-clockwise (reversed if it was clockwise).
  Polygon counter_clockwise(Polygon polygon);

  /// True if `point` lies strictly inside `polygon` (even-odd rule; boundary points excluded
  /// within `tolerance`, m).
  bool strictly_inside(const Polygon &polygon, const Point &point, double tolerance = 0.0);

  /**
   * The moat wall faces around a convex slab outline: the line of each slab edge moved outwards
   * by its gap, adjacent lines intersected. Edge k joins vertices k and k + 1 of the
   * counter-clockwise outline; `gaps` has one value per edge (or one value for all), m.
   * @throws std::invalid_argument for a non-convex outline, a gap <= 0 or a wrong count.
   */
  Polygon moat_polygon(const Polygon &slab, const std::vector<double> &gaps);

  /**
   * The linear (small-rotation) kinematics of a rigid diaphragm whose DOFs (u_x, u_y, θ) are
   * those of its reference point `reference`: the displacement of the material point at rest at
   * `point` is T·q, T = [[1, 0, −(y − y_r)], [0, 1, x − x_r]].
   */
  inline Eigen::Matrix<double, 2, 3> point_kinematics(const Point &point, const Point &reference)
  {
    Eigen::Matrix<double, 2, 3> t;
    t << 1.0, 0.0, -(point.y() - reference.y()), 0.0, 1.0, point.x() - reference.x();
    return t;
  }

  /// Rotate a point about the origin by `angle`, rad (counter-clockwise).
  Point rotated(const Point &point, double angle);
} // namespace kimp::lumped::plan
