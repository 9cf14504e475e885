// ImpactProblem absorbing boundary: Lysmer-Kuhlemeyer viscous dashpots (Lysmer & Kuhlemeyer,
// J. Eng. Mech. Div. ASCE 95, 1969) on soil faces of the far side and the base, lumped into a
// diagonal C, with the viscous-spring boundary's springs beside them (Deeks & Randolph, J. Eng.
// Mech. 120, 1994; Liu et al., Earthq. Eng. Eng. Vib. 5, 2006), their explicit and implicit
// treatment, the radiated energy and the springs' energy (docs/physics.md §6).
#include <cmath>
#include <string>
#include <utility>

#include <deal.II/base/mpi.h>

#include "fem/impact/impact_problem.h"
#include "geometry/scene_ids.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  namespace
  {
    /** |n_x n_y| above which a face counts as not axis-parallel (C would not be diagonal). */
    constexpr double axis_parallel_tolerance = 1e-9;

    double s_wave_speed(const Material &m)
    {
      return std::sqrt(m.youngs_modulus / (2 * (1 + m.poisson_ratio)) / m.density);
    }
  } // namespace

  bool ImpactProblem::is_absorbing(const unsigned int boundary_id) const
  {
    for (const unsigned int id : prm.absorbing_boundaries)
      if (id == boundary_id)
        return true;
    return false;
  }

  void ImpactProblem::constrain_non_absorbing_faces()
  {
    for (const unsigned int id : prm.absorbing_boundaries)
      require(id == geometry::fixed_base || id == geometry::soil_far_side,
              "absorbing_boundaries holds boundary id " + std::to_string(id) +
                " (must be fixed_base = " +
                std::to_string(static_cast<unsigned>(geometry::fixed_base)) +
                " or soil_far_side = " +
                std::to_string(static_cast<unsigned>(geometry::soil_far_side)) + ")");
    // The constraint a face of an absorbing id keeps when its cell is not soil: u = 0 on the
    // fixed base, u_x = 0 on the far side (as in setup_system()).
    for_each_absorbing_dof(false,
                           [&](const types::global_dof_index i, unsigned int)
                           {
                             if (constraints.can_store_line(i) && !constraints.is_constrained(i))
                               constraints.add_line(i);
                           });
  }

  void ImpactProblem::assemble_dashpots()
  {
    absorbing = !prm.absorbing_boundaries.empty();
    if (!absorbing)
      return;
    boundary_springs = prm.boundary_spring_normal + prm.boundary_spring_tangential > 0;
    Vec damping_w, spring_w;
    damping_w.reinit(locally_owned, locally_relevant, comm, true);
    spring_w.reinit(locally_owned, locally_relevant, comm, true);
    double local_length = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() == geometry::soil_material)
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && is_absorbing(face->boundary_id()))
          {
            const Material      &m  = prm.materials.at(cell->material_id());
            const Tensor<1, dim> t  = face->vertex(1) - face->vertex(0);
            const double         l  = t.norm();
            const double         nx = t[1] / l, ny = -t[0] / l; // unit normal (either sign)
            require(std::abs(nx * ny) < axis_parallel_tolerance,
                    "absorbing boundary face from (" + fmt_double(face->vertex(0)[0]) + ", " +
                      fmt_double(face->vertex(0)[1]) + ") to (" + fmt_double(face->vertex(1)[0]) +
                      ", " + fmt_double(face->vertex(1)[1]) +
                      ") m is not axis-parallel (the lumped dashpots need a diagonal C)");
            // rho c_p on the normal and rho c_s on the tangential component, half the face
            // length to each node (trapezoidal = two-point Gauss-Lobatto lumping).
            const double normal     = m.density * p_wave_speed(m),
                         tangential = m.density * s_wave_speed(m);
            const double cx         = 0.5 * l * (normal * nx * nx + tangential * ny * ny);
            const double cy         = 0.5 * l * (normal * ny * ny + tangential * nx * nx);
            const auto [kn, kt] =
              boundary_spring_stiffness(m, Point<dim>(0.5 * (face->vertex(0) + face->vertex(1))));
            const double kx = 0.5 * l * (kn * nx * nx + kt * ny * ny);
            const double ky = 0.5 * l * (kn * ny * ny + kt * nx * nx);
            for (unsigned int v = 0; v < face->n_vertices(); ++v)
            {
              damping_w(face->vertex_dof_index(v, 0)) += cx;
              damping_w(face->vertex_dof_index(v, 1)) += cy;
              spring_w(face->vertex_dof_index(v, 0)) += kx;
              spring_w(face->vertex_dof_index(v, 1)) += ky;
            }
            local_length += l;
          }
    damping_w.compress(VectorOperation::add);
    spring_w.compress(VectorOperation::add);
    damping.reinit(locally_owned, comm);
    damping = damping_w;
    Vec springs(locally_owned, comm);
    springs             = spring_w;
    const double length = Utilities::MPI::sum(local_length, comm);
    require(length > 0,
            "absorbing_boundaries: mesh '" + prm.mesh_file.string() +
              "' has no face of these boundary ids on soil cells (material id " +
              std::to_string(static_cast<unsigned>(geometry::soil_material)) + ")");

    damped_index.clear();
    damped_c.clear();
    damped_k.clear();
    damped_m.clear();
    for (const auto i : locally_owned)
      if (damping(i) > 0 && free_mask(i) > 0)
      {
        damped_index.push_back(static_cast<unsigned int>(locally_owned.index_within_set(i)));
        damped_c.push_back(damping(i));
        damped_k.push_back(springs(i));
        damped_m.push_back(mass(i));
      }
    damped_u_prev.clear();
    damped_f_prev.clear();
    radiation_local = 0;
    log_line("absorbing boundary: " + fmt_sig(length) + " m of soil faces with dashpots" +
             (boundary_springs ?
                " and springs (alpha_n " + fmt_sig(prm.boundary_spring_normal) + ", alpha_t " +
                  fmt_sig(prm.boundary_spring_tangential) + ", R from the contact band's centre (" +
                  fmt_sig(contact_centre[0]) + ", " + fmt_sig(contact_centre[1]) + ") m)" :
                std::string()));
  }

  std::pair<double, double> ImpactProblem::boundary_spring_stiffness(const Material   &material,
                                                                     const Point<dim> &mid) const
  {
    if (!boundary_springs)
      return {0.0, 0.0};
    const double g = material.youngs_modulus / (2 * (1 + material.poisson_ratio));
    const double r = mid.distance(contact_centre);
    require(r > 0,
            "viscous-spring boundary: a soil face of the far boundary at (" + fmt_double(mid[0]) +
              ", " + fmt_double(mid[1]) + ") m lies at the contact band's centre (R = 0)");
    return {prm.boundary_spring_normal * g / r, prm.boundary_spring_tangential * g / r};
  }

  double ImpactProblem::spring_rest(const unsigned int j) const
  {
    return geostatic_on ? geostatic_u.begin()[j] : 0.0;
  }

  void ImpactProblem::apply_dashpots_explicit(const bool first_step,
                                              const Vec &u,
                                              const Vec &v_half,
                                              Vec       &a) const
  {
    const double *up = u.begin(), *vp = v_half.begin();
    double       *ap = a.begin();
    for (std::size_t k = 0; k < damped_index.size(); ++k)
    {
      const unsigned int j = damped_index[k];
      const double       m = damped_m[k], c = damped_c[k];
      // f - K u - k (u - u_0): the springs are part of the stiffness.
      const double g   = ap[j] * m - damped_k[k] * (up[j] - spring_rest(j));
      const double v_n = first_step ? vp[j] : (m * vp[j] + 0.5 * dt * g) / (m + 0.5 * dt * c);
      ap[j]            = (g - c * v_n) / m;
    }
  }

  void ImpactProblem::add_dashpot_force(const Vec &u, const Vec &v, Vec &r) const
  {
    const double *up = u.begin(), *vp = v.begin();
    double       *rp = r.begin();
    for (std::size_t k = 0; k < damped_index.size(); ++k)
    {
      const unsigned int j = damped_index[k];
      rp[j] += damped_c[k] * vp[j] + damped_k[k] * (up[j] - spring_rest(j));
    }
  }

  void ImpactProblem::add_dashpot_matrix(TrilinosWrappers::SparseMatrix &matrix,
                                         const double                    factor) const
  {
    for (std::size_t k = 0; k < damped_index.size(); ++k)
      matrix.add(locally_owned.nth_index_in_set(damped_index[k]),
                 locally_owned.nth_index_in_set(damped_index[k]),
                 factor * damped_c[k] + damped_k[k]);
  }

  double ImpactProblem::boundary_spring_energy_local(const Vec &u) const
  {
    const double *up     = u.begin();
    double        energy = 0;
    for (std::size_t k = 0; k < damped_index.size(); ++k)
    {
      const double du = up[damped_index[k]] - spring_rest(damped_index[k]);
      energy += 0.5 * damped_k[k] * du * du;
    }
    return energy;
  }

  void ImpactProblem::accumulate_radiation(const Vec &u, const Vec &v)
  {
    const double *up = u.begin(), *vp = v.begin();
    const bool    first = damped_u_prev.empty();
    damped_u_prev.resize(damped_index.size());
    damped_f_prev.resize(damped_index.size());
    for (std::size_t k = 0; k < damped_index.size(); ++k)
    {
      const unsigned int j = damped_index[k];
      const double       f = damped_c[k] * vp[j];
      if (!first)
        radiation_local += 0.5 * (f + damped_f_prev[k]) * (up[j] - damped_u_prev[k]);
      damped_u_prev[k] = up[j];
      damped_f_prev[k] = f;
    }
  }

  void ImpactProblem::set_initial_slab_velocity(Vec &v)
  {
    if (!prm.initial_velocity_along_y)
    {
      for (const auto i : locally_owned)
        if (slab_mass_x(i) > 0)
          v(i) = prm.initial_velocity;
      v.compress(VectorOperation::insert);
      return;
    }
    require(!prm.rigid_slab, "initial_velocity_along_y needs an elastic (meshed) slab");
    // Every node of a slab cell moves, those shared with other cells included: E_0 is then the
    // kinetic energy of these nodes' whole lumped mass, not 1/2 m_slab v^2.
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial() && cell->material_id() == geometry::slab_material)
        for (unsigned int k = 0; k < cell->n_vertices(); ++k)
        {
          const auto i = cell->vertex_dof_index(k, 1);
          if (locally_owned.is_element(i) && !constraints.is_constrained(i))
            v(i) = prm.initial_velocity;
        }
    v.compress(VectorOperation::insert);
    double local = 0;
    for (const auto i : locally_owned)
      local += 0.5 * mass(i) * v(i) * v(i);
    e0 = Utilities::MPI::sum(local, comm);
  }
} // namespace kimp::fem::internal
