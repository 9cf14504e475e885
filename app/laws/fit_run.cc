// `kimp fit`: FEM force histories -> impact stiffness table (docs/physics.md §4 "Fit").
#include "app/laws/fit_run.h"

#include <chrono>
#include <cstdint>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "base/format.h"
#include "base/logging.h"
#include "io/results_file.h"
#include "io/summary.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::fit;
  namespace
  {
    std::string number(double value)
    {
      return fmt::format("{:.6g}", value);
    }

  } // namespace

  void
  write_fit_result(ResultsGroup &group, const FitResult &fit, double width, FitResultLayout layout)
  {
    const bool        full = layout == FitResultLayout::full;
    const std::string unit = stiffness_si_unit(fit.exponent.value, true);
    group.write_scalar("stiffness", fit.stiffness.value, unit);
    group.write_scalar("stiffness_lower", fit.stiffness.lower, unit);
    group.write_scalar("stiffness_upper", fit.stiffness.upper, unit);
    group.write_scalar("stiffness_total",
                       fit.stiffness.value * width,
                       stiffness_si_unit(fit.exponent.value));
    group.write_scalar("cor", fit.cor.value, "1");
    if (full)
    {
      group.write_scalar("cor_lower", fit.cor.lower, "1");
      group.write_scalar("cor_upper", fit.cor.upper, "1");
    }
    group.write_scalar("exponent", fit.exponent.value, "1");
    group.write_scalar("normalised_rms", fit.normalised_rms, "1");
    group.write_scalar("model_effective_cor", fit.model_effective_cor, "1");
    group.write_scalar("peak_force_ratio", fit.peak_force_ratio(), "1");
    group.write_scalar("impulse_ratio", fit.impulse_ratio(), "1");
    group.write_scalar("contact_duration_ratio", fit.contact_duration_ratio(), "1");
    if (!full)
    {
      group.write("time", fit.time, "s");
      group.write("fem_force", fit.fem_force, "N/m");
      group.write("model_force", fit.model_force, "N/m");
      return;
    }
    group.write_scalar("model_peak_force", fit.model_peak_force, "N/m");
    group.write_scalar("fem_peak_force", fit.fem_peak_force, "N/m");
    group.write_scalar("model_impulse", fit.model_impulse, "N*s/m");
    group.write_scalar("fem_impulse", fit.fem_impulse, "N*s/m");
    group.write_scalar("model_contact_duration", fit.model_contact_duration, "s");
    group.write_scalar("fem_contact_duration", fit.fem_contact_duration, "s");
    group.write_scalar("contact_start", fit.contact_start, "s");
    group.set_attribute("law", fit.law);
    group.set_attribute("iterations", fit.iterations);
    group.set_attribute("lm_status", fit.status);
    std::vector<std::int64_t> steps(fit.time.size());
    for (std::size_t i = 0; i < steps.size(); ++i)
      steps[i] = static_cast<std::int64_t>(i);
    group.write_time_series("fem_force", steps, fit.time, fit.fem_force, 1, "N/m");
    group.write_time_series("model_force", steps, fit.time, fit.model_force, 1, "N/m");
  }

  fit::ForceHistory force_history(const io::FemCase &fem_case, bool smoothed_force)
  {
    fit::ForceHistory h;
    h.time = fem_case.time;
    if (smoothed_force && fem_case.smoothed_contact_force.empty())
      throw fit::FitError(fmt::format("FEM case '{}': smoothed_contact_force is empty (fit the raw "
                                      "contact_force instead)",
                                      fem_case.name));
    h.force             = smoothed_force ? fem_case.smoothed_contact_force : fem_case.contact_force;
    h.indentation       = fem_case.indentation;
    h.slab_displacement = fem_case.slab_displacement;
    return h;
  }

  FitResult
  fit_fem_case(const io::FemCase &fem_case, const FitVariant &variant, const FitConfig &config)
  {
    ForceHistory history = force_history(fem_case, !config.raw_force);
    if (config.force_only_contact)
      history.indentation.clear();
    return fit_impact_law(history,
                          fem_case.slab_mass,
                          fem_case.impact_velocity,
                          variant.law,
                          fit_options(config, variant.options));
  }

  std::string
  fem_fit_verdict(const io::FemCase &fem_case, const fit::FitResult &fit, double peak_tolerance)
  {
    // A run ends on separation only once the slab comes in at no more than 5 % of its impact
    // speed (apparent COR >= -0.05); one stopped at its end time may have caught it moving in.
    const std::optional<double> cor     = fem_case.summary.apparent_cor;
    const auto                  stopped = fem_case.labels.find("stopped_on");
    const bool separated = stopped != fem_case.labels.end() && stopped->second == "separation";
    // Only an inelastic wall can give way: a linear wall may still be chattering with a rigid
    // slab at the end time, which is not failure.
    const double damage     = fem_case.summary.damage_dissipation.value_or(0.0);
    const double plastic    = fem_case.summary.plastic_dissipation.value_or(0.0);
    const double dissipated = plastic + damage;
    const double energy =
      0.5 * fem_case.slab_mass * fem_case.impact_velocity * fem_case.impact_velocity;
    const std::string from_fit = fit_verdict(fit, peak_tolerance);
    if (!cor || !(dissipated > 1.0e-2 * energy))
      return from_fit;
    // At the end time the slab keeps more than a quarter of its kinetic energy moving in: the
    // wall has broken, not stopped it.
    if (!separated && *cor < -0.5)
      return fmt::format(
        "failed: the slab passes through (apparent COR {:.3g} at the end time: it keeps {:.3g} % "
        "of its kinetic energy moving into the wall): the wall or the backfill fails during the "
        "impact (damage {:.4g} J/m, plastic {:.4g} J/m), so the run has no impact stiffness",
        *cor,
        100.0 * *cor * *cor,
        damage,
        plastic);
    if (from_fit.rfind("failed", 0) == 0)
      return from_fit;
    // Stopped, not rebounded: less than 1 % of the impact energy leaves with the slab.
    if (*cor < yielding_wall_cor)
      return fmt::format(
        "warning: the wall yields: {} (apparent COR {:.3g}{}; material dissipation {:.3g} % of "
        "the impact energy), so k is the equivalent stiffness of a yielding wall{}",
        !separated && *cor < 0.0 ? "the slab still moves in at the end time" :
                                   "the slab is stopped, not rebounded",
        *cor,
        separated ? "" : " at the end time",
        100.0 * dissipated / energy,
        from_fit == "ok" ? "" : "; " + from_fit);
    return from_fit;
  }

  namespace
  {
    /// The settings of `kimp fit` that its keys' ranges do not hold.
    void check_fit_config(const FitConfig &config)
    {
      if (!(config.width > 0.0))
        throw std::invalid_argument(fmt::format("fit: width = {} m (must be > 0)", config.width));
      if (!(config.cor > 0.0 && config.cor <= 1.0))
        throw std::invalid_argument(fmt::format("fit: cor = {} (must be in (0, 1])", config.cor));
      if (!(config.peak_tolerance > 0.0))
        throw std::invalid_argument(
          fmt::format("fit: peak_tolerance = {} (must be > 0)", config.peak_tolerance));
      if (!(config.displacement_weight >= 0.0))
        throw std::invalid_argument(
          fmt::format("fit: displacement_weight = {} (must be >= 0)", config.displacement_weight));
    }

    /// fit_table.csv's columns.
    const std::vector<std::string> &fit_table_header()
    {
      static const std::vector<std::string> header = {"case",
                                                      "wall_height_m",
                                                      "impact_velocity_m_per_s",
                                                      "variant",
                                                      "law",
                                                      "k_per_m",
                                                      "k_per_m_lower",
                                                      "k_per_m_upper",
                                                      "k_per_m_unit",
                                                      "k_total",
                                                      "k_total_unit",
                                                      "cor",
                                                      "cor_lower",
                                                      "cor_upper",
                                                      "exponent",
                                                      "normalised_rms",
                                                      "peak_force_ratio",
                                                      "impulse_ratio",
                                                      "contact_duration_ratio",
                                                      "status"};
      return header;
    }

    /// fit_table.csv's rows, summary.json's cases and the count of fits that are not "ok".
    struct FitOutputs
    {
      std::vector<std::vector<std::string>> rows;
      nlohmann::json                        cases    = nlohmann::json::array();
      int                                   failures = 0;
    };

    /// One variant fitted to one FEM case: its group of fit.h5 below `case_group`, its row, its
    /// summary case and its log line.
    void fit_variant(const FemCase    &fem_case,
                     const FitVariant &variant,
                     const FitConfig  &config,
                     ResultsGroup     &case_group,
                     FitOutputs       &out)
    {
      ResultsGroup group = case_group.case_group(variant.name);
      try
      {
        const FitResult   fit     = fit_fem_case(fem_case, variant, config);
        const std::string verdict = fem_fit_verdict(fem_case, fit, config.peak_tolerance);
        write_fit_result(group, fit, config.width, FitResultLayout::full);
        group.set_status(verdict);
        if (verdict != "ok")
        {
          ++out.failures;
          logger().warn("fit: {} {}: {}", fem_case.name, variant.name, verdict);
        }
        const double scale = stiffness_to_kn_per_mm(1.0, fit.exponent.value);
        out.rows.push_back({fem_case.name,
                            number(fem_case.wall_height),
                            number(fem_case.impact_velocity),
                            variant.name,
                            fit.law,
                            number(fit.stiffness_per_metre_display()),
                            number(fit.stiffness.lower * scale),
                            number(fit.stiffness.upper * scale),
                            fit.per_metre_unit(),
                            number(fit.total_stiffness_display(config.width)),
                            stiffness_display_unit(fit.exponent.value),
                            number(fit.cor.value),
                            number(fit.cor.lower),
                            number(fit.cor.upper),
                            number(fit.exponent.value),
                            number(fit.normalised_rms),
                            number(fit.peak_force_ratio()),
                            number(fit.impulse_ratio()),
                            number(fit.contact_duration_ratio()),
                            verdict});
        out.cases.push_back(
          {{"name", fem_case.name + "/" + variant.name},
           {"fem_case", fem_case.name},
           {"variant", variant.name},
           {"law", fit.law},
           {"status", verdict},
           {"wall_height", fem_case.wall_height},
           {"impact_velocity", fem_case.impact_velocity},
           {"stiffness_per_metre", fit.stiffness.value},
           {"stiffness_per_metre_unit", stiffness_si_unit(fit.exponent.value, true)},
           {"stiffness_per_metre_lower", fit.stiffness.lower},
           {"stiffness_per_metre_upper", fit.stiffness.upper},
           {"exponent", fit.exponent.value},
           {"cor", fit.cor.value},
           {"normalised_rms", fit.normalised_rms},
           {"peak_force_ratio", fit.peak_force_ratio()},
           {"impulse_ratio", fit.impulse_ratio()},
           {"contact_duration_ratio", fit.contact_duration_ratio()}});
        logger().info("fit: {} {}: k = {} {} (total {} {}), COR = {}, RMS/peak = {}, fitted/FEM "
                      "peak force {}, impulse {}, contact duration {}",
                      fem_case.name,
                      variant.name,
                      base::sig(fit.stiffness_per_metre_display()),
                      fit.per_metre_unit(),
                      base::sig(fit.total_stiffness_display(config.width)),
                      stiffness_display_unit(fit.exponent.value),
                      base::sig(fit.cor.value),
                      base::sig(fit.normalised_rms, 3),
                      base::sig(fit.peak_force_ratio(), 3),
                      base::sig(fit.impulse_ratio(), 3),
                      base::sig(fit.contact_duration_ratio(), 3));
      }
      catch (const std::exception &error)
      {
        ++out.failures;
        const std::string status = "failed: " + base::error_text(error);
        group.set_status(status);
        // No fit: empty cells up to the status.
        std::vector<std::string> row = {fem_case.name,
                                        number(fem_case.wall_height),
                                        number(fem_case.impact_velocity),
                                        variant.name,
                                        variant.law.law};
        row.resize(fit_table_header().size() - 1);
        row.push_back(status);
        out.rows.push_back(std::move(row));
        out.cases.push_back({{"name", fem_case.name + "/" + variant.name},
                             {"fem_case", fem_case.name},
                             {"variant", variant.name},
                             {"law", variant.law.law},
                             {"status", status},
                             {"wall_height", fem_case.wall_height},
                             {"impact_velocity", fem_case.impact_velocity}});
        logger().warn("fit: {} {}: {}", fem_case.name, variant.name, status);
      }
    }

    /// summary.json of `kimp fit`.
    nlohmann::json fit_summary(const FitCommandOptions                     &options,
                               const nlohmann::json                        &resolved,
                               const std::chrono::steady_clock::time_point &start,
                               const FitOutputs                            &out)
    {
      nlohmann::json summary = io::summary_preamble("fit");
      summary["fem_file"]    = options.fem_file.string();
      summary["wall_time"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      summary["options"]  = resolved;
      summary["units"]    = {{"wall_height", "m"},
                             {"impact_velocity", "m/s"},
                             {"width", "m"},
                             {"cor", "1"},
                             {"normalised_rms", "1"},
                             {"peak_force_ratio", "1"},
                             {"impulse_ratio", "1"},
                             {"contact_duration_ratio", "1"},
                             {"peak_tolerance", "1"},
                             {"wall_time", "s"}};
      summary["n_failed"] = out.failures;
      summary["cases"]    = out.cases;
      return summary;
    }
  } // namespace

  int run_fit_command(const FitCommandOptions &options)
  {
    const FitConfig &config = options.config;
    check_fit_config(config);
    const auto                 start = std::chrono::steady_clock::now();
    const std::vector<FemCase> cases = read_fem_cases(options.fem_file);
    const OutputDir            output(options.output);

    nlohmann::json resolved = nlohmann::json::parse(to_json_text(config, 0));
    resolved["fem_file"]    = options.fem_file.string();
    ResultsFile  file(output.file("fit.h5"), "", resolved.dump());
    ResultsGroup root     = file.root();
    ResultsGroup fit_root = root.group("fit");

    const std::vector<FitVariant> variants = fit_variants(config);
    FitOutputs                    out;
    for (const FemCase &fem_case : cases)
    {
      if (fem_case.status != "ok")
      {
        logger().warn("fit: case '{}' skipped, FEM status: {}", fem_case.name, fem_case.status);
        continue;
      }
      ResultsGroup case_group = fit_root.group(fem_case.name);
      case_group.write_scalar("wall_height", fem_case.wall_height, "m");
      for (const FitVariant &variant : variants)
        fit_variant(fem_case, variant, config, case_group, out);
    }
    write_csv_atomic(output.file("fit_table.csv"), fit_table_header(), out.rows);
    file.commit();
    write_json_atomic(output.file("summary.json"), fit_summary(options, resolved, start, out));
    return out.failures;
  }

} // namespace kimp::app
