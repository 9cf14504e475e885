// ImpactProblem setup: run_impact(), run() and the phases before the time loop: parameter
// validation, mesh (rigid slab: slab cells dropped), DoFs and constraints, constitutive laws,
// lumped mass and stiffness, and the explicit stability limit.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <tuple>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>

#include "fem/fe_helpers.h"
#include "fem/impact/impact_problem.h"
#include "geometry/scene_ids.h"

namespace kimp::fem
{
  double p_wave_speed(const Material &m)
  {
    const Lame l = lame(m.youngs_modulus, m.poisson_ratio);
    return std::sqrt((l.lambda + 2 * l.mu) / m.density);
  }

  double penalty_omega_ratio_for_step(double step_ratio, double damping_ratio)
  {
    internal::require(step_ratio > 0 && step_ratio < 1,
                      "penalty_step_ratio = " + internal::fmt_double(step_ratio) +
                        " (must be in (0, 1))");
    // Step of mesh and penalty over the mesh's own at omega_p = r omega_mesh.
    const auto ratio = [damping_ratio](double r)
    {
      const double q  = std::sqrt(1 + r * r);
      const double xi = damping_ratio * r / q;
      return (std::sqrt(1 + xi * xi) - xi) / q;
    };
    // ratio(r) <= 1 / sqrt(1 + r^2), so the root lies in [0, sqrt(1 / step_ratio^2 - 1)].
    double lo = 0, hi = std::sqrt(1 / (step_ratio * step_ratio) - 1);
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      if (ratio(mid) > step_ratio)
        lo = mid;
      else
        hi = mid;
    }
    return 0.5 * (lo + hi);
  }

  SubcycledStep
  subcycled_step(double omega_mesh, double omega_penalty, double dt_stable, unsigned int subcycles)
  {
    SubcycledStep s;
    s.limit = subcycle_mesh_fraction * 2 / omega_mesh;
    if (omega_penalty > 0)
      s.limit = std::min(s.limit, subcycle_phase_limit / omega_penalty);
    s.substeps =
      subcycles >= 2 ?
        subcycles :
        std::max(2u, static_cast<unsigned int>(std::ceil(s.limit / dt_stable * (1 - 1e-12))));
    return s;
  }

  ImpactResult run_impact(const ImpactParameters &parameters, MPI_Comm comm, std::ostream *log)
  {
    internal::ImpactProblem problem(parameters, comm, log);
    return problem.run();
  }
} // namespace kimp::fem

namespace kimp::fem::internal
{
  using namespace dealii;

  /** Largest ImplicitOptions::max_halvings: time is counted in integer ticks of dt / 2^max. */
  constexpr unsigned int max_step_halvings = 30;

  namespace
  {
    std::string with_digits(double x, int digits)
    {
      std::ostringstream s;
      s.precision(digits);
      s << x;
      return s.str();
    }
  } // namespace

  std::string fmt_double(double x)
  {
    return with_digits(x, 6);
  }

  std::string fmt_sig(double x)
  {
    return with_digits(x, 4);
  }

  void
  reduce_over_ranks(const double *local, double *global, std::size_t n, MPI_Op op, MPI_Comm comm)
  {
    const int ierr = MPI_Allreduce(local, global, static_cast<int>(n), MPI_DOUBLE, op, comm);
    AssertThrowMPI(ierr);
  }

  std::vector<double> sum_over_ranks(const std::vector<double> &local, MPI_Comm comm)
  {
    std::vector<double> global(local.size());
    reduce_over_ranks(local.data(), global.data(), local.size(), MPI_SUM, comm);
    return global;
  }

  void require(bool ok, const std::string &message)
  {
    AssertThrow(ok, ExcMessage(message));
  }

  ImpactProblem::ImpactProblem(const ImpactParameters &parameters,
                               MPI_Comm                comm_,
                               std::ostream           *log_)
    : prm(parameters)
    , comm(comm_)
    , log(log_)
    , triangulation(comm_)
    , fe(FE_Q<dim>(1), dim)
    , dof_handler(triangulation)
  {
  }

  void ImpactProblem::log_line(const std::string &s) const
  {
    if (log != nullptr && Utilities::MPI::this_mpi_process(comm) == 0)
      *log << s << '\n';
  }

