// Impact law 4, Jankowski's non-linear viscoelastic model (thesis eqs. 2.9-2.12).
#include "lumped/laws/jankowski_law.h"

#include <cmath>

#include "lumped/laws/kelvin_voigt_law.h"

namespace kimp::lumped
{
  double jankowski_damping_ratio(double cor)
  {
    detail::require_cor("jankowski", cor);
    constexpr double pi = 3.14159265358979323846;
    return 4.5 * std::sqrt(5.0) * (1.0 - cor * cor) / (cor * (cor * (9.0 * pi - 16.0) + 16.0));
  }

  JankowskiLaw::JankowskiLaw(const Params &params)
    : ContactLaw(params)
  {
    detail::require_dashpot_law(name(), params_, "N/m^1.5");
    damping_ratio_ = jankowski_damping_ratio(params_.cor);
    damping_scale_ = 2.0 * damping_ratio_ * std::sqrt(params_.stiffness * params_.effective_mass);
  }

  double JankowskiLaw::stability_stiffness(double max_deformation) const
  {
    detail::require_positive(name(), "max_deformation", max_deformation, "m");
    const double f = cdm_damping_factor(damping_ratio_ / std::sqrt(1.5));
    return 1.5 * params_.stiffness * std::sqrt(max_deformation) / (f * f);
  }

  void JankowskiLaw::evaluate(const ContactState &committed, ContactState &trial) const
  {
    const double x = trial.deformation;
    if (!detail::enter_contact(x, committed, trial))
      return;
    const double sqrt_x = std::sqrt(x);
    trial.elastic_force = params_.stiffness * x * sqrt_x;
    trial.stored_energy = 0.4 * trial.elastic_force * x;
    trial.force         = trial.elastic_force;
    trial.stiffness     = 1.5 * params_.stiffness * sqrt_x;
    if (trial.rate > 0.0)
    {
      const double quarter = std::sqrt(sqrt_x);
      const double c       = damping_scale_ * quarter;
      trial.force += c * trial.rate;
      trial.stiffness += 0.25 * c / x * trial.rate;
      trial.damping = c;
    }
  }
} // namespace kimp::lumped
