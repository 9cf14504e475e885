// Static plane-strain elasticity K u = f for the closed-form check of the bare cantilever wall
// (Timoshenko beam: 1/k = H^3 / (3 E' I) + H / (kappa G A)) and of the wall with backfill, and
// mesh statistics / VTU preview.
#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include "fem/fe_helpers.h"
#include "fem/impact.h"
#include "fem/material_law.h"

namespace kimp::fem
{
  double timoshenko_tip_stiffness(double height, double thickness, const Material &m)
  {
    constexpr double kappa   = 5.0 / 6.0; // rectangular section
    const double     e_plane = m.youngs_modulus / (1 - m.poisson_ratio * m.poisson_ratio);
    const double     shear   = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
    const double     inertia = thickness * thickness * thickness / 12;
    return 1.0 / (height * height * height / (3 * e_plane * inertia) +
                  height / (kappa * shear * thickness));
  }

  namespace
  {
    using namespace dealii;
    constexpr int dim = 2;
    /** Boundary ids of the static wall models. */
    constexpr types::boundary_id interior = 0, base = 1, wall_top = 2, far_side = 3;

    /**
     * K u = f on a triangulation with material ids 0 (wall) and 1 (soil), base clamped, far
     * side u_x = 0, 1 N/m total shear traction (along x) on the wall top; returns 1 / mean top
     * x displacement (N/m per metre of depth).
     */
    double top_load_stiffness(const Triangulation<dim>               &tria,
                              const std::map<unsigned int, Material> &materials,
                              double                                  top_length)
    {
      FESystem<dim>   fe(FE_Q<dim>(1), dim);
      DoFHandler<dim> dof_handler(tria);
      dof_handler.distribute_dofs(fe);

      AffineConstraints<double> constraints;
      VectorTools::interpolate_boundary_values(dof_handler,
                                               base,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints);
      VectorTools::interpolate_boundary_values(dof_handler,
                                               far_side,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints,
                                               ComponentMask(std::vector<bool>{true, false}));
      constraints.close();
      DynamicSparsityPattern dsp(dof_handler.n_dofs());
      DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
      SparsityPattern pattern;
      pattern.copy_from(dsp);
      SparseMatrix<double> matrix(pattern);
      Vector<double>       rhs(dof_handler.n_dofs()), u(dof_handler.n_dofs());

      const QGauss<dim>     quadrature(2);
      const QGauss<dim - 1> face_quadrature(2);
      FEValues<dim>         fe_values(fe, quadrature, update_gradients | update_JxW_values);
      FEFaceValues<dim>     fe_face(fe, face_quadrature, update_values | update_JxW_values);
      const unsigned int    n = fe.n_dofs_per_cell();
      FullMatrix<double>    cell_matrix(n, n);
      Vector<double>        cell_rhs(n);
      std::vector<types::global_dof_index> dof_indices(n);
      const double                         traction = 1.0 / top_length;
      for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const Material &m = materials.at(cell->material_id());
        const Lame      l = lame(m.youngs_modulus, m.poisson_ratio);
        fe_values.reinit(cell);
        cell_matrix = 0;
        cell_rhs    = 0;
        add_elastic_stiffness(fe_values, l.lambda, l.mu, cell_matrix);
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == wall_top)
          {
            fe_face.reinit(cell, f);
            add_x_traction(fe_face, traction, cell_rhs);
          }
        cell->get_dof_indices(dof_indices);
        constraints.distribute_local_to_global(cell_matrix, cell_rhs, dof_indices, matrix, rhs);
      }
      SparseDirectUMFPACK solver;
      solver.initialize(matrix);
      solver.vmult(u, rhs);
      constraints.distribute(u);

