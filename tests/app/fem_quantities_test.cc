// The engineer's quantities of an FEM record (app/fem/fem_quantities.h) on records with closed
// forms: a rigid slab on a linear spring (a half-sine pulse after a gap), a record whose first
// pulse is followed by a larger push, and broken records that the impulse-momentum check flags.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <string>

#include "app/fem/fem_quantities.h"
#include "io/fem_results.h"

namespace
{
  using kimp::io::FemCase;

  constexpr double pi = 3.14159265358979323846;
  constexpr double m = 3840.0, v = 1.0; ///< kg/m, m/s
  constexpr double omega = 2000.0;      ///< rad/s: k = m omega^2
  constexpr double t0    = 1e-3;        ///< s: the slab closes the gap v t0
  constexpr double dt    = 1e-6;        ///< s: sampling of the record
  constexpr double t_end = t0 + 2.5 * pi / omega;

  /// The exact record of a rigid slab of mass m at v on a linear spring k = m omega^2 at
  /// x = v t0, separating elastically at v_out = v after half a period.
  FemCase spring_record()
  {
    FemCase c;
    c.name                  = "spring";
    c.slab_mass             = m;
    c.impact_velocity       = v;
    c.summary.contact_start = t0;
    const double half       = pi / omega;
    for (double t = 0; t <= t_end; t += dt)
    {
      const double s  = t - t0;
      const bool   on = s > 0 && s < half;
      const double f  = on ? m * v * omega * std::sin(omega * s) : 0.0;
      const double x =
        s <= 0 ? v * t : (on ? v * t0 + v / omega * std::sin(omega * s) : v * t0 - v * (s - half));
      const double u = s <= 0 ? v : (on ? v * std::cos(omega * s) : -v);
      c.time.push_back(t);
      c.contact_force.push_back(f);
      c.smoothed_contact_force.push_back(f);
      c.slab_displacement.push_back(x);
      c.slab_velocity.push_back(u);
      c.wall_displacement.push_back(0.0);
      c.indentation.push_back(std::max(0.0, x - v * t0));
    }
    return c;
  }

  TEST(FemQuantities, SpringRecordHasTheClosedForms)
  {
    FemCase c = spring_record();
    kimp::app::set_engineer_quantities(c);
    const auto  &s    = c.summary;
    const double peak = m * v * omega;
    EXPECT_NEAR(s.first_peak_force.value(), peak, 1e-6 * peak);
    EXPECT_NEAR(s.first_peak_time.value(), 0.5 * pi / omega, 2 * dt);
    EXPECT_NEAR(s.first_peak_impulse.value(), 2 * m * v, 1e-5 * 2 * m * v);
    EXPECT_NEAR(s.max_slab_displacement.value(), v / omega, 1e-6 * v / omega);
    // E_0 / (v / omega) = m v omega / 2: half the peak of a linear spring.
    EXPECT_NEAR(s.energy_equivalent_resistance.value(), 0.5 * peak, 1e-5 * peak);
    EXPECT_NEAR(s.time_to_stop.value(), 0.5 * pi / omega, 2 * dt);
    EXPECT_NEAR(s.max_wall_displacement.value(), 0.0, 1e-15);
    EXPECT_NEAR(s.impulse_momentum_ratio.value(), 1.0, 1e-5);
    EXPECT_EQ(kimp::app::impulse_momentum_status(c), "ok");
  }

  TEST(FemQuantities, FirstPulseIsNotTheLaterPush)
  {
    // A wave peak, then a push at 60 % of it that lasts longer and carries more impulse.
    FemCase c = spring_record();
    for (std::size_t i = 0; i < c.time.size(); ++i)
    {
      const double s = c.time[i] - t0 - pi / omega;
      if (s > 0)
        c.smoothed_contact_force[i] = 0.6 * m * v * omega * std::sin(0.4 * omega * s);
    }
    kimp::app::set_engineer_quantities(c);
    EXPECT_NEAR(c.summary.first_peak_force.value(), m * v * omega, 1e-6 * m * v * omega);
    EXPECT_NEAR(c.summary.first_peak_impulse.value(), 2 * m * v, 1e-5 * 2 * m * v);
  }

  TEST(FemQuantities, BrokenRecordsAreFlagged)
  {
    // A record that lost 0.2 ms of its force (a hole in the history): ∫F dt falls short.
    FemCase holed = spring_record();
    for (std::size_t i = 0; i < holed.time.size(); ++i)
      if (holed.time[i] > t0 + 0.5e-3 && holed.time[i] < t0 + 0.7e-3)
        holed.smoothed_contact_force[i] = 0.0;
    kimp::app::set_engineer_quantities(holed);
    const double ratio = holed.summary.impulse_momentum_ratio.value();
    EXPECT_LT(ratio, 1.0 - kimp::app::impulse_momentum_tolerance);
    EXPECT_EQ(kimp::app::impulse_momentum_status(holed).rfind("warning: ", 0), 0u)
      << kimp::app::impulse_momentum_status(holed);

    // A record whose slab velocity is that of another run (rebound at half the speed).
    FemCase wrong              = spring_record();
    wrong.slab_velocity.back() = -0.5 * v;
    kimp::app::set_engineer_quantities(wrong);
    EXPECT_NEAR(wrong.summary.impulse_momentum_ratio.value(), 2.0 / 1.5, 1e-4);
    EXPECT_NE(kimp::app::impulse_momentum_status(wrong), "ok");

    // No contact: nothing to check, and no quantity is made up.
    FemCase none = spring_record();
    for (double &f : none.smoothed_contact_force)
      f = 0.0;
    kimp::app::set_engineer_quantities(none);
    EXPECT_FALSE(none.summary.first_peak_force.has_value());
    EXPECT_FALSE(none.summary.impulse_momentum_ratio.has_value());
    EXPECT_EQ(kimp::app::impulse_momentum_status(none).rfind("not checked", 0), 0u);
  }
} // namespace
