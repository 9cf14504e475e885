// The shared fitting configuration and the status rules of a fit (docs/physics.md §4).
#include "fit/fit_config.h"

#include <cmath>
#include <fmt/format.h>
#include <string>
#include <vector>

namespace kimp::fit
{
  FitOptions fit_options(const FitConfig &config, FitOptions base)
  {
    base.separation_fraction = config.separation_fraction;
    base.tail_fraction       = config.tail_fraction;
    base.contact_threshold   = config.contact_threshold;
    base.displacement_weight = config.displacement_weight;
    return base;
  }

  std::vector<FitVariant> fit_variants(const FitConfig &config)
  {
    return standard_fit_variants(fit_options(config), config.cor);
  }

  std::string fit_verdict(const FitResult &fit, double peak_tolerance)
  {
    const auto unbounded = [](const FitParameter &p)
    { return p.fitted && !(std::isfinite(p.lower) && std::isfinite(p.upper)); };
    if (unbounded(fit.stiffness) || (fit.stiffness.fitted && !(fit.stiffness.lower > 0.0)))
      return fmt::format(
        "failed: confidence interval of k unbounded ([{:.4g}, {:.4g}] N/m^n per m)",
        fit.stiffness.lower,
        fit.stiffness.upper);
    if (unbounded(fit.cor))
      return fmt::format("failed: confidence interval of the COR unbounded ([{:.4g}, {:.4g}])",
                         fit.cor.lower,
                         fit.cor.upper);
    if (unbounded(fit.exponent))
      return fmt::format("failed: confidence interval of the exponent unbounded ([{:.4g}, {:.4g}])",
                         fit.exponent.lower,
                         fit.exponent.upper);
    constexpr double at_bound = 1.0e-3;
    if (fit.exponent.fitted && fit.exponent.value - 1.0 < at_bound)
      return fmt::format("failed: exponent n = {:.6g} at its lower bound 1 (the data are not "
                         "Hertz-like)",
                         fit.exponent.value);
    if (fit.cor.fitted && (fit.cor.value < at_bound || fit.cor.value > 1.0 - at_bound))
      return fmt::format("failed: COR = {:.6g} at its bound (0 or 1)", fit.cor.value);
    std::vector<std::string> warnings;
    if (fit.contact_open_at_end)
      warnings.push_back(
        fmt::format("the contact lasts to the end of the FEM record ({:.4g} ms "
                    "after first contact): k fits a truncated contact (raise the FEM end "
                    "time)",
                    1e3 * fit.fem_contact_duration));
    if (fit.contact_extent > 0.0 &&
        fit.fem_contact_duration < min_window_coverage * fit.contact_extent)
      warnings.push_back(
        fmt::format("the misfit window covers {:.3g} % of the contact ({:.4g} of "
                    "{:.4g} ms; try force_only_contact or a larger separation_fraction)",
                    100.0 * fit.fem_contact_duration / fit.contact_extent,
                    1e3 * fit.fem_contact_duration,
                    1e3 * fit.contact_extent));
    // A zero-width interval is no precision: the misfit has a kink at the optimum (e.g. the
    // contact's end moving across a sample), where its curvature says nothing.
    if (fit.stiffness.fitted && std::isfinite(fit.stiffness.value) &&
        fit.stiffness.upper - fit.stiffness.lower <= 1.0e-6 * std::abs(fit.stiffness.value))
      warnings.push_back(
        fmt::format("confidence interval of k degenerate ([{:.6g}, {:.6g}] N/m^n "
                    "per m): the misfit has a kink at the optimum, its width is not known",
                    fit.stiffness.lower,
                    fit.stiffness.upper));
    // k is fitted to the whole pulse; a wall is sized from its peak force.
    const double peak = fit.peak_force_ratio();
    if (std::isfinite(peak) && std::abs(peak - 1.0) > peak_tolerance)
      warnings.push_back(fmt::format("the fitted peak force is {:.3g} % of the FEM's ({:.4g} of "
                                     "{:.4g} kN/m, tolerance {:.3g} %): k reproduces the pulse, "
                                     "not its peak (size the wall from the FEM peak force)",
                                     100.0 * peak,
                                     1e-3 * fit.model_peak_force,
                                     1e-3 * fit.fem_peak_force,
                                     100.0 * peak_tolerance));
    if (warnings.empty())
      return "ok";
    std::string text = "warning: " + warnings.front();
    for (std::size_t i = 1; i < warnings.size(); ++i)
      text += "; " + warnings[i];
    return text;
  }
} // namespace kimp::fit
