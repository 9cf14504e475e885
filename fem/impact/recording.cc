// ImpactProblem recording, shared by the explicit and the implicit time loop: histories, energies
// and the divergence guard, VTU output, frames with the contact pressure per node (the penalty
// forces over each node's tributary length), and the summary with the smoothed force.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include "fem/impact/impact_problem.h"
#include "fem/inelastic_laws.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  /** Divergence guard: relative energy error beyond which the run is stopped. */
  constexpr double divergence_energy_error = 0.5;

  std::vector<double> padded_force(const PenaltyContact::Evaluation &ev, std::size_t size)
  {
    std::vector<double> f = ev.force;
    f.resize(size, 0.0);
    return f;
  }

  void ImpactProblem::accumulate_contact_work(const std::vector<double> &fc,
                                              const std::vector<double> &cu)
  {
    if (!cu_prev.empty())
      for (std::size_t k = 0; k < cu.size(); ++k)
        contact_work += 0.5 * (fc[k] + fc_prev[k]) * (cu[k] - cu_prev[k]);
    cu_prev = cu;
    fc_prev = fc;
  }

  void ImpactProblem::accumulate_step_work(const Vec                        &u,
                                           const Vec                        &v_n,
                                           const Vec                        &Ku,
                                           const PenaltyContact::Evaluation &ev,
                                           const std::vector<double>        &cu,
                                           bool                              contact_subcycled)
  {
    // Contact work by the trapezoid rule over the compact DoFs (the only ones it acts on);
    // sub-cycled, the sub-steps accumulated it.
    if (!contact_subcycled)
    {
      accumulate_contact_work(padded_force(ev, cu.size()), cu);
      raw_force.push_back(ev.total_force);
      penetration_integral += ev.mean_penetration * dt;
      max_penetration = std::max(max_penetration, ev.max_penetration);
    }

    // Non-linear laws: internal work by the trapezoid rule, this rank's owned entries (the sum
    // over ranks is taken with the energies below).
    if (!linear_laws)
    {
      const std::size_t n_local = u.locally_owned_size();
      const double     *up = u.begin(), *fp = Ku.begin();
      if (u_prev_local.size() == n_local)
        for (std::size_t k = 0; k < n_local; ++k)
          internal_work_local += 0.5 * (fp[k] + f_prev_local[k]) * (up[k] - u_prev_local[k]);
      u_prev_local.assign(up, up + n_local);
      f_prev_local.assign(fp, fp + n_local);
    }

    if (absorbing)
      accumulate_radiation(u, v_n);
  }

  std::array<double, ImpactProblem::n_energy_values>
  ImpactProblem::sum_energies(const Vec &u, const Vec &v_n, const Vec &Ku)
  {
    // kinetic, strain, slab m u, slab m v; internal work, stored, plastic, damage
    // (+ geostatic: the work (f_g - f_0) . (u - u_g) of the loads of the geostatic state);
    // plastic and damage per body (slab, wall, soil, other)
    // wall and soil (every body but the slab): kinetic, x and y momentum, strain energy of
    // linear laws; the slab points' stored energy (non-linear laws)
    std::array<double, n_energy_values> local{{0,
                                               0,
                                               0,
                                               0,
                                               internal_work_local,
                                               point_energy_local[0],
                                               point_energy_local[1],
                                               point_energy_local[2],
                                               0}};
    for (unsigned int b = 0; b < 4; ++b)
      for (unsigned int i = 0; i < 2; ++i)
        local[9 + 2 * b + i] = body_dissipation_local[b][i];
    local[21] = slab_stored_local;
    {
      const double *vp = v_n.begin(), *mp = mass.begin(), *up = u.begin(), *kp = Ku.begin(),
                   *sp = slab_mass_x.begin(), *bx = body_mass_x.begin(), *by = body_mass_y.begin();
      // Geostatic: energies and displacements relative to its state (the slab's is zero).
      const double *gp = geostatic_on ? geostatic_u.begin() : nullptr;
      const double *op = geostatic_on ? geostatic_offset.begin() : nullptr;
      for (std::size_t k = 0; k < v_n.locally_owned_size(); ++k)
      {
        const double du = gp != nullptr ? up[k] - gp[k] : up[k];
        local[0] += 0.5 * mp[k] * vp[k] * vp[k];
        local[1] += 0.5 * du * kp[k];
        local[2] += sp[k] * up[k];
        local[3] += sp[k] * vp[k];
        if (op != nullptr)
          local[8] -= op[k] * du;
        const double mb = bx[k] + by[k];
        local[17] += 0.5 * mb * vp[k] * vp[k];
        local[18] += bx[k] * vp[k];
        local[19] += by[k] * vp[k];
        if (mb > 0)
          local[20] += 0.5 * du * kp[k];
      }
    }
    std::array<double, n_energy_values> global{};
    reduce_over_ranks(local.data(), global.data(), n_energy_values, MPI_SUM, comm);
    return global;
  }

  void ImpactProblem::record(const RecordedStep &step)
  {
    const auto &[n, t, u, v_n, Ku, u_r, v_r, ev, cu, subcycled] = step;
    accumulate_step_work(u, v_n, Ku, ev, cu, subcycled);

    // Energies and means at the sampled steps only (one reduction): the divergence guard
    // acts within one output interval.
    if (n % sample_every != 0)
      return;
    std::array<double, n_energy_values> global = sum_energies(u, v_n, Ku);
    track_bar_strain(t, u);
    if (geostatic_on)
      for (unsigned int i = 0; i < 3; ++i)
        global[5 + i] -= geostatic_point_energy[i];
    if (!linear_laws)
      for (unsigned int b = 0; b < 4; ++b)
        for (unsigned int i = 0; i < 2; ++i)
          body_dissipation[b][i] =
            global[9 + 2 * b + i] - (geostatic_on ? geostatic_body_dissipation[b][i] : 0.0);
    const double kinetic = global[0] + (prm.rigid_slab ? 0.5 * prm.slab_mass * v_r * v_r : 0);
    // The viscous-spring boundary's springs store the far field's energy.
    const double spring_energy =
      boundary_springs ? Utilities::MPI::sum(boundary_spring_energy_local(u), comm) : 0.0;
    {
      // Stored in wall and soil: their kinetic energy less that of a free mean translation (a
      // free body carried away keeps it for ever) and their recoverable strain energy: 1/2 du.f
      // over their DoFs for linear laws (the bodies share no node with the slab), else the
      // points' stored energy less the slab's (the slab has none in the geostatic state).
      double translation = 0;
      for (unsigned int c = 0; c < 2; ++c)
        if (body_free_mass[c] > 0)
          translation += 0.5 * global[18 + c] * global[18 + c] / body_free_mass[c];
      const double strain_energy = linear_laws ? global[20] : global[5] - global[21];
      stored_share               = (global[17] - translation + strain_energy + spring_energy) / e0;
    }
    // Linear laws: 1/2 u.Ku is the strain energy. Otherwise the integrated stress power is the
    // energy the body took, and the points split it into stored, plastic and damage.
    const double work        = linear_laws ? global[1] : global[4];
    const double strain      = linear_laws ? global[1] : global[5];
    const double radiated    = absorbing ? Utilities::MPI::sum(radiation_local, comm) : 0.0;
    const double slab_damped = slab_alpha > 0 ? Utilities::MPI::sum(slab_damping_local, comm) : 0.0;
    const double error =
      (kinetic + work - contact_work + radiated + slab_damped + spring_energy) / e0 - 1;
    if (absorbing)
      history.radiation.push_back(radiated);
    if (boundary_springs)
      history.boundary_springs.push_back(spring_energy);
    if (slab_alpha > 0)
      history.slab_damping.push_back(slab_damped);
    if (!linear_laws)
    {
      history.internal_work.push_back(global[4]);
      history.plastic_dissipation.push_back(global[6]);
      history.damage_dissipation.push_back(global[7]);
      // Geostatic: W_int includes the work of gravity; the points' energies are increments.
      // A contact interface stores penalty energy and dissipates by friction.
      const double interface_energy =
        interface ? interface_ev.penalty_energy + interface_ev.dissipation - interface_energy0 :
                    0.0;
      max_dissipation_gap = std::max(max_dissipation_gap,
                                     std::abs(global[4] + global[8] - global[5] - global[6] -
                                              global[7] - interface_energy) /
                                       e0);
      if (interface)
      {
        history.interface_normal_force.push_back(interface_ev.normal_force);
        history.interface_closed.push_back(interface_ev.n_closed);
        history.friction_dissipation.push_back(interface_ev.dissipation - interface_dissipation0);
      }
    }
    max_energy_error = std::max(max_energy_error, std::abs(error));
    if (!std::isfinite(error) || std::abs(error) > divergence_energy_error)
      throw_divergence(n, t, u);

    const double slab_u = prm.rigid_slab ? u_r : global[2] / slab_total_mass;
    const double slab_v = prm.rigid_slab ? v_r : global[3] / slab_total_mass;
    double       wall = -geostatic_wall, front = -geostatic_front;
    for (std::size_t k = 0; k < cu.size(); ++k)
    {
      wall += wall_weight[k] * cu[k];
      front += front_weight[k] * cu[k];
    }
    history.time.push_back(t);
    history.contact_force.push_back(ev.total_force);
    history.n_active.push_back(ev.active.size());
    history.slab_displacement.push_back(slab_u);
    history.slab_velocity.push_back(slab_v);
    history.wall_displacement.push_back(wall);
    history.indentation.push_back(front - wall - initial_gap);
    history.max_penetration.push_back(ev.max_penetration);
    history.kinetic.push_back(kinetic);
    history.strain.push_back(strain);
    history.penalty.push_back(ev.penalty_energy);
    history.contact_dissipation.push_back(-contact_work - ev.penalty_energy);
    history.energy_error.push_back(error);
    if (prm.log_interval > 0 && (n / sample_every) % prm.log_interval == 0)
      log_line(
        "step " + std::to_string(n) + " t = " + fmt_sig(t) + " s, F = " + fmt_sig(ev.total_force) +
        " N/m, active = " + std::to_string(ev.active.size()) +
        ", max penetration = " + fmt_sig(ev.max_penetration) + " m, dE/E0 = " + fmt_sig(error));
  }

  void ImpactProblem::track_bar_strain(double t, const Vec &u)
  {
    if (!bar_points_ready)
    {
      bar_points_ready = true;
      const auto  it   = laws.find(geometry::wall_material);
      const auto *concrete =
        it == laws.end() ? nullptr : dynamic_cast<const ConcreteDamageLaw *>(it->second.get());
      if (concrete == nullptr || !concrete->reinforcement().any())
        return;
      const ReinforcementParameters &r = concrete->reinforcement();
      bar_ratio_x                      = r.ratio_x;
      bar_ratio_y                      = r.ratio_y;
      bar_yield_strain                 = r.yield_stress / r.youngs_modulus;
      const QGauss<dim> quadrature(2);
      FEValues<dim>     fe_values(fe, quadrature, update_gradients | update_quadrature_points);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      std::vector<GaugeSegment>            segments;
      double x_min = std::numeric_limits<double>::max(), x_max = -x_min;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && cell->material_id() == geometry::wall_material)
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          double y_lo = std::numeric_limits<double>::max(), y_hi = -y_lo;
          for (unsigned int v = 0; v < cell->n_vertices(); ++v)
          {
            y_lo  = std::min(y_lo, cell->vertex(v)[1]);
            y_hi  = std::max(y_hi, cell->vertex(v)[1]);
            x_min = std::min(x_min, cell->vertex(v)[0]);
            x_max = std::max(x_max, cell->vertex(v)[0]);
          }
          const double y_mid = 0.5 * (y_lo + y_hi);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            BarPoint p;
            p.y = fe_values.quadrature_point(q)[1];
            // The point's half of the cell along its vertical line (2-point Gauss column).
            segments.push_back({fe_values.quadrature_point(q)[0],
                                p.y < y_mid ? y_lo : y_mid,
                                p.y < y_mid ? y_mid : y_hi});
            for (unsigned int i = 0; i < dofs.size() && i < 8; ++i)
            {
              const unsigned int c = fe.system_to_component_index(i).first;
              p.dofs[i]            = dofs[i];
              p.component[i]       = static_cast<unsigned char>(c);
              p.gradients[i]       = fe_values.shape_grad_component(i, q, c)[c];
            }
            bar_points.push_back(p);
          }
        }
      if (bar_ratio_y > 0)
        setup_bar_gauge(segments, x_min, x_max);
    }
    if (bar_yield_strain <= 0)
      return;
    // One rank owns every DoF in order: read u's own array. Otherwise every rank takes part in
    // the ghost exchange, with or without wall cells.
    const bool serial = Utilities::MPI::n_mpi_processes(comm) == 1;
    if (!serial)
    {
      if (bar_u_ghosted.size() == 0)
        bar_u_ghosted.reinit(locally_owned, locally_relevant, comm);
      bar_u_ghosted = u;
    }
    const double *up = u.begin();
    if (bar_gauge)
      std::fill(bar_gauge_strain.begin(), bar_gauge_strain.end(), 0.0);
    for (std::size_t k = 0; k < bar_points.size(); ++k)
    {
      const BarPoint       &p = bar_points[k];
      std::array<double, 2> e{{0, 0}};
      for (unsigned int i = 0; i < 8; ++i)
        e[p.component[i]] += p.gradients[i] * (serial ? up[p.dofs[i]] : bar_u_ghosted(p.dofs[i]));
      if (bar_gauge)
        bar_gauge_strain[bar_gauge_offset + k] = e[1];
      const double ratio =
        std::max(bar_ratio_x > 0 ? std::abs(e[0]) : 0.0, bar_ratio_y > 0 ? std::abs(e[1]) : 0.0) /
        bar_yield_strain;
      if (ratio > bar_max_ratio)
      {
        bar_max_ratio = ratio;
        bar_max_y     = p.y;
        bar_max_time  = t;
      }
    }
    if (bar_gauge)
    {
      if (!serial)
        Utilities::MPI::sum(bar_gauge_strain, comm, bar_gauge_strain);
      const GaugeStrain g = bar_gauge->largest_mean(bar_gauge_strain);
      if (g.strain > bar_gauge_max.strain)
        bar_gauge_max = g;
    }
  }

  void ImpactProblem::setup_bar_gauge(const std::vector<GaugeSegment> &local,
                                      const double                     wall_x_min,
                                      const double                     wall_x_max)
  {
    // Every rank's segments, rank by rank (collective even for a rank without wall cells).
    std::vector<double> flat;
    for (const GaugeSegment &g : local)
      flat.insert(flat.end(), {g.x, g.y_lo, g.y_hi});
    const auto                all  = Utilities::MPI::all_gather(comm, flat);
    const unsigned int        rank = Utilities::MPI::this_mpi_process(comm);
    std::vector<GaugeSegment> segments;
    for (unsigned int r = 0; r < all.size(); ++r)
    {
      if (r == rank)
        bar_gauge_offset = segments.size();
      for (std::size_t i = 0; i + 2 < all[r].size(); i += 3)
        segments.push_back({all[r][i], all[r][i + 1], all[r][i + 2]});
    }
    if (segments.empty())
      return;
    const double thickness =
      Utilities::MPI::max(wall_x_max, comm) + Utilities::MPI::max(-wall_x_min, comm);
    const double length = prm.bar_gauge_length > 0 ? prm.bar_gauge_length : 0.5 * thickness;
    bar_gauge           = std::make_unique<BarGauge>(segments, length);
    bar_gauge_strain.assign(segments.size(), 0.0);
  }

  void ImpactProblem::summarise_bar_strain(ImpactSummary &s) const
  {
    // The largest bar strain over the ranks, with its height and time.
    const auto all =
      Utilities::MPI::all_gather(comm, std::vector<double>{bar_max_ratio, bar_max_y, bar_max_time});
    std::vector<double> worst{-1, 0, 0};
    for (const auto &a : all)
      if (a[0] > worst[0])
        worst = a;
    if (worst[0] < 0)
      return;
    s.max_bar_strain_ratio  = worst[0];
    s.max_bar_strain_height = worst[1];
    s.max_bar_strain_time   = worst[2];
    if (bar_gauge)
    {
      // Every rank read the same strains (summed over the ranks): the same largest reading.
      s.max_bar_gauge_strain_ratio  = bar_gauge_max.strain / bar_yield_strain;
      s.max_bar_gauge_strain_height = bar_gauge_max.centre;
      s.bar_gauge_length            = bar_gauge->length();
    }
  }

  void ImpactProblem::throw_divergence(unsigned long n, double t, const Vec &u) const
  {
    // Locate the largest displacement to name the place of the blow-up.
    double     local_max = -1;
    Point<dim> where;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int v = 0; v < cell->n_vertices(); ++v)
          for (unsigned int c = 0; c < dim; ++c)
          {
            const auto i = cell->vertex_dof_index(v, c);
            if (!locally_owned.is_element(i))
              continue;
            const double a =
              std::isfinite(u(i)) ? std::abs(u(i)) : std::numeric_limits<double>::max();
            if (a > local_max)
            {
              local_max = a;
              where     = cell->vertex(v);
            }
          }
    const auto all =
      Utilities::MPI::all_gather(comm, std::vector<double>{local_max, where[0], where[1]});
    std::vector<double> worst{-1, 0, 0};
    for (const auto &a : all)
      if (a[0] > worst[0])
        worst = a;
    throw NumericalError("impact diverged at t = " + fmt_double(t) + " s (step " +
                           std::to_string(n) + ", dt = " + fmt_double(dt) +
                           " s): energy not conserved or not finite; largest displacement " +
                           fmt_double(worst[0]) + " m at (" + fmt_double(worst[1]) + ", " +
                           fmt_double(worst[2]) + ") m",
                         t,
                         n);
  }

  ImpactProblem::CellMeans ImpactProblem::cell_means(const Vec &u_g) const
  {
    CellMeans          m;
    const unsigned int n_cells = triangulation.n_active_cells();
    for (Vector<float> *v :
         {&m.sxx, &m.syy, &m.sxy, &m.mean_stress, &m.von_mises, &m.damage, &m.eq_plastic})
      v->reinit(n_cells);
    // Cell means over the Gauss points of the stiffness, each from its committed history.
    const QGauss<dim> quadrature(2);
    FEValues<dim>     fe_values(fe, quadrature, update_gradients | update_JxW_values);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    std::vector<double>                  scratch;
    const double                         w = 1.0 / quadrature.size();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const unsigned int c   = cell->active_cell_index();
        const MaterialLaw &law = *laws.at(cell->material_id());
        scratch.assign(std::max(1u, law.n_history()), 0.0);
        std::array<double, 4>            jxw{};
        const std::array<VoigtStrain, 4> strain = cell_strains(cell, u_g, fe_values, eps, jxw);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const VoigtStrain &e         = strain[q];
          const double      *committed = linear_laws ? scratch.data() : qp_history.committed(c, q);
          const VoigtStress  sigma     = law.stress(e, committed, scratch.data());
          const PointOutput  po        = law.output(e, linear_laws ? nullptr : scratch.data());
          const double       p         = (sigma[0] + sigma[1] + po.sigma_zz) / 3;
          const double       j2 =
            0.5 * ((sigma[0] - p) * (sigma[0] - p) + (sigma[1] - p) * (sigma[1] - p) +
                   (po.sigma_zz - p) * (po.sigma_zz - p)) +
            sigma[2] * sigma[2];
          m.sxx(c) += w * sigma[0];
          m.syy(c) += w * sigma[1];
          m.sxy(c) += w * sigma[2];
          m.mean_stress(c) += w * p;
          m.von_mises(c) += w * std::sqrt(3 * j2);
          m.damage(c) += w * po.damage;
          m.eq_plastic(c) += w * po.equivalent_plastic_strain;
        }
      }
    return m;
  }

  void ImpactProblem::output_results(double                     t,
                                     const Vec                 &u,
                                     const Vec                 &v,
                                     const std::vector<double> &contact_force)
  {
    Vec u_g(locally_owned, locally_relevant, comm), v_g(locally_owned, locally_relevant, comm);
    Vec f(locally_owned, comm);
    scatter_add(contact_force, f);
    Vec f_g(locally_owned, locally_relevant, comm);
    u_g = u;
    v_g = v;
    f_g = f;

    Vector<float> material(triangulation.n_active_cells()), subdomain(material.size());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        material(cell->active_cell_index())  = cell->material_id();
        subdomain(cell->active_cell_index()) = triangulation.locally_owned_subdomain();
      }
    const CellMeans      m   = cell_means(u_g);
    const Vector<float> &sxx = m.sxx, &syy = m.syy, &sxy = m.sxy, &mean_stress = m.mean_stress,
                        &von_mises = m.von_mises, &damage = m.damage, &eq_plastic = m.eq_plastic;
    DataOut<dim> data_out;
    data_out.attach_dof_handler(dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_field(
      dim,
      DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(u_g,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(v_g,
                             std::vector<std::string>(dim, "velocity"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(f_g,
                             std::vector<std::string>(dim, "contact_force"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(material, "material_id");
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.add_data_vector(sxx, "stress_xx");
    data_out.add_data_vector(syy, "stress_yy");
    data_out.add_data_vector(sxy, "stress_xy");
    data_out.add_data_vector(mean_stress, "mean_stress");
    data_out.add_data_vector(von_mises, "von_mises_stress");
    data_out.add_data_vector(damage, "damage");
    data_out.add_data_vector(eq_plastic, "equivalent_plastic_strain");
    data_out.build_patches();
    const unsigned int counter = pvd_records.size();
    const std::string  pvtu =
      data_out.write_vtu_with_pvtu_record(prm.vtu_dir.string() + "/", "impact", counter, comm, 4);
    pvd_records.emplace_back(t, pvtu);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
    {
      std::ofstream pvd(prm.vtu_dir / "impact.pvd");
      DataOutBase::write_pvd_record(pvd, pvd_records);
    }
  }

  void ImpactProblem::record_frame(double t, const Vec &u, const PenaltyContact::Evaluation &ev)
  {
    Vec u_g(locally_owned, locally_relevant, comm);
    u_g                      = u;
    const CellMeans    m     = cell_means(u_g);
    const unsigned int n_v   = triangulation.n_vertices();
    const unsigned int n_c   = triangulation.n_active_cells();
    const bool         root  = Utilities::MPI::this_mpi_process(comm) == 0;
    const bool         first = frames.time.empty();
    // The mesh is the unrefined coarse mesh, which every rank holds whole: vertex and level-0
    // cell numbers are the same on all ranks. Each rank fills what it owns; sums gather it.
    std::vector<double> displacement(2 * n_v, 0.0), count(n_v, 0.0);
    std::vector<double> fields(4 * n_c, 0.0);
    std::vector<double> cells, material;
    for (const auto &cell : dof_handler.active_cell_iterators())
    {
      const unsigned int c = cell->active_cell_index();
      if (first && root)
      {
        // deal.II numbers quadrilateral vertices lexicographically; the frames list them
        // counter-clockwise so that they draw as polygons.
        for (const unsigned int v : {0u, 1u, 3u, 2u})
          cells.push_back(cell->vertex_index(v));
        material.push_back(cell->material_id());
      }
      if (!cell->is_locally_owned())
        continue;
      for (unsigned int v = 0; v < cell->n_vertices(); ++v)
      {
        const unsigned int k = cell->vertex_index(v);
        for (unsigned int d = 0; d < dim; ++d)
          displacement[2 * k + d] = u_g(cell->vertex_dof_index(v, d));
        count[k] = 1;
      }
      fields[c]           = m.von_mises(c);
      fields[n_c + c]     = m.mean_stress(c);
      fields[2 * n_c + c] = m.damage(c);
      fields[3 * n_c + c] = m.eq_plastic(c);
    }
    // A vertex shared by two ranks' cells holds the same value on both: sum, then divide.
    for (std::vector<double> *x : {&displacement, &count, &fields})
      MPI_Allreduce(MPI_IN_PLACE,
                    x->data(),
                    static_cast<int>(x->size()),
                    MPI_DOUBLE,
                    MPI_SUM,
                    comm);
    if (!root)
      return;
    if (first)
    {
      for (const auto &p : triangulation.get_vertices())
        frames.vertices.insert(frames.vertices.end(), {p[0], p[1]});
      frames.cells    = std::move(cells);
      frames.material = std::move(material);
    }
    frames.time.push_back(t);
    for (unsigned int k = 0; k < n_v; ++k)
      for (unsigned int d = 0; d < dim; ++d)
        frames.displacement.push_back(count[k] > 0 ? displacement[2 * k + d] / count[k] : 0.0);
    const auto append = [&](std::vector<double> &to, unsigned int which)
    { to.insert(to.end(), fields.begin() + which * n_c, fields.begin() + (which + 1) * n_c); };
    append(frames.von_mises_stress, 0);
    append(frames.mean_stress, 1);
    if (!linear_laws)
    {
      append(frames.damage, 2);
      append(frames.equivalent_plastic_strain, 3);
    }
    record_contact_pressure(ev);
  }

  void ImpactProblem::record_contact_pressure(const PenaltyContact::Evaluation &ev)
  {
    const auto &slaves = contact->slaves();
    // Slaves in the order of the frames' contact nodes: along the face by (y, x).
    std::vector<unsigned int> order(slaves.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto &nodes = contact->nodes();
    const auto  where = [&](unsigned int s)
    { return std::make_pair(nodes[slaves[s].node].y, nodes[slaves[s].node].x); };
    std::sort(order.begin(),
              order.end(),
              [&](unsigned int a, unsigned int b) { return where(a) < where(b); });
    if (frames.contact_vertices.empty())
    {
      // The contact nodes are mesh vertices of the coarse mesh at exactly these coordinates
      // (setup_contact() took them from the face vertices).
      std::map<std::pair<double, double>, unsigned int> vertex_of;
      const auto                                       &vertices = triangulation.get_vertices();
      for (unsigned int v = 0; v < vertices.size(); ++v)
        if (triangulation.vertex_used(v))
          vertex_of[{vertices[v][0], vertices[v][1]}] = v;
      for (const unsigned int s : order)
      {
        const auto &n  = nodes[slaves[s].node];
        const auto  it = vertex_of.find({n.x, n.y});
        require(it != vertex_of.end(),
                "contact node at (" + fmt_double(n.x) + ", " + fmt_double(n.y) +
                  ") m is no mesh vertex");
        frames.contact_vertices.push_back(it->second);
        frames.contact_length.push_back(slave_length[s]);
      }
    }
    // lambda_i >= 0 is the normal force of node i per metre of depth (the dashpot included),
    // so lambda_i / l_i is the mean normal traction over its tributary length and
    // sum_i p_i l_i = ev.total_force, the contact force of the histories.
    std::vector<double> pressure(slaves.size(), 0.0);
    for (const auto &pair : ev.active)
      pressure[pair.slave] = pair.force / slave_length[pair.slave];
    for (const unsigned int s : order)
      frames.contact_pressure.push_back(pressure[s]);
  }

  void ImpactProblem::finish(ImpactResult &result, double wall_seconds)
  {
    result.frames = std::move(frames);
    // Impulse-preserving smoothing: a centred moving average (zero padded) over the window;
    // sum(F) dt is unchanged because the force is zero at both ends of the run.
    const double period =
      prm.smoothing_window > 0 ? prm.smoothing_window : contact_width / contact_wave_speed;
    const long          half  = std::max(0L, static_cast<long>(std::floor(0.5 * period / dt)));
    const long          n_raw = static_cast<long>(raw_force.size());
    std::vector<double> prefix(n_raw + 1, 0.0);
    for (long i = 0; i < n_raw; ++i)
      prefix[i + 1] = prefix[i] + raw_force[i];
    const auto smoothed = [&](long i)
    {
      const long lo = std::max(0L, i - half), hi = std::min(n_raw - 1, i + half);
      return (prefix[hi + 1] - prefix[lo]) / static_cast<double>(2 * half + 1);
    };

    ImpactSummary &s     = result.summary;
    long           first = -1, last = -1;
    for (long i = 0; i < n_raw; ++i)
    {
      s.peak_force_raw = std::max(s.peak_force_raw, raw_force[i]);
      s.peak_force     = std::max(s.peak_force, smoothed(i));
      s.impulse += raw_force[i] * dt;
      if (raw_force[i] > 0)
      {
        if (first < 0)
          first = i;
        last = i;
      }
    }
    for (std::size_t j = 0; j < history.time.size(); ++j)
      history.smoothed_contact_force.push_back(smoothed(static_cast<long>(j * sample_every)));
    if (first >= 0)
    {
      s.contact_start    = first * dt;
      s.contact_duration = (last - first + 1) * dt;
    }
    s.rebound_velocity = slab_v_end;
    s.apparent_cor     = -slab_v_end / prm.initial_velocity;
    s.energy_error     = max_energy_error;
    s.smoothing_window = (2 * half + 1) * dt;
    s.max_penetration  = max_penetration;
    s.mean_penetration = s.contact_duration > 0 ? penetration_integral / s.contact_duration : 0;
    s.initial_gap      = initial_gap;
    for (const auto &sl : contact->slaves())
      s.penalty_stiffness = std::max(s.penalty_stiffness, sl.stiffness);
    s.penalty_factor        = penalty_factor_used;
    s.contact_subcycles     = contact_substeps;
    s.n_dofs                = dof_handler.n_dofs();
    s.n_cells               = triangulation.n_global_active_cells();
    s.n_steps               = n_steps_done;
    s.n_newton              = n_newton;
    s.n_step_halvings       = n_step_halvings;
    s.n_linear_solves       = n_linear_solves;
    s.linear_solver_seconds = linear_solver_seconds;
    s.linear_setup_seconds  = linear_setup_seconds;
    s.dt                    = dt;
    s.dt_stable             = dt_stable;
    s.wall_seconds          = wall_seconds;
    s.n_ranks               = Utilities::MPI::n_mpi_processes(comm);
    s.separated             = separated_flag;
    s.truncated             = !separated_flag;
    s.stored_energy_share   = stored_share;
    if (!history.plastic_dissipation.empty())
    {
      s.plastic_dissipation = history.plastic_dissipation.back();
      s.damage_dissipation  = history.damage_dissipation.back();
      for (unsigned int b = 0; b < 3; ++b)
      {
        s.plastic_dissipation_by_body[b] = body_dissipation[b][0];
        s.damage_dissipation_by_body[b]  = body_dissipation[b][1];
      }
      s.dissipation_gap = max_dissipation_gap;
    }
    if (!history.radiation.empty())
      s.radiated_energy = history.radiation.back();
    if (!history.slab_damping.empty())
      s.slab_damping_dissipation = history.slab_damping.back();
    if (!history.boundary_springs.empty())
      s.boundary_spring_energy = history.boundary_springs.back();
    if (bar_yield_strain > 0)
      summarise_bar_strain(s);
    // After the impact: the wall's state and where the slab's energy went (last sample).
    s.permanent_indentation      = permanent_wall_indentation;
    s.wall_residual_displacement = wall_end_displacement;
    if (!history.time.empty())
    {
      s.contact_dissipation = history.contact_dissipation.back();
      const double work =
        history.internal_work.empty() ? history.strain.back() : history.internal_work.back();
      const double slab_v = history.slab_velocity.back();
      s.residual_energy   = history.kinetic.back() + work - s.plastic_dissipation -
                          s.damage_dissipation - 0.5 * slab_total_mass * slab_v * slab_v;
    }
    s.dissipation_cor =
      std::sqrt(std::max(0.0, 1 - (s.plastic_dissipation + s.damage_dissipation) / e0));
    if (geostatic_on)
    {
      s.geostatic_weight              = geostatic_summary.geostatic_weight;
      s.geostatic_residual            = geostatic_summary.geostatic_residual;
      s.geostatic_iterations          = geostatic_summary.geostatic_iterations;
      s.geostatic_plastic_dissipation = geostatic_summary.geostatic_plastic_dissipation;
      s.geostatic_max_plastic_strain  = geostatic_summary.geostatic_max_plastic_strain;
      s.geostatic_wall_displacement   = geostatic_summary.geostatic_wall_displacement;
      result.geostatic_stress         = std::move(geostatic_stress);
    }
    if (interface)
    {
      s.interface_pairs = interface->pairs().size();
      s.interface_normal_force =
        history.interface_normal_force.empty() ? 0.0 : history.interface_normal_force.front();
      s.friction_dissipation =
        history.friction_dissipation.empty() ? 0.0 : history.friction_dissipation.back();
    }
    result.history = std::move(history);
  }
} // namespace kimp::fem::internal
