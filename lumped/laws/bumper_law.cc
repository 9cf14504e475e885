// Impact law 7, rubber bumper with wall (thesis eqs. 6.2-6.4).
#include "lumped/laws/bumper_law.h"

#include <algorithm>
#include <cmath>

#include "lumped/laws/hysteretic_law.h"

namespace kimp::lumped
{
  double bumper_stiffness(double area, double modulus, double thickness, double exponent, int count)
  {
    detail::require_positive("bumper", "area", area, "m^2");
    detail::require_positive("bumper", "K_r", modulus, "N/m^2");
    detail::require_positive("bumper", "thickness", thickness, "m");
    detail::require_exponent("bumper", exponent);
    detail::require_parameter(count >= 1, "bumper", "count", count, "", "must be >= 1");
    return count * 2.25 * area * modulus / std::pow(thickness, exponent);
  }

  BumperLaw::BumperLaw(const Params &params)
    : ContactLaw(params)
  {
    detail::require_positive(name(), "k_b", params_.stiffness, "N/m^n");
    detail::require_exponent(name(), params_.exponent);
    detail::require_positive(name(), "delta_u", params_.ultimate_deformation, "m");
    detail::require_positive(name(), "k_w", params_.wall_stiffness, "N/m");
    require_impact_coefficient(name(), params_.cor, params_.effective_mass, params_.a1);
    force_u_  = params_.stiffness * std::pow(params_.ultimate_deformation, params_.exponent);
    energy_u_ = force_u_ * params_.ultimate_deformation / (params_.exponent + 1.0);
  }

  double BumperLaw::stability_stiffness(double max_deformation) const
  {
    detail::require_positive(name(), "max_deformation", max_deformation, "m");
    const double n        = params_.exponent;
    const double x        = std::min(max_deformation, params_.ultimate_deformation);
    const double k_rubber = n * params_.stiffness * std::pow(x, n - 1.0);
    return max_deformation > params_.ultimate_deformation ?
             std::max(k_rubber, params_.wall_stiffness) :
             k_rubber;
  }

  void BumperLaw::evaluate(const ContactState &committed, ContactState &trial) const
  {
    if (!enter_impact_contact(law_name, params_, committed, trial))
      return;
    const double x = trial.deformation;
    if (x < params_.ultimate_deformation)
    {
      const double n      = params_.exponent;
      const double x_n1   = std::pow(x, n - 1.0);
      const double spring = params_.stiffness * x_n1 * x;
      trial.stored_energy = spring * x / (n + 1.0);
      restitution_force(spring, n * params_.stiffness * x_n1, trial);
      return;
    }
    const double excess = x - params_.ultimate_deformation;
    trial.stored_energy =
      energy_u_ + force_u_ * excess + 0.5 * params_.wall_stiffness * excess * excess;
    restitution_force(force_u_ + params_.wall_stiffness * excess, params_.wall_stiffness, trial);
  }
} // namespace kimp::lumped
