// Impact-stiffness fitter: lumped two-body model vs FEM force history, Levenberg-Marquardt
// (Eigen unsupported module, MINPACK lmder) with a central-difference Jacobian, and the
// confidence intervals of the fitted parameters. The contact window of the history is found in
// contact_window.cc; the units, standard variants and level uncertainty are in fit_results.cc.
#include "fit/fitter.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <unsupported/Eigen/LevenbergMarquardt>
#include <utility>

#include "fit/contact_window.h"
#include "lumped/laws/law_traits.h"

namespace kimp::fit
{
  using detail::check_history;
  using detail::ContactWindow;
  using detail::find_contact_window;
  using detail::interpolate;

  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// "a, b and c": the names of the laws the fitter takes (`free_exponent`: of those whose
    /// exponent it can fit).
    std::string fittable_law_names(bool free_exponent = false)
    {
      std::vector<std::string> names;
      for (const lumped::LawTraits &t : lumped::law_traits())
        if (t.fittable && (!free_exponent || !t.fixed_exponent()))
          names.emplace_back(t.name);
      std::string text;
      for (std::size_t i = 0; i < names.size(); ++i)
        text += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
      return text;
    }

    std::string free_exponent_law_names()
    {
      return fittable_law_names(true);
    }

    double default_exponent(const lumped::ForceLawSpec &law)
    {
      return lumped::law_traits(law.law, "fit").exponent(law.exponent);
    }

    /// z with Φ(z) = p for p in (0.5, 1) (bisection on erfc; Φ(z) = ½·erfc(−z/√2)).
    double normal_quantile(double p)
    {
      double low = 0.0, high = 40.0;
      for (int i = 0; i < 200; ++i)
      {
        const double mid = 0.5 * (low + high);
        if (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p)
          low = mid;
        else
          high = mid;
      }
      return 0.5 * (low + high);
    }

    double logistic(double x)
    {
      return 1.0 / (1.0 + std::exp(-x));
    }

    /// Law parameters in physical units (the optimiser works on ln k, logit COR, ln(n − 1)).
    struct Parameters
    {
      double stiffness = 0.0;
      double cor       = 0.0;
      double exponent  = 1.0;
    };

    /// The lumped model and the misfit; operator() and df() for Eigen's LevenbergMarquardt.
    class Misfit : public Eigen::DenseFunctor<double>
    {
    public:
      Misfit(const ForceHistory         &history,
             const ContactWindow        &window,
             double                      mass,
             double                      impact_velocity,
             const lumped::ForceLawSpec &law,
             const FitOptions           &options,
             const Parameters           &start,
             int                         n_parameters,
             int                         n_residuals)
        : Eigen::DenseFunctor<double>(n_parameters, n_residuals)
        , law_(law)
        , options_(options)
        , mass_(mass)
        , velocity_(impact_velocity)
        , start_(start)
      {
        const std::size_t n = window.last - window.first + 1;
        for (std::size_t j = window.first; j <= window.last; ++j)
        {
          tau_.push_back(history.time[j] - window.start);
          force_.push_back(history.force[j]);
        }
        std::vector<double> weight(n, 0.0);
        for (std::size_t j = 0; j < n; ++j)
        {
          const double left  = j > 0 ? tau_[j] - tau_[j - 1] : 0.0;
          const double right = j + 1 < n ? tau_[j + 1] - tau_[j] : 0.0;
          weight[j]          = 0.5 * (left + right);
        }
        double total = 0.0;
        for (const double w : weight)
          total += w;
        for (const double w : weight)
          sqrt_weight_.push_back(std::sqrt(w / total));
        force_scale_ = window.peak_force;

        if (options.displacement_weight > 0.0)
        {
          const double u0 = interpolate(history.time, history.slab_displacement, window.start);
          for (std::size_t j = window.first; j <= window.last; ++j)
          {
            displacement_.push_back(history.slab_displacement[j] - u0);
            displacement_scale_ = std::max(displacement_scale_, std::abs(displacement_.back()));
          }
          if (!(displacement_scale_ > 0.0))
            throw FitError("force history: slab displacement does not change over the contact");
        }
        const double wall = options.wall_mass;
        effective_mass_   = std::isinf(wall) ? mass : mass * wall / (mass + wall);
      }

