// The equal-energy bilinear idealisation of a pushover curve and its unloading (see
// pushover_fit.h).
#include "app/study/pushover_fit.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>

#include "app/fem/pushover_run.h"
#include "base/errors.h"
#include "base/stopwatch.h"
#include "fem/numerical_error.h"

namespace kimp::app
{
  namespace
  {
    struct Point
    {
      double w = 0.0, f = 0.0;
    };

    /// The virgin loading points from (0, 0): each one beyond the largest displacement so far.
    std::vector<Point> virgin_envelope(const std::vector<fem::PushoverPoint> &curve)
    {
      std::vector<Point> env{{0.0, 0.0}};
      for (const fem::PushoverPoint &p : curve)
        if (!p.unloading && p.displacement > env.back().w)
          env.push_back({p.displacement, p.force});
      return env;
    }

    /// The first displacement at which the envelope reaches `force` (linear between points).
    double first_crossing(const std::vector<Point> &env, std::size_t end, double force)
    {
      for (std::size_t k = 1; k <= end; ++k)
        if (env[k].f >= force)
        {
          const Point &a = env[k - 1], &b = env[k];
          return a.w + (b.w - a.w) * (force - a.f) / (b.f - a.f);
        }
      return std::numeric_limits<double>::quiet_NaN();
    }

    /// Equal-energy V_y, K_e and α of the envelope up to its point `target` (see the header).
    void fit_envelope(const std::vector<Point> &env, std::size_t target, PushoverFit &fit)
    {
      const double w_d = env[target].w, f_d = env[target].f;
      double       area = 0.0;
      for (std::size_t k = 1; k <= target; ++k)
        area += 0.5 * (env[k].f + env[k - 1].f) * (env[k].w - env[k - 1].w);
      double v_y = f_d, k_e = 0.0;
      bool   converged = false, capped = false;
      for (int iteration = 0; iteration < 500 && !converged; ++iteration)
      {
        k_e                = 0.6 * v_y / first_crossing(env, target, 0.6 * v_y);
        const double denom = w_d - f_d / k_e;
        if (!(denom > 1e-6 * w_d))
          throw std::invalid_argument(
            fmt::format("pushover fit: the curve does not yield before its largest force "
                        "{:.4g} kN/m at {:.4g} mm (its secant at 0.6 V_y reaches it only at "
                        "{:.4g} mm): push further",
                        f_d / 1e3,
                        w_d * 1e3,
                        f_d / k_e * 1e3));
        const double raw  = (2.0 * area - f_d * w_d) / denom;
        const double next = std::clamp(raw, 1e-9 * f_d, f_d);
        capped            = raw >= f_d;
        converged         = std::abs(next - v_y) <= 1e-13 * f_d;
        v_y               = next;
      }
      if (!converged)
        throw std::invalid_argument("pushover fit: the equal-energy iteration for V_y did not "
                                    "converge in 500 steps");
      k_e                     = 0.6 * v_y / first_crossing(env, target, 0.6 * v_y);
      fit.capacity            = v_y;
      fit.stiffness           = k_e;
      fit.yield_displacement  = v_y / k_e;
      fit.target_displacement = w_d;
      fit.target_force        = f_d;
      fit.curve_work          = area;
      const double slope      = (f_d - v_y) / (w_d - fit.yield_displacement);
      fit.hardening_ratio     = std::clamp(slope / k_e, 0.0, 1.0 - 1e-9);
      if (capped)
        fit.note = fmt::format("F_y = the curve's largest force, alpha = 0 (its equal-energy "
                               "yield force reaches it: a flat curve, or one that has not "
                               "yielded at the end of the push, {:.4g} mm)",
                               w_d * 1e3);
    }

    /// The bilinear envelope of `fit` at w >= 0, capped at the curve's largest force (the
    /// element's ultimate_capacity).
    double bilinear(const PushoverFit &fit, double w)
    {
      return w <= fit.yield_displacement ?
               fit.stiffness * w :
               std::min(fit.capacity +
                          fit.hardening_ratio * fit.stiffness * (w - fit.yield_displacement),
                        fit.target_force);
    }

    void append(std::string &note, const std::string &text)
    {
      note += (note.empty() ? "" : "; ") + text;
    }

