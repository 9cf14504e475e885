// The wall-and-backfill part of a yielding moat wall: envelope, unloading line with the permanent
// set, tension cap, radiation dashpot, plastic and radiated work.
#include "lumped/laws/wall_backfill_law.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "lumped/laws/kelvin_voigt_law.h"
#include "lumped/parameter_check.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr const char *owner = "wall_backfill: ";

    /// y − ln(1 + y) without cancellation for small y (> −1).
    double y_minus_log1p(const double y)
    {
      if (std::abs(y) < 1e-4)
        return y * y * (0.5 - y * (1.0 / 3.0 - 0.25 * y));
      return y - std::log1p(y);
    }

    /// The parameters with a curve envelope's k (first slope) and capacity (last force) set.
    /// @throws std::invalid_argument naming the bad point.
    WallBackfillParams with_curve_derived(WallBackfillParams p)
    {
      if (p.envelope != WallEnvelope::curve)
      {
        if (!p.curve_displacements.empty() || !p.curve_forces.empty())
          throw std::invalid_argument(std::string(owner) +
                                      "curve points are the curve envelope's (envelope is not "
                                      "curve)");
        return p;
      }
      const std::string problem = wall_curve_problem(p.curve_displacements, p.curve_forces);
      if (!problem.empty())
        throw std::invalid_argument(std::string(owner) + "curve envelope: " + problem);
      p.stiffness = p.curve_forces[1] / p.curve_displacements[1];
      p.capacity  = p.curve_forces.back();
      return p;
    }
  } // namespace

  std::string wall_curve_problem(const std::vector<double> &w, const std::vector<double> &f)
  {
    if (w.size() != f.size())
      return "the displacements and forces differ in count (" + std::to_string(w.size()) + " and " +
             std::to_string(f.size()) + ")";
    if (w.size() < 2)
      return "needs at least two points, (0, 0) and one more";
    if (w[0] != 0.0 || f[0] != 0.0)
      return "point 0: must be (0, 0)";
    double first_slope = 0.0;
    double slope       = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < w.size(); ++i)
    {
      const std::string at = "point " + std::to_string(i) + ": ";
      if (!std::isfinite(w[i]) || !std::isfinite(f[i]))
        return at + "must be finite";
      if (!(w[i] > w[i - 1]))
        return at + "displacement must be larger than the previous point's (increasing)";
      if (f[i] < f[i - 1])
        return at + "force must not be below the previous point's (monotone)";
      const double s = (f[i] - f[i - 1]) / (w[i] - w[i - 1]);
      if (i == 1)
      {
        if (!(s > 0.0))
          return at + "the first segment must rise (a positive stiffness)";
        first_slope = s;
      }
      else if (s > slope + 1e-9 * first_slope)
        return at + "the slope rises from the previous segment's (the curve must be concave)";
      slope = s;
    }
    return "";
  }

  WallBackfillLaw::WallBackfillLaw(const Params &params)
    : params_(with_curve_derived(params))
  {
    const Params &p = params_;
    require_parameter(std::isfinite(p.stiffness) && p.stiffness > 0.0,
                      owner,
                      "stiffness",
                      p.stiffness,
                      "N/m",
                      "must be > 0");
    require_parameter(std::isfinite(p.capacity) && p.capacity > 0.0,
                      owner,
                      "capacity",
                      p.capacity,
                      "N",
                      "must be > 0");
    require_parameter(p.hardening_ratio >= 0.0 && p.hardening_ratio < 1.0,
                      owner,
                      "hardening_ratio",
                      p.hardening_ratio,
                      "",
                      "must be in [0, 1)");
    require_parameter(p.ultimate_capacity >= p.capacity,
                      owner,
                      "ultimate_capacity",
                      p.ultimate_capacity,
                      "N",
                      "must be >= capacity (+inf: no cap)");
    require_parameter(
      p.envelope == WallEnvelope::bilinear ||
        p.ultimate_capacity == std::numeric_limits<double>::infinity(),
      owner,
      "ultimate_capacity",
      p.ultimate_capacity,
      "N",
      "is the bilinear envelope's (the hyperbolic one has no cap, the curve's is its "
      "last force)");
    require_parameter(p.failure_ratio > 0.0 && p.failure_ratio <= 1.0,
                      owner,
                      "failure_ratio",
                      p.failure_ratio,
                      "",
                      "must be in (0, 1]");
    require_parameter(std::isfinite(p.unloading_stiffness) && p.unloading_stiffness > 0.0,
                      owner,
                      "unloading_stiffness",
                      p.unloading_stiffness,
                      "N/m",
                      "must be > 0");
    require_parameter(std::isfinite(p.tension_capacity) && p.tension_capacity >= 0.0,
                      owner,
                      "tension_capacity",
                      p.tension_capacity,
                      "N",
                      "must be >= 0");
    require_parameter(std::isfinite(p.radiation_damping) && p.radiation_damping >= 0.0,
                      owner,
                      "radiation_damping",
                      p.radiation_damping,
                      "N*s/m",
                      "must be >= 0");
    require_parameter(std::isfinite(p.mass) && p.mass > 0.0,
                      owner,
                      "mass",
                      p.mass,
                      "kg",
                      "must be > 0");
    require_parameter(p.failure_displacement > 0.0,
                      owner,
                      "failure_displacement",
                      p.failure_displacement,
                      "m",
                      "must be > 0");
    require_parameter(p.envelope != WallEnvelope::curve || p.hardening_ratio == 0.0,
                      owner,
                      "hardening_ratio",
                      p.hardening_ratio,
                      "",
                      "is the bilinear envelope's (the curve gives its own slopes)");
    if (p.envelope == WallEnvelope::curve)
    {
      curve_work_.assign(p.curve_displacements.size(), 0.0);
      for (std::size_t i = 1; i < curve_work_.size(); ++i)
        curve_work_[i] =
          curve_work_[i - 1] + 0.5 * (p.curve_forces[i - 1] + p.curve_forces[i]) *
                                 (p.curve_displacements[i] - p.curve_displacements[i - 1]);
    }
  }

  std::size_t WallBackfillLaw::curve_segment(const double w) const
  {
    const std::vector<double> &x = params_.curve_displacements;
    return static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), w) - x.begin()) - 1;
  }

  double WallBackfillLaw::envelope(const double w) const
  {
    const Params &p = params_;
    if (p.envelope == WallEnvelope::curve)
    {
      const std::size_t i = curve_segment(w);
      if (i + 1 >= p.curve_displacements.size())
        return p.curve_forces.back();
      const double *x = p.curve_displacements.data();
      const double *f = p.curve_forces.data();
      return f[i] + (f[i + 1] - f[i]) * ((w - x[i]) / (x[i + 1] - x[i]));
    }
    if (p.envelope == WallEnvelope::hyperbolic)
      return w / (1.0 / p.stiffness + p.failure_ratio * w / p.capacity);
    const double w_y = p.capacity / p.stiffness;
    return w <= w_y ? p.stiffness * w :
                      std::min(p.capacity + p.hardening_ratio * p.stiffness * (w - w_y),
                               p.ultimate_capacity);
  }

  double WallBackfillLaw::envelope_tangent(const double w) const
  {
    const Params &p = params_;
    if (p.envelope == WallEnvelope::curve)
    {
      const std::size_t i = curve_segment(w);
      if (i + 1 >= p.curve_displacements.size())
        return 0.0;
      return (p.curve_forces[i + 1] - p.curve_forces[i]) /
             (p.curve_displacements[i + 1] - p.curve_displacements[i]);
    }
    if (p.envelope == WallEnvelope::hyperbolic)
    {
      const double d = 1.0 / p.stiffness + p.failure_ratio * w / p.capacity;
      return 1.0 / (p.stiffness * d * d);
    }
    if (w < p.capacity / p.stiffness)
      return p.stiffness;
    return w < cap_displacement() ? p.hardening_ratio * p.stiffness : 0.0;
  }

  double WallBackfillLaw::cap_displacement() const
  {
    const Params &p = params_;
    if (p.envelope == WallEnvelope::curve)
      return p.curve_displacements.back();
    const double w_y = p.capacity / p.stiffness;
    if (p.ultimate_capacity == std::numeric_limits<double>::infinity())
      return std::numeric_limits<double>::infinity();
    if (p.ultimate_capacity <= p.capacity || p.hardening_ratio == 0.0)
      return w_y; // the cap is the yield force, or hardening never reaches it
    return w_y + (p.ultimate_capacity - p.capacity) / (p.hardening_ratio * p.stiffness);
  }

  double WallBackfillLaw::envelope_work(const double w) const
  {
    const Params &p = params_;
    if (p.envelope == WallEnvelope::curve)
    {
      const std::size_t i = curve_segment(w);
      const double      x = p.curve_displacements[i];
      return curve_work_[i] + 0.5 * (p.curve_forces[i] + envelope(w)) * (w - x);
    }
    if (p.envelope == WallEnvelope::hyperbolic)
    {
      // ∫ x/(a + b·x) dx = (a/b²)·(y − ln(1 + y)), y = b·x/a.
      const double a = 1.0 / p.stiffness;
      const double b = p.failure_ratio / p.capacity;
      return a / (b * b) * y_minus_log1p(b * w / a);
    }
    const double w_y = p.capacity / p.stiffness;
    if (w <= w_y)
      return 0.5 * p.stiffness * w * w;
    const double w_u = std::max(w_y, cap_displacement());
    const double dw  = std::min(w, w_u) - w_y; // hardening part
    return 0.5 * p.capacity * w_y + p.capacity * dw +
           0.5 * p.hardening_ratio * p.stiffness * dw * dw + envelope(w) * std::max(0.0, w - w_u);
  }

  double WallBackfillLaw::unloading_stiffness_at(const double w_max) const
  {
    const double k_ur = params_.unloading_stiffness;
    if (!(w_max > 0.0))
      return std::max(k_ur, params_.stiffness); // the envelope's tangent at 0 is k
    return std::max(k_ur, envelope(w_max) / w_max);
  }

  double WallBackfillLaw::permanent_set(const WallBackfillState &s) const
  {
    return s.max_deformation -
           envelope(s.max_deformation) / unloading_stiffness_at(s.max_deformation);
  }

  ForceResponse WallBackfillLaw::set_trial(const double deformation, const double rate)
  {
    trial_             = committed_;
    trial_.deformation = deformation;
    trial_.rate        = rate;
    const Params &p    = params_;
    if (deformation >= committed_.max_deformation)
    {
      trial_.max_deformation = deformation;
      trial_.spring_force    = envelope(deformation);
      trial_.stiffness       = envelope_tangent(deformation);
    }
    else
    {
      const double k_ur   = unloading_stiffness_at(committed_.max_deformation);
      const double line   = k_ur * (deformation - permanent_set(committed_));
      trial_.spring_force = std::max(line, -p.tension_capacity);
      trial_.stiffness    = line > -p.tension_capacity ? k_ur : 0.0;
    }
    trial_.force       = trial_.spring_force + p.radiation_damping * rate;
    trial_.peak_spring = std::max(committed_.peak_spring, trial_.spring_force);
    trial_.radiated = committed_.radiated + 0.5 * p.radiation_damping * (committed_.rate + rate) *
                                              (deformation - committed_.deformation);
    return {trial_.force, trial_.stiffness, p.radiation_damping};
  }

  double WallBackfillLaw::stability_stiffness(double) const
  {
    const double k  = std::max(params_.stiffness, params_.unloading_stiffness);
    const double xi = params_.radiation_damping / (2.0 * std::sqrt(k * params_.mass));
    const double f  = cdm_damping_factor(xi);
    return k / (f * f);
  }

  double WallBackfillLaw::plastic_work() const
  {
    const double w_max = committed_.max_deformation;
    const double e     = envelope(w_max);
    return envelope_work(w_max) - 0.5 * e * e / unloading_stiffness_at(w_max);
  }

  double WallBackfillLaw::stored_energy() const
  {
    const double k_ur = unloading_stiffness_at(committed_.max_deformation);
    const double d    = committed_.deformation - permanent_set(committed_);
    const double d_t  = -params_.tension_capacity / k_ur; // where the tension cap begins
    if (d >= d_t)
      return 0.5 * k_ur * d * d;
    return 0.5 * k_ur * d_t * d_t + params_.tension_capacity * (d_t - d);
  }
} // namespace kimp::lumped
