// deal.II pieces the FE solvers share (impact, static_elasticity.cc, wall_sdof.cc): reading an
// MSH mesh, the isotropic elastic cell stiffness and a uniform x traction on a face. dim = 2.
#pragma once

#include <filesystem>
#include <fstream>

#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

namespace kimp::fem
{
  /** The cells of the MSH file mesh_file (gmsh format 2 or 4, material and boundary ids from
   *  its physical groups) into the empty triangulation. */
  inline void read_msh(const std::filesystem::path &mesh_file, dealii::Triangulation<2> &tria)
  {
    dealii::GridIn<2> grid_in;
    grid_in.attach_triangulation(tria);
    std::ifstream in(mesh_file);
    grid_in.read_msh(in);
  }

  /** cell_matrix += int (lambda tr eps_i tr eps_j + 2 mu eps_i : eps_j) dA over the cell that
   *  fe_values was reinit()ed on (lambda, mu in Pa; displacement DoFs from component 0). */
  inline void add_elastic_stiffness(const dealii::FEValues<2>  &fe_values,
                                    const double                lambda,
                                    const double                mu,
                                    dealii::FullMatrix<double> &cell_matrix)
  {
    const dealii::FEValuesExtractors::Vector displacement(0);
    const unsigned int                       n = fe_values.dofs_per_cell;
    for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
      for (unsigned int i = 0; i < n; ++i)
      {
        const auto eps_i = fe_values[displacement].symmetric_gradient(i, q);
        for (unsigned int j = 0; j < n; ++j)
        {
          const auto eps_j = fe_values[displacement].symmetric_gradient(j, q);
          cell_matrix(i, j) +=
            (lambda * trace(eps_i) * trace(eps_j) + 2 * mu * scalar_product(eps_i, eps_j)) *
            fe_values.JxW(q);
        }
      }
  }

  /** cell_rhs += int traction N_i ds over the face that fe_face was reinit()ed on, for the x
   *  DoFs i (traction in N/m per metre of face). */
  inline void add_x_traction(const dealii::FEFaceValues<2> &fe_face,
                             const double                   traction,
                             dealii::Vector<double>        &cell_rhs)
  {
    const auto &fe = fe_face.get_fe();
    for (unsigned int q = 0; q < fe_face.n_quadrature_points; ++q)
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        if (fe.system_to_component_index(i).first == 0)
          cell_rhs(i) += traction * fe_face.shape_value(i, q) * fe_face.JxW(q);
  }
} // namespace kimp::fem
