// First guesses of a yielding wall's wall-and-backfill part and its engine parameters.
#include "app/laws/yielding_wall_scene.h"

#include <cmath>

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

  lumped::WallBackfillParams YieldingWallScene::resolved() const
  {
    lumped::WallBackfillParams p;
    const double               k = stiffness.value_or(default_stiffness());
    const double               f = capacity.value_or(default_capacity());
    p.envelope                   = envelope;
    p.stiffness                  = k * width;
    p.capacity                   = f * width;
    p.hardening_ratio            = hardening_ratio;
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
} // namespace kimp::app