      double effective_mass() const { return effective_mass_; }

      Parameters parameters(const Eigen::VectorXd &x) const
      {
        Parameters p = start_;
        int        i = 0;
        p.stiffness  = start_.stiffness * std::exp(x[i++]);
        if (options_.fit_cor)
          p.cor = logistic(x[i++]);
        if (options_.fit_exponent)
          p.exponent = 1.0 + std::exp(x[i++]);
        return p;
      }

      /// Simulate the model with parameters p; fills the model force (and displacement) at the
      /// misfit samples. Returns the two-body result.
      lumped::TwoBodyResult simulate(const Parameters    &p,
                                     std::vector<double> &force,
                                     std::vector<double> &displacement) const
      {
        lumped::ForceLawSpec spec = law_;
        spec.stiffness            = p.stiffness;
        spec.cor                  = p.cor;
        spec.effective_mass       = effective_mass_;
        if (!lumped::law_traits(law_.law).fixed_exponent())
          spec.exponent = p.exponent;
        const auto law = lumped::make_force_law(spec);

        const double n = p.exponent;
        const double v = velocity_;
        const double delta_c =
          std::pow((n + 1.0) * effective_mass_ * v * v / (2.0 * p.stiffness), 1.0 / (n + 1.0));
        lumped::TwoBodySetup setup;
        setup.mass_1            = mass_;
        setup.mass_2            = options_.wall_mass;
        setup.velocity_1        = v;
        setup.velocity_2        = 0.0;
        setup.time_step         = delta_c / v / static_cast<double>(options_.steps_per_time_scale);
        setup.velocity_estimate = options_.velocity_estimate;
        setup.record_history    = true;
        setup.max_steps         = 100 * options_.steps_per_time_scale;
        lumped::TwoBodyResult result = lumped::simulate_two_body(*law, setup);

        const auto &h = result.history;
        const auto  m = h.time.size();
        if (m < 3)
          throw FitError("model contact shorter than three steps");
        // Contact samples 0..b; sample b + 1 is the first open one (simulate_two_body's record).
        const std::size_t b  = m - 2;
        const double      dt = setup.time_step;
        const double      f0 = std::clamp(h.force[0] - (h.force[1] - h.force[0]) * h.time[0] / dt,
                                     0.0,
                                     std::max(h.force[0], 0.0));
        double            t_sep = h.time[b + 1], f_sep = 0.0;
        if (h.deformation[b] > 0.0 && h.deformation[b + 1] <= 0.0)
        {
          t_sep = h.time[b] + dt * h.deformation[b] / (h.deformation[b] - h.deformation[b + 1]);
          f_sep = h.force[b] + (h.force[b] - h.force[b - 1]) / dt * (t_sep - h.time[b]);
          if (f_sep * h.force[b] < 0.0)
            f_sep = 0.0;
        }
        model_time_.assign(1, 0.0);
        model_force_.assign(1, f0);
        for (std::size_t i = 0; i <= b; ++i)
          if (h.time[i] > model_time_.back())
          {
            model_time_.push_back(h.time[i]);
            model_force_.push_back(h.force[i]);
          }
        if (t_sep > model_time_.back())
        {
          model_time_.push_back(t_sep);
          model_force_.push_back(f_sep);
        }
        contact_end_ = model_time_.back();

        force.resize(tau_.size());
        const double half = 0.5 * jump_width_;
        for (std::size_t j = 0; j < tau_.size(); ++j)
        {
          const double t = tau_[j];
          if (t <= 0.0 || t > contact_end_ + half)
            force[j] = 0.0;
          else
          {
            force[j] = interpolate(model_time_, model_force_, std::min(t, contact_end_));
            if (t > contact_end_ - half)
              force[j] *= (contact_end_ + half - t) / jump_width_;
          }
        }

        if (!displacement_.empty())
        {
          // u1 = v_cm·t + m2/(m1 + m2)·δ; after the last record δ moves at the final velocity.
          const bool   wall     = std::isinf(options_.wall_mass);
          const double v_cm     = wall ? 0.0 : mass_ * v / (mass_ + options_.wall_mass);
          const double share    = wall ? 1.0 : options_.wall_mass / (mass_ + options_.wall_mass);
          const double v_after  = result.velocity_1_after - result.velocity_2_after;
          std::vector<double> t = {0.0}, d = {0.0};
          for (std::size_t i = 0; i < m; ++i)
            if (h.time[i] > t.back())
            {
              t.push_back(h.time[i]);
              d.push_back(h.deformation[i]);
            }
          displacement.resize(tau_.size());
          for (std::size_t j = 0; j < tau_.size(); ++j)
          {
            const double tj    = tau_[j];
            const double delta = tj <= 0.0      ? v * tj :
                                 tj <= t.back() ? interpolate(t, d, tj) :
                                                  d.back() + v_after * (tj - t.back());
            displacement[j]    = v_cm * tj + share * delta;
          }
        }
        return result;
      }

