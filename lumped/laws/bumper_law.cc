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
    : params_(params)
  {
    detail::require_positive(name(), "k_b", params_.stiffness, "N/m^n");
    detail::require_exponent(name(), params_.exponent);
    detail::require_positive(name(), "delta_u", params_.ultimate_deformation, "m");
    detail::require_positive(name(), "k_w", params_.wall_stiffness, "N/m");
    detail::require_cor(name(), params_.cor);
    detail::require_positive(name(), "m_eff", params_.effective_mass, "kg");
    if (params_.a1)
      detail::require_positive(name(), "a1", *params_.a1, "s/m");
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
    const double x = trial.deformation;
    if (x <= 0.0)
    {
      trial.in_contact = false;
      return;
    }
    if (!committed.in_contact)
      fix_impact_coefficient("bumper",
                             params_.cor,
                             params_.a1,
                             params_.effective_mass,
                             committed,
                             trial);
    double spring, tangent;
    if (x < params_.ultimate_deformation)
    {
      const double n      = params_.exponent;
      const double x_n1   = std::pow(x, n - 1.0);
      spring              = params_.stiffness * x_n1 * x;
      tangent             = n * params_.stiffness * x_n1;
      trial.stored_energy = spring * x / (n + 1.0);
    }
    else
    {
      const double excess = x - params_.ultimate_deformation;
      spring              = force_u_ + params_.wall_stiffness * excess;
      tangent             = params_.wall_stiffness;
      trial.stored_energy =
        energy_u_ + force_u_ * excess + 0.5 * params_.wall_stiffness * excess * excess;
    }
    trial.in_contact    = true;
    trial.elastic_force = spring;
    if (trial.rate >= 0.0)
    {
      trial.force     = spring;
      trial.stiffness = tangent;
      return;
    }
    const double g = 1.0 + trial.impact_coefficient * trial.rate;
    if (g <= 0.0)
      return; // clipped: no tension
    trial.force     = spring * g;
    trial.stiffness = tangent * g;
    trial.damping   = spring * trial.impact_coefficient;
  }
} // namespace kimp::lumped
