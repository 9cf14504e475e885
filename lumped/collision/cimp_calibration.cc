// Recalibration of C_imp of the non-linear hysteretic law (thesis eqs. 2.18-2.23) by energy
// matching in two-body collisions and a log-space least-squares power-law fit.
#include "lumped/collision/cimp_calibration.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "lumped/laws/hysteretic_law.h"

namespace kimp::lumped
{
  namespace
  {
    void require_grid(const std::vector<double> &grid,
                      const std::string         &name,
                      double                     lower,
                      double                     upper,
                      const std::string         &range)
    {
      const std::set<double> distinct(grid.begin(), grid.end());
      if (distinct.size() < 2)
        throw std::invalid_argument("calibration: " + name + " has " +
                                    std::to_string(distinct.size()) +
                                    " distinct values (must have >= 2 to fit an exponent)");
      for (const double value : grid)
        detail::require_parameter(value > lower && value <= upper,
                                  "calibration",
                                  name + " entry",
                                  value,
                                  "",
                                  range);
    }

    /// The two bodies of a grid point: m1 at v_imp against the other mass at rest.
    TwoBodySetup grid_setup(const CalibrationOptions &options, double mass, double velocity)
    {
      TwoBodySetup setup;
      setup.mass_1            = mass;
      setup.mass_2            = options.other_mass;
      setup.velocity_1        = velocity;
      setup.velocity_2        = 0.0;
      setup.time_step         = options.time_step;
      setup.velocity_estimate = options.velocity_estimate;
      setup.record_history    = false;
      return setup;
    }

    /// Simulate one collision of the hysteretic law with the given a1 (unset: eq. 2.23).
    TwoBodyResult collide(const CalibrationOptions &options,
                          const TwoBodySetup       &setup,
                          double                    cor,
                          std::optional<double>     a1)
    {
      HystereticLaw::Params params;
      params.stiffness      = options.stiffness;
      params.exponent       = options.exponent;
      params.cor            = cor;
      params.effective_mass = setup.effective_mass();
      params.a1             = a1;
      return simulate_two_body(HystereticLaw(params), setup);
    }
  } // namespace

  void CalibrationOptions::validate() const
  {
    const double inf = std::numeric_limits<double>::infinity();
    require_grid(cor_grid, "cor_grid", 0.0, 1.0 - 1e-12, "must be in (0, 1): COR = 1 needs no a1");
    require_grid(velocity_grid, "velocity_grid", 0.0, inf, "must be > 0 m/s");
    require_grid(mass_grid, "mass_grid", 0.0, inf, "must be > 0 kg");
    detail::require_positive("calibration", "other_mass", other_mass, "kg");
    detail::require_positive("calibration", "stiffness", stiffness, "N/m^n");
    detail::require_exponent("calibration", exponent);
    detail::require_positive("calibration", "time_step", time_step, "s");
    detail::require_parameter(tolerance > 0.0 && tolerance < 1.0,
                              "calibration",
                              "tolerance",
                              tolerance,
                              "",
                              "must be in (0, 1)");
  }

  double brent_root(const std::function<double(double)> &f,
                    const RootBracket                   &bracket,
                    const RootTolerance                 &tolerance)
  {
    auto [a, b, f_a, f_b] = bracket;
    if ((f_a > 0.0 && f_b > 0.0) || (f_a < 0.0 && f_b < 0.0))
    {
      std::ostringstream msg;
      msg << "brent_root: f(" << a << ") = " << f_a << " and f(" << b << ") = " << f_b
          << " (must have opposite signs)";
      throw std::invalid_argument(msg.str());
    }
    constexpr double eps = std::numeric_limits<double>::epsilon();
    double           c = b, f_c = f_b, d = b - a, e = d;
    for (std::size_t it = 0; it < tolerance.max_iterations; ++it)
    {
      if ((f_b > 0.0 && f_c > 0.0) || (f_b < 0.0 && f_c < 0.0))
      {
        c   = a;
        f_c = f_a;
        d = e = b - a;
      }
      if (std::abs(f_c) < std::abs(f_b))
      {
        // b becomes the best estimate; a and c the previous one.
        std::swap(b, c);
        std::swap(f_b, f_c);
        a   = c;
        f_a = f_c;
      }
      const double tol = 2.0 * eps * std::abs(b) + 0.5 * tolerance.x;
      const double xm  = 0.5 * (c - b);
      if (std::abs(xm) <= tol || std::abs(f_b) <= tolerance.f)
        return b;
      if (std::abs(e) >= tol && std::abs(f_a) > std::abs(f_b))
      {
        // Inverse quadratic interpolation (secant when only two points are distinct).
        const double s = f_b / f_a;
        double       p, q;
        if (a == c)
        {
          p = 2.0 * xm * s;
          q = 1.0 - s;
        }
        else
        {
          const double qa = f_a / f_c, r = f_b / f_c;
          p = s * (2.0 * xm * qa * (qa - r) - (b - a) * (r - 1.0));
          q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
        }
        if (p > 0.0)
          q = -q;
        p = std::abs(p);
        if (2.0 * p < std::min(3.0 * xm * q - std::abs(tol * q), std::abs(e * q)))
        {
          e = d;
          d = p / q;
        }
        else
        {
          d = xm;
          e = d;
        }
      }
      else
      {
        d = xm;
        e = d;
      }
      a   = b;
      f_a = f_b;
      b += std::abs(d) > tol ? d : std::copysign(tol, xm);
      f_b = f(b);
    }
    std::ostringstream msg;
    msg << "brent_root: no convergence in " << tolerance.max_iterations
        << " iterations (bracket around " << b << ", f = " << f_b << ")";
    throw std::runtime_error(msg.str());
  }