      double model_contact_end() const { return contact_end_; }

      /// ∫F dt of the last simulated contact (trapezoids), N·s/m.
      double model_impulse() const
      {
        double impulse = 0.0;
        for (std::size_t i = 1; i < model_time_.size(); ++i)
          impulse +=
            0.5 * (model_force_[i] + model_force_[i - 1]) * (model_time_[i] - model_time_[i - 1]);
        return impulse;
      }

      /// Width (s) over which the force drop at the model's separation is spread; 0: a jump.
      void set_jump_width(double width) const { jump_width_ = width; }

      /// Residuals: force misfit (and displacement misfit) weighted so that Σr² is the time-mean
      /// of the squared normalised misfit.
      int operator()(const Eigen::VectorXd &x, Eigen::VectorXd &r) const
      {
        ++n_evaluations_;
        const std::size_t n = tau_.size();
        r.resize(values());
        try
        {
          simulate(parameters(x), model_, model_displacement_);
        }
        catch (const std::exception &)
        {
          // Parameters the law or the integrator refuses: a large, flat misfit makes LM reject
          // the step and shorten it.
          r.setConstant(1.0e3);
          return 0;
        }
        for (std::size_t j = 0; j < n; ++j)
          r[static_cast<Eigen::Index>(j)] =
            sqrt_weight_[j] * (model_[j] - force_[j]) / force_scale_;
        if (!displacement_.empty())
        {
          const double w = std::sqrt(options_.displacement_weight);
          for (std::size_t j = 0; j < n; ++j)
            r[static_cast<Eigen::Index>(n + j)] = w * sqrt_weight_[j] *
                                                  (model_displacement_[j] - displacement_[j]) /
                                                  displacement_scale_;
        }
        return 0;
      }

      /// Central differences; steps in x: the model is self-similar in k (smooth, small step),
      /// while COR and n change the discrete contact length (a larger step averages that out).
      int df(const Eigen::VectorXd &x, Eigen::MatrixXd &jacobian) const
      {
        jacobian.resize(values(), inputs());
        Eigen::VectorXd plus(values()), minus(values());
        for (int i = 0; i < inputs(); ++i)
        {
          const double    h  = i == 0 ? 1.0e-6 : 1.0e-4;
          Eigen::VectorXd xp = x, xm = x;
          xp[i] += h;
          xm[i] -= h;
          (*this)(xp, plus);
          (*this)(xm, minus);
          jacobian.col(i) = (plus - minus) / (2.0 * h);
        }
        return 0;
      }

      int n_evaluations() const { return n_evaluations_; }

