// Bidirectional isolators: radial return of the bilinear and friction pendulum laws, backward
// Euler of the Park-Wen coupled Bouc-Wen law.
#include "lumped/plan/plan_isolators.h"

#include <cmath>
#include <stdexcept>

#include "lumped/isolators/bilinear_isolator.h"

namespace kimp::lumped::plan
{
  namespace
  {
    /// Newton iterations of one Bouc-Wen increment before it is halved.
    constexpr int max_newton = 50;
    /// Halvings of a Bouc-Wen increment before giving up.
    constexpr int max_halvings = 20;
  } // namespace

  PlanBilinearIsolator::PlanBilinearIsolator(const BilinearParameters &parameters, const double c)
    : HystereticIsolatorLaw(c)
    , p_(parameters)
  {
    p_.check(); // the planar isolator's checks, with its messages
  }

  double PlanBilinearIsolator::stored_energy() const
  {
    return 0.5 * p_.K2 * committed_.u.squaredNorm() +
           0.5 * committed_.f_ep.squaredNorm() / (p_.K1 - p_.K2);
  }

  PlanBoucWenIsolator::PlanBoucWenIsolator(const BoucWenParameters &parameters, const double c)
    : HystereticIsolatorLaw(c)
    , p_(parameters)
  {
    p_.check();
  }

  Point PlanBoucWenIsolator::update(const Point &z_c,
                                    const Point &du,
                                    double      &dissipated,
                                    const int    depth) const
  {
    const Point r = du / p_.yield_displacement();
    // Bracket w(z) = Σ_i (γ + β·sgn(du_i z_i))·z_i du_i and the residual's pieces at z.
    const auto factors = [&](const Point &z)
    {
      return Point(p_.gamma + p_.beta * (z.x() * du.x() > 0.0 ? 1.0 :
                                         z.x() * du.x() < 0.0 ? -1.0 :
                                                                0.0),
                   p_.gamma + p_.beta * (z.y() * du.y() > 0.0 ? 1.0 :
                                         z.y() * du.y() < 0.0 ? -1.0 :
                                                                0.0));
    };
    const auto scaled_power = [&](const double a, const double p)
    { return a > 0.0 ? std::pow(a, p) : 0.0; };
    // Explicit Euler start.
    Point z;
    {
      const Point  f = factors(z_c);
      const double w = f.x() * z_c.x() * r.x() + f.y() * z_c.y() * r.y();
      z              = z_c + p_.A * r - scaled_power(z_c.norm(), p_.n - 2.0) * w * z_c;
    }
    bool converged = false;
    for (int it = 0; it < max_newton; ++it)
    {
      const double    a  = z.norm();
      const Point     f  = factors(z);
      const double    w  = f.x() * z.x() * r.x() + f.y() * z.y() * r.y();
      const double    pw = scaled_power(a, p_.n - 2.0);
      const Point     g  = z - z_c - (p_.A * r - pw * w * z);
      Eigen::Matrix2d j  = Eigen::Matrix2d::Identity();
      if (a > 0.0)
      {
        const Point grad_w(f.x() * r.x(), f.y() * r.y());
        j += pw * (w * Eigen::Matrix2d::Identity() + z * grad_w.transpose()) +
             (p_.n - 2.0) * pw / (a * a) * w * z * z.transpose();
      }
      const Point step = j.partialPivLu().solve(g);
      z -= step;
      if (step.norm() <= 1e-15 * std::max(1.0, z.norm()))
      {
        converged = true;
        break;
      }
    }
    if (!converged || !z.allFinite())
    {
      if (depth >= max_halvings)
        throw std::runtime_error("bouc_wen isolator in plan: the backward-Euler update did not "
                                 "converge (displacement increment too large)");
      double      d_half = 0.0;
      const Point z_half = update(z_c, 0.5 * du, d_half, depth + 1);
      const Point z_end  = update(z_half, 0.5 * du, d_half, depth + 1);
      dissipated += d_half;
      return z_end;
    }
    const Point  f = factors(z);
    const double w = f.x() * z.x() * du.x() + f.y() * z.y() * du.y();
    // Work of the hysteretic spring beyond its stored energy, Q/A·|z|^n·w (>= 0 for β >= |γ|).
    dissipated += p_.strength() / p_.A * scaled_power(z.norm(), p_.n) * w;
    return z;
  }

  Point PlanBoucWenIsolator::set_trial(const Point &displacement, const Point & /*velocity*/)
  {
    trial_         = committed_;
    trial_.u       = displacement;
    const Point du = displacement - committed_.u;
    if (du.x() != 0.0 || du.y() != 0.0)
      trial_.z = update(committed_.z, du, trial_.dissipated, 0);
    return p_.alpha * p_.K1 * displacement + p_.strength() * trial_.z;
  }

  double PlanBoucWenIsolator::stored_energy() const
  {
    return 0.5 * p_.alpha * p_.K1 * committed_.u.squaredNorm() +
           0.5 * p_.strength() * p_.yield_displacement() * committed_.z.squaredNorm() / p_.A;
  }

  PlanFrictionPendulumIsolator::PlanFrictionPendulumIsolator(
    const FrictionPendulumParameters &parameters,
    const double                      c)
    : HystereticIsolatorLaw(c)
    , p_(parameters)
  {
    p_.check();
    k_pendulum_ = p_.W / p_.R;
  }

  Point PlanFrictionPendulumIsolator::set_trial(const Point &displacement, const Point &velocity)
  {
    const double mu      = p_.mu(velocity.norm());
    const double q       = mu * p_.W;
    const Point  f_trial = committed_.f_s + p_.k_init * (displacement - committed_.u);
    const double norm    = f_trial.norm();
    trial_.u             = displacement;
    trial_.dissipated    = committed_.dissipated;
    if (norm > q)
    {
      // Radial return: slip (|f_trial| − q)/k_init along f_trial at the friction force q.
      trial_.f_s = q * (f_trial / norm);
      trial_.dissipated += q * (norm - q) / p_.k_init;
    }
    else
      trial_.f_s = f_trial;
    return k_pendulum_ * displacement + trial_.f_s;
  }

  double PlanFrictionPendulumIsolator::stored_energy() const
  {
    return 0.5 * k_pendulum_ * committed_.u.squaredNorm() +
           0.5 * committed_.f_s.squaredNorm() / p_.k_init;
  }
} // namespace kimp::lumped::plan
