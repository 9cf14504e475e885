// Response summaries: energy residual, amplification factors (docs/physics.md §2).
#include "lumped/integrators/response.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kimp::lumped
{
  double EnergyBalance::residual_relative_error() const
  {
    const double left  = initial + input;
    const double right = kinetic + strain + viscous + hysteretic + contact_work;
    const double scale = std::max({std::abs(initial) + std::abs(input),
                                   std::abs(kinetic) + std::abs(strain) + std::abs(viscous) +
                                     std::abs(hysteretic) + std::abs(contact_work),
                                   1e-300});
    return std::abs(left - right) / scale;
  }

  double Response::max_interstorey_drift() const
  {
    double m = 0.0;
    for (const double d : peak_interstorey_drift)
      m = std::max(m, d);
    return m;
  }

  double ContactResult::largest_impact_velocity() const
  {
    double v = 0.0;
    for (const ImpactEvent &impact : impacts)
      v = std::max(v, std::abs(impact.velocity));
    return v;
  }

  std::vector<double> ContactResult::impact_column(double ImpactEvent::*column) const
  {
    std::vector<double> values;
    values.reserve(impacts.size());
    for (const ImpactEvent &impact : impacts)
      values.push_back(impact.*column);
    return values;
  }

  std::size_t Response::n_impacts() const
  {
    std::size_t n = 0;
    for (const ContactResult &c : contacts)
      n += c.impacts.size();
    return n;
  }

  namespace
  {
    std::vector<double>
    ratios(const std::vector<double> &a, const std::vector<double> &b, const char *what)
    {
      if (a.size() != b.size())
        throw std::invalid_argument(std::string("amplification: ") + what +
                                    " sizes differ between the two responses");
      std::vector<double> r(a.size());
      for (std::size_t i = 0; i < a.size(); ++i)
        r[i] = b[i] == 0.0 ? (a[i] == 0.0 ? 1.0 : INFINITY) : a[i] / b[i];
      return r;
    }
  } // namespace

  Amplification amplification_factors(const Response &with_pounding,
                                      const Response &without_pounding)
  {
    return {ratios(with_pounding.peak_displacement,
                   without_pounding.peak_displacement,
                   "peak_displacement"),
            ratios(with_pounding.peak_absolute_acceleration,
                   without_pounding.peak_absolute_acceleration,
                   "peak_absolute_acceleration"),
            ratios(with_pounding.peak_interstorey_drift,
                   without_pounding.peak_interstorey_drift,
                   "peak_interstorey_drift")};
  }
} // namespace kimp::lumped
