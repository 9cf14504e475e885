// Newmark average-acceleration method with Newton at the isolator and the contacts, and recursive
// step halving on non-convergence (Newmark 1959; docs/architecture.md "Time integration").
#include "lumped/integrators/newmark_integrator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "lumped/integrators/integration_errors.h"
#include "lumped/integrators/response_recorder.h"
#include "lumped/parameter_check.h"

namespace kimp::lumped
{
  NewmarkIntegrator::NewmarkIntegrator(PoundingModel model, NewmarkOptions options)
    : model_(std::move(model))
    , options_(std::move(options))
  {
    const ParameterCheck check("newmark.");
    check(options_.dt >= 0.0 && std::isfinite(options_.dt),
          "dt",
          options_.dt,
          "must be > 0 s, or 0 for the record's dt");
    check(options_.duration >= 0.0, "duration", options_.duration, "must be >= 0 s");
    check(options_.output_interval >= 0.0,
          "output_interval",
          options_.output_interval,
          "must be >= 0 s");
    check(options_.displacement_tolerance > 0.0,
          "displacement_tolerance",
          options_.displacement_tolerance,
          "must be > 0 m");
    check(options_.max_iterations >= 1, "max_iterations", options_.max_iterations, "must be >= 1");
    check(options_.max_halvings >= 0, "max_halvings", options_.max_halvings, "must be >= 0");
    require_initial_state("newmark.",
                          options_.initial_displacement,
                          options_.initial_velocity,
                          model_.n_dofs());
  }

  namespace
  {
    class NewmarkRun
    {
    public:
      NewmarkRun(const PoundingModel &model, const NewmarkOptions &opt, const GroundMotion &g)
        : model_(model)
        , opt_(opt)
        , motion_(g)
        , n_(static_cast<Eigen::Index>(model.n_dofs()))
      {
        mass_ = Eigen::Map<const Eigen::VectorXd>(model.masses().data(), n_);
        k_    = model.stiffness().to_dense();
        c_    = model.damping().to_dense();
        if (model.isolator())
        {
          iso_ = model.isolator()->clone();
          iso_->revert_to_start();
        }
        for (const ContactPair &c : model.contacts())
        {
          laws_.push_back(c.law->clone());
          laws_.back()->revert_to_start();
        }
        active_.assign(laws_.size(), 0);
        for (Eigen::VectorXd *x : {&trial_u_, &trial_a_, &trial_v_, &f_, &res_, &du_})
          x->resize(n_);
        jac_nl_.resize(n_, n_);
        jac_lin_.resize(n_, n_);
        lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(n_);
        f_prev_.assign(laws_.size(), 0.0);
        delta_prev_.assign(laws_.size(), 0.0);
      }

      Response run()
      {
        const double dt       = opt_.dt > 0.0 ? opt_.dt : motion_.dt;
        const double duration = opt_.duration > 0.0 ?
                                  opt_.duration :
                                  motion_.dt * static_cast<double>(motion_.acceleration.size());
        const long   n_steps  = std::lround(duration / dt);
        const long   every =
          opt_.output_interval > 0.0 ? std::max(1L, std::lround(opt_.output_interval / dt)) : 0L;
        rec_.start(model_, dt, n_steps, every);

        u_ = Eigen::VectorXd::Zero(n_);
        v_ = Eigen::VectorXd::Zero(n_);
        if (!opt_.initial_displacement.empty())
          u_ = Eigen::Map<const Eigen::VectorXd>(opt_.initial_displacement.data(), n_);
        if (!opt_.initial_velocity.empty())
          v_ = Eigen::Map<const Eigen::VectorXd>(opt_.initial_velocity.data(), n_);
        // ü_0 from the equation of motion at t = 0 (laws trialled, then committed at u_0).
        Eigen::VectorXd f(n_);
        Eigen::MatrixXd jac(n_, n_);
        evaluate_nonlinear(u_, v_, 0.0, f, jac, contact_force_);
        commit_nonlinear(0.0, contact_force_, u_);
        a_ = (-mass_ * ground(0.0) - c_ * v_ - k_ * u_ - f).cwiseQuotient(mass_);
        record(0.0, true);
        for (long step = 1; step <= n_steps; ++step)
        {
          const double t0 = static_cast<double>(step - 1) * dt;
          advance(t0, dt, 0, step);
          record(static_cast<double>(step) * dt, every > 0 && step % every == 0);
        }
        return rec_.finish(laws_);
      }

    private:
      double ground(const double t) const
      {
        const std::vector<double> &rec = motion_.acceleration;
        const double               x   = t / motion_.dt;
        const auto                 j   = static_cast<std::size_t>(std::floor(x + 1e-9));
        const double               fr  = std::max(0.0, x - static_cast<double>(j));
        if (j + 1 < rec.size())
          return rec[j] + fr * (rec[j + 1] - rec[j]);
        return j + 1 == rec.size() && fr < 1e-9 ? rec[j] : 0.0;
      }

