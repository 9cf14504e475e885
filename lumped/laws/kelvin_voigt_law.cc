// Impact law 2, Kelvin-Voigt F = k·δ + c·δ̇ (thesis eqs. 2.5-2.7, Anagnostopoulos 1988).
#include "lumped/laws/kelvin_voigt_law.h"

#include <cmath>

namespace kimp::lumped
{
  double kelvin_voigt_damping_ratio(double cor)
  {
    detail::require_cor("kelvin_voigt", cor);
    constexpr double pi = 3.14159265358979323846;
    const double     l  = std::log(cor);
    return -l / std::sqrt(pi * pi + l * l);
  }

  double cdm_damping_factor(double damping_ratio)
  {
    return std::sqrt(1.0 + damping_ratio * damping_ratio) - damping_ratio;
  }

  double kelvin_voigt_dashpot(double stiffness, double cor, double effective_mass)
  {
    return 2.0 * kelvin_voigt_damping_ratio(cor) * std::sqrt(stiffness * effective_mass);
  }

  double kelvin_voigt_stability_stiffness(double stiffness, double cor)
  {
    const double f = cdm_damping_factor(kelvin_voigt_damping_ratio(cor));
    return stiffness / (f * f);
  }

  void KelvinVoigtLaw::evaluate(const ContactState &committed, ContactState &trial) const
  {
    const double x = trial.deformation;
    if (!detail::enter_contact(x, committed, trial))
      return;
    trial.elastic_force = params_.stiffness * x;
    trial.stored_energy = 0.5 * params_.stiffness * x * x;
    // May be tensile near separation: the model's known flaw, kept on purpose.
    trial.force     = trial.elastic_force + damping_ * trial.rate;
    trial.stiffness = params_.stiffness;
    trial.damping   = damping_;
  }
} // namespace kimp::lumped
