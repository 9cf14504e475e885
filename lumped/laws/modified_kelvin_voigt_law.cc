// Impact law 3, modified Kelvin-Voigt with permanent indentation (thesis eq. 2.16).
#include "lumped/laws/modified_kelvin_voigt_law.h"

namespace kimp::lumped
{
  void ModifiedKelvinVoigtLaw::evaluate(const ContactState &committed, ContactState &trial) const
  {
    const double x = trial.deformation - committed.permanent_indentation;
    if (x <= 0.0)
    {
      trial.in_contact = false;
      return;
    }
    const double force = params_.stiffness * x + damping_ * trial.rate;
    if (force < 0.0)
    {
      // Contact ends: the remaining deformation is set permanently, its spring energy is lost.
      trial.in_contact            = false;
      trial.permanent_indentation = trial.deformation;
      trial.released_energy       = 0.5 * params_.stiffness * x * x;
      return;
    }
    if (!committed.in_contact)
      trial.impact_velocity = trial.rate;
    trial.in_contact    = true;
    trial.force         = force;
    trial.stiffness     = params_.stiffness;
    trial.damping       = damping_;
    trial.elastic_force = params_.stiffness * x;
    trial.stored_energy = 0.5 * params_.stiffness * x * x;
  }
} // namespace kimp::lumped
