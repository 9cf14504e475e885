// ImpactProblem implicit time loop: Newmark average acceleration with semi-smooth Newton and a
// line search on the incremental potential, step halving on non-convergence (Belytschko et al.,
// Nonlinear Finite Elements, 2014, §6.2-6.3; Wriggers, Computational Contact Mechanics, 2006);
// linear solves by KLU with the contact tangent through the Woodbury identity (Hager, SIAM
// Review 31, 1989), or by CG + AMG.
#include <chrono>
#include <cmath>
#include <limits>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/vector.h>

#include "fem/impact/impact_problem.h"
#include "fem/impact/peak_frames.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  /** Newmark average acceleration. */
  constexpr double newmark_beta  = 0.25;
  constexpr double newmark_gamma = 0.5;
  /** Newton on the contact: relative residual tolerance. */
  constexpr double newton_tolerance = 1e-10;
  /** Residual accepted when Newton's direction is no longer a descent one (round-off). */
  constexpr double newton_roundoff_tolerance = 1e-8;
  /** Line search: iteration cap and the reduction of |dPi/dalpha| that ends it. */
  constexpr unsigned int max_line_search       = 20;
  constexpr double       line_search_reduction = 0.5;
  /** CG + AMG: relative residual reduction and iteration cap. */
  constexpr double       cg_tolerance      = 1e-12;
  constexpr unsigned int max_cg_iterations = 2000;

  struct ImpactProblem::StepOperator
  {
    double                                             dt = 0, c1 = 0;
    double                                             rigid_diagonal = 0; ///< m c1
    TrilinosWrappers::SparseMatrix                     base, system;
    SolverControl                                      control;
    std::unique_ptr<TrilinosWrappers::SolverDirect>    direct;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    /** Direct only: columns of the compact block of base^{-1}, computed on first use. */
    std::vector<std::vector<double>> flexibility;
  };

  ImpactProblem::StepOperator &ImpactProblem::step_operator(unsigned int level)
  {
    auto &slot = step_operators[level];
    if (slot)
      return *slot;
    const auto start  = std::chrono::steady_clock::now();
    slot              = std::make_shared<StepOperator>();
    StepOperator &op  = *slot;
    op.dt             = dt / static_cast<double>(1UL << level);
    op.c1             = 1.0 / (newmark_beta * op.dt * op.dt);
    op.rigid_diagonal = prm.rigid_slab ? prm.slab_mass * op.c1 : 0.0;
    op.base.reinit(stiffness);
    op.base.copy_from(stiffness);
    for (const auto i : locally_owned)
      op.base.add(i, i, op.c1 * mass(i));
    add_dashpot_matrix(op.base, newmark_gamma / (newmark_beta * op.dt));
    op.base.compress(VectorOperation::add);
    if (prm.implicit_options.linear_solver == ImplicitOptions::LinearSolver::direct)
    {
      op.direct = std::make_unique<TrilinosWrappers::SolverDirect>(op.control);
      op.direct->initialize(op.base);
      op.flexibility.resize(contact_dofs.size() + 1);
    }
    else
    {
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      DoFTools::extract_constant_modes(dof_handler, ComponentMask(), data.constant_modes);
      op.amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
      op.amg->initialize(op.base, data);
      op.system.reinit(op.base);
    }
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    linear_setup_seconds += seconds;
    linear_solver_seconds += seconds;
    return op;
  }

  void ImpactProblem::base_solve(StepOperator &op, Vec &x, const Vec &b)
  {
    const auto start = std::chrono::steady_clock::now();
    op.direct->solve(x, b);
    ++n_linear_solves;
    linear_solver_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  const std::vector<double> &ImpactProblem::flexibility_column(StepOperator &op, unsigned int k)
  {
    // Column k of the compact block of (K + c1 M)^{-1} (the rigid DoF decouples: 1 / (m c1)).
    auto &column = op.flexibility[k];
    if (!column.empty())
      return column;
    if (k == contact_dofs.size())
    {
      column.assign(contact_dofs.size() + 1, 0.0);
      column.back() = 1.0 / op.rigid_diagonal;
      return column;
    }
    Vec e(locally_owned, comm), x(locally_owned, comm);
    if (locally_owned.is_element(contact_dofs[k]))
      e(contact_dofs[k]) = 1.0;
    e.compress(VectorOperation::insert);
    base_solve(op, x, e);
    column = gather_compact(x, 0.0);
    return column;
  }

  void ImpactProblem::solve_newton_system(StepOperator                     &op,
                                          const PenaltyContact::Evaluation &ev,
                                          const Vec                        &residual,
                                          double                            r_rigid,
                                          Vec                              &du,
                                          double                           &du_r)
  {
    // Newton matrix J = B + sum_i k_i g_i g_i^T, B = K + c1 M (with m c1 on the rigid DoF),
    // g_i = dg/du of active slave i on the free compact DoFs, k_i its tangent penalty.
    const std::size_t r_index = contact_dofs.size();
    std::vector<std::pair<double, std::vector<std::pair<unsigned int, double>>>> g;
    for (const auto &pair : ev.active)
    {
      if (pair.dforce_dpenetration <= 0)
        continue;
      std::vector<std::pair<unsigned int, double>> entries;
      for (unsigned int k = 0; k < pair.n_dofs; ++k)
        if (pair.dofs[k] == r_index || compact_free[pair.dofs[k]])
          entries.emplace_back(pair.dofs[k], pair.dg_du[k]);
      g.emplace_back(pair.dforce_dpenetration, std::move(entries));
    }
    Vec rhs(locally_owned, comm);
    rhs.equ(-1.0, residual);
    if (op.direct)
    {
      // Woodbury: J^{-1} r = x - B^{-1} G S^{-1} G^T x, x = B^{-1} r, S = K^{-1} + G^T B^{-1} G;
      // G^T B^{-1} G needs only the compact block of B^{-1}, cached per step size.
      base_solve(op, du, rhs);
      du_r = prm.rigid_slab ? -r_rigid / op.rigid_diagonal : 0.0;
      if (g.empty())
        return;
      const std::vector<double> xc = gather_compact(du, du_r);
      const unsigned int        m  = g.size();
      FullMatrix<double>        s(m, m);
      Vector<double>            w(m), z(m);
      for (unsigned int i = 0; i < m; ++i)
      {
        for (const auto &[k, gk] : g[i].second)
          w(i) += gk * xc[k];
        s(i, i) += 1.0 / g[i].first;
        for (const auto &[l, gl] : g[i].second)
        {
          const std::vector<double> &column = flexibility_column(op, l);
          for (unsigned int j = 0; j < m; ++j)
            for (const auto &[k, gk] : g[j].second)
              s(j, i) += gk * column[k] * gl;
        }
      }
      s.gauss_jordan();
      s.vmult(z, w);
      std::vector<double> y(r_index + 1, 0.0);
      for (unsigned int i = 0; i < m; ++i)
        for (const auto &[k, gk] : g[i].second)
          y[k] += gk * z(i);
      Vec                 correction(locally_owned, comm), dx(locally_owned, comm);
      std::vector<double> y_nodes(y.begin(), y.end());
      y_nodes.back() = 0;
      scatter_add(y_nodes, correction);
      base_solve(op, dx, correction);
      du -= dx;
      if (prm.rigid_slab)
        du_r -= y.back() / op.rigid_diagonal;
      return;
    }

    // CG + AMG on the assembled J; the rigid DoF by Sherman-Morrison on the Schur complement
    // S = A - b b^T / d (A: free block of J, b: its coupling to the rigid DoF, d: rigid entry).
    double d = op.rigid_diagonal;
    Vec    b(locally_owned, comm), z(locally_owned, comm);
    op.system.copy_from(op.base);
    for (const auto &[k_i, entries] : g)
      for (const auto &[i, gi] : entries)
        for (const auto &[j, gj] : entries)
        {
          const double value = k_i * gi * gj;
          const bool   ri = i == r_index, rj = j == r_index;
          if (ri && rj)
            d += value;
          else if (rj)
          {
            if (locally_owned.is_element(contact_dofs[i]))
              b(contact_dofs[i]) += value;
          }
          else if (!ri && locally_owned.is_element(contact_dofs[i]))
            op.system.add(contact_dofs[i], contact_dofs[j], value);
        }
    op.system.compress(VectorOperation::add);
    b.compress(VectorOperation::add);
    const auto cg_solve = [&](Vec &x, const Vec &f)
    {
      const auto                 start = std::chrono::steady_clock::now();
      SolverControl              control(max_cg_iterations, cg_tolerance * f.l2_norm());
      TrilinosWrappers::SolverCG cg(control);
      x = 0;
      if (f.l2_norm() > 0)
        cg.solve(op.system, x, f, *op.amg);
      ++n_linear_solves;
      linear_solver_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    du_r = 0;
    if (prm.rigid_slab)
    {
      const double s = -r_rigid;
      rhs.add(-s / d, b);
      cg_solve(du, rhs);
      cg_solve(z, b);
      const double bz1 = b * du, bz2 = b * z;
      du.add(bz1 / (d - bz2), z);
      du_r = (s - (b * du)) / d;
    }
    else
      cg_solve(du, rhs);
  }

  struct ImpactProblem::ImplicitState
  {
    ImplicitState(const IndexSet &owned, MPI_Comm comm)
      : u(owned, comm)
      , v(owned, comm)
      , acc(owned, comm)
      , u_np1(owned, comm)
      , v_np1(owned, comm)
      , a_np1(owned, comm)
      , Ku(owned, comm)
      , residual(owned, comm)
      , du(owned, comm)
      , rhs(owned, comm)
      , u_start(owned, comm)
    {
    }
    /// The last converged step, the Newton iterate (_np1), work vectors.
    Vec    u, v, acc, u_np1, v_np1, a_np1, Ku, residual, du, rhs, u_start;
    double u_r = 0, v_r = 0, a_r = 0;             ///< the rigid slab at the step
    double u_r_np1 = 0, v_r_np1 = 0, a_r_np1 = 0; ///< and at the iterate
    /// The contact at the iterate (after a converged step: at the step).
    PenaltyContact::Evaluation ev;
    std::vector<double>        cu;
    /// Round-off floor of the residual: |K| |u|.
    double stiffness_norm = 0;
    /// The iterate's rigid-slab residual, residual scale and norm.
    double r_rigid = 0, scale = 0, r_norm = 0;
    /// A failed Newton step's residual and tolerance.
    double r_fail = 0, tol_fail = 0;
  };

  void ImpactProblem::mark_free_contact_dofs()
  {
    compact_free.assign(contact_dofs.size(), false);
    std::vector<double> local(contact_dofs.size(), 0.0);
    for (unsigned int k = 0; k < contact_dofs.size(); ++k)
      if (locally_owned.is_element(contact_dofs[k]) && !constraints.is_constrained(contact_dofs[k]))
        local[k] = 1;
    const std::vector<double> all = sum_over_ranks(local, comm);
    for (unsigned int k = 0; k < contact_dofs.size(); ++k)
      compact_free[k] = all[k] > 0.5;
  }

  void ImpactProblem::evaluate_implicit_iterate(ImplicitState &s, double h, double c1)
  {
    const double c2            = 1.0 / (2 * newmark_beta) - 1;
    const double m_r           = prm.rigid_slab ? prm.slab_mass : 0.0;
    const double momentum_rate = slab_total_mass * prm.initial_velocity / h;
    s.a_np1                    = s.u_np1;
    s.a_np1.add(-1.0, s.u, -h, s.v);
    s.a_np1.sadd(c1, -c2, s.acc);
    s.v_np1 = s.v;
    s.v_np1.add(h * (1 - newmark_gamma), s.acc, h * newmark_gamma, s.a_np1);
    s.a_r_np1 = c1 * (s.u_r_np1 - s.u_r - h * s.v_r) - c2 * s.a_r;
    s.v_r_np1 = s.v_r + h * ((1 - newmark_gamma) * s.a_r + newmark_gamma * s.a_r_np1);

    const auto gathered          = gather_compact(s.u_np1, s.u_r_np1, s.v_np1, s.v_r_np1);
    s.cu                         = gathered.first;
    s.ev                         = contact->evaluate(s.cu, gathered.second);
    const std::vector<double> fc = padded_force(s.ev, s.cu.size());
    internal_force(s.u_np1, s.Ku);
    s.residual = s.a_np1;
    s.residual.scale(mass);
    const double inertia_norm = s.residual.l2_norm();
    s.residual += s.Ku;
    if (absorbing)
      add_dashpot_force(s.u_np1, s.v_np1, s.residual);
    s.rhs = 0;
    scatter_add(fc, s.rhs);
    s.residual -= s.rhs;
    s.residual.scale(free_mask);
    s.r_rigid = prm.rigid_slab ? m_r * s.a_r_np1 - fc[contact_dofs.size()] : 0.0;
    s.scale   = inertia_norm + s.Ku.l2_norm() + s.ev.total_force +
              s.stiffness_norm * s.u_np1.l2_norm() + momentum_rate + m_r * std::abs(s.a_r_np1) +
              std::numeric_limits<double>::min();
    s.r_norm = std::sqrt(s.residual.norm_sqr() + s.r_rigid * s.r_rigid);
  }

  // Semi-smooth Newton on the incremental potential
  //   Pi(u) = c1 / 2 |u - u~|_M^2 + u.K u / 2 + sum_i k_i max(0, p_i(u))^2 / 2,
  // whose gradient is the residual R = M a + K u - f_c. Pi is convex and C1 with a piecewise
  // constant Hessian: a full Newton step can jump across the kinks of max(0, p) and cycle
  // between active sets; a line search for the minimum of Pi along the Newton direction
  // cannot.
  bool ImpactProblem::implicit_newton_step(ImplicitState &s, unsigned int level)
  {
    StepOperator &op = step_operator(level);
    const double  h  = op.dt;
    const double  c1 = op.c1;
    s.u_np1          = s.u;
    s.u_np1.add(h, s.v, 0.5 * h * h, s.acc);
    s.u_r_np1 = s.u_r + h * s.v_r + 0.5 * h * h * s.a_r;
    evaluate_implicit_iterate(s, h, c1);
    for (unsigned int k = 0;; ++k)
    {
      if (s.r_norm <= newton_tolerance * s.scale)
        return true;
      if (k == prm.implicit_options.newton_max_iterations)
      {
        s.r_fail   = s.r_norm;
        s.tol_fail = newton_tolerance * s.scale;
        return false;
      }
      ++n_newton;
      double du_r = 0;
      solve_newton_system(op, s.ev, s.residual, s.r_rigid, s.du, du_r);
      s.du.scale(free_mask);
      const double slope = s.residual * s.du + s.r_rigid * du_r;
      if (!(slope < 0))
      {
        // Not a descent direction: only round-off is left in the residual.
        if (s.r_norm <= newton_roundoff_tolerance * s.scale)
          return true;
        s.r_fail   = s.r_norm;
        s.tol_fail = newton_tolerance * s.scale;
        return false;
      }
      // Line search on phi(alpha) = Pi(u + alpha du), convex, through its derivative
      // phi'(alpha) = R(u + alpha du) . du, which (unlike Pi itself, a sum of large terms)
      // stays accurate down to the Newton tolerance: the full step if phi'(1) <= 0 (Pi falls
      // all the way), else regula falsi (Illinois) for the minimum until |phi'| has fallen
      // by line_search_reduction. A history law has no Pi; the same search on R . du is
      // then a heuristic.
      s.u_start              = s.u_np1;
      const double u_r_start = s.u_r_np1;
      const auto   phi_prime = [&](double step)
      {
        s.u_np1 = s.u_start;
        s.u_np1.add(step, s.du);
        s.u_r_np1 = u_r_start + step * du_r;
        evaluate_implicit_iterate(s, h, c1);
        return s.residual * s.du + s.r_rigid * du_r;
      };
      double alpha = 1, lo = 0, hi = 1, phi_lo = slope, phi_hi = phi_prime(1.0);
      bool   accepted = phi_hi <= 0 || s.r_norm <= newton_tolerance * s.scale;
      for (unsigned int ls = 0; !accepted && ls < max_line_search; ++ls)
      {
        alpha                    = (lo * phi_hi - hi * phi_lo) / (phi_hi - phi_lo);
        const double phi         = phi_prime(alpha);
        accepted                 = std::abs(phi) <= line_search_reduction * std::abs(slope);
        const bool left          = phi < 0;
        (left ? lo : hi)         = alpha;
        (left ? phi_lo : phi_hi) = phi;
        // Illinois: halve the value kept at the end that did not move.
        (left ? phi_hi : phi_lo) *= 0.5;
      }
      if (!accepted)
      {
        s.r_fail   = s.r_norm;
        s.tol_fail = newton_tolerance * s.scale;
        return false;
      }
    }
  }

  void ImpactProblem::run_implicit()
  {
    ImplicitState s(locally_owned, comm);
    if (geostatic_on)
      s.u = geostatic_u;
    set_initial_slab_velocity(s.v);
    s.v_r = prm.initial_velocity;
    mark_free_contact_dofs();
    s.stiffness_norm = stiffness.linfty_norm();

    const LoopSteps steps = loop_steps();
    {
      s.cu = gather_compact(s.u, s.u_r);
      s.ev = contact->evaluate(s.cu, gather_compact(s.v, s.v_r));
      internal_force(s.u, s.Ku);
      record({0, 0.0, s.u, s.v, s.Ku, s.u_r, s.v_r, s.ev, s.cu, false});
      if (steps.write_vtu)
        output_results(0.0, s.u, s.v, padded_force(s.ev, s.cu.size()));
      if (steps.frame_every)
        record_frame(0.0, s.u, s.ev);
    }

    bool          started    = false;
    unsigned long zero_since = 0;
    PeakFrames    frame_due(steps.frame_every);
    unsigned long n = 0;
    // Time in ticks of the smallest allowed step, dt / 2^max_halvings.
    const unsigned int  max_level      = prm.implicit_options.max_halvings;
    const unsigned long ticks_per_step = 1UL << max_level;
    unsigned long       ticks          = 0;
    unsigned int        level          = 0;
    while (n < steps.n_max)
    {
      const unsigned long step_ticks = ticks_per_step >> level;
      const double        t_np1 =
        static_cast<double>(ticks + step_ticks) * dt / static_cast<double>(ticks_per_step);
      if (!implicit_newton_step(s, level))
      {
        if (!linear_laws)
          qp_history.revert();
        const double t_fail = t_np1;
        if (level == max_level)
          throw NumericalError("Newton on the contact did not converge at t = " +
                                 fmt_double(t_fail) + " s (step " + std::to_string(n + 1) +
                                 ", dt halved " + std::to_string(level) + " times to " +
                                 fmt_double(step_operator(level).dt) + " s, the floor; " +
                                 std::to_string(s.ev.active.size()) +
                                 " active contact nodes): residual " + fmt_double(s.r_fail) +
                                 " N/m vs tolerance " + fmt_double(s.tol_fail),
                               t_fail,
                               n + 1);
        ++level;
        ++n_step_halvings;
        continue;
      }
      if (!linear_laws)
        qp_history.commit();
      s.u.swap(s.u_np1);
      s.v.swap(s.v_np1);
      s.acc.swap(s.a_np1);
      s.u_r = s.u_r_np1;
      s.v_r = s.v_r_np1;
      s.a_r = s.a_r_np1;
      ticks += step_ticks;
      // Grow back once the substeps are aligned with the coarser grid.
      while (level > 0 && ticks % (ticks_per_step >> (level - 1)) == 0)
        --level;
      if (ticks % ticks_per_step != 0)
        continue;
      ++n;
      record({n, t_np1, s.u, s.v, s.Ku, s.u_r, s.v_r, s.ev, s.cu, false});
      if (steps.write_vtu && n % steps.vtu_every == 0)
        output_results(t_np1, s.u, s.v, padded_force(s.ev, s.cu.size()));
      if (frame_due(n, t_np1, s.ev.total_force))
        record_frame(t_np1, s.u, s.ev);
      if (prm.progress && n % prm.progress_interval == 0 &&
          Utilities::MPI::this_mpi_process(comm) == 0)
        prm.progress(t_np1, prm.end_time);

      if (s.ev.total_force > 0)
      {
        started    = true;
        zero_since = n + 1;
      }
      // Over as in the explicit loop: zero force for the hold time, the slab not moving in, wall
      // and soil having given back their energy (or the slab rebounding).
      if (started && n + 1 - zero_since >= steps.hold_steps && s.ev.total_force == 0 &&
          system_released_the_slab(slab_velocity(s.v, s.v_r)))
      {
        separated_flag = true;
        break;
      }
    }
    slab_v_end   = slab_velocity(s.v, s.v_r);
    n_steps_done = n;
    compute_residual_state(s.u, s.u_r);
  }

} // namespace kimp::fem::internal
