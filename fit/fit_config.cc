// The shared fitting configuration and the status rules of a fit (docs/physics.md §4).
#include "fit/fit_config.h"

#include <cmath>
#include <fmt/format.h>

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

  std::string fit_verdict(const FitResult &fit)
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
    if (fit.contact_open_at_end)
      return fmt::format("warning: the contact lasts to the end of the FEM record ({:.4g} ms "
                         "after first contact): k fits a truncated contact (raise the FEM end "
                         "time)",
                         1e3 * fit.fem_contact_duration);
    if (fit.contact_extent > 0.0 &&
        fit.fem_contact_duration < min_window_coverage * fit.contact_extent)
      return fmt::format("warning: the misfit window covers {:.3g} % of the contact ({:.4g} of "
                         "{:.4g} ms; try force_only_contact or a larger separation_fraction)",
                         100.0 * fit.fem_contact_duration / fit.contact_extent,
                         1e3 * fit.fem_contact_duration,
                         1e3 * fit.contact_extent);
    // A zero-width interval is no precision: the misfit has a kink at the optimum (e.g. the
    // contact's end moving across a sample), where its curvature says nothing.
    if (fit.stiffness.fitted && std::isfinite(fit.stiffness.value) &&
        fit.stiffness.upper - fit.stiffness.lower <= 1.0e-6 * std::abs(fit.stiffness.value))
      return fmt::format("warning: confidence interval of k degenerate ([{:.6g}, {:.6g}] N/m^n "
                         "per m): the misfit has a kink at the optimum, its width is not known",
                         fit.stiffness.lower,
                         fit.stiffness.upper);
    return "ok";
  }
} // namespace kimp::fit
