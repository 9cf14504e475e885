// Impact law 6, the thesis' non-linear hysteretic law (eqs. 2.17-2.23).
#include "lumped/laws/hysteretic_law.h"

#include <cmath>

namespace kimp::lumped
{
  double impact_damping_coefficient(double cor, double effective_mass, double impact_velocity)
  {
    detail::require_cor("hysteretic", cor);
    detail::require_positive("hysteretic", "m_eff", effective_mass, "kg");
    detail::require_positive("hysteretic", "v_imp", impact_velocity, "m/s");
    return 1.55 * (1.0 - cor * cor) /
           (std::pow(cor, 0.7076) * std::pow(effective_mass, 0.0025) *
            std::pow(impact_velocity, 0.9755));
  }

  void fix_impact_coefficient(const char           *law,
                              double                cor,
                              std::optional<double> a1,
                              double                effective_mass,
                              const ContactState   &committed,
                              ContactState         &trial)
  {
    trial.impact_velocity = detail::impact_velocity_of(law, committed, trial);
    trial.impact_coefficient =
      a1 ? *a1 * (1.0 - cor * cor) :
           impact_damping_coefficient(cor, effective_mass, trial.impact_velocity);
  }

  HystereticLaw::HystereticLaw(const Params &params)
    : params_(params)
  {
    detail::require_positive(name(), "k", params_.stiffness, "N/m^n");
    detail::require_exponent(name(), params_.exponent);
    detail::require_cor(name(), params_.cor);
    detail::require_positive(name(), "m_eff", params_.effective_mass, "kg");
    if (params_.a1)
      detail::require_positive(name(), "a1", *params_.a1, "s/m");
  }

  double HystereticLaw::stability_stiffness(double max_deformation) const
  {
    const double n = params_.exponent;
    if (n > 1.0)
      detail::require_positive(name(), "max_deformation", max_deformation, "m");
    const double x = n > 1.0 ? max_deformation : 1.0;
    return n * params_.stiffness * std::pow(x, n - 1.0);
  }

  void HystereticLaw::evaluate(const ContactState &committed, ContactState &trial) const
  {
    const double x = trial.deformation;
    if (x <= 0.0)
    {
      trial.in_contact = false;
      return;
    }
    if (!committed.in_contact)
      fix_impact_coefficient("hysteretic",
                             params_.cor,
                             params_.a1,
                             params_.effective_mass,
                             committed,
                             trial);
    const double n       = params_.exponent;
    const double x_n1    = detail::power_minus_one(x, n);
    const double spring  = params_.stiffness * x_n1 * x;
    const double tangent = n * params_.stiffness * x_n1;
    trial.in_contact     = true;
    trial.elastic_force  = spring;
    trial.stored_energy  = spring * x / (n + 1.0);
    if (trial.rate >= 0.0)
    {
      trial.force     = spring;
      trial.stiffness = tangent;
      return;
    }
    const double g = 1.0 + trial.impact_coefficient * trial.rate;
    if (g <= 0.0)
      return; // clipped: no tension, the bodies separate while δ > 0
    trial.force     = spring * g;
    trial.stiffness = tangent * g;
    trial.damping   = spring * trial.impact_coefficient;
  }
} // namespace kimp::lumped
