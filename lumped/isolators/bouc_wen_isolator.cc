// Bouc-Wen isolator: parameter checks and the implicit update of the hysteretic variable z
// (bracketed Newton on the backward-Euler residual).
#include "lumped/isolators/bouc_wen_isolator.h"

#include <cmath>

namespace kimp::lumped
{
  namespace
  {
    /// Newton iterations before giving up on quadratic convergence (bisection guarantees
    /// progress, so this only bounds the work).
    constexpr int max_iterations = 100;
  } // namespace

  void BoucWenParameters::check() const
  {
    require_positive_isolator("K1", K1, "N/m");
    require_isolator_in("alpha", alpha, 0.0, 1.0, "", "post-yield ratio K2/K1, must be in [0, 1)");
    require_isolator(std::isfinite(F_y) && F_y > 0.0, "F_y", F_y, "N", "yield force, must be > 0");
    require_isolator(std::isfinite(A) && A > 0.0, "bw_A", A, "", "must be > 0");
    require_isolator(std::isfinite(beta) && std::isfinite(gamma) && beta >= std::abs(gamma),
                     "bw_beta",
                     beta,
                     "",
                     "must be >= |bw_gamma| (non-negative dissipation)");
    require_isolator(beta + gamma > 0.0, "bw_gamma", gamma, "", "must give bw_beta + bw_gamma > 0");
    require_isolator(std::isfinite(n) && n >= 1.0, "bw_n", n, "", "must be >= 1");
  }

  BoucWenIsolator::BoucWenIsolator(const BoucWenParameters &parameters, const double c)
    : HystereticIsolatorLaw(c)
    , p_(parameters)
  {
    p_.check();
    Q_     = p_.strength();
    u_y_   = p_.yield_displacement();
    z_max_ = std::pow(p_.A / (p_.beta + p_.gamma), 1.0 / p_.n);
    n_int_ = (p_.n == std::floor(p_.n) && p_.n <= 64.0) ? static_cast<int>(p_.n) : 0;
  }

  double BoucWenIsolator::power(const double a) const
  {
    if (n_int_ == 0)
      return std::pow(a, p_.n);
    double p = a;
    for (int i = 1; i < n_int_; ++i)
      p *= a;
    return p;
  }

  IsolatorResponse BoucWenIsolator::set_trial(const double displacement, const double velocity)
  {
    (void)velocity;
    trial_          = committed_;
    trial_.u        = displacement;
    const double du = displacement - committed_.u;
    const double K2 = p_.alpha * p_.K1;
    const double zc = committed_.z;
    if (du == 0.0)
      return {K2 * displacement + Q_ * zc,
              K2 + Q_ / u_y_ * (p_.A - power(std::abs(zc)) * (p_.gamma + p_.beta)),
              0.0};
    const double ratio = du / u_y_;
    // Ψ(z) = γ + β·sgn(z·du); |z|^n vanishes where Ψ jumps, so the residual is continuous and,
    // for β >= |γ|, increasing in z.
    const double psi_with = p_.gamma + p_.beta, psi_against = p_.gamma - p_.beta;
    // Root bracket: g(z_c) <= 0 <= g(z_max) for du > 0, g(−z_max) <= 0 <= g(z_c) for du < 0.
    double lo = du > 0.0 ? zc : -z_max_;
    double hi = du > 0.0 ? z_max_ : zc;
    if (lo > hi)
      std::swap(lo, hi);
    // |z|^n, |z|^(n−1)·sgn(z)·n and Ψ at z; g and ∂g/∂z.
    double     zn_psi = 0.0, dg = 1.0;
    const auto evaluate = [&](const double z)
    {
      const double az  = std::abs(z);
      const double psi = z * du > 0.0 ? psi_with : psi_against;
      const double zn  = power(az);
      zn_psi           = zn * psi;
      // n·|z|^(n−1)·sgn(z) = n·|z|^n / z (0 at z = 0 for n >= 1).
      dg = 1.0 + ratio * (az > 0.0 ? p_.n * zn / z : 0.0) * psi;
      return z - zc - ratio * (p_.A - zn_psi);
    };
    // Start from the explicit Euler step.
    double z = std::min(std::max(zc + ratio * (p_.A - power(std::abs(zc)) *
                                                        (zc * du > 0.0 ? psi_with : psi_against)),
                                 lo),
                        hi);
    for (int it = 0; it < max_iterations; ++it)
    {
      const double g = evaluate(z);
      if (g == 0.0)
        break;
      const double step = g / dg;
      // Converged: the Newton correction is at round-off (checked before the bracket test,
      // which a correction of a few ulps can fail).
      if (std::abs(step) <= 1e-15 * std::max(1.0, std::abs(z)))
      {
        z -= step;
        break;
      }
      (g > 0.0 ? hi : lo) = z;
      z                   = z - step > lo && z - step < hi ? z - step : 0.5 * (lo + hi);
    }
    evaluate(z);
    trial_.z           = z;
    const double dz_du = (p_.A - zn_psi) / u_y_ / dg;
    // Work of the hysteretic spring beyond its stored energy (>= 0 for β >= |γ|).
    trial_.dissipated += Q_ * z * du * zn_psi / p_.A;
    return {K2 * displacement + Q_ * z, K2 + Q_ * dz_du, 0.0};
  }
} // namespace kimp::lumped
