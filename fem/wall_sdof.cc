// The wall (+ backfill) SDOF seen from the slab band: static solve and subspace iteration for the
// lowest modes of K phi = omega^2 M phi (docs/physics.md §4 "Wall SDOF"): assembly, the static
// solve, the eigen-solver and the choice of the mode.
#include "fem/wall_sdof.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/vector_tools.h>

#include "fem/fe_helpers.h"
#include "fem/material_law.h"
#include "geometry/scene_ids.h"

namespace kimp::fem
{
  double timoshenko_band_stiffness(double height, double thickness, const Material &m, double band)
  {
    if (!(band > 0) || !(band <= height))
      throw std::invalid_argument("band = " + std::to_string(band) + " m (must be in (0, " +
                                  std::to_string(height) + "])");
    constexpr double kappa   = 5.0 / 6.0; // rectangular section
    const double     e_plane = m.youngs_modulus / (1 - m.poisson_ratio * m.poisson_ratio);
    const double     shear   = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
    const double     inertia = thickness * thickness * thickness / 12;
    const double     H = height, b = height - band;
    // Mean over load point and measuring point of the cantilever's bending influence function.
    const double bending = (3 * (std::pow(H, 5) - std::pow(b, 5)) / 20 -
                            b * b * b * (H * H - b * b) / 2 + std::pow(b, 4) * (H - b) / 4) /
                           (3 * e_plane * inertia * band * band);
    const double shearing = (H - 2 * band / 3) / (kappa * shear * thickness);
    return 1.0 / (bending + shearing);
  }

  namespace
  {
    using namespace dealii;
    constexpr int dim = 2;

    void check(bool ok, const std::string &what)
    {
      if (!ok)
        throw std::invalid_argument("wall SDOF: " + what);
    }

    /** M-inner product x^T M y. */
    double m_dot(const SparseMatrix<double> &M, const Vector<double> &x, const Vector<double> &y)
    {
      return M.matrix_scalar_product(x, y);
    }
  } // namespace

  namespace
  {
    /** Refuses parameters the SDOF cannot honour. */
    void check_parameters(const WallSdofParameters &p)
    {
      check(std::filesystem::is_regular_file(p.mesh_file),
            "mesh_file = '" + p.mesh_file.string() + "' (must be an existing MSH file)");
      check(p.band_y1 > p.band_y0,
            "band y = [" + std::to_string(p.band_y0) + ", " + std::to_string(p.band_y1) +
              "] m (must be increasing)");
      check(p.fe_degree >= 1, "fe_degree = " + std::to_string(p.fe_degree) + " (must be >= 1)");
      check(p.n_modes >= 1, "n_modes = " + std::to_string(p.n_modes) + " (must be >= 1)");
      check(p.tolerance > 0, "tolerance = " + std::to_string(p.tolerance) + " (must be > 0)");
      check(p.max_iterations > 0, "max_iterations must be > 0");
    }

    /** The mesh, each of its material ids checked against the given materials. */
    void read_wall_mesh(const WallSdofParameters &p, Triangulation<dim> &tria)
    {
      read_msh(p.mesh_file, tria);
      for (const auto &cell : tria.active_cell_iterators())
      {
        const auto id = cell->material_id();
        check(p.materials.count(id) == 1,
              "the mesh has material id " + std::to_string(id) +
                " but no material is given for it");
        const Material &m = p.materials.at(id);
        check(m.youngs_modulus > 0 && m.poisson_ratio >= 0 && m.poisson_ratio < 0.5 &&
                m.density > 0,
              "material " + std::to_string(id) + ": E = " + std::to_string(m.youngs_modulus) +
                " Pa, nu = " + std::to_string(m.poisson_ratio) +
                ", rho = " + std::to_string(m.density) + " kg/m^3 (must be > 0, in [0, 0.5), > 0)");
      }
    }