    private:
      lumped::ForceLawSpec law_;
      FitOptions           options_;
      double               mass_;
      double               velocity_;
      double               effective_mass_ = 0.0;
      Parameters           start_;
      std::vector<double>  tau_, force_, sqrt_weight_, displacement_;
      double               force_scale_        = 1.0;
      double               displacement_scale_ = 0.0;

      mutable std::vector<double> model_, model_displacement_, model_time_, model_force_;
      mutable double              contact_end_   = 0.0;
      mutable double              jump_width_    = 0.0;
      mutable int                 n_evaluations_ = 0;
    };

    using S = Eigen::LevenbergMarquardtSpace::Status;

    /// A status of Eigen's Levenberg-Marquardt: whether it counts as converged, and its text.
    struct StatusInfo
    {
      S           status;
      bool        converged;
      const char *text;
    };

    constexpr StatusInfo status_table[] = {
      {S::NotStarted, false, "not started"},
      {S::Running, false, "running"},
      {S::ImproperInputParameters, false, "improper input parameters"},
      {S::RelativeReductionTooSmall,
       true,
       "converged: relative reduction of the misfit below ftol"},
      {S::RelativeErrorTooSmall, true, "converged: relative change of the parameters below xtol"},
      {S::RelativeErrorAndReductionTooSmall,
       true,
       "converged: misfit reduction and parameter change below tolerance"},
      {S::CosinusTooSmall, true, "converged: residual orthogonal to the Jacobian"},
      {S::TooManyFunctionEvaluation, false, "too many function evaluations"},
      {S::FtolTooSmall,
       true,
       "converged to machine precision: no further misfit reduction possible"},
      {S::XtolTooSmall,
       true,
       "converged to machine precision: no further parameter improvement possible"},
      {S::GtolTooSmall,
       true,
       "converged to machine precision: residual orthogonal to the Jacobian"},
      {S::UserAsked, false, "stopped by the model"},
    };

    const StatusInfo *status_info(S status)
    {
      for (const StatusInfo &info : status_table)
        if (info.status == status)
          return &info;
      return nullptr;
    }

    std::string status_text(S status)
    {
      const StatusInfo *info = status_info(status);
      return info != nullptr ? info->text : "unknown status";
    }

    bool converged(S status)
    {
      const StatusInfo *info = status_info(status);
      return info != nullptr && info->converged;
    }

    void validate(double                      mass,
                  double                      impact_velocity,
                  const lumped::ForceLawSpec &law,
                  const FitOptions           &o)
    {
      const auto fail = [](const std::string &what)
      { throw std::invalid_argument("fit: " + what); };
      if (!(std::isfinite(mass) && mass > 0.0))
        fail(fmt::format("mass = {} kg/m (must be > 0 and finite)", mass));
      if (!(std::isfinite(impact_velocity) && impact_velocity > 0.0))
        fail(fmt::format("impact_velocity = {} m/s (must be > 0 and finite)", impact_velocity));
      const lumped::LawTraits *traits = lumped::find_law_traits(law.law);
      if (traits == nullptr || !traits->fittable)
        fail(fmt::format("law = '{}' (must be one of {})", law.law, fittable_law_names()));
      if (o.fit_exponent && traits->fixed_exponent())
        fail(fmt::format("fit_exponent = true with law '{}' (only {} have a free exponent)",
                         law.law,
                         free_exponent_law_names()));
      if (o.fit_cor && !traits->uses_cor())
        fail(fmt::format("fit_cor = true with law '{}' (it has no COR)", law.law));
      if (!(law.cor > 0.0 && law.cor <= 1.0))
        fail(fmt::format("cor = {} (must be in (0, 1])", law.cor));
      if (!(o.displacement_weight >= 0.0 && std::isfinite(o.displacement_weight)))
        fail(fmt::format("displacement_weight = {} (must be >= 0)", o.displacement_weight));
      if (!(o.wall_mass > 0.0))
        fail(fmt::format("wall_mass = {} kg/m (must be > 0, or infinity for a fixed wall)",
                         o.wall_mass));
      if (o.steps_per_time_scale < 20)
        fail(fmt::format("steps_per_time_scale = {} (must be >= 20)", o.steps_per_time_scale));
      if (!(o.contact_threshold > 0.0 && o.contact_threshold < 1.0))
        fail(fmt::format("contact_threshold = {} (must be in (0, 1))", o.contact_threshold));
      if (!(o.separation_fraction > 0.0))
        fail(fmt::format("separation_fraction = {} (must be > 0)", o.separation_fraction));
      if (!(o.tail_fraction >= 0.0))
        fail(fmt::format("tail_fraction = {} (must be >= 0)", o.tail_fraction));
      if (!(o.confidence > 0.0 && o.confidence < 1.0))
        fail(fmt::format("confidence = {} (must be in (0, 1))", o.confidence));
      if (o.initial_stiffness &&
          !(*o.initial_stiffness > 0.0 && std::isfinite(*o.initial_stiffness)))
        fail(fmt::format("initial_stiffness = {} (must be > 0)", *o.initial_stiffness));
      if (!(o.tolerance > 0.0))
        fail(fmt::format("tolerance = {} (must be > 0)", o.tolerance));
      if (o.max_function_evaluations < 10)
        fail(
          fmt::format("max_function_evaluations = {} (must be >= 10)", o.max_function_evaluations));
    }

