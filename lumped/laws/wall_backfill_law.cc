// The wall-and-backfill part of a yielding moat wall: envelope, unloading line with the permanent
// set, tension cap, radiation dashpot, plastic and radiated work.
#include "lumped/laws/wall_backfill_law.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
  } // namespace

  WallBackfillLaw::WallBackfillLaw(const Params &params)
    : params_(params)
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
    require_parameter(p.envelope == WallEnvelope::bilinear ||
                        p.ultimate_capacity == std::numeric_limits<double>::infinity(),
                      owner,
                      "ultimate_capacity",
                      p.ultimate_capacity,
                      "N",
                      "is the bilinear envelope's (the hyperbolic one has no cap)");
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
  }

  double WallBackfillLaw::envelope(const double w) const
  {
    const Params &p = params_;
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
    const Params &p   = params_;
    const double  w_y = p.capacity / p.stiffness;
    if (p.ultimate_capacity == std::numeric_limits<double>::infinity())
      return std::numeric_limits<double>::infinity();
    if (p.ultimate_capacity <= p.capacity || p.hardening_ratio == 0.0)
      return w_y; // the cap is the yield force, or hardening never reaches it
    return w_y + (p.ultimate_capacity - p.capacity) / (p.hardening_ratio * p.stiffness);
  }

  double WallBackfillLaw::envelope_work(const double w) const
  {
    const Params &p = params_;
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
