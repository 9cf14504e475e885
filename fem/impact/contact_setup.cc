// ImpactProblem contact setup: the contact-face segments gathered from all ranks, the slave
// nodes with their penalty stiffness and damping, the master segments or the rigid face, the
// initial gap, and the compact gather/scatter of contact DoFs used by both time loops.
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

  std::vector<FaceSegment> ImpactProblem::gather_boundary_faces(const types::boundary_id a,
                                                                const types::boundary_id b) const
  {
    std::vector<double> local;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && (face->boundary_id() == a || face->boundary_id() == b))
          {
            local.push_back(face->boundary_id());
            local.push_back(cell->material_id());
            for (unsigned int v = 0; v < 2; ++v)
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(face->vertex(v)[d]);
            for (unsigned int d = 0; d < dim; ++d)
              local.push_back(cell->center()[d]);
            for (unsigned int v = 0; v < 2; ++v)
              for (unsigned int c = 0; c < dim; ++c)
                local.push_back(static_cast<double>(face->vertex_dof_index(v, c)));
          }
    constexpr unsigned int   record = 12;
    std::vector<FaceSegment> segments;
    for (const auto &part : Utilities::MPI::all_gather(comm, local))
      for (std::size_t k = 0; k + record <= part.size(); k += record)
      {
        FaceSegment s;
        s.boundary_id = static_cast<unsigned int>(part[k]);
        s.material_id = static_cast<unsigned int>(part[k + 1]);
        s.p0          = Point<dim>(part[k + 2], part[k + 3]);
        s.p1          = Point<dim>(part[k + 4], part[k + 5]);
        s.cell_center = Point<dim>(part[k + 6], part[k + 7]);
        for (unsigned int i = 0; i < 4; ++i)
          s.dofs[i] = static_cast<types::global_dof_index>(part[k + 8 + i]);
        segments.push_back(s);
      }
    return segments;
  }

  std::vector<double> ImpactProblem::gather_owned(const std::vector<types::global_dof_index> &dofs,
                                                  const Vec &v) const
  {
    std::vector<double> local(dofs.size(), 0.0);
    for (std::size_t k = 0; k < dofs.size(); ++k)
      if (locally_owned.is_element(dofs[k]))
        local[k] = v(dofs[k]);
    return sum_over_ranks(local, comm);
  }

  namespace
  {
    /** A contact node's key: its coordinates. */
    std::pair<double, double> key(const Point<dim> &p)
    {
      return std::make_pair(p[0], p[1]);
    }
  } // namespace

  struct ImpactProblem::ContactLayout
  {
    std::vector<FaceSegment> segments; ///< sorted by coordinates
    unsigned int             slave_id = 0;
    /// The nodes by key, sorted; each node's boundary id and DoFs.
    std::map<std::pair<double, double>, unsigned int>   node_of;
    std::vector<std::pair<double, double>>              keys;
    std::vector<unsigned int>                           node_boundary;
    std::vector<std::array<types::global_dof_index, 2>> node_dofs;
    std::vector<PenaltyContact::Node>                   nodes;
    double                                              h_contact = 0;
    /// Tributary lengths of the slave nodes, the master segments, the master's E.
    std::vector<double>                  tributary;
    std::vector<PenaltyContact::Segment> master;
    double                               e_master           = 0;
    double                               penalty_per_length = 0;
    double                               slave_y_min        = std::numeric_limits<double>::max(),
           slave_y_max                                      = -std::numeric_limits<double>::max();
    std::vector<PenaltyContact::Slave> slaves;
  };

  void ImpactProblem::number_contact_nodes(ContactLayout &c)
  {
    for (const auto &s : c.segments)
    {
      if (prm.rigid_slab && s.boundary_id != geometry::wall_contact)
        continue;
      for (unsigned int v = 0; v < 2; ++v)
      {
        const auto k = key(v == 0 ? s.p0 : s.p1);
        if (c.node_of.count(k) == 0)
        {
          c.node_of[k] = 0;
          c.keys.push_back(k);
        }
      }
    }
    std::sort(c.keys.begin(), c.keys.end());
    for (unsigned int i = 0; i < c.keys.size(); ++i)
      c.node_of[c.keys[i]] = i;
    c.node_boundary.assign(c.keys.size(), 0);
    c.node_dofs.assign(c.keys.size(), {});
    c.h_contact = std::numeric_limits<double>::max();
    for (const auto &s : c.segments)
    {
      if (prm.rigid_slab && s.boundary_id != geometry::wall_contact)
        continue;
      c.h_contact = std::min(c.h_contact, s.p0.distance(s.p1));
      for (unsigned int v = 0; v < 2; ++v)
      {
        const unsigned int i = c.node_of[key(v == 0 ? s.p0 : s.p1)];
        c.node_boundary[i]   = s.boundary_id;
        c.node_dofs[i]       = {{s.dofs[2 * v], s.dofs[2 * v + 1]}};
      }
    }
    require(!c.keys.empty(),
            "mesh '" + prm.mesh_file.string() + "' has no contact faces (boundary id " +
              std::to_string(static_cast<unsigned>(geometry::wall_contact)) + " must exist)");

    const unsigned int n_nodes = c.keys.size();
    contact_dofs.resize(2 * n_nodes);
    c.nodes.resize(n_nodes);
    for (unsigned int i = 0; i < n_nodes; ++i)
    {
      c.nodes[i]              = {c.keys[i].first, c.keys[i].second};
      contact_dofs[2 * i]     = c.node_dofs[i][0];
      contact_dofs[2 * i + 1] = c.node_dofs[i][1];
    }
  }

  void ImpactProblem::measure_contact_faces(ContactLayout &c)
  {
    // Tributary lengths of the slave nodes (clipped to the rigid face extent) and the wall
    // weights for the mean wall-face displacement.
    const double y_lo = prm.rigid_slab ? prm.slab_face_y0 : -std::numeric_limits<double>::max();
    const double y_hi = prm.rigid_slab ? prm.slab_face_y1 : std::numeric_limits<double>::max();
    c.tributary.assign(c.keys.size(), 0.0);
    for (const auto &s : c.segments)
    {
      if (prm.rigid_slab && s.boundary_id != geometry::wall_contact)
        continue;
      const unsigned int a = c.node_of[key(s.p0)], b = c.node_of[key(s.p1)];
      if (s.boundary_id == geometry::wall_contact)
      {
        c.e_master = std::max(c.e_master, prm.materials.at(s.material_id).youngs_modulus);
        contact_wave_speed =
          std::max(contact_wave_speed, p_wave_speed(prm.materials.at(s.material_id)));
        if (!prm.rigid_slab)
        {
          // Outward normal of the master cell: sign of (t_y, -t_x) . (face mid - cell centre).
          const Tensor<1, dim> t   = s.p1 - s.p0;
          const Tensor<1, dim> out = 0.5 * (s.p0 + s.p1) - s.cell_center;
          c.master.push_back({a, b, (t[1] * out[0] - t[0] * out[1]) > 0 ? 1.0 : -1.0});
        }
      }
      if (s.boundary_id != c.slave_id)
        continue;
      const Point<dim> mid = 0.5 * (s.p0 + s.p1);
      for (const auto &[node, p] : {std::make_pair(a, s.p0), std::make_pair(b, s.p1)})
      {
        // The half of the segment next to the node, clipped to [y_lo, y_hi] along y when the
        // face is not horizontal.
        const double full = p.distance(mid);
        const double lo = std::min(p[1], mid[1]), hi = std::max(p[1], mid[1]);
        double       frac = 1;
        if (hi > lo)
          frac = std::max(0.0, std::min(hi, y_hi) - std::max(lo, y_lo)) / (hi - lo);
        else if (p[1] < y_lo || p[1] > y_hi)
          frac = 0;
        c.tributary[node] += full * frac;
      }
    }
    require(c.e_master > 0, "mesh '" + prm.mesh_file.string() + "' has no wall contact faces");
  }

  void ImpactProblem::make_contact_slaves(ContactLayout &c)
  {
    const unsigned int        n_nodes   = c.keys.size();
    const std::vector<double> node_mass = [&]
    {
      std::vector<double> m = gather_compact(mass, 0.0);
      m.pop_back();
      return m;
    }();
    // The slave nodes and their reduced masses; the penalty per length is chosen after them.
    std::vector<std::pair<unsigned int, double>> slave_mass;
    for (unsigned int i = 0; i < n_nodes; ++i)
    {
      if (c.node_boundary[i] != c.slave_id || c.tributary[i] <= 0)
        continue;
      const double m_s = node_mass[2 * i];
      double       m_m = prm.slab_mass;
      if (!prm.rigid_slab)
      {
        // Master mass: the nearest master node in the reference configuration.
        double best = std::numeric_limits<double>::max();
        for (unsigned int j = 0; j < n_nodes; ++j)
          if (c.node_boundary[j] == geometry::wall_contact &&
              std::abs(c.keys[j].second - c.keys[i].second) < best)
          {
            best = std::abs(c.keys[j].second - c.keys[i].second);
            m_m  = node_mass[2 * j];
          }
      }
      require(m_s > 0 && m_m > 0,
              "contact node at (" + fmt_double(c.keys[i].first) + ", " +
                fmt_double(c.keys[i].second) + ") has no mass");
      slave_mass.emplace_back(i, 1.0 / (1.0 / m_s + 1.0 / m_m));
    }
    require(!slave_mass.empty(),
            "no slave contact node found (elastic slab: boundary id " +
              std::to_string(static_cast<unsigned>(geometry::slab_contact)) +
              "; rigid slab: wall face within [slab_face_y0, slab_face_y1])");
    penalty_factor_used  = contact_penalty_factor(c, slave_mass);
    c.penalty_per_length = penalty_factor_used * c.e_master / c.h_contact;
    // Implicit: no contact damping. Newton needs a residual with few kinks; a dashpot adds a
    // jump at first touch and a clamp while separating, and Newmark needs no chatter control
    // for stability.
    const double xi = prm.integrator == ImpactParameters::Integrator::implicit_newmark ?
                        0.0 :
                        prm.contact_damping_ratio;
    omega_penalty   = 0;
    for (const auto &[i, m_red] : slave_mass)
    {
      const double k       = c.penalty_per_length * c.tributary[i];
      const double damping = 2 * xi * std::sqrt(k * m_red);
      c.slaves.push_back({i, k, damping});
      slave_length.push_back(c.tributary[i]);
      contact_width += c.tributary[i];
      omega_penalty = std::max(omega_penalty, std::sqrt(k / m_red));
      c.slave_y_min = std::min(c.slave_y_min, c.keys[i].second);
      c.slave_y_max = std::max(c.slave_y_max, c.keys[i].second);
    }
  }

  double ImpactProblem::contact_penalty_factor(
    const ContactLayout                                &c,
    const std::vector<std::pair<unsigned int, double>> &slave_mass) const
  {
    if (prm.penalty_step_ratio <= 0)
      return prm.penalty_factor;
    // k_i = factor E / h l_i, so omega_p = sqrt(factor) omega_p(1): the factor that puts the
    // highest slave's omega_p at r omega_cells, r from the damped limit's step ratio.
    double omega_unit = 0;
    for (const auto &[i, m_red] : slave_mass)
      omega_unit =
        std::max(omega_unit, std::sqrt(c.e_master / c.h_contact * c.tributary[i] / m_red));
    const double r =
      penalty_omega_ratio_for_step(prm.penalty_step_ratio, prm.contact_damping_ratio);
    const double omega_p = r * cells_omega();
    return omega_p * omega_p / (omega_unit * omega_unit);
  }

  void ImpactProblem::check_initial_gaps(const ContactLayout &c)
  {
    // An overlap (or a slave that sees no master) is refused.
    const std::vector<double> gaps = contact->reference_gaps();
    initial_gap                    = std::numeric_limits<double>::max();
    for (unsigned int s = 0; s < gaps.size(); ++s)
    {
      const auto &n = c.nodes[c.slaves[s].node];
      require(gaps[s] >= 0,
              "slab overlaps the wall: contact node at (" + fmt_double(n.x) + ", " +
                fmt_double(n.y) + ") m has initial gap " + fmt_double(gaps[s]) +
                " m (must be >= 0)");
      if (std::isfinite(gaps[s]))
        initial_gap = std::min(initial_gap, gaps[s]);
    }
    require(initial_gap < std::numeric_limits<double>::max(),
            "no slave contact node projects onto the wall face");
  }

  void ImpactProblem::set_face_weights(const ContactLayout &c)
  {
    // Tributary lengths, normalised.
    const unsigned int n_nodes = c.keys.size();
    wall_weight.assign(2 * n_nodes + 1, 0.0);
    front_weight.assign(2 * n_nodes + 1, 0.0);
    if (prm.rigid_slab)
    {
      front_weight[2 * n_nodes] = 1;
      for (const auto &s : c.slaves)
        wall_weight[2 * s.node] = c.tributary[s.node];
    }
    else
    {
      for (const auto &s : c.slaves)
        front_weight[2 * s.node] = c.tributary[s.node];
      for (const auto &s : c.segments)
        if (s.boundary_id == geometry::wall_contact)
        {
          const double lo = std::max(std::min(s.p0[1], s.p1[1]), c.slave_y_min);
          const double hi = std::min(std::max(s.p0[1], s.p1[1]), c.slave_y_max);
          if (hi > lo)
          {
            wall_weight[2 * c.node_of.at(key(s.p0))] += 0.5 * (hi - lo);
            wall_weight[2 * c.node_of.at(key(s.p1))] += 0.5 * (hi - lo);
          }
        }
    }
    for (auto *w : {&wall_weight, &front_weight})
    {
      double sum = 0;
      for (double x : *w)
        sum += x;
      if (sum > 0)
        for (double &x : *w)
          x /= sum;
    }
    // The contact band's centre, the wall face's weighted mean point: the waves' source for the
    // viscous-spring boundary's distances.
    contact_centre = Point<dim>();
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      contact_centre[0] += wall_weight[2 * k] * c.nodes[k].x;
      contact_centre[1] += wall_weight[2 * k] * c.nodes[k].y;
    }
  }

  void ImpactProblem::setup_contact()
  {
    ContactLayout c;
    c.segments = gather_boundary_faces(geometry::slab_contact, geometry::wall_contact);
    // Deterministic order independent of the partition: by coordinates.
    std::sort(c.segments.begin(),
              c.segments.end(),
              [&](const FaceSegment &a, const FaceSegment &b) {
                return std::make_pair(key(a.p0), key(a.p1)) < std::make_pair(key(b.p0), key(b.p1));
              });
    c.slave_id = prm.rigid_slab ? geometry::wall_contact : geometry::slab_contact;
    number_contact_nodes(c);
    measure_contact_faces(c);
    make_contact_slaves(c);
    if (prm.rigid_slab)
      contact = std::make_unique<PenaltyContact>(c.nodes, c.slaves, prm.slab_front_x);
    else
      contact = std::make_unique<PenaltyContact>(c.nodes, c.slaves, c.master);
    check_initial_gaps(c);
    set_face_weights(c);
    log_line("contact: " + std::to_string(c.slaves.size()) + " slave nodes, " +
             std::to_string(c.master.size()) + " master segments" +
             (prm.rigid_slab ? " (rigid face)" : "") + ", k/l = " + fmt_sig(c.penalty_per_length) +
             " N/m^2 (penalty factor " + fmt_sig(penalty_factor_used) +
             (prm.penalty_step_ratio > 0 ?
                ", from penalty_step_ratio " + fmt_sig(prm.penalty_step_ratio) :
                std::string()) +
             "), h_contact = " + fmt_sig(c.h_contact) +
             " m, initial gap = " + fmt_sig(initial_gap) + " m");
  }

  std::vector<double> ImpactProblem::gather_compact(const Vec &v, double rigid_value) const
  {
    std::vector<double> all = gather_owned(contact_dofs, v);
    all.push_back(rigid_value);
    return all;
  }

  std::pair<std::vector<double>, std::vector<double>>
  ImpactProblem::gather_compact(const Vec &a, double rigid_a, const Vec &b, double rigid_b) const
  {
    const std::size_t   n = contact_dofs.size();
    std::vector<double> local(2 * n, 0.0), all(2 * n);
    for (std::size_t k = 0; k < n; ++k)
      if (locally_owned.is_element(contact_dofs[k]))
      {
        local[k]     = a(contact_dofs[k]);
        local[n + k] = b(contact_dofs[k]);
      }
    reduce_over_ranks(local.data(), all.data(), local.size(), MPI_SUM, comm);
    std::vector<double> ca(all.begin(), all.begin() + n), cb(all.begin() + n, all.end());
    ca.push_back(rigid_a);
    cb.push_back(rigid_b);
    return {std::move(ca), std::move(cb)};
  }

  void ImpactProblem::scatter_add(const std::vector<double> &compact, Vec &f) const
  {
    for (unsigned int k = 0; k < contact_dofs.size(); ++k)
      if (compact[k] != 0 && locally_owned.is_element(contact_dofs[k]))
        f(contact_dofs[k]) += compact[k];
    f.compress(VectorOperation::add);
  }
} // namespace kimp::fem::internal