    /// Physically based start: the linear oscillator's contact duration π·sqrt(m/k) and the
    /// energy balance ½·m·v² = F_peak·δ_max/(n + 1); the impulse m·v·(1 + COR) gives the COR.
    Parameters start_parameters(const ContactWindow        &window,
                                double                      mass,
                                double                      v,
                                const lumped::ForceLawSpec &law,
                                const FitOptions           &options)
    {
      const double wall  = options.wall_mass;
      const double m_eff = std::isinf(wall) ? mass : mass * wall / (mass + wall);
      const double dur   = window.separation - window.start;
      Parameters   start;
      start.exponent = default_exponent(law);
      if (options.fit_exponent)
        start.exponent = std::max(start.exponent, 1.05);
      start.cor =
        options.fit_cor ? std::clamp(window.impulse / (m_eff * v) - 1.0, 0.05, 0.95) : law.cor;
      const double delta_max = (start.exponent + 1.0) * m_eff * v * v / (2.0 * window.peak_force);
      double       k0        = window.peak_force / std::pow(delta_max, start.exponent);
      if (start.exponent == 1.0 && dur > 0.0)
        k0 = std::sqrt(k0 * m_eff * (pi / dur) * (pi / dur));
      start.stiffness = options.initial_stiffness.value_or(k0);
      return start;
    }

    /// Levenberg-Marquardt from `x` in two stages, adding the Jacobian evaluations to
    /// `iterations`. Sampled at points, a law whose force drops abruptly at separation
    /// (Kelvin-Voigt's tension) gives a misfit that jumps whenever the drop crosses a sample, and
    /// LM can stall one sample short of the optimum, or in a ripple of local minima when the data
    /// jump too. Stage 1 spreads the drop over eight sample intervals `spacing` (a smooth misfit
    /// whose optimum puts the drop where the data drop, by symmetry), stage 2 restores the jump
    /// starting from there.
    Eigen::LevenbergMarquardtSpace::Status minimise(Misfit           &misfit,
                                                    Eigen::VectorXd  &x,
                                                    double            spacing,
                                                    const FitOptions &options,
                                                    int              &iterations)
    {
      Eigen::LevenbergMarquardtSpace::Status status = Eigen::LevenbergMarquardtSpace::NotStarted;
      for (const double width : {8.0 * spacing, 0.0})
      {
        misfit.set_jump_width(width);
        Eigen::LevenbergMarquardt<Misfit> lm(misfit);
        // On the sampled misfit LM can only creep along the steps once the smooth optimum is
        // reached; a looser tolerance there stops it without losing the exact-data optimum.
        const double tolerance =
          width > 0.0 ? options.tolerance : std::max(options.tolerance, 1.0e-6);
        lm.setFtol(tolerance);
        lm.setXtol(tolerance);
        lm.setMaxfev(static_cast<Eigen::Index>(options.max_function_evaluations));
        status = lm.minimize(x);
        iterations += static_cast<int>(lm.njev());
        if (!converged(status))
          break;
      }
      return status;
    }