    /** Fixed base, far side on rollers. */
    void constrain_supports(const DoFHandler<dim> &dofs, AffineConstraints<double> &constraints)
    {
      VectorTools::interpolate_boundary_values(dofs,
                                               geometry::fixed_base,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints);
      VectorTools::interpolate_boundary_values(dofs,
                                               geometry::soil_far_side,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints,
                                               ComponentMask(std::vector<bool>{true, false}));
      constraints.close();
    }

    /** K, the consistent M (constrained DoFs out of the eigenproblem) and f, 1 N/m spread
     *  over the band; returns the total mass (kg/m). */
    double assemble_band_system(const WallSdofParameters        &p,
                                const DoFHandler<dim>           &dofs,
                                const AffineConstraints<double> &constraints,
                                SparseMatrix<double>            &K,
                                SparseMatrix<double>            &M,
                                Vector<double>                  &f)
    {
      const FiniteElement<dim> &fe = dofs.get_fe();
      const unsigned int        n  = dofs.n_dofs();
      const QGauss<dim>         quadrature(p.fe_degree + 1);
      const QGauss<dim - 1>     face_quadrature(p.fe_degree + 1);
      FEValues<dim>      fv(fe, quadrature, update_values | update_gradients | update_JxW_values);
      FEFaceValues<dim>  ffv(fe,
                            face_quadrature,
                            update_values | update_quadrature_points | update_JxW_values);
      const unsigned int nc = fe.n_dofs_per_cell();
      FullMatrix<double> ck(nc, nc), cm(nc, nc);
      Vector<double>     cf(nc);
      std::vector<types::global_dof_index> indices(nc);
      const double                         traction   = 1.0 / (p.band_y1 - p.band_y0);
      double                               total_mass = 0, loaded_length = 0;
      const double                         tol_y = 1e-9 * (p.band_y1 - p.band_y0);
      for (const auto &cell : dofs.active_cell_iterators())
      {
        const Material &m = p.materials.at(cell->material_id());
        const Lame      l = lame(m.youngs_modulus, m.poisson_ratio);
        fv.reinit(cell);
        ck = 0;
        cm = 0;
        cf = 0;
        add_elastic_stiffness(fv, l.lambda, l.mu, ck);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          total_mass += m.density * fv.JxW(q);
          for (unsigned int i = 0; i < nc; ++i)
            for (unsigned int j = 0; j < nc; ++j)
              if (fe.system_to_component_index(j).first == fe.system_to_component_index(i).first)
                cm(i, j) += m.density * fv.shape_value(i, q) * fv.shape_value(j, q) * fv.JxW(q);
        }
        for (const auto face : cell->face_indices())
          if (cell->face(face)->at_boundary() &&
              cell->face(face)->boundary_id() == geometry::wall_contact)
          {
            const double y = cell->face(face)->center()[1];
            if (y < p.band_y0 - tol_y || y > p.band_y1 + tol_y)
              continue;
            ffv.reinit(cell, face);
            loaded_length += cell->face(face)->measure();
            add_x_traction(ffv, traction, cf);
          }
        cell->get_dof_indices(indices);
        constraints.distribute_local_to_global(ck, cf, indices, K, f);
        constraints.distribute_local_to_global(cm, indices, M);
      }
      // The band must be resolved by the mesh (its ends on cell edges): else the load would not
      // total 1 N/m and k would not be the band's.
      check(std::abs(loaded_length - (p.band_y1 - p.band_y0)) < 1e-6 * (p.band_y1 - p.band_y0),
            "the wall_contact faces with their centre in y = [" + std::to_string(p.band_y0) + ", " +
              std::to_string(p.band_y1) + "] m total " + std::to_string(loaded_length) +
              " m (the band's ends must be mesh lines)");
      // Constrained DoFs: K keeps a positive diagonal, M none, so they leave the eigenproblem.
      for (unsigned int i = 0; i < n; ++i)
        if (constraints.is_constrained(i))
          M.set(i, i, 0.0);
      return total_mass;
    }

