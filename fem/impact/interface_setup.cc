// ImpactProblem wall-soil contact interface: node pairs of the wall_back and soil_front faces
// (gathered from all ranks, matched by position), their penalty stiffness, and the interface
// forces and springs the internal force and the geostatic operator take.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include <deal.II/base/mpi.h>

#include "fem/impact/impact_problem.h"
#include "geometry/scene_ids.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  void ImpactProblem::setup_interface()
  {
    const InterfaceOptions &o = prm.wall_soil_interface;
    require(o.friction >= 0,
            "wall_soil_interface.friction = " + fmt_double(o.friction) + " (must be >= 0)");
    require(o.penalty_factor > 0,
            "wall_soil_interface.penalty_factor = " + fmt_double(o.penalty_factor) +
              " (must be > 0)");
    require(prm.integrator == ImpactParameters::Integrator::explicit_central_difference,
            "wall_soil_interface.contact needs the explicit integrator (the implicit Newton has "
            "no frictional interface tangent)");
    // Node by (position, boundary id): compact index, DoFs, tributary length.
    using Key = std::tuple<double, double, unsigned int>;
    std::map<Key, std::array<double, 3>> nodes; // dof x, dof y, tributary length
    double                               h_min  = std::numeric_limits<double>::max();
    double                               e_soil = 0;
    for (const FaceSegment &s : gather_boundary_faces(geometry::wall_back, geometry::soil_front))
    {
      const double length = std::hypot(s.p1[0] - s.p0[0], s.p1[1] - s.p0[1]);
      h_min               = std::min(h_min, length);
      if (s.boundary_id == geometry::soil_front)
        e_soil = std::max(e_soil, prm.materials.at(s.material_id).youngs_modulus);
      for (unsigned int v = 0; v < 2; ++v)
      {
        const Point<dim> &p = v == 0 ? s.p0 : s.p1;
        auto             &n = nodes[{p[0], p[1], s.boundary_id}];
        n[0]                = static_cast<double>(s.dofs[2 * v]);
        n[1]                = static_cast<double>(s.dofs[2 * v + 1]);
        n[2] += 0.5 * length;
      }
    }
    require(!nodes.empty() && e_soil > 0,
            "wall_soil_interface.contact: mesh '" + prm.mesh_file.string() +
              "' has no wall_back / soil_front faces (boundary ids " +
              std::to_string(static_cast<unsigned>(geometry::wall_back)) + ", " +
              std::to_string(static_cast<unsigned>(geometry::soil_front)) +
              "; mesh it with the contact interface)");
    // Compact numbering in map order (by position): deterministic on any partition.
    std::map<Key, unsigned int> index;
    interface_dofs.clear();
    for (const auto &[key, n] : nodes)
    {
      index[key] = interface_dofs.size() / 2;
      interface_dofs.push_back(static_cast<types::global_dof_index>(n[0]));
      interface_dofs.push_back(static_cast<types::global_dof_index>(n[1]));
    }
    const std::vector<double>              node_mass = gather_owned(interface_dofs, mass);
    std::vector<FrictionalInterface::Pair> pairs;
    omega_interface = 0;
    for (const auto &[key, n] : nodes)
    {
      if (std::get<2>(key) != geometry::wall_back)
        continue;
      const auto other = index.find({std::get<0>(key), std::get<1>(key), geometry::soil_front});
      require(other != index.end(),
              "wall_soil_interface.contact: wall back node at (" + fmt_double(std::get<0>(key)) +
                ", " + fmt_double(std::get<1>(key)) + ") m has no soil node at its place");
      FrictionalInterface::Pair p;
      p.a                    = index.at(key);
      p.b                    = other->second;
      p.nx                   = 1; // from the wall into the backfill (+x)
      p.ny                   = 0;
      p.normal_stiffness     = o.penalty_factor * e_soil / h_min * n[2];
      p.tangential_stiffness = p.normal_stiffness;
      p.friction             = o.friction;
      const double m_a = node_mass[2 * p.a], m_b = node_mass[2 * p.b];
      if (m_a > 0 && m_b > 0)
        omega_interface =
          std::max(omega_interface, std::sqrt(p.normal_stiffness * (1 / m_a + 1 / m_b)));
      pairs.push_back(p);
    }
    interface = std::make_unique<FrictionalInterface>(pairs, interface_dofs.size() / 2);
    log_line("wall-soil interface: " + std::to_string(pairs.size()) +
             " node pairs, mu = " + fmt_sig(o.friction) +
             ", k_N/l = " + fmt_sig(o.penalty_factor * e_soil / h_min) + " N/m^2");
  }

  void ImpactProblem::subtract_interface_force(const Vec &u, Vec &f)
  {
    const std::vector<double> all = gather_owned(interface_dofs, u);
    interface_ev                  = interface->evaluate(all);
    for (std::size_t k = 0; k < interface_dofs.size(); ++k)
      if (interface_ev.force[k] != 0 && locally_owned.is_element(interface_dofs[k]) &&
          !constraints.is_constrained(interface_dofs[k]))
        f(interface_dofs[k]) -= interface_ev.force[k];
    f.compress(VectorOperation::add);
  }

  void ImpactProblem::add_interface_stiffness(TrilinosWrappers::SparseMatrix &matrix,
                                              const Vec                      *u,
                                              double                          floor) const
  {
    // Per pair [[A, -A], [-A, A]] over (u_a, u_b) on the free DoFs: without u the stick springs
    // k_N n n^T + k_T t t^T (n = +x, t = +y), with u the consistent tangent of the pair's state
    // at u plus floor x the stick springs.
    const std::vector<double> all =
      u ? gather_owned(interface_dofs, *u) : std::vector<double>(interface_dofs.size(), 0.0);
    const auto fixed = [&](types::global_dof_index i)
    { return locally_relevant.is_element(i) && constraints.is_constrained(i); };
    const std::vector<FrictionalInterface::Pair> &pairs = interface->pairs();
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
      const FrictionalInterface::Pair &p = pairs[k];
      std::array<double, 4>            a = interface->tangent(k, all, u == nullptr);
      if (u)
      {
        const std::array<double, 4> stick = interface->tangent(k, all, true);
        for (unsigned int e = 0; e < 4; ++e)
          a[e] += floor * stick[e];
      }
      const std::array<types::global_dof_index, 4> dofs{{interface_dofs[2 * p.a],
                                                         interface_dofs[2 * p.a + 1],
                                                         interface_dofs[2 * p.b],
                                                         interface_dofs[2 * p.b + 1]}};
      for (unsigned int r = 0; r < 4; ++r)
        for (unsigned int c = 0; c < 4; ++c)
        {
          const double value = a[2 * (r % 2) + c % 2];
          if (value == 0 || !locally_owned.is_element(dofs[r]) || fixed(dofs[r]) || fixed(dofs[c]))
            continue;
          matrix.add(dofs[r], dofs[c], (r / 2 == c / 2 ? 1.0 : -1.0) * value);
        }
    }
  }
} // namespace kimp::fem::internal
