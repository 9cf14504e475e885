// Recalibration of the impact coefficient of the non-linear hysteretic law (thesis §2, eqs.
// 2.18-2.23): C_imp = a1·(1 − COR²), a1 iterated until the loop area equals
// ΔE = ½·m_eff·(1 − COR²)·v_imp², then a1 = c/(COR^p1·m_eff^p2·v_imp^p3) fitted in log space.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "lumped/collision/two_body.h"

namespace kimp::lumped
{
  /// Grid and numerics of the calibration (SI; the thesis' set-up by default).
  struct CalibrationOptions
  {
    /// Nominal COR values; the thesis fitted COR in about 0.3-0.95 (lower COR: see the report).
    std::vector<double> cor_grid =
      {0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95};
    std::vector<double> velocity_grid = {0.5, 1.0, 1.5, 2.0, 2.5}; ///< v_imp, m/s
    std::vector<double> mass_grid =
      {100e3, 200e3, 300e3, 400e3, 500e3, 600e3, 700e3, 800e3, 900e3, 1000e3}; ///< m1, kg
    double           other_mass = 300e3;     ///< m2, kg (struck at rest)
    double           stiffness  = 2.3717e10; ///< k, N/m^1.5 (750 kN/mm^1.5, the thesis' default)
    double           exponent   = 1.5;       ///< n
    double           time_step  = 2e-5;      ///< Δt, s
    double           tolerance  = 1e-7; ///< relative tolerance on the energy balance of each root
    VelocityEstimate velocity_estimate = VelocityEstimate::backward_difference;

    /// @throws std::invalid_argument naming the bad field (each grid needs >= 2 distinct values).
    void validate() const;
  };

  /// One grid point of the calibration.
  struct CalibrationPoint
  {
    double      cor             = 0.0; ///< nominal COR
    double      impact_velocity = 0.0; ///< v_imp, m/s
    double      mass            = 0.0; ///< m1, kg
    double      effective_mass  = 0.0; ///< m_eff, kg
    double      a1              = 0.0; ///< calibrated a1, s/m
    double      a1_thesis       = 0.0; ///< a1 of (2.23), s/m
    double      cor_thesis      = 0.0; ///< effective COR with C_imp of (2.23)
    double      cor_fit         = 0.0; ///< effective COR with the fitted power law
    std::size_t n_evaluations   = 0;   ///< collisions simulated for the root
  };

  struct CalibrationResult
  {
    std::vector<CalibrationPoint> points;
    double                        c         = 0.0; ///< thesis: 1.55
    double                        p1        = 0.0; ///< COR exponent, thesis: 0.7076
    double                        p2        = 0.0; ///< m_eff exponent (kg), thesis: 0.0025
    double                        p3        = 0.0; ///< v_imp exponent, thesis: 0.9755
    double                        r_squared = 0.0; ///< of the fit of ln a1
    double max_cor_error_thesis             = 0.0; ///< max |COR_eff − COR|/COR with (2.23)
    double max_cor_error_fit                = 0.0; ///< the same with the fitted power law
  };

  /**
   * For every (COR, v_imp, m1) of the grid find a1 with Brent's method (bracket [0, a1_hi], a1_hi
   * doubled from the thesis value until the loss exceeds ΔE) so that the hysteretic law's
   * dissipated energy in one two-body collision equals ΔE; then fit the power law by linear least
   * squares on ln a1 and measure the COR error of (2.23) and of the fit over the grid.
   * @throws std::invalid_argument for bad options; CollisionError or std::runtime_error when a
   *         collision or a root search fails (the message names the grid point).
   */
  CalibrationResult calibrate_impact_coefficient(const CalibrationOptions &options);

  /// An interval [a, b] with f(a) and f(b), of opposite signs for a root to be bracketed.
  struct RootBracket
  {
    double a   = 0.0;
    double b   = 0.0;
    double f_a = 0.0;
    double f_b = 0.0;
  };

  /// When a root search stops: the bracket is below `x` or |f| <= `f`; after `max_iterations`
  /// it fails.
  struct RootTolerance
  {
    double      x              = 0.0;
    double      f              = 0.0;
    std::size_t max_iterations = 100;
  };

  /**
   * Root of f in the bracket by Brent's method (inverse quadratic interpolation, secant and
   * bisection). @throws std::invalid_argument if the root is not bracketed; std::runtime_error
   * without convergence in tolerance.max_iterations.
   */
  double brent_root(const std::function<double(double)> &f,
                    const RootBracket                   &bracket,
                    const RootTolerance                 &tolerance);
} // namespace kimp::lumped
