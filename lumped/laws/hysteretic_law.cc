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

  void require_impact_coefficient(const std::string    &law,
                                  double                cor,
                                  double                effective_mass,
                                  std::optional<double> a1)
  {
    detail::require_cor(law, cor);
    detail::require_positive(law, "m_eff", effective_mass, "kg");
    if (a1)
      detail::require_positive(law, "a1", *a1, "s/m");
  }

  bool enter_impact_contact(const char           *law,
                            double                cor,
                            std::optional<double> a1,
                            double                effective_mass,
                            const ContactState   &committed,
                            ContactState         &trial)
  {
    if (trial.deformation <= 0.0)
    {
      trial.in_contact = false;
      return false;
    }
    if (!committed.in_contact)
    {
      trial.impact_velocity = detail::impact_velocity_of(law, committed, trial);
      trial.impact_coefficient =
        a1 ? *a1 * (1.0 - cor * cor) :
             impact_damping_coefficient(cor, effective_mass, trial.impact_velocity);
    }
    trial.in_contact = true;
    return true;
  }

  HystereticLaw::HystereticLaw(const Params &params)
    : ContactLaw(params)
  {
    detail::require_positive(name(), "k", params_.stiffness, "N/m^n");
    detail::require_exponent(name(), params_.exponent);
    require_impact_coefficient(name(), params_.cor, params_.effective_mass, params_.a1);
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
    if (!enter_impact_contact(law_name, params_, committed, trial))
      return;
    const double x      = trial.deformation;
    const double n      = params_.exponent;
    const double x_n1   = detail::power_minus_one(x, n);
    const double spring = params_.stiffness * x_n1 * x;
    trial.stored_energy = spring * x / (n + 1.0);
    restitution_force(spring, n * params_.stiffness * x_n1, trial);
  }
} // namespace kimp::lumped