      /// Trial evaluation of the isolator and the contacts at (u, v); `damping_factor` = γ/(βΔt)
      /// turns the laws' dF/dδ̇ into a stiffness contribution (0: stiffness only).
      void evaluate_nonlinear(const Eigen::VectorXd &u,
                              const Eigen::VectorXd &v,
                              const double           damping_factor,
                              Eigen::VectorXd       &f,
                              Eigen::MatrixXd       &jac,
                              std::vector<double>   &contact_force)
      {
        f.setZero();
        jac.setZero();
        if (iso_)
        {
          const IsolatorResponse r = iso_->set_trial(u(0), v(0));
          f(0) += r.force;
          jac(0, 0) += r.stiffness + damping_factor * r.damping;
        }
        contact_force.assign(laws_.size(), 0.0);
        for (std::size_t c = 0; c < laws_.size(); ++c)
        {
          const ContactPair  &cp = model_.contacts()[c];
          const double        uL = cp.left_dof >= 0 ? u(cp.left_dof) : 0.0;
          const double        uR = cp.right_dof >= 0 ? u(cp.right_dof) : 0.0;
          const double        vL = cp.left_dof >= 0 ? v(cp.left_dof) : 0.0;
          const double        vR = cp.right_dof >= 0 ? v(cp.right_dof) : 0.0;
          const ForceResponse r  = laws_[c]->set_trial(uL - uR - cp.gap, vL - vR);
          contact_force[c]       = r.force;
          const double kt        = r.stiffness + damping_factor * r.damping;
          if (cp.left_dof >= 0)
          {
            f(cp.left_dof) += r.force;
            jac(cp.left_dof, cp.left_dof) += kt;
          }
          if (cp.right_dof >= 0)
          {
            f(cp.right_dof) -= r.force;
            jac(cp.right_dof, cp.right_dof) += kt;
          }
          if (cp.left_dof >= 0 && cp.right_dof >= 0)
          {
            jac(cp.left_dof, cp.right_dof) -= kt;
            jac(cp.right_dof, cp.left_dof) -= kt;
          }
        }
      }

      void
      commit_nonlinear(const double t, const std::vector<double> &force, const Eigen::VectorXd &u)
      {
        if (iso_)
        {
          iso_->commit();
          rec_.isolator_force(iso_->committed_force());
        }
        for (std::size_t c = 0; c < laws_.size(); ++c)
        {
          const ContactPair &cp = model_.contacts()[c];
          laws_[c]->commit();
          const int    now   = laws_[c]->in_contact() ? 1 : 0;
          const double delta = (cp.left_dof >= 0 ? u(cp.left_dof) : 0.0) -
                               (cp.right_dof >= 0 ? u(cp.right_dof) : 0.0) - cp.gap;
          if (now && !active_[c])
          {
            const double vL = cp.left_dof >= 0 ? v_(cp.left_dof) : 0.0;
            const double vR = cp.right_dof >= 0 ? v_(cp.right_dof) : 0.0;
            rec_.impact(c, t, vL - vR);
          }
          active_[c] = now;
          w_contact_ += 0.5 * (f_prev_[c] + force[c]) * (delta - delta_prev_[c]);
          f_prev_[c]     = force[c];
          delta_prev_[c] = delta;
          rec_.contact_force(c, force[c], delta, t);
        }
      }

      /// Advance the committed state from t by h, halving on failure.
      void advance(const double t, const double h, const int depth, const long step)
      {
        double residual_norm = 0.0;
        if (try_step(t, h, residual_norm))
          return;
        if (depth >= opt_.max_halvings)
        {
          std::ostringstream msg;
          msg << "Newmark: Newton did not converge at t = " << t + h << " s (step " << step
              << ", dt = " << h << " s after " << depth << " halvings), residual norm "
              << residual_norm << " N";
          throw ConvergenceError(msg.str(), t + h, step, residual_norm);
        }
        advance(t, 0.5 * h, depth + 1, step);
        record(t + 0.5 * h, false);
        advance(t + 0.5 * h, 0.5 * h, depth + 1, step);
      }

