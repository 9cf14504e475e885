// Impact law 1, linear elastic spring F = k·δ (thesis eq. 2.4).
#include "lumped/laws/linear_elastic_law.h"

namespace kimp::lumped
{
  LinearElasticLaw::LinearElasticLaw(const Params &params)
    : ContactLaw(params)
  {
    detail::require_positive(name(), "k", params_.stiffness, "N/m");
  }

  void LinearElasticLaw::evaluate(const ContactState &committed, ContactState &trial) const
  {
    const double x = trial.deformation;
    if (!detail::enter_contact(x, committed, trial))
      return;
    trial.force         = params_.stiffness * x;
    trial.stiffness     = params_.stiffness;
    trial.elastic_force = trial.force;
    trial.stored_energy = 0.5 * params_.stiffness * x * x;
  }
} // namespace kimp::lumped
