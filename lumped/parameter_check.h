// The parameter checks of the lumped engine's constructors (laws, isolators, integrators): one
// message format, "<owner><key> = <value>[ <unit>] (<rule>)", thrown as std::invalid_argument.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

namespace kimp::lumped
{
  /**
   * Throws std::invalid_argument "<owner><key> = <value>[ <unit>] (<rule>)" unless ok, e.g.
   * owner "isolator." and key "K1", or owner "jankowski law: " and key "cor". Write ok as the
   * admissible range (value > 0.0, not !(value <= 0.0)) so that NaN fails it.
   */
  void require_parameter(bool             ok,
                         std::string_view owner,
                         std::string_view key,
                         double           value,
                         std::string_view unit,
                         std::string_view rule);

  /// require_parameter() of one owner: check(ok, key, value, rule) for a parameter without a
  /// unit, check(ok, key, value, unit, rule) for one with.
  class ParameterCheck
  {
  public:
    explicit ParameterCheck(std::string_view owner)
      : owner_(owner)
    {
    }
    void operator()(bool ok, std::string_view key, double value, std::string_view rule) const
    {
      require_parameter(ok, owner_, key, value, "", rule);
    }
    void operator()(bool             ok,
                    std::string_view key,
                    double           value,
                    std::string_view unit,
                    std::string_view rule) const
    {
      require_parameter(ok, owner_, key, value, unit, rule);
    }

  private:
    std::string_view owner_;
  };

  /**
   * The initial conditions of an integrator: u_0 and v_0 (m, m/s) empty (at rest) or one value per
   * DOF. @throws std::invalid_argument "<owner>initial_displacement.size = ..." otherwise.
   */
  void require_initial_state(std::string_view           owner,
                             const std::vector<double> &initial_displacement,
                             const std::vector<double> &initial_velocity,
                             std::size_t                n_dofs);

  /**
   * The time-stepping options every central-difference integrator shares, checked under the
   * keys "central_difference.<name>": dt (s, > 0, or 0 for auto), safety (0, 1], duration and
   * output_interval (s, >= 0), divergence_energy_factor (> 1).
   * @throws std::invalid_argument naming the first key out of range.
   */
  void check_stepping_options(double dt,
                              double safety,
                              double duration,
                              double output_interval,
                              double divergence_energy_factor);
} // namespace kimp::lumped
