// What the fits are read with: the units of a fitted stiffness, the standard set of fitted
// laws, and the uncertainty of a value over mesh or penalty refinement levels (see fitter.h).
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "fit/fitter.h"

namespace kimp::fit
{
  double stiffness_to_kn_per_mm(double stiffness, double exponent)
  {
    return stiffness * std::pow(1.0e-3, exponent + 1.0);
  }

  namespace
  {
    /// "<length>" for n = 1, "<length>^n" otherwise, then "/m" per metre of wall.
    std::string
    stiffness_unit(const char *force_per_length, double exponent, bool per_metre_of_wall)
    {
      const std::string n = fmt::format("{:.6g}", exponent);
      const std::string unit =
        n == "1" ? std::string(force_per_length) : std::string(force_per_length) + "^" + n;
      return per_metre_of_wall ? unit + "/m" : unit;
    }
  } // namespace

  std::string stiffness_display_unit(double exponent, bool per_metre_of_wall)
  {
    return stiffness_unit("kN/mm", exponent, per_metre_of_wall);
  }

  std::string stiffness_si_unit(double exponent, bool per_metre_of_wall)
  {
    return stiffness_unit("N/m", exponent, per_metre_of_wall);
  }

  namespace
  {
    double ratio(double fitted, double fem)
    {
      return fem > 0.0 && std::isfinite(fem) ? fitted / fem :
                                               std::numeric_limits<double>::quiet_NaN();
    }
  } // namespace

  double FitResult::peak_force_ratio() const
  {
    return ratio(model_peak_force, fem_peak_force);
  }

  double FitResult::impulse_ratio() const
  {
    return ratio(model_impulse, fem_impulse);
  }

  double FitResult::contact_duration_ratio() const
  {
    return ratio(model_contact_duration, fem_contact_duration);
  }

  double FitResult::stiffness_per_metre_display() const
  {
    return stiffness_to_kn_per_mm(stiffness.value, exponent.value);
  }

  double FitResult::total_stiffness_display(double width) const
  {
    return stiffness_per_metre_display() * width;
  }

  std::string FitResult::per_metre_unit() const
  {
    return stiffness_display_unit(exponent.value, true);
  }

  std::vector<FitVariant> standard_fit_variants(const FitOptions &base, double cor)
  {
    std::vector<FitVariant> variants;
    const auto add = [&](std::string name, std::string law, bool fit_cor, bool fit_exponent)
    {
      FitVariant variant;
      variant.name                 = std::move(name);
      variant.law.law              = std::move(law);
      variant.law.cor              = cor;
      variant.options              = base;
      variant.options.fit_cor      = fit_cor;
      variant.options.fit_exponent = fit_exponent;
      variants.push_back(std::move(variant));
    };
    add("kelvin_voigt_cor_fixed", "kelvin_voigt", false, false);
    add("jankowski_cor_fixed", "jankowski", false, false);
    add("kelvin_voigt_cor_free", "kelvin_voigt", true, false);
    add("jankowski_cor_free", "jankowski", true, false);
    add("hertz_free_exponent", "hysteretic", false, true);
    return variants;
  }

  LevelEstimate level_uncertainty(const std::vector<double> &values,
                                  double                     refinement_ratio,
                                  double                     assumed_order)
  {
    if (values.size() < 2)
      throw std::invalid_argument(
        fmt::format("level_uncertainty: {} values (need at least two levels)", values.size()));
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i]))
        throw std::invalid_argument(
          fmt::format("level_uncertainty: values[{}] = {} (must be finite)", i, values[i]));
    if (!(refinement_ratio > 1.0))
      throw std::invalid_argument(
        fmt::format("level_uncertainty: refinement_ratio = {} (must be > 1)", refinement_ratio));
    if (!(assumed_order > 0.0))
      throw std::invalid_argument(
        fmt::format("level_uncertainty: assumed_order = {} (must be > 0)", assumed_order));

    const std::size_t n = values.size();
    LevelEstimate     e;
    e.finest          = values[n - 1];
    e.previous        = values[n - 2];
    const double e21  = e.finest - e.previous;
    e.relative_change = e.finest != 0.0 ? std::abs(e21 / e.finest) : std::abs(e21);
    e.order_used      = assumed_order;
    if (n >= 3)
    {
      const double e32 = e.previous - values[n - 3];
      if (e21 != 0.0 && e21 * e32 > 0.0)
      {
        e.observed_order = std::log(e32 / e21) / std::log(refinement_ratio);
        if (e.observed_order >= 0.5 && e.observed_order <= 4.0)
          e.order_used = e.observed_order;
      }
    }
    e.extrapolated   = e.finest + e21 / (std::pow(refinement_ratio, e.order_used) - 1.0);
    e.error_estimate = std::abs(e.extrapolated - e.finest);
    e.relative_error = e.finest != 0.0 ? e.error_estimate / std::abs(e.finest) : e.error_estimate;
    return e;
  }
} // namespace kimp::fit
