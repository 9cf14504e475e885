// First guesses of a yielding wall's wall-and-backfill part and its engine parameters.
#include "app/laws/yielding_wall_scene.h"

#include <cmath>
#include <limits>
#include <utility>

#include "io/units.h"

namespace kimp::app
{
  namespace
  {
    constexpr double foot          = 0.3048;          // m
    constexpr double kip           = 4448.2216152605; // N
    constexpr double kip_per_in    = kip / 0.0254;    // N/m
    constexpr double per_foot      = 1.0 / foot;      // feet of wall per metre
    constexpr double failure_drift = 0.10;            // failure_displacement / height
  }                                                   // namespace

  double YieldingWallScene::default_stiffness() const
  {
    const double h = height / foot;
    return per_foot * (5.5 * h + 20.0) * kip_per_in;
  }

  double YieldingWallScene::default_capacity() const
  {
    const double h = height / foot;
    return per_foot * 5.5 * std::pow(h, 2.5) / (1.0 + 2.37 * h) * kip;
  }

  double YieldingWallScene::capacity_per_metre() const
  {
    if (envelope == lumped::WallEnvelope::curve)
      return curve.empty() ? 0.0 : curve.back().force;
    return capacity.value_or(default_capacity());
  }

  namespace
  {
    /// The curve envelope's k (first slope) and capacity (last force) per metre; NaN for a curve
    /// of fewer than two points (the law refuses it).
    std::pair<double, double> curve_stiffness_and_capacity(const YieldingWallScene &y)
    {
      if (y.curve.size() < 2 || !(y.curve[1].displacement > 0.0))
        return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
      return {y.curve[1].force / y.curve[1].displacement, y.curve.back().force};
    }
  } // namespace

  lumped::WallBackfillParams YieldingWallScene::resolved() const
  {
    lumped::WallBackfillParams p;
    const bool                 is_curve = envelope == lumped::WallEnvelope::curve;
    const auto [k_c, f_c]               = curve_stiffness_and_capacity(*this);
    const double k                      = is_curve ? k_c : stiffness.value_or(default_stiffness());
    const double f                      = is_curve ? f_c : capacity.value_or(default_capacity());
    p.envelope                          = envelope;
    for (const WallCurvePointScene &c : curve)
    {
      p.curve_displacements.push_back(c.displacement);
      p.curve_forces.push_back(c.force * width);
    }
    p.stiffness       = k * width;
    p.capacity        = f * width;
    p.hardening_ratio = hardening_ratio;
    if (ultimate_capacity)
      p.ultimate_capacity = *ultimate_capacity * width;
    p.failure_ratio       = failure_ratio;
    p.unloading_stiffness = unloading_stiffness.value_or(k) * width;
    p.tension_capacity    = tension_capacity.value_or(f) * width;
    p.radiation_damping =
      radiation_damping.value_or(soil_density * soil_wave_speed * height) * width;
    p.failure_displacement = failure_displacement.value_or(failure_drift * height);
    return p;
  }

  void validate_yielding_wall(const YieldingWallScene &y,
                              const std::string       &prefix,
                              io::ValidationContext   &ctx)
  {
    if (y.envelope != lumped::WallEnvelope::curve)
    {
      ctx.check(y.curve.empty(),
                prefix + "curve",
                std::to_string(y.curve.size()) + " points",
                "is the curve envelope's: set envelope: curve, or leave curve out");
      return;
    }
    const auto unset = [&](bool is_unset, const char *key)
    {
      ctx.check(is_unset,
                prefix + key,
                "set",
                "is given by the curve envelope's points: leave it out (or null)");
    };
    unset(!y.stiffness, "stiffness");
    unset(!y.capacity, "capacity");
    unset(y.hardening_ratio == 0.0, "hardening_ratio");
    unset(!y.ultimate_capacity, "ultimate_capacity");
    std::vector<double> w, f;
    for (const WallCurvePointScene &c : y.curve)
    {
      w.push_back(c.displacement);
      f.push_back(c.force);
    }
    const std::string problem = lumped::wall_curve_problem(w, f);
    if (problem.empty())
      return;
    // "point i: ..." names the item: the key is the list's item, the value the point.
    const std::string tag   = "point ";
    std::string       key   = prefix + "curve";
    std::string       value = std::to_string(y.curve.size()) + " points";
    std::string       why   = problem;
    if (problem.rfind(tag, 0) == 0)
    {
      const std::size_t colon = problem.find(':');
      const std::size_t i     = std::stoul(problem.substr(tag.size(), colon - tag.size()));
      key += "[" + std::to_string(i) + "]";
      value = "{" + io::format_quantity(y.curve[i].displacement, "mm") + ", " +
              io::format_quantity(y.curve[i].force, "kN/m") + "}";
      why = problem.substr(colon + 2);
    }
    ctx.fail(key, value, why + " (a concave, monotone curve from {0 mm, 0 kN/m})");
  }
} // namespace kimp::app
