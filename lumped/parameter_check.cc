// The message of a rejected parameter; see parameter_check.h.
#include "lumped/parameter_check.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kimp::lumped
{
  void require_parameter(const bool             ok,
                         const std::string_view owner,
                         const std::string_view key,
                         const double           value,
                         const std::string_view unit,
                         const std::string_view rule)
  {
    if (ok)
      return;
    std::ostringstream msg;
    msg << owner << key << " = " << value;
    if (!unit.empty())
      msg << ' ' << unit;
    msg << " (" << rule << ')';
    throw std::invalid_argument(msg.str());
  }

  void require_initial_state(const std::string_view     owner,
                             const std::vector<double> &initial_displacement,
                             const std::vector<double> &initial_velocity,
                             const std::size_t          n_dofs)
  {
    const auto check = [&](const std::vector<double> &values, const char *key)
    {
      require_parameter(values.empty() || values.size() == n_dofs,
                        owner,
                        key,
                        static_cast<double>(values.size()),
                        "",
                        "must be 0 or the number of DOFs");
    };
    check(initial_displacement, "initial_displacement.size");
    check(initial_velocity, "initial_velocity.size");
  }

  void check_stepping_options(const double dt,
                              const double safety,
                              const double duration,
                              const double output_interval,
                              const double divergence_energy_factor)
  {
    const ParameterCheck check("central_difference.");
    check(dt >= 0.0 && std::isfinite(dt), "dt", dt, "must be > 0 s, or 0 for auto");
    check(safety > 0.0 && safety <= 1.0, "safety", safety, "must be in (0, 1]");
    check(duration >= 0.0 && std::isfinite(duration),
          "duration",
          duration,
          "must be >= 0 s (0: the record's length)");
    check(output_interval >= 0.0 && std::isfinite(output_interval),
          "output_interval",
          output_interval,
          "must be >= 0 s (0: no histories)");
    check(divergence_energy_factor > 1.0,
          "divergence_energy_factor",
          divergence_energy_factor,
          "must be > 1");
  }
} // namespace kimp::lumped
