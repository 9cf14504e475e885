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

    /// The upper concave hull of env[0..target] (monotone chain; collinear points dropped).
    void concave_hull(const std::vector<Point> &env, std::size_t target, PushoverFit &fit)
    {
      std::vector<Point> hull;
      for (std::size_t k = 0; k <= target; ++k)
      {
        const Point &p = env[k];
        while (hull.size() >= 2)
        {
          const Point &a = hull[hull.size() - 2], &b = hull.back();
          if ((b.w - a.w) * (p.f - a.f) - (b.f - a.f) * (p.w - a.w) >= 0.0)
            hull.pop_back(); // b lies on or below the chord a-p
          else
            break;
        }
        hull.push_back(p);
      }
      fit.hull_displacements.clear();
      fit.hull_forces.clear();
      for (const Point &p : hull)
      {
        fit.hull_displacements.push_back(p.w);
        fit.hull_forces.push_back(p.f);
      }
    }

    /// The element's envelope of `fit` at w >= 0: its concave hull (flat at V_d past it), or,
    /// without one, the bilinear capped at the curve's largest force.
    double element_envelope(const PushoverFit &fit, double w)
    {
      const std::vector<double> &x = fit.hull_displacements, &f = fit.hull_forces;
      if (x.size() >= 2)
      {
        if (w >= x.back())
          return f.back();
        const std::size_t i =
          static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), w) - x.begin()) - 1;
        return f[i] + (f[i + 1] - f[i]) * ((w - x[i]) / (x[i + 1] - x[i]));
      }
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

    /// Every unloading of `curve` that reaches zero force: where it starts, its force there and
    /// the displacement at zero force (linear between the points that bracket it).
    std::vector<PushoverUnloading> curve_unloadings(const std::vector<fem::PushoverPoint> &curve)
    {
      std::vector<PushoverUnloading> out;
      for (std::size_t k = 1; k < curve.size(); ++k)
      {
        if (!curve[k].unloading || curve[k - 1].unloading)
          continue;
        std::size_t j = k;
        while (j + 1 < curve.size() && curve[j + 1].unloading && curve[j].force > 0)
          ++j;
        const fem::PushoverPoint &a = curve[j - 1], &b = curve[j];
        if (b.force <= 0 && a.force > 0)
          out.push_back(
            {curve[k - 1].displacement,
             curve[k - 1].force,
             a.displacement + (b.displacement - a.displacement) * a.force / (a.force - b.force),
             0.0});
      }
      return out;
    }

    /// The element's set after unloading from w_un at k_ur (docs/physics.md §2: never steeper
    /// than the envelope's secant there, so never below 0).
    double element_set(const PushoverFit &fit, double w_un, double k_ur)
    {
      const double e = element_envelope(fit, w_un);
      return w_un - e / std::max(k_ur, e / w_un);
    }

    /// k_ur and the permanent sets from the unloadings of `curve` (see the header).
    void fit_unloading(const std::vector<fem::PushoverPoint> &curve, PushoverFit &fit)
    {
      fit.unloadings          = curve_unloadings(curve);
      fit.unloading_stiffness = fit.stiffness;
      fit.unloaded_from = fit.pushover_permanent_set = fit.permanent_set =
        std::numeric_limits<double>::quiet_NaN();
      if (fit.unloadings.empty())
      {
        append(fit.note, "no unloading to zero force in the curve: k_ur = k");
        return;
      }
      // Least squares on 1/k_ur of the sets w_un − E(w_un)/k_ur over the unloadings that leave
      // one (more than a tenth of w_un); if none does, the smallest unloading secant.
      double num = 0.0, den = 0.0, smallest_secant = std::numeric_limits<double>::infinity();
      for (const PushoverUnloading &u : fit.unloadings)
      {
        const double e  = element_envelope(fit, u.from);
        smallest_secant = std::min(smallest_secant, e / (u.from - u.permanent_set));
        if (u.permanent_set > 0.1 * u.from)
        {
          num += e * (u.from - u.permanent_set);
          den += e * e;
        }
      }
      fit.unloading_stiffness = den > 0.0 ? den / num : smallest_secant;
      if (den == 0.0)
        append(fit.note,
               fmt::format("every unloading springs back to within a tenth of its start: k_ur "
                           "= the smallest unloading secant, {:.4g} kN/mm/m",
                           smallest_secant / 1e6));
      std::string sets;
      for (PushoverUnloading &u : fit.unloadings)
      {
        u.element_set = element_set(fit, u.from, fit.unloading_stiffness);
        sets += fmt::format("{}{:.3g}: {:.3g} / {:.3g}",
                            sets.empty() ? "" : ", ",
                            u.from * 1e3,
                            u.permanent_set * 1e3,
                            u.element_set * 1e3);
      }
      fit.unloaded_from          = fit.unloadings.front().from;
      fit.pushover_permanent_set = fit.unloadings.front().permanent_set;
      fit.permanent_set          = fit.unloadings.front().element_set;
      if (fit.unloading_stiffness < fit.stiffness)
        append(fit.note,
               fmt::format("k_ur {:.4g} kN/mm/m < k: the wall springs back softer than it was "
                           "loaded (set after unloading from w_un mm, curve / element: {} mm)",
                           fit.unloading_stiffness / 1e6,
                           sets));
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
    concave_hull(env, target, fit);
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
    if (coarse.materials.concrete.model == FemConcrete::Model::damage_plasticity &&
        coarse.pushover.unload_at.empty())
      for (const double drift : study_pushover_unload_drifts)
        if (drift * wall_height <
            coarse.pushover.displacement.value_or(study_pushover_drift * wall_height))
          coarse.pushover.unload_at.push_back(drift * wall_height);
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
    in.capacity               = r.fit.capacity;
    in.stiffness              = r.fit.stiffness;
    in.hardening_ratio        = r.fit.hardening_ratio;
    in.ultimate_capacity      = r.fit.target_force; // the curve's largest force: the cap
    in.unloading_stiffness    = r.fit.unloading_stiffness;
    in.envelope_displacements = r.fit.hull_displacements;
    in.envelope_forces        = r.fit.hull_forces;
    return r;
  }
} // namespace kimp::app