  ImpactResult ImpactProblem::run()
  {
    const auto start = std::chrono::steady_clock::now();
    validate_parameters();
    make_grid();
    setup_system();
    make_laws();
    // The lumped mass is needed by the contact setup (reduced masses), the contact DoFs by the
    // implicit sparsity pattern: assemble the mass first with a provisional pattern.
    contact_dofs.clear();
    assemble_system();
    setup_contact();
    if (prm.wall_soil_interface.contact)
      setup_interface();
    if (prm.integrator == ImpactParameters::Integrator::implicit_newmark || interface)
      assemble_system();
    assemble_dashpots();
    setup_slab_damping();
    if (prm.geostatic.enabled)
      run_geostatic_step();
    compute_time_step();
    e0 = 0.5 * slab_total_mass * prm.initial_velocity * prm.initial_velocity;
    log_line("mesh: " + std::to_string(triangulation.n_global_active_cells()) + " cells, " +
             std::to_string(dof_handler.n_dofs()) + " DoFs on " +
             std::to_string(Utilities::MPI::n_mpi_processes(comm)) + " ranks; dt = " + fmt_sig(dt) +
             " s (stable " + fmt_sig(dt_stable) + " s, mesh omega " + fmt_sig(omega_mesh) +
             " rad/s, penalty omega " + fmt_sig(omega_penalty) + " rad/s)");
    if (prm.integrator == ImpactParameters::Integrator::explicit_central_difference)
      run_explicit();
    else
      run_implicit();
    if (prm.progress && Utilities::MPI::this_mpi_process(comm) == 0)
      prm.progress(n_steps_done * dt, prm.end_time);
    ImpactResult result;
    finish(result, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    log_line(
      "done: " + std::to_string(result.summary.n_steps) + " steps, peak force " +
      fmt_sig(result.summary.peak_force) + " N/m, contact " +
      fmt_sig(result.summary.contact_duration) + " s, impulse " + fmt_sig(result.summary.impulse) +
      " N s/m, COR " + fmt_sig(result.summary.apparent_cor) + ", max |dE/E0| " +
      fmt_sig(result.summary.energy_error) + ", " + fmt_sig(result.summary.wall_seconds) + " s");
    return result;
  }

  void ImpactProblem::validate_parameters() const
  {
    require(std::filesystem::is_regular_file(prm.mesh_file),
            "mesh_file = '" + prm.mesh_file.string() + "' (must be an existing MSH file)");
    require(!prm.materials.empty(), "materials is empty (must give one per material id)");
    for (const auto &[id, m] : prm.materials)
    {
      const std::string key = "materials[" + std::to_string(id) + "].";
      require(m.youngs_modulus > 0,
              key + "youngs_modulus = " + fmt_double(m.youngs_modulus) + " Pa (must be > 0)");
      require(m.poisson_ratio >= 0 && m.poisson_ratio < 0.5,
              key + "poisson_ratio = " + fmt_double(m.poisson_ratio) + " (must be in [0, 0.5))");
      require(m.density > 0, key + "density = " + fmt_double(m.density) + " kg/m^3 (must be > 0)");
    }
    for (const auto &[id, law] : prm.material_laws)
      require(law != nullptr && prm.materials.count(id) > 0,
              "material_laws[" + std::to_string(id) +
                "] (must be a law for a material id that has an entry in materials)");
    if (prm.rigid_slab)
    {
      require(prm.slab_mass > 0,
              "slab_mass = " + fmt_double(prm.slab_mass) + " kg/m (must be > 0 for a rigid slab)");
      require(prm.slab_face_y1 > prm.slab_face_y0,
              "slab_face_y1 = " + fmt_double(prm.slab_face_y1) +
                " m (must be > slab_face_y0 = " + fmt_double(prm.slab_face_y0) + " m)");
    }
    require(prm.initial_velocity > 0,
            "initial_velocity = " + fmt_double(prm.initial_velocity) + " m/s (must be > 0)");
    require(prm.penalty_factor > 0,
            "penalty_factor = " + fmt_double(prm.penalty_factor) + " (must be > 0)");
    require(prm.penalty_step_ratio >= 0 && prm.penalty_step_ratio < 1,
            "penalty_step_ratio = " + fmt_double(prm.penalty_step_ratio) +
              " (must be in [0, 1); 0 = off)");
    require(prm.contact_subcycles <= 64 &&
              (prm.contact_subcycles == 1 ||
               prm.integrator == ImpactParameters::Integrator::explicit_central_difference),
            "contact_subcycles = " + std::to_string(prm.contact_subcycles) +
              " (must be in [0, 64]: 1 off, 0 automatic, N sub-steps; explicit integrator only)");
    require(prm.contact_damping_ratio >= 0 && prm.contact_damping_ratio <= 1,
            "contact_damping_ratio = " + fmt_double(prm.contact_damping_ratio) +
              " (must be in [0, 1])");
    require(prm.slab_damping_ratio >= 0 && prm.slab_damping_ratio <= 1,
            "slab_damping_ratio = " + fmt_double(prm.slab_damping_ratio) + " (must be in [0, 1])");
    require(prm.slab_damping_ratio == 0 ||
              (!prm.rigid_slab &&
               prm.integrator == ImpactParameters::Integrator::explicit_central_difference),
            "slab_damping_ratio = " + fmt_double(prm.slab_damping_ratio) +
              " (needs an elastic slab and the explicit integrator; 0 = off)");
    require(prm.boundary_spring_normal >= 0 && prm.boundary_spring_tangential >= 0 &&
              (prm.boundary_spring_normal + prm.boundary_spring_tangential == 0 ||
               !prm.absorbing_boundaries.empty()),
            "boundary springs alpha_n = " + fmt_double(prm.boundary_spring_normal) +
              ", alpha_t = " + fmt_double(prm.boundary_spring_tangential) +
              " (must be >= 0; either > 0 needs absorbing_boundaries)");
    require(prm.smoothing_window >= 0,
            "smoothing_window = " + fmt_double(prm.smoothing_window) + " s (must be >= 0)");
    require(prm.dt >= 0, "dt = " + fmt_double(prm.dt) + " s (must be >= 0; 0 = automatic)");
    require(prm.explicit_options.dt_over_limit >= 0 &&
              (prm.explicit_options.dt_over_limit == 0 || prm.dt == 0),
            "dt_over_limit = " + fmt_double(prm.explicit_options.dt_over_limit) +
              " (must be >= 0, and dt must be 0 when it is used)");
    require(prm.explicit_options.cfl_safety > 0 && prm.explicit_options.cfl_safety <= 1,
            "cfl_safety = " + fmt_double(prm.explicit_options.cfl_safety) + " (must be in (0, 1])");
    require(prm.implicit_options.dt_factor > 0,
            "implicit_dt_factor = " + fmt_double(prm.implicit_options.dt_factor) +
              " (must be > 0)");
    require(prm.end_time > 0, "end_time = " + fmt_double(prm.end_time) + " s (must be > 0)");
    require(prm.separation_velocity_fraction >= 0 && prm.separation_velocity_fraction < 1,
            "separation_velocity_fraction = " + fmt_double(prm.separation_velocity_fraction) +
              " (must be in [0, 1))");
    require(prm.stored_energy_fraction > 0 && prm.stored_energy_fraction <= 1,
            "stored_energy_fraction = " + fmt_double(prm.stored_energy_fraction) +
              " (must be in (0, 1])");
    require(prm.rebound_velocity_fraction > 0 && prm.rebound_velocity_fraction <= 1,
            "rebound_velocity_fraction = " + fmt_double(prm.rebound_velocity_fraction) +
              " (must be in (0, 1])");
    require(prm.separation_hold_time >= 0,
            "separation_hold_time = " + fmt_double(prm.separation_hold_time) + " s (must be >= 0)");
    require(prm.output_interval >= 0,
            "output_interval = " + fmt_double(prm.output_interval) + " s (must be >= 0)");
    require(prm.implicit_options.max_halvings <= max_step_halvings,
            "implicit_max_halvings = " + std::to_string(prm.implicit_options.max_halvings) +
              " (must be <= " + std::to_string(max_step_halvings) + ")");
    require(prm.implicit_options.newton_max_iterations > 0,
            "implicit_newton_max_iterations = " +
              std::to_string(prm.implicit_options.newton_max_iterations) + " (must be > 0)");
    require(prm.progress_interval > 0,
            "progress_interval = " + std::to_string(prm.progress_interval) +
              " steps (must be > 0)");
    require(prm.vtu_interval >= 0,
            "vtu_interval = " + fmt_double(prm.vtu_interval) + " s (must be >= 0)");
    require(prm.frame_interval >= 0,
            "frame_interval = " + fmt_double(prm.frame_interval) + " s (must be >= 0)");
  }

  void ImpactProblem::make_grid()
  {
    Triangulation<dim> serial;
    read_msh(prm.mesh_file, serial);
    for (const auto &cell : serial.active_cell_iterators())
      require(prm.materials.count(cell->material_id()) > 0,
              "mesh '" + prm.mesh_file.string() + "' has material id " +
                std::to_string(cell->material_id()) + " (no entry in materials)");
    if (!prm.rigid_slab)
    {
      triangulation.copy_triangulation(serial);
      return;
    }
    // Rigid slab: drop the slab cells; boundary ids are restored from the face centres because
    // removing cells does not carry them over.
    // Keyed by the face centre and the cell's material: the wall_back and soil_front faces of
    // a contact interface share their centres.
    std::map<std::tuple<double, double, unsigned int>, types::boundary_id> boundary_of;
    std::set<typename Triangulation<dim>::active_cell_iterator>            slab_cells;
    for (const auto &cell : serial.active_cell_iterators())
    {
      if (cell->material_id() == geometry::slab_material)
        slab_cells.insert(cell);
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          boundary_of[{face->center()[0], face->center()[1], cell->material_id()}] =
            face->boundary_id();
    }
    Triangulation<dim> reduced;
    if (slab_cells.empty())
      reduced.copy_triangulation(serial);
    else
      GridGenerator::create_triangulation_with_removed_cells(serial, slab_cells, reduced);
    for (const auto &cell : reduced.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
        {
          const auto it =
            boundary_of.find({face->center()[0], face->center()[1], cell->material_id()});
          face->set_boundary_id(it == boundary_of.end() ? 0 : it->second);
        }
    triangulation.copy_triangulation(reduced);
  }

  void ImpactProblem::setup_system()
  {
    dof_handler.distribute_dofs(fe);
    locally_owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant);

    constraints.clear();
    constraints.reinit(locally_relevant);
    if (!is_absorbing(geometry::fixed_base))
      VectorTools::interpolate_boundary_values(dof_handler,
                                               geometry::fixed_base,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints);
    if (!is_absorbing(geometry::soil_far_side))
      VectorTools::interpolate_boundary_values(dof_handler,
                                               geometry::soil_far_side,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints,
                                               ComponentMask(std::vector<bool>{true, false}));
    constrain_non_absorbing_faces();
    constraints.close();
  }

  void ImpactProblem::make_stiffness_sparsity()
  {
    DynamicSparsityPattern dsp(locally_relevant);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    if (prm.integrator == ImpactParameters::Integrator::implicit_newmark)
      for (const auto i : contact_dofs)
        if (locally_relevant.is_element(i))
          for (const auto j : contact_dofs)
            dsp.add(i, j);
    // The wall-soil interface springs couple nodes of different cells (geostatic operator).
    for (const auto i : interface_dofs)
      if (locally_relevant.is_element(i))
        for (const auto j : interface_dofs)
          dsp.add(i, j);
    SparsityTools::distribute_sparsity_pattern(dsp, locally_owned, comm, locally_relevant);
    stiffness.reinit(locally_owned, locally_owned, dsp, comm);
  }

  void ImpactProblem::mark_free_dofs()
  {
    inverse_mass.reinit(locally_owned, comm);
    free_mask.reinit(locally_owned, comm);
    for (const auto i : locally_owned)
      if (!constraints.is_constrained(i) && mass(i) > 0)
      {
        inverse_mass(i) = 1.0 / mass(i);
        free_mask(i)    = 1.0;
      }
    inverse_mass.compress(VectorOperation::insert);
    free_mask.compress(VectorOperation::insert);
    slab_total_mass = prm.rigid_slab ? prm.slab_mass : slab_mass_x.l1_norm();
    require(slab_total_mass > 0,
            "mesh '" + prm.mesh_file.string() + "' has no slab cells (material id " +
              std::to_string(static_cast<unsigned>(geometry::slab_material)) +
              ") and rigid_slab is false");
  }

  void ImpactProblem::assemble_system()
  {
    make_stiffness_sparsity();
    Vec mass_w, slab_w, body_x_w, body_y_w;
    mass_w.reinit(locally_owned, locally_relevant, comm, true);
    slab_w.reinit(locally_owned, locally_relevant, comm, true);
    body_x_w.reinit(locally_owned, locally_relevant, comm, true);
    body_y_w.reinit(locally_owned, locally_relevant, comm, true);

    const QGauss<dim>        quadrature(2);
    const QGaussLobatto<dim> lobatto(2);
    FEValues<dim>            fe_values(fe, quadrature, update_gradients | update_JxW_values);
    FEValues<dim>            fe_mass(fe, lobatto, update_values | update_JxW_values);
    const unsigned int       n = fe.n_dofs_per_cell();
    FullMatrix<double>       cell_matrix(n, n);
    Vector<double>           cell_mass(n), cell_slab(n), cell_x(n), cell_y(n);
    std::vector<types::global_dof_index> dof_indices(n);
    std::vector<std::array<double, 3>>   b(4 * n);          // by Gauss point, then DoF
    std::array<double, 2>                body_held{{0, 0}}; // a constrained DoF, per component
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const Material    &m   = prm.materials.at(cell->material_id());
        const MaterialLaw &law = *laws.at(cell->material_id());
        // K from the law's tangent in the virgin state (modified Newton for non-linear laws).
        std::vector<double> history(law.n_history());
        law.initial_history(history.data());
        const VoigtTangent d = law.tangent({{0, 0, 0}}, history.data());
        fe_values.reinit(cell);
        fe_mass.reinit(cell);
        cell_matrix = 0;
        cell_mass   = 0;
        cell_slab   = 0;
        strain_columns(cell->material_id(), fe_values, b); // B-bar in the soil's cells
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const std::array<double, 3> *bq = &b[q * n];
          for (unsigned int i = 0; i < n; ++i)
          {
            std::array<double, 3> db{};
            for (unsigned int r = 0; r < 3; ++r)
              for (unsigned int c = 0; c < 3; ++c)
                db[c] += bq[i][r] * d[3 * r + c];
            for (unsigned int j = 0; j < n; ++j)
              cell_matrix(i, j) +=
                (db[0] * bq[j][0] + db[1] * bq[j][1] + db[2] * bq[j][2]) * fe_values.JxW(q);
          }
        }
        // Gauss-Lobatto points are the vertices: the mass matrix is diagonal.
        for (unsigned int q = 0; q < lobatto.size(); ++q)
          for (unsigned int i = 0; i < n; ++i)
          {
            const double phi = fe_mass.shape_value(i, q);
            cell_mass(i) += m.density * phi * phi * fe_mass.JxW(q);
          }
        cell_x = 0;
        cell_y = 0;
        if (cell->material_id() == geometry::slab_material)
          for (unsigned int i = 0; i < n; ++i)
            if (fe.system_to_component_index(i).first == 0)
              cell_slab(i) = cell_mass(i);
        cell->get_dof_indices(dof_indices);
        if (cell->material_id() != geometry::slab_material)
          for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int c          = fe.system_to_component_index(i).first;
            (c == 0 ? cell_x : cell_y)(i) = cell_mass(i);
            if (constraints.is_constrained(dof_indices[i]))
              body_held[c] = 1;
          }
        constraints.distribute_local_to_global(cell_matrix, dof_indices, stiffness);
        mass_w.add(dof_indices, cell_mass);
        slab_w.add(dof_indices, cell_slab);
        body_x_w.add(dof_indices, cell_x);
        body_y_w.add(dof_indices, cell_y);
      }
    stiffness.compress(VectorOperation::add);
    mass_w.compress(VectorOperation::add);
    slab_w.compress(VectorOperation::add);
    body_x_w.compress(VectorOperation::add);
    body_y_w.compress(VectorOperation::add);
    mass.reinit(locally_owned, comm);
    slab_mass_x.reinit(locally_owned, comm);
    mass        = mass_w;
    slab_mass_x = slab_w;
    body_mass_x.reinit(locally_owned, comm);
    body_mass_y.reinit(locally_owned, comm);
    body_mass_x = body_x_w;
    body_mass_y = body_y_w;
    // A translation of wall and soil is carried away, not stored, only along a component no
    // support holds (the free struck bar of the wave checks; never the scene's wall).
    std::array<double, 2> held{};
    reduce_over_ranks(body_held.data(), held.data(), 2, MPI_MAX, comm);
    body_free_mass = {
      {held[0] > 0 ? 0.0 : body_mass_x.l1_norm(), held[1] > 0 ? 0.0 : body_mass_y.l1_norm()}};
    mark_free_dofs();
  }

  void ImpactProblem::make_laws()
  {
    laws.clear();
    linear_laws           = true;
    unsigned int n_values = 0;
    for (const auto &[id, m] : prm.materials)
    {
      const auto it = prm.material_laws.find(id);
      laws[id] =
        it != prm.material_laws.end() ? it->second : std::make_shared<const LinearElasticLaw>(m);
      linear_laws = linear_laws && laws[id]->is_linear();
      n_values    = std::max(n_values, laws[id]->n_history());
    }
    // A wall-soil contact interface is not linear: energies from the internal work.
    if (prm.wall_soil_interface.contact)
      linear_laws = false;
    if (linear_laws)
      return;
    qp_history.reinit(triangulation.n_active_cells(), QGauss<dim>(2).size(), n_values);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        // The wall's cells on the clamped base anchor its bars (strain penetration).
        double anchored_height = 0;
        if (cell->material_id() == geometry::wall_material)
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == geometry::fixed_base)
              anchored_height = cell->extent_in_direction(1);
        // Crack-band length of a quadrilateral: the square root of its area.
        qp_history.initialize_cell(cell->active_cell_index(),
                                   *laws.at(cell->material_id()),
                                   std::sqrt(cell->measure()),
                                   anchored_height);
      }
    u_ghosted.reinit(locally_owned, locally_relevant, comm);
    force_writable.reinit(locally_owned, locally_relevant, comm, true);
    setup_internal_force();
  }

  void ImpactProblem::internal_force(const Vec &u, Vec &f)
  {
    laws_internal_force(u, f);
    if (geostatic_on)
      f += geostatic_offset;
    if (interface)
      subtract_interface_force(u, f);
  }

  double ImpactProblem::slab_velocity(const Vec &v, double v_r) const
  {
    return prm.rigid_slab ? v_r : (slab_mass_x * v) / slab_total_mass;
  }

  ImpactProblem::LoopSteps ImpactProblem::loop_steps() const
  {
    LoopSteps s;
    s.write_vtu = !prm.vtu_dir.empty() && prm.vtu_interval > 0;
    s.vtu_every = s.write_vtu ? std::max<unsigned long>(1, std::lround(prm.vtu_interval / dt)) : 0;
    s.frame_every =
      prm.frame_interval > 0 ? std::max<unsigned long>(1, std::lround(prm.frame_interval / dt)) : 0;
    s.n_max      = static_cast<unsigned long>(std::ceil(prm.end_time / dt));
    s.hold_steps = static_cast<unsigned long>(std::ceil(prm.separation_hold_time / dt));
    return s;
  }

  bool ImpactProblem::slab_no_longer_comes_in(double slab_v) const
  {
    return !(slab_v > prm.separation_velocity_fraction * prm.initial_velocity);
  }

  bool ImpactProblem::system_released_the_slab(double slab_v) const
  {
    return slab_no_longer_comes_in(slab_v) &&
           (stored_share <= prm.stored_energy_fraction ||
            -slab_v >= prm.rebound_velocity_fraction * prm.initial_velocity);
  }

  double ImpactProblem::cells_omega() const
  {
    double local_omega = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        double h = std::numeric_limits<double>::max();
        for (unsigned int l = 0; l < cell->n_lines(); ++l)
          h = std::min(h, cell->line(l)->diameter());
        local_omega =
          std::max(local_omega, 2 * p_wave_speed(prm.materials.at(cell->material_id())) / h);
      }
    return Utilities::MPI::max(local_omega, comm);
  }

  void ImpactProblem::compute_time_step()
  {
    // Q1 with a lumped mass: the highest mode of a cell of smallest edge h is omega = 2 c_p / h
    // (exact in 1D); a contact spring adds omega_c^2 = k (1/m_s + 1/m_m) at its nodes. The
    // damped central-difference limit is dt = 2 / omega (sqrt(1 + xi^2) - xi) (Belytschko
    // et al. 2014, eq. 6.3.14) with xi the contact damping seen by the highest mode.
    omega_mesh = cells_omega();
    if (omega_interface > 0) // the wall-soil interface springs
      omega_mesh = std::sqrt(omega_mesh * omega_mesh + omega_interface * omega_interface);
    const double omega = std::sqrt(omega_mesh * omega_mesh + omega_penalty * omega_penalty);
    const double xi    = prm.contact_damping_ratio * omega_penalty / omega;
    dt_stable          = 2 / omega * (std::sqrt(1 + xi * xi) - xi);
    if (prm.contact_subcycles != 1)
      compute_subcycled_step();
    else if (prm.integrator == ImpactParameters::Integrator::explicit_central_difference)
    {
      require(prm.dt <= dt_stable,
              "dt = " + fmt_double(prm.dt) + " s is above the explicit stability limit " +
                fmt_double(dt_stable) + " s (mesh omega = " + fmt_double(omega_mesh) +
                " rad/s, contact penalty omega = " + fmt_double(omega_penalty) + " rad/s)");
      dt = prm.dt > 0                             ? prm.dt :
           prm.explicit_options.dt_over_limit > 0 ? prm.explicit_options.dt_over_limit * dt_stable :
                                                    prm.explicit_options.cfl_safety * dt_stable;
    }
    else
      dt = prm.dt > 0 ? prm.dt : prm.implicit_options.dt_factor * dt_stable;
    dt_contact   = dt / contact_substeps;
    sample_every = prm.output_interval > 0 ?
                     std::max<unsigned long>(1, std::lround(prm.output_interval / dt)) :
                     1;
  }

  void ImpactProblem::compute_subcycled_step()
  {
    // The contact nodes feel the mesh as an impulse per step and the penalty at every sub-step:
    // the step is the cells' own unless the penalty turns by more than subcycle_phase_limit in
    // it; each sub-step must keep the damped penalty spring alone stable.
    const SubcycledStep s =
      subcycled_step(omega_mesh, omega_penalty, dt_stable, prm.contact_subcycles);
    require(prm.dt <= s.limit,
            "dt = " + fmt_double(prm.dt) + " s is above the sub-cycled stability limit " +
              fmt_double(s.limit) + " s (mesh omega = " + fmt_double(omega_mesh) +
              " rad/s, contact penalty omega = " + fmt_double(omega_penalty) + " rad/s)");
    dt                    = prm.dt > 0                             ? prm.dt :
                            prm.explicit_options.dt_over_limit > 0 ? prm.explicit_options.dt_over_limit * s.limit :
                                                                     prm.explicit_options.cfl_safety * s.limit;
    contact_substeps      = s.substeps;
    const double xi       = prm.contact_damping_ratio;
    const double dt_alone = omega_penalty > 0 ? 2 / omega_penalty * (std::sqrt(1 + xi * xi) - xi) :
                                                std::numeric_limits<double>::infinity();
    require(dt / contact_substeps <= dt_alone,
            "contact_subcycles = " + std::to_string(contact_substeps) + ": the sub-step " +
              fmt_double(dt / contact_substeps) +
              " s is above the damped penalty spring's own limit " + fmt_double(dt_alone) +
              " s (more sub-steps, or 0 for automatic)");
    dt_stable = s.limit;
    log_line("contact sub-cycling: " + std::to_string(contact_substeps) + " sub-steps of " +
             fmt_sig(dt / contact_substeps) + " s per step of " + fmt_sig(dt) +
             " s (sub-cycled limit " + fmt_sig(s.limit) +
             " s, omega_p dt = " + fmt_sig(omega_penalty * dt) + ")");
  }
} // namespace kimp::fem::internal
