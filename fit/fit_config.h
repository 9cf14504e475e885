// The one fitting configuration shared by `kimp fit` and `kimp study` (docs/physics.md §4
// "Fitting configuration"): force source, misfit window, COR, width; and the status rules.
#pragma once

#include <string>
#include <vector>

#include "fit/fitter.h"

namespace kimp::fit
{
  /**
   * What both routes to k (`kimp fem` + `kimp fit`, and `kimp study`) fit with. The keys, units,
   * ranges and meanings are declared once by visit() (app/laws/fit_run.h): the study's `fit:`
   * section and the flags of `kimp fit` are that declaration.
   */
  /// Largest relative miss of the FEM peak force by the fitted law's peak (|F_fit/F_FEM − 1|)
  /// for a fit to be "ok" rather than "warning" (FitConfig::peak_tolerance).
  inline constexpr double default_peak_tolerance = 0.25;

  struct FitConfig
  {
    double cor       = lumped::thesis_cor;    ///< COR of the fixed-COR fits, (0, 1]
    double width     = thesis_building_width; ///< building side W, m: k_total = k_per_m·W
    bool   raw_force = false; ///< fit the raw instead of the smoothed FEM contact force
    /// Contact window from the force alone (the FEM indentation of a chattering rigid slab turns
    /// negative while the force is still on, which would cut the window at the first bounce).
    bool   force_only_contact  = true;
    double separation_fraction = 1.0;    ///< FitOptions::separation_fraction (> 0)
    double tail_fraction       = 0.5;    ///< FitOptions::tail_fraction (>= 0)
    double contact_threshold   = 1.0e-3; ///< FitOptions::contact_threshold, (0, 1)
    /// FitOptions::displacement_weight: also fit the slab's advance since first contact (>= 0).
    double displacement_weight = 0.0;
    /// fit_verdict(): a fit whose peak force misses the FEM's by more than this is a warning.
    double peak_tolerance = default_peak_tolerance;
  };

  /// `base` with the window and misfit settings of `config`.
  FitOptions fit_options(const FitConfig &config, FitOptions base = {});

  /// standard_fit_variants() with the options and COR of `config`.
  std::vector<FitVariant> fit_variants(const FitConfig &config);

  /// Smallest share of the contact (first to last force above the threshold) that the misfit
  /// window must span for a fit to be "ok" rather than "warning".
  inline constexpr double min_window_coverage = 0.5;

  /**
   * Status of a converged fit (docs/physics.md §4 "Status of a fit"): "failed: <reason>" if a
   * fitted parameter's confidence interval is unbounded (non-finite, or k's lower bound not > 0)
   * or a fitted exponent or COR sits at its bound (n − 1 < 1e-3; COR < 1e-3 or > 1 − 1e-3);
   * "warning: <reasons>" (joined by "; ") if the FEM contact lasts to the end of its record (a
   * truncated contact), the misfit window spans less than min_window_coverage of the contact,
   * k's confidence interval is degenerate, or the fitted peak force misses the FEM's by more
   * than `peak_tolerance` (|FitResult::peak_force_ratio() − 1| > peak_tolerance: the law matches
   * the pulse in the least-squares sense, not the force a wall is sized for); "ok" otherwise.
   */
  std::string fit_verdict(const FitResult &fit, double peak_tolerance = default_peak_tolerance);
} // namespace kimp::fit
