// The message of a rejected parameter; see parameter_check.h.
#include "lumped/parameter_check.h"

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
} // namespace kimp::lumped
