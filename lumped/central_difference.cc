// Central difference method for pounding (thesis eq. 3.9-3.13): stability limit, time-step choice
// and the allocation-free time loop over the block-tridiagonal system.
#include "lumped/central_difference.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "lumped/bilinear_isolator.h"
#include "lumped/integration_errors.h"
#include "lumped/linear_isolator.h"

namespace kimp::lumped
{
  namespace
  {
    double largest_omega(const std::vector<double> &masses, const Eigen::MatrixXd &k)
    {
      const auto      n = static_cast<Eigen::Index>(masses.size());
      Eigen::VectorXd inv_sqrt_m(n);
      for (Eigen::Index i = 0; i < n; ++i)
        inv_sqrt_m(i) = 1.0 / std::sqrt(masses[static_cast<std::size_t>(i)]);
      const Eigen::MatrixXd a = inv_sqrt_m.asDiagonal() * k * inv_sqrt_m.asDiagonal();
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a, Eigen::EigenvaluesOnly);
      return std::sqrt(std::max(solver.eigenvalues().maxCoeff(), 0.0));
    }
  } // namespace

  StabilityLimit stability_limit(const PoundingModel &model, const double expected_max_penetration)
  {
    if (!(expected_max_penetration > 0.0))
    {
      std::ostringstream msg;
      msg << "expected_max_penetration = " << expected_max_penetration << " m (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
    StabilityLimit  s;
    Eigen::MatrixXd k = model.initial_stiffness_matrix();
    s.omega_structure = largest_omega(model.masses(), k);
    std::string impact_name;
    for (const ContactPair &c : model.contacts())
    {
      const double kt = c.law->initial_stiffness(expected_max_penetration);
      const double w  = std::sqrt(kt / c.effective_mass);
      if (w > s.omega_impact)
      {
        s.omega_impact = w;
        impact_name    = c.name;
      }
      if (c.left_dof >= 0)
        k(c.left_dof, c.left_dof) += kt;
      if (c.right_dof >= 0)
        k(c.right_dof, c.right_dof) += kt;
      if (c.left_dof >= 0 && c.right_dof >= 0)
      {
        k(c.left_dof, c.right_dof) -= kt;
        k(c.right_dof, c.left_dof) -= kt;
      }
    }
    s.omega_closed =
      model.contacts().empty() ? s.omega_structure : largest_omega(model.masses(), k);
    const double w_max = std::max({s.omega_structure, s.omega_closed, s.omega_impact});
    s.dt_critical      = 2.0 / w_max;
    std::ostringstream g;
    if (w_max == s.omega_impact && !impact_name.empty())
      g << "contact '" << impact_name << "': omega_imp = sqrt(k_t/m_eff) = " << s.omega_impact
        << " rad/s with k_t at a penetration of " << expected_max_penetration << " m";
    else if (w_max == s.omega_structure)
      g << "structure: omega_max = " << s.omega_structure << " rad/s";
    else
      g << "structure with all contacts closed: omega_max = " << s.omega_closed
        << " rad/s with k_t at a penetration of " << expected_max_penetration << " m";
    s.governing = g.str();
    return s;
  }

  CentralDifference::CentralDifference(PoundingModel model, CentralDifferenceOptions options)
    : model_(std::move(model))
    , options_(std::move(options))
  {
    const auto fail = [](const char *key, const double v, const char *rule)
    {
      std::ostringstream msg;
      msg << "central_difference." << key << " = " << v << " (" << rule << ')';
      throw std::invalid_argument(msg.str());
    };
    if (!(options_.dt >= 0.0 && std::isfinite(options_.dt)))
      fail("dt", options_.dt, "must be > 0 s, or 0 for auto");
    if (!(options_.safety > 0.0 && options_.safety <= 1.0))
      fail("safety", options_.safety, "must be in (0, 1]");
    if (!(options_.duration >= 0.0 && std::isfinite(options_.duration)))
      fail("duration", options_.duration, "must be >= 0 s (0: the record's length)");
    if (!(options_.output_interval >= 0.0 && std::isfinite(options_.output_interval)))
      fail("output_interval", options_.output_interval, "must be >= 0 s (0: no histories)");
    if (!(options_.divergence_energy_factor > 1.0))
      fail("divergence_energy_factor", options_.divergence_energy_factor, "must be > 1");
    const std::size_t n = model_.n_dofs();
    if (!options_.initial_displacement.empty() && options_.initial_displacement.size() != n)
      fail("initial_displacement.size",
           static_cast<double>(options_.initial_displacement.size()),
           "must be 0 or the number of DOFs");
    if (!options_.initial_velocity.empty() && options_.initial_velocity.size() != n)
      fail("initial_velocity.size",
           static_cast<double>(options_.initial_velocity.size()),
           "must be 0 or the number of DOFs");
    stability_ = stability_limit(model_, options_.expected_max_penetration);
  }

  double CentralDifference::time_step(const double record_dt) const
  {
    if (!(record_dt > 0.0 && std::isfinite(record_dt)))
    {
      std::ostringstream msg;
      msg << "ground motion dt = " << record_dt << " s (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
    if (options_.dt > 0.0)
    {
      if (options_.dt >= stability_.dt_critical)
      {
        std::ostringstream msg;
        msg << "time step dt = " << options_.dt
            << " s exceeds the stability limit of the central difference method dt_cr = "
               "2/omega_max = "
            << stability_.dt_critical << " s (governed by " << stability_.governing
            << "); use dt < " << stability_.dt_critical << " s or dt = auto";
        throw TimeStepError(msg.str(), options_.dt, stability_.dt_critical);
      }
      return options_.dt;
    }
    const double target = options_.safety * stability_.dt_critical;
    const double n_sub  = std::ceil(record_dt / target * (1.0 - 1e-12));
    return record_dt / std::max(n_sub, 1.0);
  }

  namespace
  {
    /**
     * Inverse of the constant effective matrix A = M/Δt² + C/(2Δt). A is block-tridiagonal with
     * one block per building (zero coupling between blocks, and between DOFs without damping
     * coupling). Small blocks keep their dense inverse: a matrix-vector product has a much shorter
     * dependency chain than the sequential Thomas sweeps, which matters because every step waits
     * for the previous one; blocks above `max_dense` DOFs use the pre-factorised Thomas algorithm.
     */
    class EffectiveMatrixInverse
    {
    public:
      static constexpr std::size_t max_dense = 16;

      explicit EffectiveMatrixInverse(const TridiagonalMatrix &a)
      {
        const std::size_t n     = a.size();
        std::size_t       first = 0;
        while (first < n)
        {
          std::size_t last = first;
          while (last + 1 < n && a.upper[last] != 0.0)
            ++last;
          Block b;
          b.first = first;
          b.size  = last - first + 1;
          TridiagonalMatrix sub(b.size);
          for (std::size_t i = 0; i < b.size; ++i)
            sub.diag[i] = a.diag[first + i];
          for (std::size_t i = 0; i + 1 < b.size; ++i)
            sub.upper[i] = a.upper[first + i];
          if (b.size <= max_dense)
          {
            const Eigen::MatrixXd inv = sub.to_dense().inverse();
            b.inverse.resize(b.size * b.size);
            // Column-major: y += A⁻¹(:, j)·x_j vectorises over the rows.
            for (std::size_t j = 0; j < b.size; ++j)
              for (std::size_t i = 0; i < b.size; ++i)
                b.inverse[j * b.size + i] =
                  inv(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
          }
          else
            b.thomas = TridiagonalSolver(sub);
          blocks_.push_back(std::move(b));
          first = last + 1;
        }
      }

      /// y = A⁻¹·x (x and y distinct).
      void apply(const double *x, double *y) const
      {
        for (const Block &b : blocks_)
        {
          const double     *xb = x + b.first;
          double           *yb = y + b.first;
          const std::size_t m  = b.size;
          if (!b.inverse.empty())
          {
            const double *col = b.inverse.data();
            for (std::size_t i = 0; i < m; ++i)
              yb[i] = col[i] * xb[0];
            for (std::size_t j = 1; j < m; ++j)
            {
              col += m;
              for (std::size_t i = 0; i < m; ++i)
                yb[i] += col[i] * xb[j];
            }
          }
          else
          {
            for (std::size_t i = 0; i < m; ++i)
              yb[i] = xb[i];
            b.thomas.solve_in_place(yb);
          }
        }
      }

    private:
      struct Block
      {
        std::size_t         first = 0;
        std::size_t         size  = 0;
        std::vector<double> inverse;
        TridiagonalSolver   thomas;
      };
      std::vector<Block> blocks_;
    };

    /// Everything the time loop touches, allocated once per run.
    struct Workspace
    {
      std::size_t n  = 0; ///< DOFs; displacement arrays have n + 1 entries, [n] = ground = 0
      double      dt = 0.0;

      std::vector<double>                     mass;
      std::vector<double>                     b_diag, b_upper; ///< 2M/Δt² − K
      std::vector<double>                     d_diag, d_upper; ///< −M/Δt² + C/(2Δt)
      std::unique_ptr<EffectiveMatrixInverse> a_inverse;       ///< (M/Δt² + C/(2Δt))⁻¹
      std::vector<double>      dense_inverse; ///< the same, dense column-major, for small fixed N
      std::vector<double>      dense_ab, dense_ad, dense_am; ///< A⁻¹B, A⁻¹D, A⁻¹M·1
      const TridiagonalMatrix *k = nullptr;
      const TridiagonalMatrix *c = nullptr;

      std::vector<double> buf[4];
      double             *u_prev2 = nullptr, *u_prev = nullptr, *u = nullptr, *u_next = nullptr;
      std::vector<double> force, rhs, velocity, accel;

      // contacts
      std::size_t                            n_contacts = 0;
      std::vector<std::unique_ptr<ForceLaw>> laws;
      std::vector<int>                       left, right;
      std::vector<double>                    gap, f, delta_prev, delta_prev2, peak_force;
      std::vector<int>                       active, called_prev;

      std::vector<int> storey_low, storey_up;
    };

    inline double law_rate(const LawVelocity scheme,
                           const double      x_n,
                           const double      x_nm1,
                           const double      x_nm2,
                           const double      inv_dt)
    {
      return scheme == LawVelocity::backward ? (x_n - x_nm1) * inv_dt :
                                               (3.0 * x_n - 4.0 * x_nm1 + x_nm2) * (0.5 * inv_dt);
    }

    /**
     * The time loop, instantiated per isolator type so that final classes are devirtualised, and
     * for the common sizes N of a single isolated building (3-5 storeys) so that every DOF loop
     * has a compile-time trip count (N = 0: run-time size).
     */
    template <class IsolatorType, int N>
    void time_loop(Workspace                      &w,
                   IsolatorType                   *iso,
                   const GroundMotion             &motion,
                   const CentralDifferenceOptions &opt,
                   const long                      n_steps,
                   Response                       &r)
    {
      const std::size_t n       = N > 0 ? static_cast<std::size_t>(N) : w.n;
      const double      dt      = w.dt;
      const double      inv_dt  = 1.0 / dt;
      const double      inv_dt2 = inv_dt * inv_dt;
      const std::size_t nc      = w.n_contacts;
      const std::size_t ns      = w.storey_low.size();
      const LawVelocity scheme  = opt.law_velocity;

      // Ground motion: integer sub-stepping when Δt divides the record's dt (the usual case).
      const double     *rec   = motion.acceleration.data();
      const std::size_t n_rec = motion.acceleration.size();
      const double      ratio = motion.dt / dt;
      const long        sub   = std::lround(ratio);
      const bool   integral = sub > 0 && std::abs(ratio - static_cast<double>(sub)) < 1e-9 * ratio;
      const double inv_sub  = 1.0 / static_cast<double>(sub > 0 ? sub : 1);
      std::size_t  rec_j    = 0;
      long         rec_s    = 0;

      const long every =
        opt.output_interval > 0.0 ? std::max(1L, std::lround(opt.output_interval / dt)) : 0L;
      if (every > 0)
      {
        const std::size_t n_samples = static_cast<std::size_t>(n_steps / every + 1);
        r.history.interval          = static_cast<double>(every) * dt;
        r.history.time.reserve(n_samples);
        r.history.displacement.reserve(n_samples * n);
        r.history.absolute_acceleration.reserve(n_samples * n);
        r.history.interstorey_drift.reserve(n_samples * ns);
        r.history.contact_force.reserve(n_samples * nc);
        r.history.energy_input.reserve(n_samples);
        r.history.energy_error.reserve(n_samples);
      }
      long until_sample = 0;

      double *const                 peak_u  = r.peak_displacement.data();
      double *const                 peak_a  = r.peak_absolute_acceleration.data();
      double *const                 peak_d  = r.peak_interstorey_drift.data();
      double *const                 peak_f  = w.peak_force.data();
      double *const                 f       = w.force.data();
      double *const                 rhs     = w.rhs.data();
      double *const                 v       = w.velocity.data();
      double *const                 a       = w.accel.data();
      double *const                 cf      = w.f.data();
      double *const                 dp      = w.delta_prev.data();
      double *const                 dpp     = w.delta_prev2.data();
      int *const                    active  = w.active.data();
      int *const                    called  = w.called_prev.data();
      const int *const              left    = w.left.data();
      const int *const              right   = w.right.data();
      const double *const           gap     = w.gap.data();
      const int *const              s_low   = w.storey_low.data();
      const int *const              s_up    = w.storey_up.data();
      const double *const           bd      = w.b_diag.data();
      const double *const           bu      = w.b_upper.data();
      const double *const           dd      = w.d_diag.data();
      const double *const           du      = w.d_upper.data();
      const double *const           m       = w.mass.data();
      const EffectiveMatrixInverse &a_inv   = *w.a_inverse;
      const double *const           a_dense = w.dense_inverse.data();
      const double *const           a_b     = w.dense_ab.data();
      const double *const           a_d     = w.dense_ad.data();
      const double *const           a_m     = w.dense_am.data();
      const double *const           kd      = w.k->diag.data();
      const double *const           ku      = w.k->upper.data();
      const double *const           cd      = w.c->diag.data();
      const double *const           cu      = w.c->upper.data();

      EnergyBalance &e    = r.energy;
      double         w_in = 0.0, w_visc = 0.0, w_contact = 0.0;
      double         p_in_prev = 0.0, p_visc_prev = 0.0;
      double         e0 = 0.0, max_supplied = 0.0, e_kin = 0.0, e_strain = 0.0;
      double         max_residual = 0.0;
      const double   factor       = opt.divergence_energy_factor;

      double *u = w.u, *up = w.u_prev, *upp = w.u_prev2, *un = w.u_next;
      for (long step = 0; step <= n_steps; ++step)
      {
        const double t = static_cast<double>(step) * dt;
        double       ag;
        {
          std::size_t j;
          double      frac;
          if (integral)
          {
            j    = rec_j;
            frac = static_cast<double>(rec_s) * inv_sub;
            if (++rec_s == sub)
            {
              rec_s = 0;
              ++rec_j;
            }
          }
          else
          {
            const double x = t / motion.dt;
            j              = static_cast<std::size_t>(x);
            frac           = x - static_cast<double>(j);
          }
          if (j + 1 < n_rec)
            ag = rec[j] + frac * (rec[j + 1] - rec[j]);
          else
            ag = (j + 1 == n_rec && frac == 0.0) ? rec[j] : 0.0;
        }

        for (std::size_t i = 0; i <= n; ++i)
          f[i] = 0.0;
        if (iso)
        {
          f[0] = iso->set_trial(u[0], law_rate(scheme, u[0], up[0], upp[0], inv_dt)).force;
          iso->commit();
        }
        for (std::size_t c = 0; c < nc; ++c)
        {
          const int    L     = left[c];
          const int    R     = right[c];
          const double delta = u[L] - u[R] - gap[c];
          double       force = 0.0;
          if (delta > 0.0 || active[c])
          {
            ForceLaw    &law  = *w.laws[c];
            const double rate = law_rate(scheme, delta, dp[c], dpp[c], inv_dt);
            if (!called[c])
            {
              // Bring the law to the last open state it skipped, so that its first
              // contact step starts from δ_{n−1} <= 0 (not from an older open state).
              law.set_trial(dp[c], (dp[c] - dpp[c]) * inv_dt);
              law.commit();
            }
            force = law.set_trial(delta, rate).force;
            law.commit();
            const int now_active = law.in_contact() ? 1 : 0;
            if (now_active && !active[c])
              r.contacts[c].impacts.push_back({t, rate});
            active[c] = now_active;
            called[c] = 1;
          }
          else
            called[c] = 0;
          // Contact work ∫F dδ, trapezoid between t_{n−1} and t_n.
          w_contact += 0.5 * (cf[c] + force) * (delta - dp[c]);
          cf[c]  = force;
          dpp[c] = dp[c];
          dp[c]  = delta;
          f[L] += force;
          f[R] -= force;
          peak_f[c] = std::max(peak_f[c], force);
        }

        if constexpr (N > 0)
        {
          // u_{n+1} = A⁻¹B·u_n + A⁻¹D·u_{n−1} − A⁻¹M1·ü_g − A⁻¹·f_nl: the first three terms do
          // not depend on the forces just evaluated, so only the (sparse) force term remains on
          // the step-to-step dependency chain. Accumulate in registers (un may alias the inputs
          // as far as the compiler knows).
          double acc[N > 0 ? N : 1];
          for (std::size_t i = 0; i < n; ++i)
            acc[i] = -a_m[i] * ag;
          for (std::size_t j = 0; j < n; ++j)
            for (std::size_t i = 0; i < n; ++i)
              acc[i] += a_b[j * n + i] * u[j] + a_d[j * n + i] * up[j];
          for (std::size_t j = 0; j < n; ++j)
            if (f[j] != 0.0)
              for (std::size_t i = 0; i < n; ++i)
                acc[i] -= a_dense[j * n + i] * f[j];
          for (std::size_t i = 0; i < n; ++i)
            un[i] = acc[i];
        }
        else
        {
          // (M/Δt² + C/(2Δt))·u_{n+1} = B·u_n + D·u_{n−1} − M·1·ü_g − f_nl.
          for (std::size_t i = 0; i < n; ++i)
            rhs[i] = bd[i] * u[i] + dd[i] * up[i] - m[i] * ag - f[i];
          for (std::size_t i = 0; i + 1 < n; ++i)
          {
            rhs[i] += bu[i] * u[i + 1] + du[i] * up[i + 1];
            rhs[i + 1] += bu[i] * u[i] + du[i] * up[i];
          }
          a_inv.apply(rhs, un);
        }

        // State at t_n: central velocity, the step's acceleration, energies, peaks.
        double mv = 0.0, mvv = 0.0, kuu = 0.0, cvv = 0.0;
        for (std::size_t i = 0; i < n; ++i)
        {
          const double vi = (un[i] - up[i]) * (0.5 * inv_dt);
          const double ai = (un[i] - 2.0 * u[i] + up[i]) * inv_dt2 + ag;
          v[i]            = vi;
          a[i]            = ai;
          mv += m[i] * vi;
          mvv += m[i] * vi * vi;
          kuu += kd[i] * u[i] * u[i];
          cvv += cd[i] * vi * vi;
          peak_u[i] = std::max(peak_u[i], std::abs(u[i]));
          peak_a[i] = std::max(peak_a[i], std::abs(ai));
        }
        for (std::size_t i = 0; i + 1 < n; ++i)
        {
          kuu += 2.0 * ku[i] * u[i] * u[i + 1];
          cvv += 2.0 * cu[i] * v[i] * v[i + 1];
        }
        for (std::size_t s = 0; s < ns; ++s)
          peak_d[s] = std::max(peak_d[s], std::abs(u[s_up[s]] - u[s_low[s]]));

        const double p_in   = -ag * mv;
        const double p_visc = cvv;
        e_kin               = 0.5 * mvv;
        e_strain            = 0.5 * kuu + (iso ? iso->stored_energy() : 0.0);
        if (step == 0)
          e0 = e_kin + e_strain;
        else
        {
          w_in += 0.5 * (p_in_prev + p_in) * dt;
          w_visc += 0.5 * (p_visc_prev + p_visc) * dt;
        }
        p_in_prev    = p_in;
        p_visc_prev  = p_visc;
        max_supplied = std::max(max_supplied, e0 + w_in);

        const bool sample = every > 0 && until_sample == 0;
        if (every > 0 && --until_sample < 0)
          until_sample = every - 1;
        if (sample || (step & 511) == 0 || step == n_steps)
        {
          e.initial      = e0;
          e.input        = w_in;
          e.kinetic      = e_kin;
          e.strain       = e_strain;
          e.viscous      = w_visc;
          e.hysteretic   = iso ? iso->dissipated_energy() : 0.0;
          e.contact_work = w_contact;
          // Relative to the largest energy supplied so far, so that the first steps (where
          // every term is tiny) do not dominate the maximum.
          const double residual = std::abs(
            e.residual_relative_error() * std::max(std::abs(e0) + std::abs(w_in),
                                                   e_kin + e_strain + std::abs(w_visc) +
                                                     std::abs(e.hysteretic) + std::abs(w_contact)));
          const double err = residual / std::max(max_supplied, 1e-300);
          max_residual     = std::max(max_residual, residual);
          for (std::size_t i = 0; i < n; ++i)
            if (!std::isfinite(un[i]))
            {
              std::ostringstream msg;
              msg << "central difference diverged: u[" << i << "] is not finite at t = " << t + dt
                  << " s (step " << step + 1 << ", dt = " << dt << " s)";
              throw DivergenceError(msg.str(), t + dt, step + 1, static_cast<int>(i));
            }
          if (e_kin + e_strain > factor * max_supplied && e_kin + e_strain > 1e-12)
          {
            std::size_t worst = 0;
            for (std::size_t i = 1; i < n; ++i)
              if (std::abs(v[i]) > std::abs(v[worst]))
                worst = i;
            std::ostringstream msg;
            msg << "central difference diverged: mechanical energy " << e_kin + e_strain
                << " J exceeds " << factor << " x the energy supplied (" << max_supplied
                << " J) at t = " << t << " s (step " << step << ", fastest DoF " << worst
                << ", dt = " << dt << " s)";
            throw DivergenceError(msg.str(), t, step, static_cast<int>(worst));
          }
          if (sample)
          {
            ResponseHistory &h = r.history;
            h.time.push_back(t);
            h.displacement.insert(h.displacement.end(), u, u + n);
            h.absolute_acceleration.insert(h.absolute_acceleration.end(), a, a + n);
            for (std::size_t s = 0; s < ns; ++s)
              h.interstorey_drift.push_back(u[s_up[s]] - u[s_low[s]]);
            h.contact_force.insert(h.contact_force.end(), cf, cf + nc);
            h.energy_input.push_back(e0 + w_in);
            h.energy_error.push_back(err);
          }
        }

        // Rotate the displacement levels (the ground slot [n] stays 0 in every buffer).
        double *const recycled = upp;
        upp                    = up;
        up                     = u;
        u                      = un;
        un                     = recycled;
      }
      e.relative_error     = e.residual_relative_error();
      e.max_relative_error = max_residual / std::max(max_supplied, 1e-300);
      for (std::size_t c = 0; c < nc; ++c)
        r.contacts[c].peak_force = peak_f[c];
    }
  } // namespace

  Response CentralDifference::run(const GroundMotion &motion) const
  {
    if (!(motion.dt > 0.0) || motion.acceleration.empty())
      throw std::invalid_argument("ground motion '" + motion.name +
                                  "': dt must be > 0 and the record non-empty");
    const double dt       = time_step(motion.dt);
    const double duration = options_.duration > 0.0 ?
                              options_.duration :
                              motion.dt * static_cast<double>(motion.acceleration.size());
    const long   n_steps  = std::lround(duration / dt);

    Workspace         w;
    const std::size_t n           = model_.n_dofs();
    w.n                           = n;
    w.dt                          = dt;
    w.mass                        = model_.masses();
    w.k                           = &model_.stiffness();
    w.c                           = &model_.damping();
    const double      inv_dt2     = 1.0 / (dt * dt);
    const double      half_inv_dt = 0.5 / dt;
    TridiagonalMatrix a(n);
    w.b_diag.resize(n);
    w.d_diag.resize(n);
    w.b_upper.resize(n > 0 ? n - 1 : 0);
    w.d_upper.resize(n > 0 ? n - 1 : 0);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double mi = w.mass[i];
      a.diag[i]       = mi * inv_dt2 + w.c->diag[i] * half_inv_dt;
      w.b_diag[i]     = 2.0 * mi * inv_dt2 - w.k->diag[i];
      w.d_diag[i]     = -mi * inv_dt2 + w.c->diag[i] * half_inv_dt;
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      a.upper[i]   = w.c->upper[i] * half_inv_dt;
      w.b_upper[i] = -w.k->upper[i];
      w.d_upper[i] = w.c->upper[i] * half_inv_dt;
    }
    w.a_inverse = std::make_unique<EffectiveMatrixInverse>(a);
    if (n <= EffectiveMatrixInverse::max_dense)
    {
      const Eigen::MatrixXd inv = a.to_dense().inverse();
      w.dense_inverse.assign(inv.data(), inv.data() + inv.size());
      TridiagonalMatrix b(n), d(n);
      b.diag                   = w.b_diag;
      b.upper                  = w.b_upper;
      d.diag                   = w.d_diag;
      d.upper                  = w.d_upper;
      const Eigen::MatrixXd ab = inv * b.to_dense();
      const Eigen::MatrixXd ad = inv * d.to_dense();
      const Eigen::VectorXd am =
        inv * Eigen::Map<const Eigen::VectorXd>(w.mass.data(), static_cast<Eigen::Index>(n));
      w.dense_ab.assign(ab.data(), ab.data() + ab.size());
      w.dense_ad.assign(ad.data(), ad.data() + ad.size());
      w.dense_am.assign(am.data(), am.data() + am.size());
    }
    for (auto &b : w.buf)
      b.assign(n + 1, 0.0);
    w.u_prev2 = w.buf[0].data();
    w.u_prev  = w.buf[1].data();
    w.u       = w.buf[2].data();
    w.u_next  = w.buf[3].data();
    w.force.assign(n + 1, 0.0); // [n]: the ground, absorbs wall reactions
    w.velocity.assign(n, 0.0);
    w.accel.assign(n, 0.0);
    w.rhs.assign(n, 0.0);

    const int ground_slot = static_cast<int>(n);
    w.n_contacts          = model_.contacts().size();
    Response r;
    r.dt        = dt;
    r.n_steps   = n_steps;
    r.duration  = static_cast<double>(n_steps) * dt;
    r.n_dofs    = n;
    r.n_storeys = model_.storeys().size();
    r.peak_displacement.assign(n, 0.0);
    r.peak_absolute_acceleration.assign(n, 0.0);
    r.peak_interstorey_drift.assign(r.n_storeys, 0.0);
    for (const ContactPair &c : model_.contacts())
    {
      std::unique_ptr<ForceLaw> law = c.law->clone();
      law->revert_to_start();
      w.laws.push_back(std::move(law));
      w.left.push_back(c.left_dof >= 0 ? c.left_dof : ground_slot);
      w.right.push_back(c.right_dof >= 0 ? c.right_dof : ground_slot);
      w.gap.push_back(c.gap);
      ContactResult cr;
      cr.name = c.name;
      r.contacts.push_back(std::move(cr));
    }
    w.f.assign(w.n_contacts, 0.0);
    w.active.assign(w.n_contacts, 0);
    w.called_prev.assign(w.n_contacts, 1);
    w.peak_force.assign(w.n_contacts, 0.0);
    for (const Storey &s : model_.storeys())
    {
      w.storey_low.push_back(s.lower_dof >= 0 ? s.lower_dof : ground_slot);
      w.storey_up.push_back(s.upper_dof);
    }

    std::unique_ptr<Isolator> iso;
    if (model_.isolator())
    {
      iso = model_.isolator()->clone();
      iso->revert_to_start();
    }

    // Initial conditions: u_{−1}, u_{−2} from a Taylor expansion with a_0 = M⁻¹(p_0 − C·v_0 −
    // K·u_0 − f_nl(u_0)); the laws are only trialled here, the loop commits at step 0.
    std::vector<double> u0(n, 0.0), v0(n, 0.0);
    if (!options_.initial_displacement.empty())
      u0 = options_.initial_displacement;
    if (!options_.initial_velocity.empty())
      v0 = options_.initial_velocity;
    std::vector<double> f0(n + 1, 0.0), cv(n), ku(n);
    if (iso)
    {
      f0[0] += iso->set_trial(u0[0], v0[0]).force;
      iso->revert_to_last_commit();
    }
    std::vector<double> u0g = u0;
    u0g.push_back(0.0);
    std::vector<double> v0g = v0;
    v0g.push_back(0.0);
    for (std::size_t c = 0; c < w.n_contacts; ++c)
    {
      const double delta = u0g[static_cast<std::size_t>(w.left[c])] -
                           u0g[static_cast<std::size_t>(w.right[c])] - w.gap[c];
      const double rate =
        v0g[static_cast<std::size_t>(w.left[c])] - v0g[static_cast<std::size_t>(w.right[c])];
      w.delta_prev.push_back(delta - dt * rate);
      w.delta_prev2.push_back(delta - 2.0 * dt * rate);
      if (delta > 0.0)
      {
        const double force = w.laws[c]->set_trial(delta, rate).force;
        w.laws[c]->revert_to_last_commit();
        f0[static_cast<std::size_t>(w.left[c])] += force;
        f0[static_cast<std::size_t>(w.right[c])] -= force;
      }
    }
    w.c->multiply(v0.data(), cv.data());
    w.k->multiply(u0.data(), ku.data());
    const double ag0 = motion.acceleration[0];
    for (std::size_t i = 0; i < n; ++i)
    {
      const double a0 = (-w.mass[i] * ag0 - cv[i] - ku[i] - f0[i]) / w.mass[i];
      w.u[i]          = u0[i];
      w.u_prev[i]     = u0[i] - dt * v0[i] + 0.5 * dt * dt * a0;
      w.u_prev2[i]    = u0[i] - 2.0 * dt * v0[i] + 2.0 * dt * dt * a0;
    }

    Isolator *raw = iso.get();
    if (auto *b = dynamic_cast<BilinearIsolator *>(raw))
      switch (n)
      {
        case 4:
          time_loop<BilinearIsolator, 4>(w, b, motion, options_, n_steps, r);
          break;
        case 5:
          time_loop<BilinearIsolator, 5>(w, b, motion, options_, n_steps, r);
          break;
        case 6:
          time_loop<BilinearIsolator, 6>(w, b, motion, options_, n_steps, r);
          break;
        default:
          time_loop<BilinearIsolator, 0>(w, b, motion, options_, n_steps, r);
      }
    else if (auto *l = dynamic_cast<LinearIsolator *>(raw))
      time_loop<LinearIsolator, 0>(w, l, motion, options_, n_steps, r);
    else
      time_loop<Isolator, 0>(w, raw, motion, options_, n_steps, r);

    for (std::size_t c = 0; c < w.n_contacts; ++c)
    {
      r.contacts[c].permanent_indentation = w.laws[c]->permanent_indentation();
      r.contacts[c].dissipated_energy     = w.laws[c]->dissipated_energy();
      r.energy.impact_dissipated += r.contacts[c].dissipated_energy;
    }
    return r;
  }
} // namespace kimp::lumped
