// Node-to-segment penalty contact: g = (x_s - x_a(xi)) . n, p = -g, lambda = max(0, k p + c dp/dt).
#include "fem/penalty_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace kimp::fem
{
  namespace
  {
    /** Projection tolerance on xi: a slave exactly at a segment end belongs to both segments. */
    constexpr double xi_tolerance = 1e-8;
    /** Largest overhang (in segment lengths) beyond the ends of the master chain still in
     *  contact with the extended end segment. */
    constexpr double max_overhang = 0.25;
  } // namespace

  PenaltyContact::PenaltyContact(std::vector<Node>    nodes,
                                 std::vector<Slave>   slaves,
                                 std::vector<Segment> segments)
    : nodes_(std::move(nodes))
    , slaves_(std::move(slaves))
    , segments_(std::move(segments))
  {
    if (segments_.empty())
      throw std::invalid_argument("contact master surface has no segments (must have >= 1)");
    for (const auto &s : segments_)
      if (s.a >= nodes_.size() || s.b >= nodes_.size() || s.a == s.b)
        throw std::invalid_argument("contact segment (" + std::to_string(s.a) + ", " +
                                    std::to_string(s.b) + ") has an invalid node index");
    for (const auto &s : slaves_)
      if (s.node >= nodes_.size() || !(s.stiffness > 0) || s.damping < 0)
        throw std::invalid_argument("contact slave node " + std::to_string(s.node) +
                                    ": invalid index, stiffness or damping");
  }

  PenaltyContact::PenaltyContact(std::vector<Node> nodes, std::vector<Slave> slaves, double plane_x)
    : nodes_(std::move(nodes))
    , slaves_(std::move(slaves))
    , rigid_(true)
    , plane_x_(plane_x)
  {
    for (const auto &s : slaves_)
      if (s.node >= nodes_.size() || !(s.stiffness > 0) || s.damping < 0)
        throw std::invalid_argument("contact slave node " + std::to_string(s.node) +
                                    ": invalid index, stiffness or damping");
  }

  unsigned int PenaltyContact::n_compact_dofs() const
  {
    return 2 * static_cast<unsigned int>(nodes_.size()) + (rigid_ ? 1 : 0);
  }

  bool PenaltyContact::project(unsigned int               s,
                               const std::vector<double> &u,
                               ActivePair                &pair,
                               double                    &gap) const
  {
    const unsigned int i  = slaves_[s].node;
    const double       xs = nodes_[i].x + u[2 * i];
    const double       ys = nodes_[i].y + u[2 * i + 1];
    pair.slave            = s;
    if (rigid_)
    {
      const unsigned int r = 2 * static_cast<unsigned int>(nodes_.size());
      gap                  = xs - (plane_x_ + u[r]);
      pair.n_dofs          = 2;
      pair.dofs[0]         = 2 * i;
      pair.dg_du[0]        = 1;
      pair.dofs[1]         = r;
      pair.dg_du[1]        = -1;
      return true;
    }
    bool   found    = false;
    double best_abs = std::numeric_limits<double>::max();
    // First the segments the slave projects onto; if there is none (a slave just beyond an end
    // of the master chain, e.g. the slab's top corner at the wall's top edge once the wall
    // bends), the extended end segments, with the same linear weights: the gap and the penalty
    // energy then stay continuous where the slave slides off the end, which Newton needs.
    for (const double overhang : {xi_tolerance, max_overhang})
    {
      if (found)
        break;
      for (const auto &seg : segments_)
      {
        const double xa = nodes_[seg.a].x + u[2 * seg.a], ya = nodes_[seg.a].y + u[2 * seg.a + 1];
        const double xb = nodes_[seg.b].x + u[2 * seg.b], yb = nodes_[seg.b].y + u[2 * seg.b + 1];
        const double len = std::hypot(xb - xa, yb - ya);
        const double tx = (xb - xa) / len, ty = (yb - ya) / len;
        const double xi = ((xs - xa) * tx + (ys - ya) * ty) / len;
        if (xi < -overhang || xi > 1 + overhang)
          continue;
        const double nx = seg.normal_sign * ty, ny = -seg.normal_sign * tx;
        const double g = (xs - xa) * nx + (ys - ya) * ny;
        if (std::abs(g) >= best_abs)
          continue;
        best_abs          = std::abs(g);
        found             = true;
        gap               = g;
        const double xi_c = overhang == xi_tolerance ? std::clamp(xi, 0.0, 1.0) : xi;
        pair.n_dofs       = 0;
        const auto add    = [&pair](unsigned int dof, double d)
        {
          if (d != 0 && pair.n_dofs < pair.dofs.size())
          {
            pair.dofs[pair.n_dofs]  = dof;
            pair.dg_du[pair.n_dofs] = d;
            ++pair.n_dofs;
          }
        };
        add(2 * i, nx);
        add(2 * i + 1, ny);
        const std::array<std::pair<unsigned int, double>, 4> master{
          {{2 * seg.a, -(1 - xi_c) * nx},
           {2 * seg.a + 1, -(1 - xi_c) * ny},
           {2 * seg.b, -xi_c * nx},
           {2 * seg.b + 1, -xi_c * ny}}};
        for (const auto &m : master)
          add(m.first, m.second);
      }
    }
    return found;
  }

  std::vector<double> PenaltyContact::reference_gaps() const
  {
    const std::vector<double> zero(n_compact_dofs(), 0.0);
    std::vector<double>       gaps(slaves_.size(), std::numeric_limits<double>::infinity());
    for (unsigned int s = 0; s < slaves_.size(); ++s)
    {
      ActivePair pair;
      double     g = 0;
      if (project(s, zero, pair, g))
        gaps[s] = g;
    }
    return gaps;
  }

  PenaltyContact::Evaluation PenaltyContact::evaluate(const std::vector<double> &u,
                                                      const std::vector<double> &v) const
  {
    Evaluation out;
    out.force.assign(n_compact_dofs(), 0.0);
    double k_sum = 0;
    for (unsigned int s = 0; s < slaves_.size(); ++s)
    {
      k_sum += slaves_[s].stiffness;
      ActivePair pair;
      double     g = 0;
      if (!project(s, u, pair, g) || g >= 0)
        continue;
      out.mean_penetration += slaves_[s].stiffness * (-g);
      double rate = 0;
      for (unsigned int k = 0; k < pair.n_dofs; ++k)
        rate -= pair.dg_du[k] * v[pair.dofs[k]];
      const double p           = -g;
      const double k_pen       = slaves_[s].stiffness;
      const double f_d         = slaves_[s].damping * rate;
      double       f_damp      = f_d;
      pair.dforce_dpenetration = k_pen;
      pair.dforce_drate        = slaves_[s].damping;
      if (continuous_damping_ && f_d > k_pen * p)
      {
        f_damp                   = k_pen * p;
        pair.dforce_dpenetration = 2 * k_pen;
        pair.dforce_drate        = 0;
      }
      else if (f_d < -k_pen * p)
      {
        f_damp                   = -k_pen * p;
        pair.dforce_dpenetration = 0;
        pair.dforce_drate        = 0;
      }
      const double lambda = k_pen * p + f_damp;
      pair.penetration    = p;
      pair.force          = lambda;
      for (unsigned int k = 0; k < pair.n_dofs; ++k)
        out.force[pair.dofs[k]] += lambda * pair.dg_du[k];
      out.total_force += lambda;
      out.penalty_energy += 0.5 * slaves_[s].stiffness * p * p;
      out.max_penetration = std::max(out.max_penetration, p);
      out.active.push_back(pair);
    }
    if (k_sum > 0)
      out.mean_penetration /= k_sum;
    return out;
  }
} // namespace kimp::fem
