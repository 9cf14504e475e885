// Single friction pendulum bearing: parameter checks and the return mapping of the friction force.
#include "lumped/isolators/friction_pendulum_isolator.h"

#include <cmath>

namespace kimp::lumped
{
  void FrictionPendulumParameters::check() const
  {
    require_isolator(std::isfinite(W) && W > 0.0, "weight", W, "N", "must be > 0 and finite");
    require_isolator(std::isfinite(R) && R > 0.0, "radius", R, "m", "must be > 0 and finite");
    require_isolator(std::isfinite(mu_slow) && mu_slow >= 0.0 && mu_slow < 1.0,
                     "mu_slow",
                     mu_slow,
                     "",
                     "must be in [0, 1)");
    require_isolator(std::isfinite(mu_fast) && mu_fast >= mu_slow && mu_fast < 1.0,
                     "mu_fast",
                     mu_fast,
                     "",
                     "must be in [mu_slow, 1)");
    require_isolator(std::isfinite(rate) && rate >= 0.0,
                     "rate",
                     rate,
                     "s/m",
                     "must be >= 0 and finite");
    require_isolator(std::isfinite(k_init) && k_init > 0.0,
                     "k_init",
                     k_init,
                     "N/m",
                     "must be > 0 and finite");
  }

  FrictionPendulumIsolator::FrictionPendulumIsolator(const double W,
                                                     const double R,
                                                     const double mu_slow,
                                                     const double mu_fast,
                                                     const double rate,
                                                     const double k_init,
                                                     const double c)
    : HystereticLaw(c)
    , W_(W)
    , mu_slow_(mu_slow)
    , mu_fast_(mu_fast)
    , rate_(rate)
    , k_init_(k_init)
  {
    FrictionPendulumParameters{W, R, mu_slow, mu_fast, rate, k_init}.check();
    k_pendulum_ = W / R;
  }

  double FrictionPendulumIsolator::friction_coefficient(const double velocity) const
  {
    return mu_fast_ - (mu_fast_ - mu_slow_) * std::exp(-rate_ * std::abs(velocity));
  }

  IsolatorResponse FrictionPendulumIsolator::set_trial(const double displacement,
                                                       const double velocity)
  {
    trial_               = committed_;
    trial_.u             = displacement;
    const double e       = std::exp(-rate_ * std::abs(velocity));
    const double mu      = mu_fast_ - (mu_fast_ - mu_slow_) * e;
    const double q       = mu * W_;
    const double f_trial = committed_.f_s + k_init_ * (displacement - committed_.u);
    if (f_trial > q || f_trial < -q)
    {
      // Return mapping: slip |Δu_slip| = (|f_trial| − q)/k_init at the friction force ±q.
      const double sign = f_trial > 0.0 ? 1.0 : -1.0;
      trial_.f_s        = sign * q;
      trial_.sliding    = true;
      trial_.dissipated += q * (std::abs(f_trial) - q) / k_init_;
      const double dmu_dv = (mu_fast_ - mu_slow_) * rate_ * e * (velocity >= 0.0 ? 1.0 : -1.0);
      return {k_pendulum_ * displacement + trial_.f_s, k_pendulum_, sign * W_ * dmu_dv};
    }
    trial_.f_s     = f_trial;
    trial_.sliding = false;
    return {k_pendulum_ * displacement + f_trial, k_pendulum_ + k_init_, 0.0};
  }
} // namespace kimp::lumped