      bool try_step(const double t, const double h, double &residual_norm)
      {
        const double ag = ground(t + h);
        if (h != jac_lin_h_)
        {
          // M·4/Δt² + C·2/Δt + K, rebuilt only when the step size changes.
          jac_lin_ = c_ * (2.0 / h) + k_;
          jac_lin_.diagonal() += mass_ * (4.0 / (h * h));
          jac_lin_h_ = h;
        }
        Eigen::VectorXd &u = trial_u_, &a = trial_a_, &v = trial_v_;
        u = u_ + h * v_ + 0.25 * h * h * a_;
        for (int it = 0; it < opt_.max_iterations; ++it)
        {
          a = 4.0 / (h * h) * (u - u_) - 4.0 / h * v_ - a_;
          v = v_ + 0.5 * h * (a_ + a);
          evaluate_nonlinear(u, v, 2.0 / h, f_, jac_nl_, force_);
          res_.noalias() = c_ * v;
          res_.noalias() += k_ * u;
          res_ += mass_.cwiseProduct(a) + f_ + mass_ * ag;
          residual_norm = res_.norm();
          jac_nl_ += jac_lin_;
          lu_.compute(jac_nl_);
          du_.noalias() = lu_.solve(res_);
          u -= du_;
          if (!u.allFinite())
            break;
          if (du_.lpNorm<Eigen::Infinity>() <= opt_.displacement_tolerance)
          {
            // Final state consistent with the converged u.
            a = 4.0 / (h * h) * (u - u_) - 4.0 / h * v_ - a_;
            v = v_ + 0.5 * h * (a_ + a);
            evaluate_nonlinear(u, v, 2.0 / h, f_, jac_nl_, force_);
            const double p_old = -ag_prev_ * mass_.dot(v_);
            const double c_old = v_.dot(c_ * v_);
            u_                 = u;
            v_                 = v;
            a_                 = a;
            commit_nonlinear(t + h, force_, u_);
            const double p_new = -ag * mass_.dot(v_);
            w_in_ += 0.5 * (p_old + p_new) * h;
            w_visc_ += 0.5 * (c_old + v_.dot(c_ * v_)) * h;
            ag_prev_ = ag;
            return true;
          }
        }
        if (iso_)
          iso_->revert_to_last_commit();
        for (auto &law : laws_)
          law->revert_to_last_commit();
        return false;
      }

      /// Peaks and energies of the committed state at t (macro or sub-step); a history sample
      /// when `sample`.
      void record(const double t, const bool sample)
      {
        Response         &r  = rec_.response();
        const double      ag = ground(t);
        const std::size_t n  = static_cast<std::size_t>(n_);
        for (std::size_t i = 0; i < n; ++i)
        {
          const auto ii          = static_cast<Eigen::Index>(i);
          r.peak_displacement[i] = std::max(r.peak_displacement[i], std::abs(u_(ii)));
          r.peak_absolute_acceleration[i] =
            std::max(r.peak_absolute_acceleration[i], std::abs(a_(ii) + ag));
        }
        const auto drift = [&](const Storey &s)
        { return u_(s.upper_dof) - (s.lower_dof >= 0 ? u_(s.lower_dof) : 0.0); };
        for (std::size_t s = 0; s < model_.storeys().size(); ++s)
          r.peak_interstorey_drift[s] =
            std::max(r.peak_interstorey_drift[s], std::abs(drift(model_.storeys()[s])));

        EnergyBalance terms;
        terms.kinetic = 0.5 * mass_.dot(v_.cwiseProduct(v_));
        terms.strain  = 0.5 * u_.dot(k_ * u_) + (iso_ ? iso_->stored_energy() : 0.0);
        if (t == 0.0)
        {
          e_initial_ = terms.kinetic + terms.strain;
          ag_prev_   = ag;
        }
        terms.initial      = e_initial_;
        terms.input        = w_in_;
        terms.viscous      = w_visc_;
        terms.hysteretic   = iso_ ? iso_->dissipated_energy() : 0.0;
        terms.contact_work = w_contact_;
        rec_.supplied(e_initial_ + w_in_);
        const double err = rec_.check_energy(terms);
        if (sample)
          rec_.sample(
            t,
            [&](const std::size_t i) { return u_(static_cast<Eigen::Index>(i)); },
            [&](const std::size_t i) { return a_(static_cast<Eigen::Index>(i)) + ag; },
            [&](const std::size_t s) { return drift(model_.storeys()[s]); },
            f_prev_,
            e_initial_ + w_in_,
            err);
      }

      const PoundingModel                   &model_;
      const NewmarkOptions                  &opt_;
      const GroundMotion                    &motion_;
      Eigen::Index                           n_;
      Eigen::VectorXd                        mass_;
      Eigen::MatrixXd                        k_, c_;
      std::unique_ptr<Isolator>              iso_;
      std::vector<std::unique_ptr<ForceLaw>> laws_;
      std::vector<int>                       active_;
      std::vector<double>                    f_prev_, delta_prev_, contact_force_;
      Eigen::VectorXd                        u_, v_, a_;
      // Newton workspace, sized once.
      Eigen::VectorXd                      trial_u_, trial_a_, trial_v_, f_, res_, du_;
      Eigen::MatrixXd                      jac_nl_, jac_lin_;
      double                               jac_lin_h_ = -1.0;
      Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
      std::vector<double>                  force_;
      double w_in_ = 0.0, w_visc_ = 0.0, w_contact_ = 0.0, ag_prev_ = 0.0, e_initial_ = 0.0;
      ResponseRecorder rec_;
    };
  } // namespace

  Response NewmarkIntegrator::run(const GroundMotion &motion) const
  {
    if (!(motion.dt > 0.0) || motion.acceleration.empty())
      throw std::invalid_argument("ground motion '" + motion.name +
                                  "': dt must be > 0 and the record non-empty");
    NewmarkRun run(model_, options_, motion);
    return run.run();
  }
} // namespace kimp::lumped