      // Mean x displacement of the top edge (trapezoid over the vertices).
      double sum = 0, length = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == wall_top)
          {
            const auto   face = cell->face(f);
            const double l    = face->measure();
            for (unsigned int v = 0; v < 2; ++v)
              sum += 0.5 * l * u(face->vertex_dof_index(v, 0));
            length += l;
          }
      return 1.0 / (sum / length);
    }
  } // namespace

  double cantilever_tip_stiffness(double          height,
                                  double          thickness,
                                  const Material &m,
                                  unsigned int    n_thickness)
  {
    return backfilled_wall_tip_stiffness({height, thickness, m, 0, 0, Material{}, n_thickness});
  }

  double backfilled_wall_tip_stiffness(const BackfilledWall &w)
  {
    const double       height = w.height, thickness = w.thickness;
    const double       backfill_width = w.backfill_width, backfill_height = w.backfill_height;
    const Material    &wall = w.wall, &soil = w.soil;
    const unsigned int n_thickness = w.n_thickness;
    AssertThrow(height > 0 && thickness > 0 && n_thickness > 0,
                ExcMessage("wall: height = " + std::to_string(height) +
                           " m, thickness = " + std::to_string(thickness) + " m, n_thickness = " +
                           std::to_string(n_thickness) + " (all must be > 0)"));
    const bool with_soil = backfill_width > 0;
    AssertThrow(!with_soil ||
                  (backfill_height > 0 && backfill_height <= height && soil.youngs_modulus > 0 &&
                   soil.poisson_ratio >= 0 && soil.poisson_ratio < 0.5),
                ExcMessage("backfill: height = " + std::to_string(backfill_height) +
                           " m (must be in (0, " + std::to_string(height) +
                           "]), soil E = " + std::to_string(soil.youngs_modulus) +
                           " Pa (must be > 0), nu = " + std::to_string(soil.poisson_ratio) +
                           " (must be in [0, 0.5))"));
    // Square-ish cells of size h = thickness / n_thickness; the soil shares the wall's rows.
    const double       h        = thickness / n_thickness;
    const unsigned int n_height = std::max(1u, static_cast<unsigned int>(std::lround(height / h)));
    const double       dy       = height / n_height;
    Triangulation<dim> tria;
    GridGenerator::subdivided_hyper_rectangle(tria,
                                              {n_thickness, n_height},
                                              Point<dim>(0, 0),
                                              Point<dim>(thickness, height));
    if (with_soil)
    {
      const unsigned int n_soil_y =
        std::max(1u, static_cast<unsigned int>(std::lround(backfill_height / dy)));
      const unsigned int n_soil_x =
        std::max(1u, static_cast<unsigned int>(std::lround(backfill_width / h)));
      Triangulation<dim> backfill, merged;
      GridGenerator::subdivided_hyper_rectangle(backfill,
                                                {n_soil_x, n_soil_y},
                                                Point<dim>(thickness, 0),
                                                Point<dim>(thickness + backfill_width,
                                                           n_soil_y * dy));
      for (const auto &cell : backfill.active_cell_iterators())
        cell->set_material_id(1);
      GridGenerator::merge_triangulations(tria, backfill, merged, 1e-9 * h);
      tria.clear();
      tria.copy_triangulation(merged);
    }
    const double tol = 1e-9 * h;
    for (const auto &cell : tria.active_cell_iterators())
    {
      cell->set_material_id(cell->center()[0] > thickness ? 1 : 0);
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
        {
          const Point<dim> c = face->center();
          face->set_boundary_id(c[1] < tol                                        ? base :
                                std::abs(c[1] - height) < tol && c[0] < thickness ? wall_top :
                                with_soil && std::abs(c[0] - thickness - backfill_width) < tol ?
                                                                                    far_side :
                                                                                    interior);
        }
    }
    std::map<unsigned int, Material> materials{{0, wall}};
    if (with_soil)
      materials[1] = soil;
    return top_load_stiffness(tria, materials, thickness);
  }

  MeshInfo read_mesh_info(const std::filesystem::path &mesh_file,
                          const std::filesystem::path &vtu_file)
  {
    using namespace dealii;
    constexpr int dim = 2;
    AssertThrow(std::filesystem::is_regular_file(mesh_file),
                ExcMessage("mesh_file = '" + mesh_file.string() +
                           "' (must be an existing MSH file)"));
    Triangulation<dim> tria;
    read_msh(mesh_file, tria);

    MeshInfo info;
    info.n_cells           = tria.n_active_cells();
    info.n_vertices        = tria.n_used_vertices();
    info.min_cell_diameter = std::numeric_limits<double>::max();
    Vector<float> material(tria.n_active_cells());
    for (const auto &cell : tria.active_cell_iterators())
    {
      info.area_by_material[cell->material_id()] += cell->measure();
      info.min_cell_diameter              = std::min(info.min_cell_diameter, cell->diameter());
      material(cell->active_cell_index()) = cell->material_id();
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary() && face->boundary_id() != 0)
          info.length_by_boundary[face->boundary_id()] += face->measure();
    }
    if (!vtu_file.empty())
    {
      DataOut<dim> data_out;
      data_out.attach_triangulation(tria);
      data_out.add_data_vector(material, "material_id");
      data_out.build_patches();
      std::ofstream out(vtu_file);
      AssertThrow(out, ExcMessage("vtu_file = '" + vtu_file.string() + "' (cannot be written)"));
      data_out.write_vtu(out);
    }
    return info;
  }
} // namespace kimp::fem