    /// The fitted k, COR and n of `result` with their confidence intervals, linearised at the
    /// optimum `x` (residuals `r`, `jacobian`; `start` scales k), and the misfit's RMS parts.
    void set_fitted_parameters(FitResult             &result,
                               const Parameters      &p,
                               const Parameters      &start,
                               const Eigen::VectorXd &x,
                               const Eigen::VectorXd &r,
                               const Eigen::MatrixXd &jacobian,
                               int                    n_samples,
                               const FitOptions      &options)
    {
      const auto                              n_parameters = static_cast<int>(x.size());
      const auto                              n_residuals  = static_cast<int>(r.size());
      const double                            z = normal_quantile(0.5 * (1.0 + options.confidence));
      const double                            s2 = r.squaredNorm() / (n_residuals - n_parameters);
      const Eigen::MatrixXd                   normal = jacobian.transpose() * jacobian;
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(normal);
      Eigen::VectorXd                         sigma(n_parameters);
      if (lu.rank() == n_parameters)
        sigma = (s2 * lu.inverse()).diagonal().cwiseMax(0.0).cwiseSqrt();
      else
      {
        sigma.setConstant(std::numeric_limits<double>::infinity());
        result.status += " (Jacobian rank-deficient: confidence intervals unbounded)";
      }

      int i                   = 0;
      result.stiffness.value  = p.stiffness;
      result.stiffness.lower  = start.stiffness * std::exp(x[i] - z * sigma[i]);
      result.stiffness.upper  = start.stiffness * std::exp(x[i] + z * sigma[i]);
      result.stiffness.fitted = true;
      ++i;
      result.cor = {p.cor, p.cor, p.cor, false};
      if (options.fit_cor)
      {
        result.cor = {p.cor, logistic(x[i] - z * sigma[i]), logistic(x[i] + z * sigma[i]), true};
        ++i;
      }
      result.exponent = {p.exponent, p.exponent, p.exponent, false};
      if (options.fit_exponent && p.exponent - 1.0 < 1.0e-3)
        result.status += " (n at its lower bound 1: the data are not Hertz-like)";
      if (options.fit_exponent)
        result.exponent = {p.exponent,
                           1.0 + std::exp(x[i] - z * sigma[i]),
                           1.0 + std::exp(x[i] + z * sigma[i]),
                           true};

      // Time-RMS of each misfit part (Σ of the weighted squares is the time mean).
      double force_sq = 0.0, displacement_sq = 0.0;
      for (int j = 0; j < n_samples; ++j)
        force_sq += r[j] * r[j];
      for (int j = n_samples; j < n_residuals; ++j)
        displacement_sq += r[j] * r[j];
      result.normalised_rms = std::sqrt(force_sq);
      if (options.displacement_weight > 0.0)
        result.normalised_displacement_rms =
          std::sqrt(displacement_sq / options.displacement_weight);
    }

