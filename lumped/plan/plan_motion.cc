// Two-component ground motion: rotation of one or two records to an angle of incidence.
#include "lumped/plan/plan_motion.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kimp::lumped::plan
{
  namespace
  {
    void require_angle(const double angle)
    {
      if (!std::isfinite(angle))
        throw std::invalid_argument("ground motion in plan: angle is not finite");
    }
  } // namespace

  PlanGroundMotion along_angle(const GroundMotion &record, const double angle)
  {
    lumped::validate(record);
    require_angle(angle);
    const double     c = std::cos(angle), s = std::sin(angle);
    PlanGroundMotion m;
    m.dt   = record.dt;
    m.name = record.name;
    m.x.reserve(record.acceleration.size());
    m.y.reserve(record.acceleration.size());
    for (const double a : record.acceleration)
    {
      m.x.push_back(a * c);
      m.y.push_back(a * s);
    }
    return m;
  }

  PlanGroundMotion
  two_components(const GroundMotion &first, const GroundMotion &second, const double angle)
  {
    lumped::validate(first);
    if (second.acceleration.empty())
      throw std::invalid_argument("ground motion in plan: the second component of '" + first.name +
                                  "' is missing (no samples)");
    lumped::validate(second);
    require_angle(angle);
    if (first.dt != second.dt)
    {
      std::ostringstream msg;
      msg << "ground motion in plan: the components '" << first.name << "' (dt = " << first.dt
          << " s) and '" << second.name << "' (dt = " << second.dt
          << " s) must have the same sampling interval";
      throw std::invalid_argument(msg.str());
    }
    const double      c = std::cos(angle), s = std::sin(angle);
    const std::size_t n = std::max(first.acceleration.size(), second.acceleration.size());
    PlanGroundMotion  m;
    m.dt   = first.dt;
    m.name = first.name + "+" + second.name;
    m.x.resize(n);
    m.y.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double a1 = i < first.acceleration.size() ? first.acceleration[i] : 0.0;
      const double a2 = i < second.acceleration.size() ? second.acceleration[i] : 0.0;
      m.x[i]          = a1 * c - a2 * s;
      m.y[i]          = a1 * s + a2 * c;
    }
    return m;
  }

  void validate(const PlanGroundMotion &m)
  {
    if (!(std::isfinite(m.dt) && m.dt > 0.0))
    {
      std::ostringstream msg;
      msg << "ground motion in plan '" << m.name << "': dt = " << m.dt << " s (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
    if (m.x.empty() || m.x.size() != m.y.size())
      throw std::invalid_argument("ground motion in plan '" + m.name +
                                  "': " + std::to_string(m.x.size()) + " samples along x and " +
                                  std::to_string(m.y.size()) +
                                  " along y (need the same number, > 0)");
    for (std::size_t i = 0; i < m.x.size(); ++i)
      if (!std::isfinite(m.x[i]) || !std::isfinite(m.y[i]))
        throw std::invalid_argument("ground motion in plan '" + m.name + "': sample " +
                                    std::to_string(i) + " is not finite");
  }
} // namespace kimp::lumped::plan
