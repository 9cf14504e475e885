// Impact law 5, Hertzdamp (Muthukumar & DesRoches 2006; Ye, Li & Zhu 2009 as an option).
#include "lumped/laws/hertzdamp_law.h"

#include <cmath>

namespace kimp::lumped
{
  HertzdampLaw::HertzdampLaw(const Params &params)
    : ContactLaw(params)
  {
    detail::require_positive(name(), "k", params_.stiffness, "N/m^n");
    detail::require_exponent(name(), params_.exponent);
    detail::require_cor(name(), params_.cor);
    const double e = params_.cor;
    beta_          = params_.ye ? 8.0 * (1.0 - e) / (5.0 * e) : 0.75 * (1.0 - e * e);
  }

  double HertzdampLaw::stability_stiffness(double max_deformation) const
  {
    const double n = params_.exponent;
    if (n > 1.0)
      detail::require_positive(name(), "max_deformation", max_deformation, "m");
    const double x = n > 1.0 ? max_deformation : 1.0;
    return n * params_.stiffness * std::pow(x, n - 1.0) * (1.0 + beta_);
  }

  void HertzdampLaw::evaluate(const ContactState &committed, ContactState &trial) const
  {
    const double x = trial.deformation;
    if (x <= 0.0)
    {
      trial.in_contact = false;
      return;
    }
    const double n        = params_.exponent;
    const double x_n1     = detail::power_minus_one(x, n);
    const double spring   = params_.stiffness * x_n1 * x;
    trial.in_contact      = true;
    trial.elastic_force   = spring;
    trial.stored_energy   = spring * x / (n + 1.0);
    trial.impact_velocity = detail::impact_velocity_of("hertzdamp", committed, trial);
    if (!committed.in_contact)
    {
      // v_imp = δ̇ at this trial, so the dashpot term β·δ̇/v_imp is the constant β.
      trial.impact_coefficient = beta_ / trial.impact_velocity;
      trial.force              = spring * (1.0 + beta_);
      trial.stiffness          = n * params_.stiffness * x_n1 * (1.0 + beta_);
      trial.damping            = 0.0;
      return;
    }
    const double g  = 1.0 + trial.impact_coefficient * trial.rate;
    trial.force     = spring * g;
    trial.stiffness = n * params_.stiffness * x_n1 * g;
    trial.damping   = spring * trial.impact_coefficient;
  }
} // namespace kimp::lumped
