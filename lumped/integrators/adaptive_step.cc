// Variable-step central differences (`dt: auto`): the leap-frog step with a changing Δt, the
// step choice around contacts and the step-factor error estimate over contact windows
// (docs/physics.md §2, "Variable-step central differences"). One file of ~1000 lines on purpose:
// the run is one algorithm, the class template AdaptiveRun over the DOF count, whose step choice,
// step, forces, window bookkeeping and estimate re-run share the run's state and are instantiated
// together here (N = 1..8 and any N); split across files it would only move into a header.
#include "lumped/integrators/adaptive_step.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "lumped/integrators/integration_errors.h"
#include "lumped/integrators/response_recorder.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/parameter_check.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// The values of State: copied as they are.
    template <int N>
    struct StateValues
    {
      using Vec      = Eigen::Matrix<double, N, 1>;
      double t       = 0.0;
      double h_prev  = 0.0; ///< h_{n−1}
      double h_prev2 = 0.0; ///< h_{n−2}
      long   n       = 0;
      Vec    u, v_half, f; ///< u_n, v_{n−1/2}, f_nl,n
      /// Fast path: C·v_{n−1/2} (carried from the last step), 1/h_{n−1}, 1/h_{n−2} and
      /// h_{n−1}/(h_{n−1} + h_{n−2}) of the three-point rate.
      Vec                 cv_half;
      double              ih_prev = 0.0, ih_prev2 = 0.0, w_rate = 0.0;
      std::vector<double> dp, dpp, delta, cf;
      std::vector<double> closing; ///< fast path: closing rate at t_n, m/s
      std::vector<int>    active;
      /// Fast path: the rate of the last step per contact, and whether the law was called then
      /// (its committed state is that step's); a law skipped while open is first brought to the
      /// last skipped state before it is called again.
      std::vector<double> rate_prev;
      std::vector<int>    called;
      double              iso_u1 = 0.0, iso_u2 = 0.0; ///< u_0 at n−1, n−2
      /// Isolator rate u̇_0 at t_n (three-point) and the relative acceleration ü_0 at t_{n−1}.
      double iso_rate = 0.0, iso_acc = 0.0;
      double w_in = 0.0, w_visc = 0.0, w_contact = 0.0, p_in_prev = 0.0, p_visc_prev = 0.0;
      double tail_until = -std::numeric_limits<double>::infinity();
    };

    /// Everything that evolves during a run: copied (laws cloned) for the error-estimate re-run.
    /// N: the number of DOFs (Eigen::Dynamic for any).
    template <int N>
    struct State : StateValues<N>
    {
      std::unique_ptr<Isolator>              iso;
      std::vector<std::unique_ptr<ForceLaw>> laws;

      State copy() const
      {
        State s;
        static_cast<StateValues<N> &>(s) = *this;
        if (iso)
          s.iso = iso->clone();
        for (const auto &law : laws)
          s.laws.push_back(law->clone());
        return s;
      }
    };

    /// The step sizes of one run's tiers, s (see AdaptiveCentralDifference).
    struct StepSizes
    {
      double large;    ///< Δt_large: every contact open and far
      double approach; ///< Δt_a: a gap closes within approach_time
      double contact;  ///< Δt_c: a contact active or imminent
      double stick;    ///< Δt_stick: a stick-slip isolator sticks
    };

    /// Peaks inside one contact window.
    struct WindowPeaks
    {
      std::vector<double> force, acceleration, displacement;
      void                reset(std::size_t n_contacts, std::size_t n_dofs)
      {
        force.assign(n_contacts, 0.0);
        acceleration.assign(n_dofs, 0.0);
        displacement.assign(n_dofs, 0.0);
      }
    };

    /**
     * One variable-step run. N: the number of DOFs as a compile-time size (fixed-size vectors and
     * matrices, nothing allocated per step), or Eigen::Dynamic. Fast: the effective matrix of
     * each step size as a cached inverse (one product per step instead of an LU solve) and the
     * laws not called while their gap is open (as in the fused fixed-step kernel); otherwise
     * the reference path (dynamic LU per step size, every law every step), the oracle of the fast
     * one in the tests.
     */
    template <int N, bool Fast>
    class AdaptiveRun
    {
      using Vec   = Eigen::Matrix<double, N, 1>;
      using Mat   = Eigen::Matrix<double, N, N>;
      using State = kimp::lumped::State<N>;

    public:
      AdaptiveRun(const PoundingModel            &model,
                  const CentralDifferenceOptions &cdm,
                  const AdaptiveStepOptions      &opt,
                  const GroundMotion             &g,
                  const StepSizes                &steps)
        : model_(model)
        , cdm_(cdm)
        , opt_(opt)
        , motion_(g)
        , n_(static_cast<Eigen::Index>(model.n_dofs()))
        , big_(steps.large)
        , fine_(steps.contact)
        , approach_(steps.approach)
        , stick_(steps.stick)
        , est_(opt.estimate_factor)
      {
        mass_          = Eigen::Map<const Vec>(model.masses().data(), n_);
        bilinear_      = dynamic_cast<const BilinearIsolator *>(model.isolator()) != nullptr;
        stick_slip_    = model.isolator() && model.isolator()->stick_slip();
        inv_record_dt_ = 1.0 / g.dt;
        k_             = model.stiffness().to_dense();
        c_             = model.damping().to_dense();
      }

      /// `replay`: take these steps (a run's `taken`) instead of choosing them, no estimate;
      /// `taken`: the steps of this run.
      Response
      run(AdaptiveStepReport *report, const std::vector<double> *replay, std::vector<double> *taken)
      {
        const double duration = cdm_.duration > 0.0 ?
                                  cdm_.duration :
                                  motion_.dt * static_cast<double>(motion_.acceleration.size());
        const double interval = cdm_.output_interval;
        const long   every    = interval > 0.0 ? std::max(1L, std::lround(interval / big_)) : 0L;
        rec_.start(model_, big_, std::lround(duration / big_), every);
        // One row every output_interval (the N/every + 1 rows start() reserves assume Δt_large).
        if (interval > 0.0)
          rec_.reserve_samples(static_cast<std::size_t>(std::ceil(duration / interval)) + 2);
        report_.dt_min = std::numeric_limits<double>::infinity();
        State s        = initial_state();
        e0_            = 0.5 * mass_.dot(s.v_half.cwiseProduct(s.v_half)) + 0.5 * s.u.dot(k_ * s.u);
        if (s.iso)
          e0_ += s.iso->stored_energy();

        const double eps = 1e-6 * std::min(big_, fine_);
        interval_        = interval;
        eps_             = eps;
        next_sample_     = interval > 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
        sample_k_        = 0;
        left_.u.assign(static_cast<std::size_t>(n_), 0.0);
        left_.a.assign(static_cast<std::size_t>(n_), 0.0);
        left_.drift.assign(model_.storeys().size(), 0.0);
        left_.cf.assign(s.laws.size(), 0.0);
        row_                  = left_;
        bool        in_window = false;
        State       snapshot;
        WindowPeaks peaks;
        while (true)
        {
          forces(s, true);
          const bool   last      = s.t >= duration - eps;
          const double target    = target_step(s, 1.0);
          const bool   replaying = replay && static_cast<std::size_t>(s.n) < replay->size();
          if (in_window && target >= big_)
          {
            close_window(snapshot, peaks, s.t);
            in_window = false;
          }
          if (target < big_ && !in_window && opt_.error_estimate && !replay && !last)
          {
            snapshot  = s.copy();
            in_window = true;
            peaks.reset(s.laws.size(), static_cast<std::size_t>(n_));
            ++report_.windows;
          }
          double h = choose_step(s, std::min(target, 2.0 * s.h_prev));
          if (h < big_)
            ++report_.contact_steps_taken;
          // The steps do not land on the history samples: a sample inside a step is
          // interpolated between the step's ends (record_step()); they end at the end of the run.
          h = clip(h, duration - s.t);
          if (replaying)
            h = (*replay)[static_cast<std::size_t>(s.n)];
          if (taken)
            taken->push_back(h);
          // Rows due at t_n: those inside the last step and one at t_n itself.
          const bool sample_now = next_sample_ <= s.t + eps;
          const bool check      = sample_now || s.n % 512 == 0 || last;
          step(s, h, true, in_window ? &peaks : nullptr, sample_now, check, last);
          if (last)
            break;
          report_.dt_min = std::min(report_.dt_min, h);
          // Land exactly on the end, so that the time does not drift.
          s.t = std::abs(s.t + h - duration) <= eps ? duration : s.t + h;
          ++s.n;
        }
        if (in_window)
          close_window(snapshot, peaks, s.t + eps);
        Response r          = rec_.release(s.laws);
        r.n_steps           = s.n;
        r.duration          = duration;
        r.history.interval  = interval;
        report_.dt_large    = big_;
        report_.dt_contact  = fine_;
        report_.dt_approach = approach_;
        report_.steps       = s.n;
        if (report)
          *report = report_;
        return r;
      }

    private:
      double ground(const double t) const
      {
        const std::vector<double> &rec = motion_.acceleration;
        const double               x   = Fast ? t * inv_record_dt_ : t / motion_.dt;
        const auto                 j   = static_cast<std::size_t>(std::floor(x + 1e-9));
        const double               fr  = std::max(0.0, x - static_cast<double>(j));
        if (j + 1 < rec.size())
          return rec[j] + fr * (rec[j + 1] - rec[j]);
        return j + 1 == rec.size() && fr < 1e-9 ? rec[j] : 0.0;
      }

      double delta_of(const ContactPair &cp, const Vec &u) const
      {
        return (cp.left_dof >= 0 ? u(cp.left_dof) : 0.0) -
               (cp.right_dof >= 0 ? u(cp.right_dof) : 0.0) - cp.gap;
      }

      State initial_state()
      {
        State s;
        s.u      = Vec::Zero(n_);
        s.v_half = Vec::Zero(n_);
        s.f      = Vec::Zero(n_);
        if (!cdm_.initial_displacement.empty())
          s.u = Eigen::Map<const Vec>(cdm_.initial_displacement.data(), n_);
        Vec v0 = Vec::Zero(n_);
        if (!cdm_.initial_velocity.empty())
          v0 = Eigen::Map<const Vec>(cdm_.initial_velocity.data(), n_);
        if (model_.isolator())
        {
          s.iso = model_.isolator()->clone();
          s.iso->revert_to_start();
        }
        for (const ContactPair &c : model_.contacts())
        {
          s.laws.push_back(c.law->clone());
          s.laws.back()->revert_to_start();
        }
        // ü_0 from the linear part and the isolator at u_0 (contacts open at the start); the
        // half-step velocity v_{−1/2} = u̇_0 − (Δt/2)·ü_0 and u_{−1}, u_{−2} follow from it.
        Vec r = -mass_ * ground(0.0) - c_ * v0 - k_ * s.u;
        if (s.iso)
        {
          r(0) -= s.iso->set_trial(s.u(0), v0(0)).force;
          s.iso->revert_to_start();
        }
        const Vec a0 = r.cwiseQuotient(mass_);
        s.h_prev     = big_;
        s.h_prev2    = big_;
        s.v_half     = v0 - 0.5 * big_ * a0;
        const Vec u1 = s.u - big_ * s.v_half;
        const Vec u2 = u1 - big_ * s.v_half;
        s.iso_u1     = u1(0);
        s.iso_u2     = u2(0);
        s.iso_acc    = a0(0);
        s.cv_half    = c_ * s.v_half;
        set_rate_weights(s);
        const std::size_t nc = s.laws.size();
        s.dp.resize(nc);
        s.dpp.resize(nc);
        s.delta.assign(nc, 0.0);
        s.cf.assign(nc, 0.0);
        s.active.assign(nc, 0);
        for (std::size_t c = 0; c < nc; ++c) // permanent pairs: in contact from the start
          s.active[c] = s.laws[c]->in_contact() ? 1 : 0;
        s.closing.assign(nc, 0.0);
        s.rate_prev.assign(nc, 0.0);
        s.called.assign(nc, 1); // the virgin state is current: nothing to catch up
        for (std::size_t c = 0; c < nc; ++c)
        {
          s.dp[c]  = delta_of(model_.contacts()[c], u1);
          s.dpp[c] = delta_of(model_.contacts()[c], u2);
        }
        return s;
      }

      /// Rate of x at t_n from x_n, x_{n−1}, x_{n−2} and the steps h_{n−1}, h_{n−2}: the
      /// three-point (second-order) formula for unequal steps, whatever the options' law_velocity:
      /// the run aims at the Δt → 0 response, which both rates share, and the second-order one
      /// reaches it with fewer steps (the backward rate lags by h/2, a first-order error in the
      /// dashpot force of the laws).
      double rate(const State &s, const double x0, const double x1, const double x2) const
      {
        if constexpr (Fast)
        {
          const double s1 = (x0 - x1) * s.ih_prev;
          const double s2 = (x1 - x2) * s.ih_prev2;
          return s1 + s.w_rate * (s1 - s2);
        }
        const double s1 = (x0 - x1) / s.h_prev;
        const double s2 = (x1 - x2) / s.h_prev2;
        return s1 + s.h_prev / (s.h_prev + s.h_prev2) * (s1 - s2);
      }

      /// The reciprocal steps and the weight of rate() (fast path), after h_{n−1} changed.
      static void set_rate_weights(State &s)
      {
        s.ih_prev  = 1.0 / s.h_prev;
        s.ih_prev2 = 1.0 / s.h_prev2;
        s.w_rate   = s.h_prev / (s.h_prev + s.h_prev2);
      }

      /// Isolator and contact forces at t_n (explicit, trial + commit) into s.f.
      void forces(State &s, const bool record)
      {
        s.f.setZero();
        if (s.iso)
        {
          const double u0 = s.u(0);
          const double v0 = rate(s, u0, s.iso_u1, s.iso_u2);
          double       f  = 0.0;
          if (Fast && bilinear_)
          {
            // The final class: set_trial and commit inlined, no virtual call.
            auto &b = static_cast<BilinearIsolator &>(*s.iso);
            f       = b.set_trial(u0, v0).force;
            b.commit();
          }
          else
          {
            f = s.iso->set_trial(u0, v0).force;
            s.iso->commit();
          }
          if (record)
            rec_.isolator_force(f);
          s.f(0) += f;
          s.iso_rate = v0;
          s.iso_u2   = s.iso_u1;
          s.iso_u1   = u0;
        }
        for (std::size_t c = 0; c < s.laws.size(); ++c)
        {
          const ContactPair &cp    = model_.contacts()[c];
          const double       delta = delta_of(cp, s.u);
          const double       r     = rate(s, delta, s.dp[c], s.dpp[c]);
          ForceLaw          &law   = *s.laws[c];
          if constexpr (Fast)
          {
            // Open gap, out of contact, no force: every law returns zero here and its history
            // matters only from the next contact on (docs/architecture.md "Force laws"), so the
            // call is skipped; the work term 0.5·(0 + 0)·Δδ and the zero force change nothing.
            if (!(delta > 0.0) && !s.active[c] && s.cf[c] == 0.0)
            {
              s.called[c]    = 0;
              s.rate_prev[c] = r;
              s.delta[c]     = delta;
              s.dpp[c]       = s.dp[c];
              s.dp[c]        = delta;
              s.closing[c]   = (s.dp[c] - s.dpp[c]) * s.ih_prev;
              continue;
            }
            if (!s.called[c])
            {
              // The call of the last step, skipped: the law's state the reference path has.
              law.set_trial(s.dp[c], s.rate_prev[c]);
              law.commit();
            }
            s.called[c]    = 1;
            s.rate_prev[c] = r;
          }
          const double force = law.set_trial(delta, r).force;
          law.commit();
          const int now = law.in_contact() ? 1 : 0;
          if (record && now && !s.active[c])
            rec_.impact(c, s.t, r);
          s.active[c] = now;
          s.w_contact += 0.5 * (s.cf[c] + force) * (delta - s.dp[c]);
          s.cf[c]    = force;
          s.delta[c] = delta;
          s.dpp[c]   = s.dp[c];
          s.dp[c]    = delta;
          if constexpr (Fast)
            s.closing[c] = (s.dp[c] - s.dpp[c]) * s.ih_prev;
          if (record)
            rec_.contact_force(c, force, delta, s.t);
          if (cp.left_dof >= 0)
            s.f(cp.left_dof) += force;
          if (cp.right_dof >= 0)
            s.f(cp.right_dof) -= force;
        }
      }

      /// Closing rate of contact c at t_n (after forces()), m/s.
      double closing_rate(const State &s, const std::size_t c) const
      {
        if constexpr (Fast)
          return s.closing[c];
        return (s.dp[c] - s.dpp[c]) / s.h_prev;
      }

      /**
       * The step wanted at t_n (after forces()), the steps of the error estimate scaled by
       * `scale`: Δt_c while a contact is in contact, its gap closed or closing within
       * lookahead·Δt_large (and for `tail` after), Δt_a while a gap closes within the approach
       * time at its present rate, else Δt_large.
       */
      double target_step(State &s, const double scale) const
      {
        bool hot = false, near = false;
        for (std::size_t c = 0; c < s.laws.size(); ++c)
        {
          const double ahead = s.delta[c] + closing_rate(s, c) * opt_.lookahead * big_;
          hot  = hot || s.active[c] || s.delta[c] > 0.0 || s.cf[c] != 0.0 || ahead > 0.0;
          near = near || s.delta[c] + closing_rate(s, c) * opt_.approach_time > 0.0;
        }
        if (hot)
          s.tail_until = s.t + opt_.tail;
        if (hot || s.t < s.tail_until)
          return scale * fine_;
        return near ? std::min(big_, scale * approach_) : big_;
      }

      /**
       * `h`, shortened so that a step does not carry an open gap past closing (at its rate), and
       * for a stick-slip isolator (Isolator::stick_slip()) not past a reversal of its velocity
       * (at the last acceleration: the kink of the friction force is located within the step, as
       * a contact onset) and not beyond Δt_stick while it sticks.
       */
      double choose_step(const State &s, double h) const
      {
        if (stick_slip_)
        {
          if (s.iso->sticking())
            h = std::min(h, stick_);
          // Reversal of u̇_0 ahead at the last acceleration: end the step there (not below
          // Δt_large/16).
          const double v = s.iso_rate, acc = s.iso_acc;
          if (v * acc < 0.0 && std::abs(v) < std::abs(acc) * h)
            h = std::max(std::abs(v / acc), std::min(big_ / 16.0, h));
        }
        for (std::size_t c = 0; c < s.laws.size(); ++c)
        {
          if (s.active[c] || s.delta[c] > 0.0)
            continue;
          const double r = closing_rate(s, c);
          if (r > 0.0 && s.delta[c] + r * h > 0.0)
            h = std::max(-s.delta[c] / r, fine_ / 16.0);
        }
        return h;
      }

      /// A step h that ends on `remaining` when that is within two steps (no sliver steps).
      static double clip(const double h, const double remaining)
      {
        if (!(remaining > 0.0) || remaining > 2.001 * h) // k > 2 for sure: no division
          return h;
        const double k = std::ceil(remaining / h * (1.0 - 1e-12));
        return k <= 2.0 ? remaining / k : h;
      }

      /**
       * Inverse of a symmetric positive definite matrix (M/h̄ + w₊·C, M diagonal and positive, C
       * symmetric positive semi-definite) by Gauss-Jordan elimination without pivoting: the
       * effective matrix of every step size that is not in the cache (onsets located within a
       * step, the step growth after a window, the last step) costs ≈ 2N³ flops instead of a general
       * LU and N triangular solves.
       */
      static Mat spd_inverse(Mat a)
      {
        Mat inv = Mat::Identity();
        for (int k = 0; k < N; ++k)
        {
          const double p = 1.0 / a(k, k);
          a.row(k) *= p;
          inv.row(k) *= p;
          for (int i = 0; i < N; ++i)
            if (i != k && a(i, k) != 0.0)
            {
              const double f = a(i, k);
              a.row(i) -= f * a.row(k);
              inv.row(i) -= f * inv.row(k);
            }
        }
        return inv;
      }

      /// What the fast path needs of a step h after a step h_prev (cached).
      struct Factor
      {
        double h_prev = 0.0, h = 0.0;
        bool   valid = false;
        double ihbar = 0.0, wp = 0.0, wm = 0.0; ///< 1/h̄, w₊, w₋
        Mat    inv;                             ///< (M/h̄ + w₊·C)⁻¹
      };

      /// The Factor of (h_prev, h), from the cache of the last few.
      const Factor &factor(const double h_prev, const double h)
      {
        {
          const Factor &e = factors_[last_factor_];
          if (e.h_prev == h_prev && e.h == h && e.valid)
            return e;
        }
        for (std::size_t i = 0; i < factors_.size(); ++i)
        {
          const Factor &e = factors_[i];
          if (e.h_prev == h_prev && e.h == h && e.valid)
          {
            last_factor_ = i;
            return e;
          }
        }
        last_factor_      = next_factor_;
        next_factor_      = (next_factor_ + 1) % factors_.size();
        Factor      &e    = factors_[last_factor_];
        const double hbar = 0.5 * (h_prev + h);
        e.wp              = h_prev / (h_prev + h);
        e.wm              = h / (h_prev + h);
        e.ihbar           = 1.0 / hbar;
        Mat a             = e.wp * c_;
        a.diagonal() += mass_ / hbar;
        if constexpr (N == Eigen::Dynamic)
          e.inv = a.partialPivLu().inverse();
        else
          e.inv = spd_inverse(a);
        e.h_prev = h_prev;
        e.h      = h;
        e.valid  = true;
        return e;
      }

      const Eigen::PartialPivLU<Eigen::MatrixXd> &effective(const double hbar, const double wp)
      {
        for (auto &e : lu_cache_)
          if (e.hbar == hbar && e.wp == wp && e.valid)
            return e.lu;
        auto &e           = lu_cache_[next_lu_];
        next_lu_          = (next_lu_ + 1) % lu_cache_.size();
        Eigen::MatrixXd a = wp * c_;
        a.diagonal() += mass_ / hbar;
        e.lu.compute(a);
        e.hbar  = hbar;
        e.wp    = wp;
        e.valid = true;
        return e.lu;
      }

      /// One step h from t_n (forces at t_n in s.f): v_{n+1/2}, the record at t_n, u_{n+1}.
      void step(State       &s,
                const double h,
                const bool   record,
                WindowPeaks *peaks,
                const bool   sample,
                const bool   check,
                const bool   last = false)
      {
        const double ag = ground(s.t);
        Vec          v_plus, a, v, ku;
        double       p_visc = 0.0;
        ku.noalias()        = k_ * s.u;
        if constexpr (Fast)
        {
          // One cached entry per (h_{n−1}, h_n): (M/h̄ + w₊·C)⁻¹, 1/h̄ and the weights; C·v
          // carried from the last step, so three products per step (K·u, the inverse, C·v).
          const Factor &e = factor(s.h_prev, h);
          const Vec     rhs =
            mass_.cwiseProduct(s.v_half) * e.ihbar - e.wm * s.cv_half - mass_ * ag - ku - s.f;
          v_plus.noalias() = e.inv * rhs;
          Vec cv_plus;
          cv_plus.noalias() = c_ * v_plus;
          a                 = (v_plus - s.v_half) * e.ihbar;
          s.iso_acc         = a(0);
          v                 = e.wm * s.v_half + e.wp * v_plus;
          p_visc            = v.dot(e.wm * s.cv_half + e.wp * cv_plus);
          s.cv_half         = cv_plus;
        }
        else
        {
          const double hbar = 0.5 * (s.h_prev + h);
          const double wp   = s.h_prev / (s.h_prev + h);
          const double wm   = h / (s.h_prev + h);
          const Vec    rhs =
            mass_.cwiseProduct(s.v_half) / hbar - wm * (c_ * s.v_half) - mass_ * ag - ku - s.f;
          v_plus    = effective(hbar, wp).solve(rhs);
          a         = (v_plus - s.v_half) / hbar;
          s.iso_acc = a(0);
          v         = wm * s.v_half + wp * v_plus;
          p_visc    = v.dot(c_ * v);
        }
        const double p_in = -ag * mass_.dot(v);
        if (s.n > 0)
        {
          s.w_in += 0.5 * (s.p_in_prev + p_in) * s.h_prev;
          s.w_visc += 0.5 * (s.p_visc_prev + p_visc) * s.h_prev;
        }
        s.p_in_prev   = p_in;
        s.p_visc_prev = p_visc;
        if (!v_plus.allFinite())
        {
          std::ostringstream msg;
          msg << "variable-step central differences diverged at t = " << s.t << " s (step " << s.n
              << ", dt = " << h << " s)";
          throw DivergenceError(msg.str(), s.t, s.n, 0);
        }
        if (peaks)
        {
          for (std::size_t c = 0; c < s.cf.size(); ++c)
            peaks->force[c] = std::max(peaks->force[c], s.cf[c]);
          for (Eigen::Index i = 0; i < n_; ++i)
          {
            const auto q           = static_cast<std::size_t>(i);
            peaks->acceleration[q] = std::max(peaks->acceleration[q], std::abs(a(i) + ag));
            peaks->displacement[q] = std::max(peaks->displacement[q], std::abs(s.u(i)));
          }
        }
        if (record)
          record_step(s, a, v, ku, ag, h, sample, check, last);
        s.u += h * v_plus;
        const bool same_steps = h == s.h_prev && s.h_prev == s.h_prev2;
        s.v_half              = v_plus;
        s.h_prev2             = s.h_prev;
        s.h_prev              = h;
        if constexpr (Fast)
          if (!same_steps) // else the weights are those of the last step
            set_rate_weights(s);
      }

      /**
       * Peaks at t_n (every step), the energy balance at check steps, and the history rows due at
       * t_n: each sample time inside the last step (t_{n−1}, t_n) interpolated linearly between
       * the values at its ends (u is linear within a central-difference step; ü, the drifts, the
       * forces and the energies are interpolated likewise; the energy error is that of t_n), and
       * one at t_n itself when a sample time falls on it. The values at t_n are kept when the
       * next step h will contain a sample time.
       */
      void record_step(const State &s,
                       const Vec   &a,
                       const Vec   &v,
                       const Vec   &ku,
                       const double ag,
                       const double h,
                       const bool   sample,
                       const bool   check,
                       const bool   last)
      {
        Response &r = rec_.response();
        for (Eigen::Index i = 0; i < n_; ++i)
        {
          const auto q           = static_cast<std::size_t>(i);
          r.peak_displacement[q] = std::max(r.peak_displacement[q], std::abs(s.u(i)));
          r.peak_absolute_acceleration[q] =
            std::max(r.peak_absolute_acceleration[q], std::abs(a(i) + ag));
        }
        for (std::size_t q = 0; q < model_.storeys().size(); ++q)
          r.peak_interstorey_drift[q] =
            std::max(r.peak_interstorey_drift[q], std::abs(drift(s, model_.storeys()[q])));
        if (check)
        {
          EnergyBalance terms;
          terms.kinetic      = 0.5 * mass_.dot(v.cwiseProduct(v));
          terms.strain       = 0.5 * s.u.dot(ku) + (s.iso ? s.iso->stored_energy() : 0.0);
          terms.initial      = e0_;
          terms.input        = s.w_in;
          terms.viscous      = s.w_visc;
          terms.hysteretic   = s.iso ? s.iso->dissipated_energy() : 0.0;
          terms.contact_work = s.w_contact;
          rec_.supplied(e0_ + s.w_in);
          const double err = rec_.check_energy(terms);
          if (terms.kinetic + terms.strain >
              cdm_.divergence_energy_factor * std::max(rec_.max_supplied(), 1e-300))
          {
            std::ostringstream msg;
            msg << "variable-step central differences diverged at t = " << s.t
                << " s: E_kin + E_strain = " << terms.kinetic + terms.strain << " J exceeds "
                << cdm_.divergence_energy_factor << " x the energy supplied";
            throw DivergenceError(msg.str(), s.t, s.n, 0);
          }
          if (sample)
            emit_samples(s, a, ag, err, terms.hysteretic);
        }
        if (!last && next_sample_ < s.t + h - eps_)
          keep_left(s, a, ag);
      }

      /// Interstorey drift of storey @p st at the state @p s, m.
      static double drift(const State &s, const Storey &st)
      {
        return s.u(st.upper_dof) - (st.lower_dof >= 0 ? s.u(st.lower_dof) : 0.0);
      }

      /// The values at t_n of the rows interpolated inside the next step.
      void keep_left(const State &s, const Vec &a, const double ag)
      {
        left_.t = s.t;
        for (Eigen::Index i = 0; i < n_; ++i)
        {
          const auto q = static_cast<std::size_t>(i);
          left_.u[q]   = s.u(i);
          left_.a[q]   = a(i) + ag;
        }
        for (std::size_t q = 0; q < model_.storeys().size(); ++q)
          left_.drift[q] = drift(s, model_.storeys()[q]);
        std::copy(s.cf.begin(), s.cf.end(), left_.cf.begin());
        left_.isolator   = rec_.last_isolator_force();
        left_.hysteretic = s.iso ? s.iso->dissipated_energy() : 0.0;
        left_.input      = e0_ + s.w_in;
      }

      /// The rows of the sample times up to t_n (after the energy check at t_n).
      void emit_samples(const State &s,
                        const Vec   &a,
                        const double ag,
                        const double err,
                        const double hysteretic)
      {
        while (next_sample_ <= s.t + eps_)
        {
          const double ts = next_sample_;
          next_sample_    = static_cast<double>(++sample_k_) * interval_;
          if (ts >= s.t - eps_)
          {
            // On the step.
            rec_.sample(
              ts,
              [&](const std::size_t i) { return s.u(static_cast<Eigen::Index>(i)); },
              [&](const std::size_t i) { return a(static_cast<Eigen::Index>(i)) + ag; },
              [&](const std::size_t q) { return drift(s, model_.storeys()[q]); },
              s.cf,
              e0_ + s.w_in,
              err);
            continue;
          }
          // Inside the last step (t_{n−1}, t_n): linear between its ends.
          const double th  = (ts - left_.t) / (s.t - left_.t);
          const auto   mix = [th](const double x0, const double x1) { return x0 + th * (x1 - x0); };
          for (Eigen::Index i = 0; i < n_; ++i)
          {
            const auto q = static_cast<std::size_t>(i);
            row_.u[q]    = mix(left_.u[q], s.u(i));
            row_.a[q]    = mix(left_.a[q], a(i) + ag);
          }
          for (std::size_t q = 0; q < model_.storeys().size(); ++q)
            row_.drift[q] = mix(left_.drift[q], drift(s, model_.storeys()[q]));
          for (std::size_t c = 0; c < s.cf.size(); ++c)
            row_.cf[c] = mix(left_.cf[c], s.cf[c]);
          rec_.sample_row(ts,
                          row_.u.data(),
                          row_.a.data(),
                          row_.drift.data(),
                          row_.cf.data(),
                          mix(left_.isolator, rec_.last_isolator_force()),
                          mix(left_.hysteretic, hysteretic),
                          mix(left_.input, e0_ + s.w_in),
                          err);
        }
      }

      /// Re-run the window from `start` to `t_end` at 2·Δt_c and compare its peaks with `fine`.
      void close_window(const State &start, const WindowPeaks &fine, const double t_end)
      {
        State       z = start.copy();
        WindowPeaks coarse;
        coarse.reset(z.laws.size(), static_cast<std::size_t>(n_));
        const double eps   = 1e-6 * fine_;
        bool         first = true;
        while (z.t < t_end - eps)
        {
          if (!first)
            forces(z, false);
          first = false;
          double h =
            clip(choose_step(z, std::min(target_step(z, est_), 2.0 * z.h_prev)), t_end - z.t);
          step(z, h, false, &coarse, false, false);
          z.t += h;
          ++z.n;
          ++report_.estimate_steps;
        }
        const Response &r = rec_.response();
        // First order in Δt: P_h − P_0 ≈ (P_fh − P_h)/(f − 1) for the factor f of the re-run.
        const double f   = est_;
        const auto   rel = [f](const std::vector<double> &a,
                             const std::vector<double> &b,
                             const std::vector<double> &scale)
        {
          double e = 0.0;
          for (std::size_t i = 0; i < a.size(); ++i)
            if (scale[i] > 0.0)
              e = std::max(e, std::abs(a[i] - b[i]) / ((f - 1.0) * scale[i]));
          return e;
        };
        std::vector<double> force_scale(fine.force.size());
        for (std::size_t c = 0; c < force_scale.size(); ++c)
          force_scale[c] = std::max(fine.force[c], rec_peak_force(c));
        report_.force_error =
          std::max(report_.force_error, rel(fine.force, coarse.force, force_scale));
        report_.acceleration_error =
          std::max(report_.acceleration_error,
                   rel(fine.acceleration, coarse.acceleration, r.peak_absolute_acceleration));
        report_.displacement_error =
          std::max(report_.displacement_error,
                   rel(fine.displacement, coarse.displacement, r.peak_displacement));
      }

      double rec_peak_force(const std::size_t c) const
      {
        const ContactResult &cr = rec_.response().contacts[c];
        double               m  = 0.0;
        for (const double f : cr.pulse_force)
          m = std::max(m, f);
        return m;
      }


      struct CachedLu
      {
        double                               hbar  = 0.0;
        double                               wp    = 0.0;
        bool                                 valid = false;
        Eigen::PartialPivLU<Eigen::MatrixXd> lu;
      };

      const PoundingModel            &model_;
      const CentralDifferenceOptions &cdm_;
      const AdaptiveStepOptions      &opt_;
      const GroundMotion             &motion_;
      Eigen::Index                    n_;
      double                          big_, fine_, approach_, stick_;
      bool                            stick_slip_ = false; ///< Isolator::stick_slip()
      double                          est_;
      Vec                             mass_;
      Mat                             k_, c_;
      std::array<CachedLu, 4>         lu_cache_;
      std::size_t                     next_lu_ = 0;
      std::array<Factor, 8>           factors_;
      std::size_t                     last_factor_ = 0, next_factor_ = 0;
      /// A history row: the values at the start of the step that contains the next sample time
      /// (left_) and the row interpolated from them (row_).
      struct Row
      {
        double              t = 0.0;
        std::vector<double> u, a, drift, cf;
        double              isolator = 0.0, hysteretic = 0.0, input = 0.0;
      };
      Row                left_, row_;
      double             interval_      = 0.0;   ///< output_interval, s (0: none)
      double             next_sample_   = 0.0;   ///< time of the next history row, s
      long               sample_k_      = 0;     ///< its index
      double             eps_           = 0.0;   ///< time tolerance of the run, s
      bool               bilinear_      = false; ///< the isolator is a BilinearIsolator
      double             inv_record_dt_ = 0.0;   ///< 1/(the record's dt), 1/s
      double             e0_            = 0.0;
      ResponseRecorder   rec_;
      AdaptiveStepReport report_;
    };
  } // namespace

  std::string AdaptiveStepReport::text() const
  {
    std::ostringstream o;
    o.precision(4);
    o << "variable step: " << dt_large << " s, " << dt_approach << " s approaching, " << dt_contact
      << " s at contacts (" << windows << " windows, " << steps << " steps of which "
      << contact_steps_taken << " below the large step, +" << estimate_steps
      << " for the estimate); estimated errors: peak force " << 100.0 * force_error
      << " %, peak acceleration " << 100.0 * acceleration_error << " %, peak displacement "
      << 100.0 * displacement_error << " %";
    return o.str();
  }

  AdaptiveCentralDifference::AdaptiveCentralDifference(PoundingModel            model,
                                                       CentralDifferenceOptions cdm,
                                                       AdaptiveStepOptions      options)
    : model_(std::move(model))
    , cdm_(std::move(cdm))
    , options_(options)
  {
    if (cdm_.dt != 0.0)
      throw std::invalid_argument("variable-step central differences choose dt themselves "
                                  "(central_difference.dt must be 0)");
    const ParameterCheck check("adaptive ");
    check(options_.contact_steps >= 4.0, "contact_steps", options_.contact_steps, "must be >= 4");
    check(options_.lookahead >= 1.0, "lookahead", options_.lookahead, "must be >= 1");
    check(options_.approach_steps >= 4.0,
          "approach_steps",
          options_.approach_steps,
          "must be >= 4");
    check(options_.approach_time >= 0.0,
          "approach_time",
          options_.approach_time,
          "s",
          "must be >= 0");
    check(options_.structure_step > 0.0 && options_.structure_step <= 2.0,
          "structure_step",
          options_.structure_step,
          "must be in (0, 2]");
    check(options_.stick_step > 0.0 && options_.stick_step <= 2.0,
          "stick_step",
          options_.stick_step,
          "must be in (0, 2]");
    check(options_.estimate_factor >= 2.0,
          "estimate_factor",
          options_.estimate_factor,
          "must be >= 2");
    check(options_.tail >= 0.0, "tail", options_.tail, "s", "must be >= 0");
    // Validates the shared options and gives ω_structure, ω_closed and ω_imp.
    stability_     = CentralDifference(model_, cdm_).stability();
    double contact = std::numeric_limits<double>::infinity();
    if (stability_.omega_impact > 0.0)
      contact = pi / (options_.contact_steps * stability_.omega_impact);
    if (!model_.contacts().empty())
      contact = std::min(contact, cdm_.safety * stability_.dt_critical);
    dt_contact_ = contact;
    dt_approach_ =
      2.0 * pi / (options_.approach_steps * std::max(stability_.omega_structure, 1e-300));
  }

  double AdaptiveCentralDifference::large_step(const double record_dt) const
  {
    if (!(record_dt > 0.0 && std::isfinite(record_dt)))
      throw std::invalid_argument("ground motion dt = " + std::to_string(record_dt) +
                                  " s (must be > 0)");
    // The fixed step of `dt: stable` (safety·Δt_cr with every contact at its tangent), so that
    // the run costs that many steps away from contacts.
    CentralDifferenceOptions o = cdm_;
    o.dt                       = 0.0;
    const double stable        = CentralDifference(model_, o).time_step(record_dt);
    const double target = options_.structure_step / std::max(stability_.omega_structure, 1e-300);
    const double n_sub  = std::ceil(record_dt / target * (1.0 - 1e-12));
    return std::min(stable, record_dt / std::max(n_sub, 1.0));
  }

  Response AdaptiveCentralDifference::run(const GroundMotion  &motion,
                                          AdaptiveStepReport  *report,
                                          std::vector<double> *steps) const
  {
    if (steps)
      steps->clear();
    return run_with(motion, report, nullptr, steps);
  }

  Response AdaptiveCentralDifference::replay(const GroundMotion        &motion,
                                             const std::vector<double> &steps) const
  {
    return run_with(motion, nullptr, &steps, nullptr);
  }

  Response AdaptiveCentralDifference::run_with(const GroundMotion        &motion,
                                               AdaptiveStepReport        *report,
                                               const std::vector<double> *replay,
                                               std::vector<double>       *taken) const
  {
    if (!(motion.dt > 0.0) || motion.acceleration.empty())
      throw std::invalid_argument("ground motion '" + motion.name +
                                  "': dt must be > 0 and the record non-empty");
    StepSizes steps;
    steps.large    = large_step(motion.dt);
    steps.approach = std::min(steps.large / 3.0, dt_approach_);
    steps.contact  = std::min(steps.approach, dt_contact_);
    steps.stick =
      std::min(steps.large, options_.stick_step / std::max(stability_.omega_structure, 1e-300));
    const auto go = [&](auto &&run) { return run.run(report, replay, taken); };
    if (options_.reference_kernel)
      return go(AdaptiveRun<Eigen::Dynamic, false>(model_, cdm_, options_, motion, steps));
#define KIMP_ADAPTIVE_FIXED(n) \
  case n:                      \
    return go(AdaptiveRun<n, true>(model_, cdm_, options_, motion, steps));
    switch (model_.n_dofs())
    {
      KIMP_ADAPTIVE_FIXED(1)
      KIMP_ADAPTIVE_FIXED(2)
      KIMP_ADAPTIVE_FIXED(3)
      KIMP_ADAPTIVE_FIXED(4)
      KIMP_ADAPTIVE_FIXED(5)
      KIMP_ADAPTIVE_FIXED(6)
      KIMP_ADAPTIVE_FIXED(7)
      KIMP_ADAPTIVE_FIXED(8)
      default:
        return go(AdaptiveRun<Eigen::Dynamic, true>(model_, cdm_, options_, motion, steps));
    }
#undef KIMP_ADAPTIVE_FIXED
  }
} // namespace kimp::lumped
