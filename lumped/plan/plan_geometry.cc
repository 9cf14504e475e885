// Plan geometry: polygon properties, checks and the moat offset.
#include "lumped/plan/plan_geometry.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kimp::lumped::plan
{
  namespace
  {
    double cross(const Point &a, const Point &b)
    {
      return a.x() * b.y() - a.y() * b.x();
    }

    /// Sign of the orientation of (a, b, c): > 0 counter-clockwise.
    double orientation(const Point &a, const Point &b, const Point &c)
    {
      return cross(b - a, c - a);
    }

    bool on_segment(const Point &a, const Point &b, const Point &p)
    {
      return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
             std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
    }

    /// Closed segments [a, b] and [c, d] share a point.
    bool segments_intersect(const Point &a, const Point &b, const Point &c, const Point &d)
    {
      const double o1 = orientation(a, b, c), o2 = orientation(a, b, d);
      const double o3 = orientation(c, d, a), o4 = orientation(c, d, b);
      if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
        return true;
      return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
             (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
    }
  } // namespace

  Polygon rectangle(const double width, const double depth, const Point &centre)
  {
    const double hx = 0.5 * width, hy = 0.5 * depth;
    return {centre + Point(-hx, -hy),
            centre + Point(hx, -hy),
            centre + Point(hx, hy),
            centre + Point(-hx, hy)};
  }

  double signed_area(const Polygon &polygon)
  {
    double a = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i)
      a += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
    return 0.5 * a;
  }

  Point centroid(const Polygon &polygon)
  {
    // About the first vertex, for accuracy far from the origin.
    const Point o = polygon.front();
    Point       s = Point::Zero();
    double      a = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i)
    {
      const Point  p = polygon[i] - o, q = polygon[(i + 1) % polygon.size()] - o;
      const double w = cross(p, q);
      a += w;
      s += w * (p + q);
    }
    return o + s / (3.0 * a);
  }

  double polar_moment(const Polygon &polygon, const Point &point)
  {
    double j = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i)
    {
      const Point  p = polygon[i] - point, q = polygon[(i + 1) % polygon.size()] - point;
      const double w = cross(p, q);
      j += w * (p.squaredNorm() + p.dot(q) + q.squaredNorm());
    }
    // Positive whatever the orientation.
    return std::abs(j) / 12.0;
  }

  void validate_polygon(const Polygon &polygon, const std::string &where)
  {
    const std::size_t n = polygon.size();
    if (n < 3)
      throw std::invalid_argument(where + ": " + std::to_string(n) +
                                  " vertices (a polygon needs at least 3)");
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!polygon[i].allFinite())
        throw std::invalid_argument(where + ": vertex " + std::to_string(i) + " is not finite");
      if ((polygon[(i + 1) % n] - polygon[i]).norm() == 0.0)
        throw std::invalid_argument(where + ": vertices " + std::to_string(i) + " and " +
                                    std::to_string((i + 1) % n) + " coincide (zero-length edge)");
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
      {
        // Adjacent edges share a vertex; only non-adjacent ones must not meet.
        if (j == i + 1 || (i == 0 && j == n - 1))
          continue;
        if (segments_intersect(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n]))
          throw std::invalid_argument(where + ": edges " + std::to_string(i) + " and " +
                                      std::to_string(j) +
                                      " intersect (the polygon must not be self-intersecting)");
      }
    if (!(std::abs(signed_area(polygon)) > 0.0))
      throw std::invalid_argument(where + ": zero area");
  }

  Polygon counter_clockwise(Polygon polygon)
  {
    if (signed_area(polygon) < 0.0)
      std::reverse(polygon.begin(), polygon.end());
    return polygon;
  }

  bool strictly_inside(const Polygon &polygon, const Point &point, const double tolerance)
  {
    const std::size_t n      = polygon.size();
    bool              inside = false;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
    {
      const Point &a = polygon[i], &b = polygon[j];
      // Distance to the edge: on (or within tolerance of) the boundary is not inside.
      const Point  ab = b - a;
      const double s  = std::clamp((point - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      if ((a + s * ab - point).norm() <= tolerance)
        return false;
      if ((a.y() > point.y()) != (b.y() > point.y()) &&
          point.x() < (b.x() - a.x()) * (point.y() - a.y()) / (b.y() - a.y()) + a.x())
        inside = !inside;
    }
    return inside;
  }

  Polygon moat_polygon(const Polygon &slab_in, const std::vector<double> &gaps)
  {
    validate_polygon(slab_in, "slab outline");
    const Polygon     slab = counter_clockwise(slab_in);
    const std::size_t n    = slab.size();
    if (gaps.size() != 1 && gaps.size() != n)
    {
      std::ostringstream msg;
      msg << "moat: " << gaps.size() << " gaps for a slab of " << n
          << " edges (give one gap for all edges or one per edge)";
      throw std::invalid_argument(msg.str());
    }
    for (std::size_t k = 0; k < n; ++k)
    {
      const double g = gaps[gaps.size() == 1 ? 0 : k];
      if (!(std::isfinite(g) && g > 0.0))
      {
        std::ostringstream msg;
        msg << "moat: gap[" << k << "] = " << g << " m (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
      const Point e0 = slab[k] - slab[(k + n - 1) % n], e1 = slab[(k + 1) % n] - slab[k];
      if (!(cross(e0, e1) > 0.0))
        throw std::invalid_argument("moat: the slab outline is not convex at vertex " +
                                    std::to_string(k) +
                                    " (give the wall polygon explicitly for a non-convex slab)");
    }
    // Line of edge k moved outwards: n_k·x = n_k·P_k + g_k, n_k the outward normal.
    std::vector<Point>  normal(n);
    std::vector<double> offset(n);
    for (std::size_t k = 0; k < n; ++k)
    {
      const Point d = (slab[(k + 1) % n] - slab[k]).normalized();
      normal[k]     = Point(d.y(), -d.x());
      offset[k]     = normal[k].dot(slab[k]) + gaps[gaps.size() == 1 ? 0 : k];
    }
    Polygon wall(n);
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::size_t km = (k + n - 1) % n;
      Eigen::Matrix2d   a;
      a.row(0) = normal[km].transpose();
      a.row(1) = normal[k].transpose();
      wall[k]  = a.partialPivLu().solve(Eigen::Vector2d(offset[km], offset[k]));
    }
    return wall;
  }

  Point rotated(const Point &point, const double angle)
  {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * point.x() - s * point.y(), s * point.x() + c * point.y()};
  }
} // namespace kimp::lumped::plan
