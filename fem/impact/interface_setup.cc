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
    // Every interface face of the owned cells: boundary id, material, end points, their DoFs.
    std::vector<double> local;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && (face->boundary_id() == geometry::wall_back ||
                                      face->boundary_id() == geometry::soil_front))
          {
            local.push_back(face->boundary_id());
            local.push_back(cell->material_id());
            for (unsigned int v = 0; v < 2; ++v)
            {
              local.push_back(face->vertex(v)[0]);
              local.push_back(face->vertex(v)[1]);
              local.push_back(static_cast<double>(face->vertex_dof_index(v, 0)));
              local.push_back(static_cast<double>(face->vertex_dof_index(v, 1)));
            }
          }
    constexpr unsigned int record = 10;
    // Node by (position, boundary id): compact index, DoFs, tributary length.
    using Key = std::tuple<double, double, unsigned int>;
    std::map<Key, std::array<double, 3>> nodes; // dof x, dof y, tributary length
    double                               h_min  = std::numeric_limits<double>::max();
    double                               e_soil = 0;
    for (const auto &part : Utilities::MPI::all_gather(comm, local))
      for (std::size_t k = 0; k + record <= part.size(); k += record)
      {
        const auto   id     = static_cast<unsigned int>(part[k]);
        const double length = std::hypot(part[k + 6] - part[k + 2], part[k + 7] - part[k + 3]);
        h_min               = std::min(h_min, length);
        if (id == geometry::soil_front)
          e_soil =
            std::max(e_soil,
                     prm.materials.at(static_cast<unsigned int>(part[k + 1])).youngs_modulus);
        for (unsigned int v = 0; v < 2; ++v)
        {
          auto &n = nodes[{part[k + 2 + 4 * v], part[k + 3 + 4 * v], id}];
          n[0]    = part[k + 4 + 4 * v];
          n[1]    = part[k + 5 + 4 * v];
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
    const std::vector<double> node_mass = [&]
    {
      std::vector<double> m(interface_dofs.size(), 0.0), all(m.size());
      for (std::size_t k = 0; k < interface_dofs.size(); ++k)
        if (locally_owned.is_element(interface_dofs[k]))
          m[k] = mass(interface_dofs[k]);
      const int ierr =
        MPI_Allreduce(m.data(), all.data(), static_cast<int>(m.size()), MPI_DOUBLE, MPI_SUM, comm);
      AssertThrowMPI(ierr);
      return all;
    }();
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
             " node pairs, mu = " + fmt_double(o.friction) +
             ", k_N/l = " + fmt_double(o.penalty_factor * e_soil / h_min) + " N/m^2");
  }

  void ImpactProblem::subtract_interface_force(const Vec &u, Vec &f)
  {
    std::vector<double> local(interface_dofs.size(), 0.0), all(local.size());
    for (std::size_t k = 0; k < interface_dofs.size(); ++k)
      if (locally_owned.is_element(interface_dofs[k]))
        local[k] = u(interface_dofs[k]);
    const int ierr = MPI_Allreduce(local.data(),
                                   all.data(),
                                   static_cast<int>(local.size()),
                                   MPI_DOUBLE,
                                   MPI_SUM,
                                   comm);
    AssertThrowMPI(ierr);
    interface_ev = interface->evaluate(all);
    for (std::size_t k = 0; k < interface_dofs.size(); ++k)
      if (interface_ev.force[k] != 0 && locally_owned.is_element(interface_dofs[k]) &&
          !constraints.is_constrained(interface_dofs[k]))
        f(interface_dofs[k]) -= interface_ev.force[k];
    f.compress(VectorOperation::add);
  }

  void ImpactProblem::add_interface_stiffness(TrilinosWrappers::SparseMatrix &matrix) const
  {
    // k_N n n^T + k_T t t^T between the pair's nodes, on the free DoFs; n = +x, t = +y.
    for (const auto &p : interface->pairs())
    {
      const std::array<types::global_dof_index, 4> dofs{{interface_dofs[2 * p.a],
                                                         interface_dofs[2 * p.a + 1],
                                                         interface_dofs[2 * p.b],
                                                         interface_dofs[2 * p.b + 1]}};
      const std::array<double, 2>                  k{{p.normal_stiffness, p.tangential_stiffness}};
      for (unsigned int r = 0; r < 4; ++r)
        for (unsigned int c = 0; c < 4; ++c)
        {
          const auto fixed = [&](types::global_dof_index i)
          { return locally_relevant.is_element(i) && constraints.is_constrained(i); };
          if (r % 2 != c % 2 || !locally_owned.is_element(dofs[r]) || fixed(dofs[r]) ||
              fixed(dofs[c]))
            continue;
          matrix.add(dofs[r], dofs[c], (r / 2 == c / 2 ? 1.0 : -1.0) * k[r % 2]);
        }
    }
  }
} // namespace kimp::fem::internal