    /** Subspace iteration for the lowest modes: Y = K^-1 M X, Rayleigh-Ritz on span(Y), X =
     *  the Ritz vectors (M-normalised), started from the static deflection; @p lambda the
     *  Ritz values, ascending; returns the iterations. */
    unsigned int subspace_iteration(const WallSdofParameters        &p,
                                    const AffineConstraints<double> &constraints,
                                    const SparseMatrix<double>      &K,
                                    const SparseMatrix<double>      &M,
                                    const SparseDirectUMFPACK       &K_inverse,
                                    const Vector<double>            &static_deflection,
                                    unsigned int                     q,
                                    std::vector<Vector<double>>     &X,
                                    std::vector<double>             &lambda)
    {
      const unsigned int                     n     = static_deflection.size();
      const unsigned int                     block = X.size();
      std::vector<Vector<double>>            Y(block, Vector<double>(n));
      std::mt19937                           rng(20240531); // fixed: reproducible modes
      std::uniform_real_distribution<double> uniform(-1.0, 1.0);
      Vector<double>                         tmp(n);
      Y[0] = static_deflection; // the band's own deflection: every participating mode is in it
      for (unsigned int j = 1; j < block; ++j)
      {
        for (unsigned int i = 0; i < n; ++i)
          tmp(i) = constraints.is_constrained(i) ? 0.0 : uniform(rng);
        M.vmult(X[j], tmp);
        K_inverse.vmult(Y[j], X[j]);
      }
      std::vector<double> previous(block, 0.0);
      bool                converged  = false;
      unsigned int        iterations = 0;
      for (unsigned int it = 1; it <= p.max_iterations && !converged; ++it)
      {
        LAPACKFullMatrix<double>    Kr(block, block), Mr(block, block);
        std::vector<Vector<double>> MY(block, Vector<double>(n)), KY(block, Vector<double>(n));
        for (unsigned int j = 0; j < block; ++j)
        {
          M.vmult(MY[j], Y[j]);
          K.vmult(KY[j], Y[j]);
        }
        for (unsigned int a = 0; a < block; ++a)
          for (unsigned int b = a; b < block; ++b)
          {
            const double kab = Y[a] * KY[b], mab = Y[a] * MY[b];
            Kr(a, b) = Kr(b, a) = 0.5 * (kab + Y[b] * KY[a]);
            Mr(a, b) = Mr(b, a) = 0.5 * (mab + Y[b] * MY[a]);
          }
        std::vector<Vector<double>> Q(block, Vector<double>(block));
        Kr.compute_generalized_eigenvalues_symmetric(Mr, Q);
        std::vector<unsigned int> order(block);
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(),
                  order.end(),
                  [&](unsigned int a, unsigned int b)
                  { return Kr.eigenvalue(a).real() < Kr.eigenvalue(b).real(); });
        for (unsigned int j = 0; j < block; ++j)
        {
          lambda[j] = Kr.eigenvalue(order[j]).real();
          X[j]      = 0;
          for (unsigned int a = 0; a < block; ++a)
            X[j].add(Q[order[j]](a), Y[a]);
          X[j] /= std::sqrt(m_dot(M, X[j], X[j])); // M-normalised Ritz vector
        }
        converged = it > 1;
        for (unsigned int j = 0; j < q; ++j)
          converged = converged && std::abs(lambda[j] - previous[j]) <= p.tolerance * lambda[j];
        previous   = lambda;
        iterations = it;
        if (!converged)
          for (unsigned int j = 0; j < block; ++j)
          {
            M.vmult(tmp, X[j]);
            K_inverse.vmult(Y[j], tmp);
          }
      }
      if (!converged)
        throw NumericalError("wall SDOF: the subspace iteration did not converge in " +
                               std::to_string(p.max_iterations) + " iterations",
                             0,
                             iterations);
      return iterations;
    }

    /** The modes' share of the band's static compliance, the mode that carries most of it,
     *  and the effective mass of the static deflection. */
    void choose_mode(WallSdof                          &result,
                     const SparseMatrix<double>        &M,
                     const Vector<double>              &f,
                     const Vector<double>              &static_deflection,
                     const std::vector<Vector<double>> &X,
                     const std::vector<double>         &lambda,
                     unsigned int                       q)
    {
      for (unsigned int j = 0; j < q; ++j)
      {
        check(lambda[j] > 0,
              "mode " + std::to_string(j) + " has omega^2 = " + std::to_string(lambda[j]) +
                " (the model is not supported)");
        WallMode     mode;
        const double participation = f * X[j]; // X is M-normalised
        mode.omega                 = std::sqrt(lambda[j]);
        mode.frequency             = mode.omega / (2 * M_PI);
        mode.share     = participation * participation / lambda[j] * result.static_stiffness;
        mode.band_mass = participation != 0 ? 1.0 / (participation * participation) :
                                              std::numeric_limits<double>::infinity();
        result.modes.push_back(mode);
      }
      const auto best =
        std::max_element(result.modes.begin(),
                         result.modes.end(),
                         [](const WallMode &a, const WallMode &b) { return a.share < b.share; });
      result.mode           = static_cast<unsigned int>(best - result.modes.begin());
      result.mode_frequency = best->frequency;
      result.mode_share     = best->share;
      result.mode_mass      = result.static_stiffness / (best->omega * best->omega);
      const double k        = result.static_stiffness;
      result.effective_mass = k * k * m_dot(M, static_deflection, static_deflection);
      result.omega          = std::sqrt(k / result.effective_mass);
      result.frequency      = result.omega / (2 * M_PI);
      for (const WallMode &m : result.modes)
        result.modal_sum_mass += k * m.share / (m.omega * m.omega);
    }
  } // namespace

  WallSdof wall_sdof(const WallSdofParameters &p)
  {
    check_parameters(p);
    Triangulation<dim> tria;
    read_wall_mesh(p, tria);
    FESystem<dim>   fe(FE_Q<dim>(p.fe_degree), dim);
    DoFHandler<dim> dofs(tria);
    dofs.distribute_dofs(fe);
    const unsigned int        n = dofs.n_dofs();
    AffineConstraints<double> constraints;
    constrain_supports(dofs, constraints);
    DynamicSparsityPattern dsp(n);
    DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
    SparsityPattern pattern;
    pattern.copy_from(dsp);
    SparseMatrix<double> K(pattern), M(pattern);
    Vector<double>       f(n);
    const double         total_mass = assemble_band_system(p, dofs, constraints, K, M, f);

    WallSdof result;
    result.n_dofs     = n;
    result.n_cells    = tria.n_active_cells();
    result.total_mass = total_mass;

    SparseDirectUMFPACK K_inverse;
    K_inverse.initialize(K);
    Vector<double> static_deflection(n);
    K_inverse.vmult(static_deflection, f);
    const double compliance = f * static_deflection;
    if (!(compliance > 0))
      throw NumericalError("wall SDOF: static compliance " + std::to_string(compliance) +
                             " m per N/m (the wall is not supported)",
                           0,
                           0);
    result.static_stiffness = 1.0 / compliance;

    const unsigned int          n_free = n - constraints.n_constraints();
    const unsigned int          q      = std::min(p.n_modes, n_free);
    const unsigned int          block  = std::min(2 * q + 2, n_free);
    std::vector<Vector<double>> X(block, Vector<double>(n));
    std::vector<double>         lambda(block, 0.0);
    result.iterations =
      subspace_iteration(p, constraints, K, M, K_inverse, static_deflection, q, X, lambda);
    choose_mode(result, M, f, static_deflection, X, lambda, q);
    return result;
  }
} // namespace kimp::fem