    /// k_ur and the permanent set from the first unloading of `curve` (see the header).
    void fit_unloading(const std::vector<fem::PushoverPoint> &curve, PushoverFit &fit)
    {
      const fem::PushoverSummary s = fem::summarise_pushover(curve);
      fit.unloaded_from            = s.unloaded_from;
      fit.pushover_permanent_set   = s.permanent_set;
      fit.unloading_stiffness      = fit.stiffness;
      if (std::isnan(s.permanent_set) || std::isnan(s.unloaded_from))
      {
        fit.permanent_set = std::numeric_limits<double>::quiet_NaN();
        append(fit.note, "no unloading to zero force in the curve: k_ur = k");
        return;
      }
      const double e_un = bilinear(fit, s.unloaded_from);
      const double k_ur = e_un / (s.unloaded_from - s.permanent_set);
      if (k_ur >= fit.stiffness)
        fit.unloading_stiffness = k_ur;
      fit.permanent_set = s.unloaded_from - e_un / fit.unloading_stiffness;
      if (k_ur < fit.stiffness)
        append(fit.note,
               fmt::format("the curve unloads softer ({:.4g} kN/mm/m) than k: k_ur = k, the "
                           "element's set {:.4g} mm against the curve's {:.4g} mm",
                           k_ur / 1e6,
                           fit.permanent_set * 1e3,
                           s.permanent_set * 1e3));
    }
  } // namespace

  PushoverFit fit_pushover(const std::vector<fem::PushoverPoint> &curve)
  {
    const std::vector<Point> env = virgin_envelope(curve);
    if (env.size() < 3)
      throw std::invalid_argument(fmt::format(
        "pushover fit: the curve has {} loading points; at least two beyond (0, 0) needed",
        env.size() - 1));
    std::size_t target = 0;
    for (std::size_t k = 1; k < env.size(); ++k)
      if (env[k].f > env[target].f)
        target = k;
    if (!(env[target].f > 0.0))
      throw std::invalid_argument("pushover fit: the curve has no positive force");
    PushoverFit fit;
    fit_envelope(env, target, fit);
    if (env.back().f < 0.97 * env[target].f)
      append(fit.note,
             fmt::format("the curve softens past its largest force ({:.4g} kN/m at {:.4g} mm, "
                         "{:.4g} kN/m at its end {:.4g} mm): not modelled",
                         env[target].f / 1e3,
                         env[target].w * 1e3,
                         env.back().f / 1e3,
                         env.back().w * 1e3));
    fit_unloading(curve, fit);
    return fit;
  }

  namespace
  {
    /// The first sentence of a pushover's error (its Newton residuals left out).
    std::string short_reason(const std::string &text)
    {
      const auto cut = text.find("; relative residuals");
      return cut == std::string::npos ? text : text.substr(0, cut);
    }

    /// The study's pushover of `scene` (see pushover_resistance()): the implicit damage update
    /// first; IMPL-EX only when Newton stalls with it. `fallback` says why IMPL-EX ran ("" when
    /// it did not).
    fem::PushoverResult
    implicit_then_implex(const FemScene &scene, double wall_height, std::string &fallback)
    {
      fem::PushoverParameters p = pushover_parameters(scene, wall_height);
      if (p.wall != fem::PushoverParameters::Wall::reinforced)
        return fem::run_pushover(p);
      p.implex = false;
      try
      {
        return fem::run_pushover(p);
      }
      catch (const fem::NumericalError &stall)
      {
        fallback = fmt::format("IMPL-EX damage update at {:.4g} mm steps (the implicit update "
                               "stalled: {})",
                               std::min(p.increment, study_pushover_implex_increment) * 1e3,
                               short_reason(stall.what()));
      }
      p.implex    = true;
      p.increment = std::min(p.increment, study_pushover_implex_increment);
      return fem::run_pushover(p);
    }
  } // namespace

  PushoverResistance
  pushover_resistance(const FemScene &scene, const double wall_height, YieldingWallInputs &in)
  {
    FemScene coarse           = scene;
    coarse.geometry.h_contact = study_pushover_h_contact;
    coarse.geometry.h_max     = study_pushover_h_max;
    coarse.mesh_level         = 0;
    PushoverResistance r;
    const auto         start = base::SteadyClock::now();
    std::string        fallback;
    try
    {
      const fem::PushoverResult p = implicit_then_implex(coarse, wall_height, fallback);
      r.cells                     = p.n_cells;
      r.seconds                   = base::seconds_since(start);
      r.fit                       = fit_pushover(p.curve);
      r.curve                     = p.curve;
    }
    catch (const std::exception &error)
    {
      r.seconds = base::seconds_since(start);
      r.reason  = "pushover failed: " + short_reason(base::error_text(error));
      if (!fallback.empty())
        r.reason += " (with the " + fallback + ")";
      return r;
    }
    r.source = "pushover";
    r.reason = fallback;
    append(r.reason, r.fit.note);
    in.capacity            = r.fit.capacity;
    in.stiffness           = r.fit.stiffness;
    in.hardening_ratio     = r.fit.hardening_ratio;
    in.ultimate_capacity   = r.fit.target_force; // the curve's largest force: the cap
    in.unloading_stiffness = r.fit.unloading_stiffness;
    return r;
  }
} // namespace kimp::app