  CalibrationResult calibrate_impact_coefficient(const CalibrationOptions &options)
  {
    options.validate();
    CalibrationResult result;

    for (const double mass : options.mass_grid)
      for (const double v : options.velocity_grid)
        for (const double cor : options.cor_grid)
        {
          const TwoBodySetup setup = grid_setup(options, mass, v);

          CalibrationPoint point;
          point.cor             = cor;
          point.impact_velocity = v;
          point.mass            = mass;
          point.effective_mass  = setup.effective_mass();
          point.a1_thesis =
            impact_damping_coefficient(cor, point.effective_mass, v) / (1.0 - cor * cor);

          const double target = 0.5 * point.effective_mass * (1.0 - cor * cor) * v * v;
          const auto   excess = [&](double a1)
          {
            ++point.n_evaluations;
            return collide(options, setup, cor, a1).dissipated_energy - target;
          };

          // a1 = 0 dissipates nothing; double the upper end until the loop area exceeds ΔE
          // (a1 → ∞ loses all the approach energy, more than ΔE for COR > 0).
          double hi = 2.0 * point.a1_thesis, f_hi = excess(hi);
          for (int doubling = 0; f_hi < 0.0; ++doubling)
          {
            if (doubling == 60)
              throw std::runtime_error("calibration: no a1 bracket at COR " + std::to_string(cor) +
                                       ", v_imp " + std::to_string(v) + " m/s, m1 " +
                                       std::to_string(mass) + " kg");
            hi *= 2.0;
            f_hi = excess(hi);
          }
          point.a1         = brent_root(excess,
                                {0.0, hi, -target, f_hi},
                                {1e-12 * hi, options.tolerance * target, 200});
          point.cor_thesis = collide(options, setup, cor, std::nullopt).effective_cor;
          result.points.push_back(point);
        }

    // ln a1 = ln c − p1·ln COR − p2·ln m_eff − p3·ln v_imp, least squares.
    const auto      n = static_cast<Eigen::Index>(result.points.size());
    Eigen::MatrixXd A(n, 4);
    Eigen::VectorXd y(n);
    for (Eigen::Index i = 0; i < n; ++i)
    {
      const CalibrationPoint &p = result.points[i];
      A.row(i) << 1.0, -std::log(p.cor), -std::log(p.effective_mass), -std::log(p.impact_velocity);
      y(i) = std::log(p.a1);
    }
    const Eigen::VectorXd x        = A.colPivHouseholderQr().solve(y);
    const Eigen::VectorXd residual = y - A * x;
    const double          ss_tot   = (y.array() - y.mean()).square().sum();
    result.c                       = std::exp(x(0));
    result.p1                      = x(1);
    result.p2                      = x(2);
    result.p3                      = x(3);
    result.r_squared               = ss_tot > 0.0 ? 1.0 - residual.squaredNorm() / ss_tot : 1.0;

    for (CalibrationPoint &p : result.points)
    {
      const TwoBodySetup setup = grid_setup(options, p.mass, p.impact_velocity);
      const double       a1_fit =
        result.c / (std::pow(p.cor, result.p1) * std::pow(p.effective_mass, result.p2) *
                    std::pow(p.impact_velocity, result.p3));
      p.cor_fit = collide(options, setup, p.cor, a1_fit).effective_cor;
      result.max_cor_error_thesis =
        std::max(result.max_cor_error_thesis, std::abs(p.cor_thesis - p.cor) / p.cor);
      result.max_cor_error_fit =
        std::max(result.max_cor_error_fit, std::abs(p.cor_fit - p.cor) / p.cor);
    }
    return result;
  }
} // namespace kimp::lumped
