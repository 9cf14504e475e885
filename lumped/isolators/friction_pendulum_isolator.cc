// Single friction pendulum bearing: parameter checks and the return mapping of the friction force.
#include "lumped/isolators/friction_pendulum_isolator.h"

#include <cmath>

namespace kimp::lumped
{
  void FrictionPendulumParameters::check() const
  {
    require_positive_isolator("weight", W, "N");
    require_positive_isolator("radius", R, "m");
    require_isolator_in("mu_slow", mu_slow, 0.0, 1.0, "", "must be in [0, 1)");
    require_isolator_in("mu_fast", mu_fast, mu_slow, 1.0, "", "must be in [mu_slow, 1)");
    require_non_negative_isolator("rate", rate, "s/m");
    require_positive_isolator("k_init", k_init, "N/m");
  }

  FrictionPendulumIsolator::FrictionPendulumIsolator(const FrictionPendulumParameters &parameters,
                                                     const double                      c)
    : HystereticIsolatorLaw(c)
    , p_(parameters)
  {
    p_.check();
    k_pendulum_ = p_.W / p_.R;
  }

  double FrictionPendulumIsolator::friction_coefficient(const double velocity) const
  {
    return p_.mu(std::abs(velocity));
  }

  IsolatorResponse FrictionPendulumIsolator::set_trial(const double displacement,
                                                       const double velocity)
  {
    trial_               = committed_;
    trial_.u             = displacement;
    const double e       = std::exp(-p_.rate * std::abs(velocity));
    const double mu      = p_.mu_fast - (p_.mu_fast - p_.mu_slow) * e;
    const double q       = mu * p_.W;
    const double f_trial = committed_.f_s + p_.k_init * (displacement - committed_.u);
    if (f_trial > q || f_trial < -q)
    {
      // Return mapping: slip |Δu_slip| = (|f_trial| − q)/k_init at the friction force ±q.
      const double sign = f_trial > 0.0 ? 1.0 : -1.0;
      trial_.f_s        = sign * q;
      trial_.sliding    = true;
      trial_.dissipated += q * (std::abs(f_trial) - q) / p_.k_init;
      const double dmu_dv =
        (p_.mu_fast - p_.mu_slow) * p_.rate * e * (velocity >= 0.0 ? 1.0 : -1.0);
      return {k_pendulum_ * displacement + trial_.f_s, k_pendulum_, sign * p_.W * dmu_dv};
    }
    trial_.f_s     = f_trial;
    trial_.sliding = false;
    return {k_pendulum_ * displacement + f_trial, k_pendulum_ + p_.k_init, 0.0};
  }
} // namespace kimp::lumped
