// ImpactProblem internal force of non-linear laws, f = sum over cells of B^T sigma(eps(u), h) JxW:
// a kernel over per-cell data precomputed once (DoF positions, shape gradients, JxW) with one law
// call per batch of points, and the FEValues loop it replaces, kept as its reference.
#include <algorithm>
#include <array>
#include <cmath>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>

#include "fem/impact/impact_problem.h"
#include "fem/mean_dilatation.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  namespace
  {
    /** Cells per law call: bounds the stack buffers of strains, stresses and energies. */
    constexpr unsigned int max_batch_cells = 32;

    /** The JxW of the four points of a cell's kernel data g (per point 4 d/dx, 4 d/dy, JxW). */
    std::array<double, 4> cell_weights(const double *g)
    {
      constexpr unsigned int width = 9;
      return {{g[8], g[width + 8], g[2 * width + 8], g[3 * width + 8]}};
    }
  } // namespace

  bool ImpactProblem::mean_dilatation(const types::material_id id) const
  {
    return prm.mean_dilatation && !linear_laws && id == geometry::soil_material &&
           !laws.at(id)->is_linear();
  }

  std::array<VoigtStrain, 4>
  ImpactProblem::cell_strains(const types::material_id                    id,
                              const std::vector<SymmetricTensor<2, dim>> &eps,
                              const std::array<double, 4>                &jxw) const
  {
    std::array<VoigtStrain, 4> e{};
    for (unsigned int q = 0; q < 4; ++q)
      e[q] = {{eps[q][0][0], eps[q][1][1], 2 * eps[q][0][1]}};
    if (mean_dilatation(id))
      average_in_plane_trace(e.data(), jxw.data(), 4);
    return e;
  }

  std::array<VoigtStrain, 4>
  ImpactProblem::cell_strains(const DoFHandler<dim>::active_cell_iterator &cell,
                              const Vec                                   &u,
                              FEValues<dim>                               &fv,
                              std::vector<SymmetricTensor<2, dim>>        &eps,
                              std::array<double, 4>                       &jxw) const
  {
    const FEValuesExtractors::Vector displacement(0);
    fv.reinit(cell);
    fv[displacement].get_function_symmetric_gradients(u, eps);
    Assert(fv.n_quadrature_points == 4, ExcInternalError());
    for (unsigned int q = 0; q < 4; ++q)
      jxw[q] = fv.JxW(q);
    return cell_strains(cell->material_id(), eps, jxw);
  }

  void ImpactProblem::strain_columns(const types::material_id            id,
                                     const FEValues<dim>                &fv,
                                     std::vector<std::array<double, 3>> &b) const
  {
    const FEValuesExtractors::Vector displacement(0);
    const unsigned int               n = fe.n_dofs_per_cell(), n_q = fv.n_quadrature_points;
    b.resize(static_cast<std::size_t>(n_q) * n);
    for (unsigned int q = 0; q < n_q; ++q)
      for (unsigned int i = 0; i < n; ++i)
      {
        const auto e = fv[displacement].symmetric_gradient(i, q);
        b[q * n + i] = {{e[0][0], e[1][1], 2 * e[0][1]}};
      }
    if (!mean_dilatation(id))
      return;
    Assert(n_q == 4, ExcInternalError());
    const std::array<double, 4> jxw{{fv.JxW(0), fv.JxW(1), fv.JxW(2), fv.JxW(3)}};
    for (unsigned int i = 0; i < n; ++i)
    {
      std::array<VoigtStrain, 4> column{};
      for (unsigned int q = 0; q < 4; ++q)
        column[q] = b[q * n + i];
      average_in_plane_trace(column.data(), jxw.data(), 4);
      for (unsigned int q = 0; q < 4; ++q)
        b[q * n + i] = column[q];
    }
  }

  void ImpactProblem::setup_internal_force()
  {
    force_cells.clear();
    force_gradients.clear();
    fast_internal_force = false;
    if (linear_laws || prm.reference_internal_force)
      return;
    // The kernel assumes Q1 vector elements with dof i = component i % 2 of vertex i / 2 and
    // homogeneous constraints without entries (Dirichlet zero); otherwise the reference path.
    if (fe.n_dofs_per_cell() != dofs_per_cell)
      return;
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      if (fe.system_to_component_index(i) != std::make_pair(i % 2, i / 2))
        return;
    for (const auto &line : constraints.get_lines())
      if (!line.entries.empty())
        return;

    const QGauss<dim> quadrature(2);
    if (quadrature.size() != points_per_cell)
      return;
    FEValues<dim> fe_values(fe, quadrature, update_gradients | update_JxW_values);
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    const Epetra_BlockMap               &ghosted_map = u_ghosted.trilinos_vector().Map();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dof_indices);
        ForceCell fc;
        fc.law  = laws.at(cell->material_id()).get();
        fc.cell = cell->active_cell_index();
        fc.body = body_of(cell->material_id());
        fc.bbar = mean_dilatation(cell->material_id());
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          fc.lid[i] = ghosted_map.LID(static_cast<int>(dof_indices[i]));
          if (fc.lid[i] < 0)
            return;
        }
        for (unsigned int q = 0; q < points_per_cell; ++q)
        {
          // Both components of a vertex share the scalar shape gradient: stored once.
          std::array<double, 2 * vertices_per_cell + 1> g{};
          for (unsigned int a = 0; a < vertices_per_cell; ++a)
          {
            const Tensor<1, dim> gx = fe_values.shape_grad(2 * a, q);
            const Tensor<1, dim> gy = fe_values.shape_grad(2 * a + 1, q);
            if (gx[0] != gy[0] || gx[1] != gy[1])
              return;
            g[a]                     = gx[0];
            g[vertices_per_cell + a] = gx[1];
          }
          g[2 * vertices_per_cell] = fe_values.JxW(q);
          force_gradients.insert(force_gradients.end(), g.begin(), g.end());
        }
        force_cells.push_back(fc);
      }

    // Positions of the ghosted vector: owned ones map into f, ghost ones go to their owner.
    const int n_ghosted = ghosted_map.NumMyElements();
    force_local.assign(n_ghosted, 0.0);
    force_owned_lid.assign(n_ghosted, -1);
    force_constrained.assign(n_ghosted, 0);
    force_ghost_lid.clear();
    force_ghost_gid.clear();
    const Vec              owned_vector(locally_owned, comm);
    const Epetra_BlockMap &owned_map = owned_vector.trilinos_vector().Map();
    for (int k = 0; k < n_ghosted; ++k)
    {
      const types::global_dof_index gid = ghosted_map.GID(k);
      force_constrained[k]              = constraints.is_constrained(gid) ? 1 : 0;
      if (locally_owned.is_element(gid))
        force_owned_lid[k] = owned_map.LID(static_cast<int>(gid));
      else if (!force_constrained[k])
      {
        force_ghost_lid.push_back(k);
        force_ghost_gid.push_back(gid);
      }
    }
    force_ghost_values.assign(force_ghost_lid.size(), 0.0);
    fast_internal_force = true;
  }

  void ImpactProblem::add_force_to_owners(Vec &f)
  {
    const double *fl        = force_local.data();
    const auto    n_ghosted = force_local.size();
    // Constrained DoFs get no force (distribute_local_to_global drops them); ghost entries are
    // added on their owner, after which the owned sums are added (own + imported, as before).
    double *fp = f.trilinos_vector()[0];
    if (force_ghost_lid.empty() && Utilities::MPI::n_mpi_processes(comm) == 1)
    {
      for (std::size_t k = 0; k < n_ghosted; ++k)
        if (force_owned_lid[k] >= 0)
          fp[force_owned_lid[k]] = force_constrained[k] ? 0.0 : fl[k];
      return;
    }
    for (std::size_t j = 0; j < force_ghost_lid.size(); ++j)
      force_ghost_values[j] = fl[force_ghost_lid[j]];
    force_writable = 0;
    force_writable.add(force_ghost_gid.size(), force_ghost_gid.data(), force_ghost_values.data());
    force_writable.compress(VectorOperation::add);
    f  = force_writable;
    fp = f.trilinos_vector()[0];
    for (std::size_t k = 0; k < n_ghosted; ++k)
      if (force_owned_lid[k] >= 0 && !force_constrained[k])
        fp[force_owned_lid[k]] += fl[k];
  }

  void ImpactProblem::laws_internal_force(const Vec &u, Vec &f)
  {
    if (linear_laws)
    {
      stiffness.vmult(f, u);
      return;
    }
    if (!fast_internal_force)
    {
      internal_force_reference(u, f);
      return;
    }
    // The same sums in the same order as internal_force_reference() (cells, then Gauss points,
    // then DoFs), so that both give the same numbers; deal.II's symmetric gradient of a
    // component-0 shape function is {gx, 0, gy / 2} and the factors 2 and 1/2 are exact.
    u_ghosted                = u;
    const double *ug         = u_ghosted.trilinos_vector()[0];
    const double  zero       = 0.0;
    double       *fl         = force_local.data();
    const auto    n_ghosted  = force_local.size();
    const auto    n_cells    = force_cells.size();
    const double *gradients  = force_gradients.data();
    const auto    cell_width = static_cast<std::size_t>(points_per_cell) * gradient_width;
    std::fill(fl, fl + n_ghosted, zero);
    point_energy_local     = {{0, 0, 0}};
    body_dissipation_local = {};
    slab_stored_local      = 0;

    constexpr unsigned int                   n_buf = max_batch_cells * 4;
    std::array<VoigtStrain, n_buf>           strain;
    std::array<VoigtStress, n_buf>           stress;
    std::array<std::array<double, 3>, n_buf> energy;
    static_assert(points_per_cell == 4, "buffers sized for four Gauss points per cell");
    static_assert(gradient_width == 9, "cell_weights() reads JxW at offset 8 of 9 per point");
    const unsigned int n_values = qp_history.n_values();
    for (std::size_t b0 = 0; b0 < n_cells;)
    {
      // A batch: consecutive cells of one law whose histories are contiguous.
      const MaterialLaw *law = force_cells[b0].law;
      std::size_t        b1  = b0 + 1;
      while (b1 < n_cells && b1 - b0 < max_batch_cells && force_cells[b1].law == law &&
             force_cells[b1].cell == force_cells[b1 - 1].cell + 1)
        ++b1;
      for (std::size_t k = b0; k < b1; ++k)
      {
        const ForceCell &fc = force_cells[k];
        double           ue[dofs_per_cell];
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          ue[i] = ug[fc.lid[i]];
        const double *g = gradients + k * cell_width;
        for (unsigned int q = 0; q < points_per_cell; ++q, g += gradient_width)
        {
          const double *gx = g, *gy = g + vertices_per_cell;
          double        exx = 0, eyy = 0, gxy = 0;
          for (unsigned int a = 0; a < vertices_per_cell; ++a)
          {
            exx += ue[2 * a] * gx[a];
            gxy += ue[2 * a] * gy[a];
            eyy += ue[2 * a + 1] * gy[a];
            gxy += ue[2 * a + 1] * gx[a];
          }
          strain[(k - b0) * points_per_cell + q] = {{exx, eyy, gxy}};
        }
        if (fc.bbar)
          average_in_plane_trace(&strain[(k - b0) * points_per_cell],
                                 cell_weights(gradients + k * cell_width).data(),
                                 points_per_cell);
      }
      const unsigned int n_points = static_cast<unsigned int>((b1 - b0) * points_per_cell);
      law->update_points(n_points,
                         strain.data(),
                         qp_history.committed(force_cells[b0].cell, 0),
                         qp_history.trial(force_cells[b0].cell, 0),
                         n_values,
                         stress.data(),
                         point_energy_needed ? energy.data() : nullptr);
      for (std::size_t k = b0; k < b1; ++k)
      {
        const ForceCell &fc                      = force_cells[k];
        double           fe_local[dofs_per_cell] = {};
        const double    *g                       = gradients + k * cell_width;
        // B-bar: sum_q B_bar^T sigma w = sum_q B^T sigma_hat w, sigma_hat the same trace mean.
        if (fc.bbar)
          average_in_plane_trace(&stress[(k - b0) * points_per_cell],
                                 cell_weights(g).data(),
                                 points_per_cell);
        for (unsigned int q = 0; q < points_per_cell; ++q, g += gradient_width)
        {
          const unsigned int p  = static_cast<unsigned int>((k - b0) * points_per_cell + q);
          const double      *gx = g, *gy = g + vertices_per_cell;
          const double       jxw = g[2 * vertices_per_cell];
          const VoigtStress &s   = stress[p];
          if (point_energy_needed)
          {
            point_energy_local[0] += energy[p][0] * jxw;
            point_energy_local[1] += energy[p][1] * jxw;
            point_energy_local[2] += energy[p][2] * jxw;
            body_dissipation_local[fc.body][0] += energy[p][1] * jxw;
            body_dissipation_local[fc.body][1] += energy[p][2] * jxw;
            if (fc.body == 0)
              slab_stored_local += energy[p][0] * jxw;
          }
          for (unsigned int a = 0; a < vertices_per_cell; ++a)
          {
            fe_local[2 * a] += (s[0] * gx[a] + s[2] * gy[a]) * jxw;
            fe_local[2 * a + 1] += (s[1] * gy[a] + s[2] * gx[a]) * jxw;
          }
        }
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          fl[fc.lid[i]] += fe_local[i];
      }
      b0 = b1;
    }

    add_force_to_owners(f);
  }

  void ImpactProblem::internal_force_reference(const Vec &u, Vec &f)
  {
    // f = sum over cells of B^T sigma(eps(u), h) JxW (Gauss points of the stiffness).
    u_ghosted      = u;
    force_writable = 0;
    const QGauss<dim>  quadrature(2);
    FEValues<dim>      fe_values(fe, quadrature, update_gradients | update_JxW_values);
    const unsigned int n = fe.n_dofs_per_cell();
    Vector<double>     cell_force(n);
    std::vector<types::global_dof_index> dof_indices(n);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    point_energy_local     = {{0, 0, 0}};
    body_dissipation_local = {};
    slab_stored_local      = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const MaterialLaw               &law = *laws.at(cell->material_id());
        const unsigned int               c   = cell->active_cell_index();
        std::array<double, 4>            jxw{};
        const std::array<VoigtStrain, 4> strain =
          cell_strains(cell, u_ghosted, fe_values, eps, jxw);
        std::array<VoigtStress, 4> sigma{};
        cell_force = 0;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          sigma[q] = law.stress(strain[q], qp_history.committed(c, q), qp_history.trial(c, q));
          const PointOutput po = law.output(strain[q], qp_history.trial(c, q));
          point_energy_local[0] += po.stored_energy * jxw[q];
          point_energy_local[1] += po.plastic_dissipation * jxw[q];
          point_energy_local[2] += po.damage_dissipation * jxw[q];
          auto &body = body_dissipation_local[body_of(cell->material_id())];
          body[0] += po.plastic_dissipation * jxw[q];
          body[1] += po.damage_dissipation * jxw[q];
          if (body_of(cell->material_id()) == 0)
            slab_stored_local += po.stored_energy * jxw[q];
        }
        // B-bar: the force of the mean-dilatation strain is B^T of the stress's trace mean.
        if (mean_dilatation(cell->material_id()))
          average_in_plane_trace(sigma.data(), jxw.data(), 4);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          for (unsigned int i = 0; i < n; ++i)
          {
            const auto e = fe_values[displacement].symmetric_gradient(i, q);
            cell_force(i) +=
              (sigma[q][0] * e[0][0] + sigma[q][1] * e[1][1] + 2 * sigma[q][2] * e[0][1]) * jxw[q];
          }
        cell->get_dof_indices(dof_indices);
        constraints.distribute_local_to_global(cell_force, dof_indices, force_writable);
      }
    force_writable.compress(VectorOperation::add);
    f = force_writable;
  }
} // namespace kimp::fem::internal