    /// What the fit is judged by: the FEM's contact (window, extent above the threshold) and
    /// the fitted model's (`p`), with both force histories over the window.
    void set_comparison(FitResult           &result,
                        const Misfit        &misfit,
                        const Parameters    &p,
                        const ForceHistory  &history,
                        const ContactWindow &window,
                        const FitOptions    &options)
    {
      result.function_evaluations = misfit.n_evaluations();
      result.fem_peak_force       = window.peak_force;
      result.fem_contact_duration = window.separation - window.start;
      {
        const double peak  = *std::max_element(history.force.begin(), history.force.end());
        const auto   above = [&](double f) { return f > options.contact_threshold * peak; };
        const auto   first = std::find_if(history.force.begin(), history.force.end(), above);
        const auto   last  = std::find_if(history.force.rbegin(), history.force.rend(), above);
        result.contact_extent =
          history.time[static_cast<std::size_t>(std::distance(last, history.force.rend())) - 1] -
          history.time[static_cast<std::size_t>(std::distance(history.force.begin(), first))];
      }
      result.fem_impulse         = window.impulse;
      result.contact_start       = window.start;
      result.contact_open_at_end = window.open_at_end;

      std::vector<double>         model_force, model_displacement;
      const lumped::TwoBodyResult model = misfit.simulate(p, model_force, model_displacement);
      result.model_peak_force           = model.peak_force;
      result.model_contact_duration     = misfit.model_contact_end();
      result.model_impulse              = misfit.model_impulse();
      result.model_effective_cor        = model.effective_cor;
      for (std::size_t j = window.first; j <= window.last; ++j)
      {
        result.time.push_back(history.time[j]);
        result.fem_force.push_back(history.force[j]);
      }
      result.model_force = std::move(model_force);
    }
  } // namespace

  FitResult fit_impact_law(const ForceHistory         &history,
                           double                      mass,
                           double                      impact_velocity,
                           const lumped::ForceLawSpec &law,
                           const FitOptions           &options)
  {
    validate(mass, impact_velocity, law, options);
    check_history(history);
    if (options.displacement_weight > 0.0 && history.slab_displacement.empty())
      throw FitError("force history: displacement_weight > 0 but no slab displacement given");
    const ContactWindow window = find_contact_window(history, options);

    const int n_parameters = 1 + (options.fit_cor ? 1 : 0) + (options.fit_exponent ? 1 : 0);
    const int n_samples    = static_cast<int>(window.last - window.first + 1);
    const int n_residuals  = n_samples * (options.displacement_weight > 0.0 ? 2 : 1);
    if (n_samples < n_parameters + 3)
      throw FitError(fmt::format("force history: {} samples in the contact window ({} s to {} s), "
                                 "too few for {} parameters",
                                 n_samples,
                                 window.start,
                                 window.separation,
                                 n_parameters));

    const double     v     = impact_velocity;
    const Parameters start = start_parameters(window, mass, v, law, options);
    Misfit misfit(history, window, mass, v, law, options, start, n_parameters, n_residuals);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n_parameters);
    {
      int i = 1;
      if (options.fit_cor)
        x[i++] = std::log(start.cor / (1.0 - start.cor));
      if (options.fit_exponent)
        x[i++] = std::log(start.exponent - 1.0);
    }

    const double spacing = (history.time[window.last] - history.time[window.first]) /
                           static_cast<double>(window.last - window.first);
    FitResult                                    result;
    const Eigen::LevenbergMarquardtSpace::Status status =
      minimise(misfit, x, spacing, options, result.iterations);
    result.law         = law.law;
    result.status_code = static_cast<int>(status);
    result.status      = status_text(status);
    const Parameters p = misfit.parameters(x);
    if (!converged(status) || !x.allFinite())
      throw FitError(fmt::format("fit of law '{}': {} after {} iterations (k = {} N/m^{} per m, "
                                 "COR = {}, n = {})",
                                 law.law,
                                 result.status,
                                 result.iterations,
                                 p.stiffness,
                                 p.exponent,
                                 p.cor,
                                 p.exponent));

    // Residuals and Jacobian at the optimum (operator() last: the model state is the optimum's).
    Eigen::VectorXd r(n_residuals);
    Eigen::MatrixXd jacobian;
    misfit.df(x, jacobian);
    misfit(x, r);
    if (!r.allFinite() || r.cwiseAbs().maxCoeff() >= 1.0e3)
      throw FitError(fmt::format("fit of law '{}': the model fails at the optimum (k = {})",
                                 law.law,
                                 p.stiffness));
    set_fitted_parameters(result, p, start, x, r, jacobian, n_samples, options);
    set_comparison(result, misfit, p, history, window, options);
    return result;
  }
} // namespace kimp::fit
