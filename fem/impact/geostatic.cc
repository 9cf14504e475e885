// ImpactProblem geostatic step: gravity on every body but the slab, the K0 initial stress of the
// backfill, and the static equilibrium the impact starts from: modified Newton on the virgin
// stiffness, then full Newton on the consistent tangent once points yield (docs/physics.md §6).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <tuple>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/vector.h>

#include "fem/impact/impact_problem.h"
#include "fem/mean_dilatation.h"
#include "geometry/scene_ids.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  namespace
  {
    /** Share of the virgin stiffness added to the consistent tangent of the geostatic step. */
    constexpr double tangent_regularization = 1e-3;

    /** Top (m) of the cells of every material of @p k0, the same on all ranks. */
    std::map<unsigned int, double> material_tops(const DoFHandler<dim>                &dofs,
                                                 const std::map<unsigned int, double> &k0,
                                                 MPI_Comm                              comm)
    {
      std::vector<double> local(k0.size(), -std::numeric_limits<double>::max());
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
        {
          const auto it = k0.find(cell->material_id());
          if (it == k0.end())
            continue;
          const std::size_t m = std::distance(k0.begin(), it);
          for (unsigned int v = 0; v < cell->n_vertices(); ++v)
            local[m] = std::max(local[m], cell->vertex(v)[1]);
        }
      std::vector<double> global(local.size());
      reduce_over_ranks(local.data(), global.data(), local.size(), MPI_MAX, comm);
      std::map<unsigned int, double> tops;
      std::size_t                    m = 0;
      for (const auto &entry : k0)
        tops[entry.first] = global[m++];
      return tops;
    }
  } // namespace

  void ImpactProblem::run_geostatic_step()
  {
    const GeostaticOptions &g = prm.geostatic;
    require(g.gravity > 0, "geostatic.gravity = " + fmt_double(g.gravity) + " m/s^2 (must be > 0)");
    require(g.tolerance > 0, "geostatic.tolerance = " + fmt_double(g.tolerance) + " (must be > 0)");
    require(g.max_iterations > 0, "geostatic.max_iterations = 0 (must be > 0)");
    for (const auto &[id, k0] : g.initial_stress_K0)
      require(k0 >= 0 && prm.materials.count(id) > 0,
              "geostatic.initial_stress_K0[" + std::to_string(id) + "] = " + fmt_double(k0) +
                " (must be >= 0, for a material id that has an entry in materials)");
    GeostaticHold hold;
    const double  weight = geostatic_gravity_load(hold);
    hold_geostatic_supports(hold);
    Vec                       u(locally_owned, comm);
    const GeostaticIterations it = solve_geostatic_equilibrium(hold, weight, u);
    if (absorbing)
      apply_support_reactions(u, hold);
    commit_geostatic_state(u);
    gap_after_geostatic(u);

    geostatic_stress                                = gather_point_stresses(u);
    geostatic_summary.geostatic_weight              = weight;
    geostatic_summary.geostatic_residual            = it.residual / weight;
    geostatic_summary.geostatic_iterations          = it.k;
    geostatic_summary.geostatic_plastic_dissipation = geostatic_point_energy[1];
    geostatic_summary.geostatic_wall_displacement   = geostatic_wall;
    log_line("geostatic: weight " + fmt_sig(weight) + " N/m, out-of-balance " +
             fmt_sig(it.residual / weight) + " of it after " + std::to_string(it.k) +
             " iterations (" + std::to_string(it.n_tangent) + " on the consistent tangent, " +
             fmt_sig(it.seconds) + " s), wall face u_x = " + fmt_sig(geostatic_wall) +
             " m, plastic dissipation " + fmt_sig(geostatic_point_energy[1]) + " J/m");
  }

  double ImpactProblem::geostatic_gravity_load(GeostaticHold &hold)
  {
    const GeostaticOptions              &g = prm.geostatic;
    const std::map<unsigned int, double> tops =
      material_tops(dof_handler, g.initial_stress_K0, comm);
    // sigma0 at height y in a material of K0 (tension positive), or false.
    const auto initial_stress = [&](unsigned int material, double y, InitialStress &sigma)
    {
      const auto it = g.initial_stress_K0.find(material);
      if (it == g.initial_stress_K0.end())
        return false;
      const double sv = -prm.materials.at(material).density * g.gravity * (tops.at(material) - y);
      sigma           = {{it->second * sv, sv, it->second * sv, 0}};
      return true;
    };

    // Gravity load f_g (consistent with the Gauss-Lobatto lumped mass: exact for a constant
    // body force on a parallelogram) and f_0 = int B^T sigma0 of the points whose law cannot
    // hold sigma0; the others get it in their history.
    Vec offset_w;
    offset_w.reinit(locally_owned, locally_relevant, comm, true);
    const QGauss<dim>                    quadrature(2);
    const QGaussLobatto<dim>             lobatto(2);
    FEValues<dim>                        fe_values(fe,
                            quadrature,
                            update_gradients | update_JxW_values | update_quadrature_points);
    FEValues<dim>                        fe_mass(fe, lobatto, update_values | update_JxW_values);
    const unsigned int                   n = fe.n_dofs_per_cell();
    Vector<double>                       cell_force(n);
    std::vector<types::global_dof_index> dof_indices(n);
    const FEValuesExtractors::Vector     displacement(0);
    double                               weight_local = 0;
    const bool                           weigh_all    = g.initial_stress_K0.empty();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const unsigned int mid = cell->material_id();
        cell->get_dof_indices(dof_indices);
        if (mid == geometry::slab_material)
        {
          // The slab rides on its isolators: no weight. Its DoFs get a diagonal in the static
          // operator (it is free and unloaded, so it stays at rest).
          for (const auto i : dof_indices)
            if (locally_owned.is_element(i))
              hold.slab_dofs.insert(i);
          continue;
        }
        const double rho = prm.materials.at(mid).density;
        fe_values.reinit(cell);
        fe_mass.reinit(cell);
        cell_force = 0;
        for (unsigned int q = 0; q < lobatto.size(); ++q)
          for (unsigned int i = 0; i < n; ++i)
            if (fe.system_to_component_index(i).first == 1)
              cell_force(i) += rho * g.gravity * fe_mass.shape_value(i, q) * fe_mass.JxW(q);
        if (weigh_all || g.initial_stress_K0.count(mid) > 0)
          weight_local += rho * g.gravity * cell->measure();
        const MaterialLaw &law = *laws.at(mid);
        const unsigned int c   = cell->active_cell_index();
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          InitialStress sigma{};
          if (!initial_stress(mid, fe_values.quadrature_point(q)[1], sigma))
            continue;
          if (!linear_laws && law.n_history() > 0 &&
              law.set_initial_stress(qp_history.trial(c, q), sigma))
            continue;
          for (unsigned int i = 0; i < n; ++i)
          {
            const auto e = fe_values[displacement].symmetric_gradient(i, q);
            cell_force(i) +=
              (sigma[0] * e[0][0] + sigma[1] * e[1][1] + 2 * sigma[3] * e[0][1]) * fe_values.JxW(q);
          }
        }
        constraints.distribute_local_to_global(cell_force, dof_indices, offset_w);
      }
    offset_w.compress(VectorOperation::add);
    if (!linear_laws)
      qp_history.commit(); // the initial stress becomes the committed state
    geostatic_offset.reinit(locally_owned, comm);
    geostatic_offset    = offset_w;
    geostatic_on        = true;
    const double weight = Utilities::MPI::sum(weight_local, comm);
    require(weight > 0, "geostatic step: the bodies under gravity have no weight");
    return weight;
  }

  void ImpactProblem::hold_geostatic_supports(GeostaticHold &hold) const
  {
    // Absorbing boundaries release the soil's far side and base: the static step holds them as
    // the rollers do (base u = 0, far side u_x = 0), the DoFs of `supported` (owned, free), and
    // their reactions become constant nodal forces of the impact (FLAC's and PLAXIS' way with
    // viscous boundaries), so that the dashpots start from an equilibrium.
    hold.static_mask = Vec(free_mask);
    if (absorbing)
    {
      for_each_absorbing_dof(true,
                             [&](const types::global_dof_index i, const unsigned int c)
                             {
                               if (locally_owned.is_element(i) && free_mask(i) > 0 &&
                                   hold.static_mask(i) > 0)
                               {
                                 hold.static_mask(i) = 0;
                                 hold.supported.push_back(i);
                                 hold.supported_component.push_back(c);
                               }
                             });
      hold.static_mask.compress(VectorOperation::insert);
    }
  }

  void ImpactProblem::finish_static_operator(TrilinosWrappers::SparseMatrix &matrix,
                                             const GeostaticHold            &hold,
                                             const Vec                      *u) const
  {
    // The virgin stiffness (or tangent), with the free slab's DoFs held by their diagonal and
    // the supported rows replaced by their diagonal (their residual is zero, so du = 0 there:
    // the constrained solve). The interface: its stick springs in the virgin operator, the
    // pairs' consistent tangent at u (open, stick, slip) with the same regularising share of
    // the springs as the bodies' in the tangent.
    for (const auto i : hold.slab_dofs)
      matrix.add(i, i, stiffness.diag_element(i));
    if (interface)
      add_interface_stiffness(matrix, u, tangent_regularization);
    matrix.compress(VectorOperation::add);
    for (const auto i : hold.supported)
      matrix.clear_row(i, stiffness.diag_element(i));
  }

  void ImpactProblem::assemble_geostatic_tangent(const Vec                      &u,
                                                 const GeostaticHold            &hold,
                                                 TrilinosWrappers::SparseMatrix &tangent)
  {
    // The laws' tangent from the committed initial state, which is the whole step's start,
    // assembled into `tangent` (the sparsity of the stiffness).
    if (tangent.m() == 0)
      tangent.reinit(stiffness);
    tangent = 0;
    Vec u_g(locally_owned, locally_relevant, comm);
    u_g = u;
    const QGauss<dim>                    quadrature(2);
    const unsigned int                   n = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dof_indices(n);
    FEValues<dim>                        fe_t(fe, quadrature, update_gradients | update_JxW_values);
    FullMatrix<double>                   cell_matrix(n, n);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    std::vector<std::array<double, 3>>   b(4 * n); // by point, then DoF
    std::vector<double>                  virgin;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const MaterialLaw &law = *laws.at(cell->material_id());
        const unsigned int c   = cell->active_cell_index();
        cell_matrix            = 0;
        // B-bar cells: the strains and the B rows with the mean dilatation.
        std::array<double, 4>            jxw{};
        const std::array<VoigtStrain, 4> strain = cell_strains(cell, u_g, fe_t, eps, jxw);
        strain_columns(cell->material_id(), fe_t, b);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const VoigtStrain &e = strain[q];
          const double      *h = nullptr;
          if (!linear_laws && law.n_history() > 0)
            h = qp_history.committed(c, q);
          else
          {
            virgin.assign(std::max(1u, law.n_history()), 0.0);
            law.initial_history(virgin.data());
            h = virgin.data();
          }
          const VoigtTangent           t  = law.tangent(e, h);
          const std::array<double, 3> *bq = &b[q * n];
          for (unsigned int j = 0; j < n; ++j)
          {
            const std::array<double, 3> tb{{t[0] * bq[j][0] + t[1] * bq[j][1] + t[2] * bq[j][2],
                                            t[3] * bq[j][0] + t[4] * bq[j][1] + t[5] * bq[j][2],
                                            t[6] * bq[j][0] + t[7] * bq[j][1] + t[8] * bq[j][2]}};
            for (unsigned int i = 0; i < n; ++i)
              cell_matrix(i, j) +=
                (bq[i][0] * tb[0] + bq[i][1] * tb[1] + bq[i][2] * tb[2]) * jxw[q];
          }
        }
        cell->get_dof_indices(dof_indices);
        constraints.distribute_local_to_global(cell_matrix, dof_indices, tangent);
      }
    tangent.compress(VectorOperation::add);
    // Points at the apex of the tension cut-off carry a constant stress (zero tangent); nodes
    // surrounded by them made the matrix singular (Newton steps of 1e11 m). A small share
    // of the virgin stiffness keeps it regular; it only slows the final quadratic rate by a
    // linear term of that order.
    tangent.add(tangent_regularization, stiffness);
    finish_static_operator(tangent, hold, &u);
  }

  ImpactProblem::GeostaticIterations
  ImpactProblem::solve_geostatic_equilibrium(const GeostaticHold &hold, double weight, Vec &u)
  {
    const GeostaticOptions &g = prm.geostatic;
    // Static operator: the virgin stiffness, factorised once.
    TrilinosWrappers::SparseMatrix op;
    op.reinit(stiffness);
    op.copy_from(stiffness);
    finish_static_operator(op, hold);
    SolverControl                  control;
    TrilinosWrappers::SolverDirect direct(control);
    direct.initialize(op);
    TrilinosWrappers::SparseMatrix tangent;

    // Modified Newton, u <- u - K0^-1 r(u), r = f_int(u) + f_0 - f_g: one iteration for linear
    // laws and for inelastic ones that stay elastic. Once points yield it converges only
    // linearly, at a rate that degrades as the mesh refines (surface points at the tension
    // cut-off); when the rate observed predicts more than a few further iterations, the step
    // switches to full Newton on the consistent tangent, refreshed every iteration, with a
    // backtracking line search on |r|. A tangent step that does not reduce |r| (a singular or
    // poor tangent) falls back to the virgin-stiffness step.
    const auto    t_start = std::chrono::steady_clock::now();
    const double  target  = g.tolerance * weight;
    Vec           r(locally_owned, comm), du(locally_owned, comm);
    Vec           u0(locally_owned, comm);
    double        residual = 0, previous = 0;
    unsigned long k = 0, n_tangent = 0;
    bool          use_tangent = false;
    const auto    evaluate    = [&](const Vec &x)
    {
      internal_force(x, r);
      r.scale(hold.static_mask);
      return r.l2_norm();
    };
    residual = evaluate(u);
    for (; residual > target; ++k)
    {
      if (k == g.max_iterations)
        throw NumericalError("geostatic step did not converge: out-of-balance force " +
                               fmt_double(residual) + " N/m after " + std::to_string(k) +
                               " Newton iterations (" + std::to_string(n_tangent) +
                               " on the consistent tangent), above " + fmt_double(g.tolerance) +
                               " x the weight " + fmt_double(weight) +
                               " N/m (the backfill may be collapsing under its own weight)",
                             0.0,
                             0);
      if (!use_tangent && !linear_laws && k >= 2 && residual > 0 && previous > residual)
      {
        const double rate = residual / previous;
        use_tangent       = std::log(target / residual) / std::log(rate) > 8;
      }
      else if (!use_tangent && !linear_laws && k >= 2)
        use_tangent = true; // modified Newton is not contracting at all
      previous      = residual;
      u0            = u;
      bool accepted = false;
      if (use_tangent)
      {
        try
        {
          assemble_geostatic_tangent(u, hold, tangent);
          TrilinosWrappers::SolverDirect newton(control);
          newton.initialize(tangent);
          newton.solve(du, r);
          ++n_linear_solves;
          ++n_tangent;
          for (unsigned int cut = 0; cut <= 10 && std::isfinite(du.l2_norm()); ++cut)
          {
            u = u0;
            u.add(-std::pow(0.5, cut), du);
            residual = evaluate(u);
            if (std::isfinite(residual) && residual < previous)
            {
              accepted = true;
              break;
            }
          }
        }
        catch (const std::exception &)
        {
          // A singular tangent: the virgin-stiffness step below.
        }
      }
      if (!accepted)
      {
        // The same residual as at u0 (the line search may have moved the trial history on).
        u = u0;
        if (use_tangent)
          evaluate(u);
        direct.solve(du, r);
        ++n_linear_solves;
        u.add(-1.0, du);
        residual = evaluate(u);
      }
    }
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return {residual, k, n_tangent, seconds};
  }

  void ImpactProblem::apply_support_reactions(const Vec &u, const GeostaticHold &hold)
  {
    // The supports' reactions R = r there (f_int + f_0 = f_g + R): applied as constant
    // forces, f(u_g) = f_int + f_0 - f_g - R vanishes on the released DoFs too.
    Vec r(locally_owned, comm);
    internal_force(u, r);
    Vec reaction(locally_owned, comm);
    for (const auto i : hold.supported)
      reaction(i) = r(i);
    reaction.compress(VectorOperation::insert);
    geostatic_offset.add(-1.0, reaction);
    double resultant[2] = {0, 0}; // the supports' force on the soil, N/m
    for (std::size_t j = 0; j < hold.supported.size(); ++j)
      resultant[hold.supported_component[j]] += r(hold.supported[j]);
    resultant[0] = Utilities::MPI::sum(resultant[0], comm);
    resultant[1] = Utilities::MPI::sum(resultant[1], comm);
    log_line("geostatic: the absorbing boundary's supports hold the soil with (" +
             fmt_sig(resultant[0]) + ", " + fmt_sig(resultant[1]) +
             ") N/m, applied as constant nodal forces during the impact");
  }

  void ImpactProblem::commit_geostatic_state(const Vec &u)
  {
    if (!linear_laws)
      qp_history.commit();
    if (interface)
    {
      interface->commit();
      interface_energy0      = interface_ev.penalty_energy + interface_ev.dissipation;
      interface_dissipation0 = interface_ev.dissipation;
    }
    geostatic_u                       = u;
    const std::array<double, 3> local = point_energy_local;
    for (unsigned int i = 0; i < 3; ++i)
      geostatic_point_energy[i] = Utilities::MPI::sum(local[i], comm);
    for (unsigned int b = 0; b < 4; ++b)
      for (unsigned int i = 0; i < 2; ++i)
        geostatic_body_dissipation[b][i] = Utilities::MPI::sum(body_dissipation_local[b][i], comm);
  }

  void ImpactProblem::gap_after_geostatic(const Vec &u)
  {
    const std::vector<double> cu = gather_compact(u, 0.0);
    for (std::size_t i = 0; i < cu.size(); ++i)
    {
      geostatic_wall += wall_weight[i] * cu[i];
      geostatic_front += front_weight[i] * cu[i];
    }
    const auto ev = contact->evaluate(cu, std::vector<double>(cu.size(), 0.0));
    require(ev.total_force == 0,
            "geostatic step: the wall moved onto the slab under the earth pressure (largest "
            "penetration " +
              fmt_double(ev.max_penetration) + " m); increase geometry.gap");
    initial_gap += geostatic_wall - geostatic_front;
  }

  std::vector<PointStress> ImpactProblem::gather_point_stresses(const Vec &u)
  {
    const GeostaticOptions &g    = prm.geostatic;
    const auto              tops = material_tops(dof_handler, g.initial_stress_K0, comm);
    Vec                     u_g(locally_owned, locally_relevant, comm);
    u_g = u;
    const QGauss<dim>                    quadrature(2);
    FEValues<dim>                        fe_values(fe,
                            quadrature,
                            update_gradients | update_quadrature_points | update_JxW_values);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    std::vector<double>                  local, scratch, probe;
    double                               max_plastic = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() != geometry::slab_material)
      {
        const unsigned int mid = cell->material_id();
        const unsigned int c   = cell->active_cell_index();
        const MaterialLaw &law = *laws.at(mid);
        scratch.assign(std::max(1u, law.n_history()), 0.0);
        std::array<double, 4>            jxw{};
        const std::array<VoigtStrain, 4> strain = cell_strains(cell, u_g, fe_values, eps, jxw);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const VoigtStrain &e       = strain[q];
          const bool         history = !linear_laws && law.n_history() > 0;
          const double      *h       = history ? qp_history.committed(c, q) : scratch.data();
          VoigtStress        s       = law.stress(e, h, scratch.data());
          const PointOutput  po      = law.output(e, history ? scratch.data() : nullptr);
          double             szz     = po.sigma_zz;
          max_plastic                = std::max(max_plastic, po.equivalent_plastic_strain);
          const auto point           = fe_values.quadrature_point(q);
          const auto it              = g.initial_stress_K0.find(mid);
          probe.assign(scratch.size(), 0.0);
          if (it != g.initial_stress_K0.end() &&
              !(history && law.set_initial_stress(probe.data(), InitialStress{})))
          {
            // A law without history: its stress is the increment; add sigma0.
            const double sv =
              -prm.materials.at(mid).density * g.gravity * (tops.at(mid) - point[1]);
            s[0] += it->second * sv;
            s[1] += sv;
            szz += it->second * sv;
          }
          local.insert(local.end(), {point[0], point[1], double(mid), s[0], s[1], szz, s[2]});
        }
      }
    geostatic_summary.geostatic_max_plastic_strain = Utilities::MPI::max(max_plastic, comm);
    std::vector<PointStress> points;
    for (const auto &part : Utilities::MPI::all_gather(comm, local))
      for (std::size_t k = 0; k + 7 <= part.size(); k += 7)
        points.push_back({part[k],
                          part[k + 1],
                          static_cast<unsigned int>(part[k + 2]),
                          part[k + 3],
                          part[k + 4],
                          part[k + 5],
                          part[k + 6]});
    std::sort(points.begin(),
              points.end(),
              [](const PointStress &a, const PointStress &b)
              { return std::tie(a.material_id, a.x, a.y) < std::tie(b.material_id, b.x, b.y); });
    return points;
  }
} // namespace kimp::fem::internal
