// The engineer's quantities of an FEM impact record, from its histories.
#include "app/fem/fem_quantities.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fmt/format.h>
#include <vector>

namespace kimp::app
{
  namespace
  {
    /** Trapezoid ∫ f dt over the samples [from, to]. */
    double trapezoid(const std::vector<double> &t,
                     const std::vector<double> &f,
                     std::size_t                from,
                     std::size_t                to)
    {
      double sum = 0.0;
      for (std::size_t i = from + 1; i <= to && i < t.size(); ++i)
        sum += 0.5 * (f[i] + f[i - 1]) * (t[i] - t[i - 1]);
      return sum;
    }

    /** f at time x by linear interpolation between the samples (clamped to the record). */
    double interpolate(const std::vector<double> &t, const std::vector<double> &f, double x)
    {
      const auto it = std::upper_bound(t.begin(), t.end(), x);
      if (it == t.begin())
        return f.front();
      if (it == t.end())
        return f.back();
      const auto   i = static_cast<std::size_t>(it - t.begin());
      const double w = (x - t[i - 1]) / (t[i] - t[i - 1]);
      return (1 - w) * f[i - 1] + w * f[i];
    }

    /** The first pulse of `force` from sample `start`: its peak's index and its last sample. */
    struct Pulse
    {
      std::size_t peak = 0, end = 0;
    };

    Pulse first_pulse(const std::vector<double> &force, std::size_t start)
    {
      Pulse p{start, force.size() - 1};
      for (std::size_t i = start; i < force.size(); ++i)
      {
        if (force[i] > force[p.peak])
          p.peak = i;
        if (force[p.peak] > 0 && force[i] <= 0.5 * force[p.peak])
        {
          std::size_t j = i;
          while (j + 1 < force.size() && force[j + 1] < force[j])
            ++j;
          p.end = j;
          return p;
        }
      }
      return p;
    }

    /**
     * The first instant after sample `start` at which `x` − `x_c` reaches
     * stop_travel_fraction × `travel` (linear interpolation between the samples).
     */
    double time_to_travel(const std::vector<double> &t,
                          const std::vector<double> &x,
                          std::size_t                start,
                          double                     x_c,
                          double                     travel)
    {
      const double target = x_c + stop_travel_fraction * travel;
      for (std::size_t i = std::max<std::size_t>(start, 1); i < t.size(); ++i)
        if (x[i] >= target)
        {
          if (x[i - 1] >= target || x[i] == x[i - 1])
            return t[i];
          const double w = (target - x[i - 1]) / (x[i] - x[i - 1]);
          return t[i - 1] + w * (t[i] - t[i - 1]);
        }
      return t.back();
    }
  } // namespace

  void set_engineer_quantities(io::FemCase &c)
  {
    io::FemSummary            &s = c.summary;
    const std::vector<double> &t = c.time;
    const std::vector<double> &force =
      c.smoothed_contact_force.size() == t.size() ? c.smoothed_contact_force : c.contact_force;
    if (t.empty() || force.size() != t.size())
      return;
    std::size_t first = 0;
    while (first < force.size() && !(force[first] > 0))
      ++first;
    if (first == force.size())
      return; // no contact in the record
    // The sample before the first non-zero force: the pulse starts from zero there.
    const std::size_t start = first > 0 ? first - 1 : 0;
    const Pulse       pulse = first_pulse(force, start);
    // The first contact: the solver's (every step) if the record has it, else the sample.
    const double t_c     = s.contact_start.value_or(t[start]);
    s.first_peak_force   = force[pulse.peak];
    s.first_peak_time    = t[pulse.peak] - t_c;
    s.first_peak_impulse = trapezoid(t, force, start, pulse.end);

    const double m = c.slab_mass, v_in = c.impact_velocity;
    if (c.slab_displacement.size() == t.size())
    {
      const double x_c    = interpolate(t, c.slab_displacement, t_c);
      double       travel = 0.0;
      for (std::size_t i = start; i < t.size(); ++i)
        travel = std::max(travel, c.slab_displacement[i] - x_c);
      s.max_slab_displacement = travel;
      // Only once the slab has stopped: before, the largest travel is the last sample's.
      const bool stopped = c.slab_velocity.size() == t.size() &&
                           std::any_of(c.slab_velocity.begin() + static_cast<std::ptrdiff_t>(start),
                                       c.slab_velocity.end(),
                                       [](double u) { return u <= 0; });
      if (travel > 0 && stopped)
        s.time_to_95_travel = time_to_travel(t, c.slab_displacement, start, x_c, travel) - t_c;
      if (travel > 0 && m > 0 && v_in > 0)
        s.energy_equivalent_resistance = 0.5 * m * v_in * v_in / travel;
    }
    if (c.wall_displacement.size() == t.size())
      s.max_wall_displacement =
        *std::max_element(c.wall_displacement.begin() + static_cast<std::ptrdiff_t>(start),
                          c.wall_displacement.end());
    if (c.slab_velocity.size() == t.size())
    {
      for (std::size_t i = start; i < t.size(); ++i)
        if (c.slab_velocity[i] <= 0)
        {
          s.time_to_stop = t[i] - t_c;
          break;
        }
      const double momentum = m * (v_in - c.slab_velocity.back());
      if (m > 0 && momentum > 0)
        s.impulse_momentum_ratio = trapezoid(t, force, 0, t.size() - 1) / momentum;
    }
  }

  std::string impulse_momentum_status(const io::FemCase &c)
  {
    if (!c.summary.impulse_momentum_ratio)
      return "not checked: the record has no contact, slab mass or change of the slab's momentum";
    const double ratio = *c.summary.impulse_momentum_ratio;
    if (std::abs(ratio - 1.0) <= impulse_momentum_tolerance)
      return "ok";
    return fmt::format("warning: the record's impulse ∫F dt is {:.4g} × the slab's momentum "
                       "change m (v_in + v_out) (tolerance {:.3g} %): the force history does not "
                       "account for the slab's motion (output interval too coarse for the force, "
                       "or a broken record)",
                       ratio,
                       100.0 * impulse_momentum_tolerance);
  }
} // namespace kimp::app
