// Moat wall in plan: checks and the contact points of the slab edges against the wall faces.
#include "lumped/plan/plan_moat.h"

#include <cmath>
#include <limits>
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

    /// Open segments (a, b) and (c, d) cross (proper intersection).
    bool segments_cross(const Point &a, const Point &b, const Point &c, const Point &d)
    {
      const double o1 = cross(b - a, c - a), o2 = cross(b - a, d - a);
      const double o3 = cross(d - c, a - c), o4 = cross(d - c, b - c);
      return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) &&
             ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
    }

    std::string point_text(const Point &p)
    {
      std::ostringstream s;
      s << "(" << p.x() << ", " << p.y() << ") m";
      return s.str();
    }

    /// The law of a slab edge of length `length`: stiffnesses per metre times the length.
    ForceLawSpec edge_law(const PlanMoat &moat, const double length, const double m_eff)
    {
      ForceLawSpec spec = moat.law;
      spec.stiffness *= length;
      spec.bumper_wall_stiffness *= length;
      spec.effective_mass = m_eff;
      return spec;
    }
  } // namespace

  Polygon moat_around(const PlanBuilding &building, const std::vector<double> &gaps)
  {
    if (building.levels.empty())
      throw std::invalid_argument("moat: the building has no levels");
    return moat_polygon(building.levels[0].outline, gaps);
  }

  namespace
  {
    /// The yielding faces: existing, each once, on a convex wall (no re-entrant corner, whose
    /// contact would belong to two faces), with valid wall-and-backfill parameters.
    void validate_yielding(const PlanMoat &moat)
    {
      if (moat.yielding.empty())
        return;
      const Polygon     wall = counter_clockwise(moat.wall);
      const std::size_t nw   = wall.size();
      for (std::size_t j = 0; j < nw; ++j)
      {
        const Point a = wall[(j + nw - 1) % nw], b = wall[j], c = wall[(j + 1) % nw];
        const Point u = b - a, v = c - b;
        if (u.x() * v.y() - u.y() * v.x() < 0.0)
          throw std::invalid_argument("moat.yielding: needs a convex wall polygon (vertex " +
                                      std::to_string(j) + " " + point_text(b) +
                                      " is a re-entrant corner)");
      }
      std::vector<char> seen(nw, 0);
      for (std::size_t i = 0; i < moat.yielding.size(); ++i)
      {
        const PlanYieldingWall &y     = moat.yielding[i];
        const std::string       where = "moat.yielding[" + std::to_string(i) + "]";
        if (y.segment >= nw)
          throw std::invalid_argument(where + ".segment = " + std::to_string(y.segment) +
                                      " (the wall has faces 0 to " + std::to_string(nw - 1) + ")");
        if (seen[y.segment]++)
          throw std::invalid_argument(where + ".segment = " + std::to_string(y.segment) +
                                      " (that face already has a yielding wall)");
        if (!(std::isfinite(y.params.mass) && y.params.mass > 0.0))
          throw std::invalid_argument(where + ".mass = " + std::to_string(y.params.mass) +
                                      " kg (the wall DOF's mass, must be > 0)");
        try
        {
          (void)WallBackfillLaw(y.params);
        }
        catch (const std::invalid_argument &e)
        {
          throw std::invalid_argument(where + ": " + e.what());
        }
      }
    }

    /// The mass the sliding along a face meets at a contact point of level 0 (mass m0, inertia
    /// i0 about its centre of mass): 1/(t_x²/m0 + t_y²/m0 + t_θ²/i0), t = ds/dq_0.
    double tangential_mass(const Eigen::RowVector3d &t, const double m0, const double i0)
    {
      const double inv_mt = t(0) * t(0) / m0 + t(1) * t(1) / m0 + t(2) * t(2) / i0;
      return 1.0 / inv_mt;
    }
  } // namespace

  void validate(const PlanMoat &moat, const PlanBuilding &building)
  {
    validate(building);
    validate_polygon(moat.wall, "moat.wall");
    const Polygon &slab = building.levels[0].outline;
    for (std::size_t k = 0; k < slab.size(); ++k)
      if (!strictly_inside(moat.wall, slab[k]))
        throw std::invalid_argument("moat.wall does not enclose the slab: vertex " +
                                    std::to_string(k) + " of level 0's outline " +
                                    point_text(slab[k]) +
                                    " is on or outside the wall (every gap must be > 0)");
    for (std::size_t e = 0; e < slab.size(); ++e)
      for (std::size_t j = 0; j < moat.wall.size(); ++j)
        if (segments_cross(slab[e],
                           slab[(e + 1) % slab.size()],
                           moat.wall[j],
                           moat.wall[(j + 1) % moat.wall.size()]))
          throw std::invalid_argument("moat.wall does not enclose the slab: wall face " +
                                      std::to_string(j) + " crosses edge " + std::to_string(e) +
                                      " of level 0's outline");
    const auto check = [](const bool ok, const std::string &key, const double v, const char *rule)
    {
      if (!ok)
      {
        std::ostringstream msg;
        msg << "moat." << key << " = " << v << " (" << rule << ")";
        throw std::invalid_argument(msg.str());
      }
    };
    check(std::isfinite(moat.mass) && moat.mass > 0.0, "mass", moat.mass, "must be > 0 kg");
    check(std::isfinite(moat.friction) && moat.friction >= 0.0,
          "friction",
          moat.friction,
          "must be >= 0");
    check(std::isfinite(moat.stick_velocity) && moat.stick_velocity > 0.0,
          "stick_velocity",
          moat.stick_velocity,
          "must be > 0 m/s");
    check(moat.points_per_edge >= 2,
          "points_per_edge",
          moat.points_per_edge,
          "must be >= 2 (the corners)");
    check(moat.facing_cosine > 0.0 && moat.facing_cosine <= 1.0,
          "facing_cosine",
          moat.facing_cosine,
          "must be in (0, 1]");
    try
    {
      (void)make_force_law(edge_law(moat, 1.0, 1.0));
    }
    catch (const std::invalid_argument &e)
    {
      throw std::invalid_argument(std::string("moat.law: ") + e.what());
    }
    validate_yielding(moat);
  }

  std::vector<PlanContact> moat_contacts(const PlanMoat &moat, const PlanBuilding &building)
  {
    validate(moat, building);
    const Polygon     slab  = counter_clockwise(building.levels[0].outline);
    const Polygon     wall  = counter_clockwise(moat.wall);
    const PlanLevel  &l0    = building.levels[0];
    const double      m0    = l0.mass;
    const double      i0    = l0.inertia();
    const double      m_eff = m0 * moat.mass / (m0 + moat.mass);
    const std::size_t ns = slab.size(), nw = wall.size();
    const int         np = moat.points_per_edge;

    // Vertex j of the counter-clockwise wall polygon is convex (seen from inside the moat).
    const auto convex = [&](const std::size_t j)
    { return cross(wall[j] - wall[(j + nw - 1) % nw], wall[(j + 1) % nw] - wall[j]) > 0.0; };
    std::vector<PlanContact> contacts;
    for (std::size_t e = 0; e < ns; ++e)
    {
      const Point                     a = slab[e], b = slab[(e + 1) % ns];
      const double                    length = (b - a).norm();
      const Point                     de     = (b - a) / length;
      const Point                     n_e(de.y(), -de.x()); // outward (counter-clockwise outline)
      std::shared_ptr<const ForceLaw> law(make_force_law(edge_law(moat, length, m_eff)));
      for (std::size_t j = 0; j < nw; ++j)
      {
        const Point wa = wall[j], wb = wall[(j + 1) % nw];
        const Point t = (wb - wa).normalized();
        const Point m(t.y(), -t.x()); // away from the slab (outward of the wall polygon)
        if (n_e.dot(m) < moat.facing_cosine)
          continue;
        for (int k = 0; k < np; ++k)
        {
          const double f = static_cast<double>(k) / static_cast<double>(np - 1);
          PlanContact  c;
          c.edge    = e;
          c.point   = static_cast<std::size_t>(k);
          c.segment = j;
          c.name =
            "edge" + std::to_string(e) + "_point" + std::to_string(k) + "_wall" + std::to_string(j);
          c.position = k == 0 ? a : k == np - 1 ? b : Point(a + f * (b - a));
          const Eigen::Matrix<double, 2, 3> tk = level_kinematics(building, 0, c.position);
          c.normal_row                         = m.transpose() * tk;
          c.tangent_row                        = t.transpose() * tk;
          c.gap                                = m.dot(wa) - m.dot(c.position);
          c.s_rest                             = t.dot(c.position);
          // At a convex corner of the wall the next face continues the wall: a point past the
          // end of this face is inside the corner block and still meets its line. Only a
          // reflex (re-entrant) corner ends the face.
          c.s_lo   = convex(j) ? -std::numeric_limits<double>::infinity() : t.dot(wa);
          c.s_hi   = convex((j + 1) % nw) ? std::numeric_limits<double>::infinity() : t.dot(wb);
          c.weight = (k == 0 || k == np - 1 ? 0.5 : 1.0) / static_cast<double>(np - 1);
          c.effective_mass  = m_eff;
          c.tangential_mass = tangential_mass(c.tangent_row, m0, i0);
          c.law             = law;
          // A point behind the face's line (beyond a re-entrant corner) never meets the face.
          if (c.gap > 0.0)
            contacts.push_back(std::move(c));
        }
      }
      // Re-entrant corners of the wall in front of the edge: the edge's material point facing
      // the corner meets it, with the normal of the edge and the weight of a slab corner (½ of
      // the edge's law), while the corner faces the moved edge.
      for (std::size_t j = 0; j < nw; ++j)
      {
        if (convex(j))
          continue;
        const double along = (wall[j] - a).dot(de), gap = (wall[j] - a).dot(n_e);
        if (!(gap > 0.0) || along < 0.0 || along > length)
          continue;
        PlanContact c;
        c.edge     = e;
        c.point    = static_cast<std::size_t>(np);
        c.segment  = j;
        c.name     = "edge" + std::to_string(e) + "_wallcorner" + std::to_string(j);
        c.position = a + along * de;
        const Eigen::Matrix<double, 2, 3> tk = level_kinematics(building, 0, c.position);
        c.normal_row                         = n_e.transpose() * tk;
        c.tangent_row                        = de.transpose() * tk;
        c.gap                                = gap;
        // The edge's point at the corner is at along − s: on the edge while 0 <= along − s <= ℓ.
        c.s_rest          = 0.0;
        c.s_lo            = along - length;
        c.s_hi            = along;
        c.weight          = 0.5;
        c.effective_mass  = m_eff;
        c.tangential_mass = tangential_mass(c.tangent_row, m0, i0);
        c.law             = law;
        contacts.push_back(std::move(c));
      }
    }
    return contacts;
  }
} // namespace kimp::lumped::plan
