// ImpactProblem frames: the slab-wall contact pressure of a frame, per contact node, from the
// penalty forces of the contact evaluation (lambda_i over the node's tributary length).
#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

#include "fem/impact/impact_problem.h"

namespace kimp::fem::internal
{
  void ImpactProblem::record_contact_pressure(const PenaltyContact::Evaluation &ev)
  {
    const auto &slaves = contact->slaves();
    // Slaves in the order of the frames' contact nodes: along the face by (y, x).
    std::vector<unsigned int> order(slaves.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto &nodes = contact->nodes();
    const auto  where = [&](unsigned int s)
    { return std::make_pair(nodes[slaves[s].node].y, nodes[slaves[s].node].x); };
    std::sort(order.begin(),
              order.end(),
              [&](unsigned int a, unsigned int b) { return where(a) < where(b); });
    if (frames.contact_vertices.empty())
    {
      // The contact nodes are mesh vertices of the coarse mesh at exactly these coordinates
      // (setup_contact() took them from the face vertices).
      std::map<std::pair<double, double>, unsigned int> vertex_of;
      const auto                                       &vertices = triangulation.get_vertices();
      for (unsigned int v = 0; v < vertices.size(); ++v)
        if (triangulation.vertex_used(v))
          vertex_of[{vertices[v][0], vertices[v][1]}] = v;
      for (const unsigned int s : order)
      {
        const auto &n  = nodes[slaves[s].node];
        const auto  it = vertex_of.find({n.x, n.y});
        require(it != vertex_of.end(),
                "contact node at (" + fmt_double(n.x) + ", " + fmt_double(n.y) +
                  ") m is no mesh vertex");
        frames.contact_vertices.push_back(it->second);
        frames.contact_length.push_back(slave_length[s]);
      }
    }
    // lambda_i >= 0 is the normal force of node i per metre of depth (the dashpot included),
    // so lambda_i / l_i is the mean normal traction over its tributary length and
    // sum_i p_i l_i = ev.total_force, the contact force of the histories.
    std::vector<double> pressure(slaves.size(), 0.0);
    for (const auto &pair : ev.active)
      pressure[pair.slave] = pair.force / slave_length[pair.slave];
    for (const unsigned int s : order)
      frames.contact_pressure.push_back(pressure[s]);
  }
} // namespace kimp::fem::internal
