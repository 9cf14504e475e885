// Cost and plausibility of a `kimp lumped` case: the integrator options of its integration
// section, the estimate of its steps, history rows and wall time before it runs, the step and
// memory budget, and the plausibility of its peaks after it ran.
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "app/lumped/lumped_run_internal.h"
#include "io/units.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::app
{
  using namespace kimp::io;

  namespace lumped_internal
  {
    lumped::CentralDifferenceOptions cdm_options(const IntegrationScene      &in,
                                                 const std::optional<double> &dt)
    {
      lumped::CentralDifferenceOptions options;
      options.dt                       = dt.value_or(0.0);
      options.safety                   = in.safety;
      options.expected_max_penetration = in.expected_max_penetration;
      options.duration                 = in.duration.value_or(0.0);
      options.output_interval          = in.output_interval;
      options.law_velocity             = in.law_velocity;
      return options;
    }

    lumped::NewmarkOptions newmark_options(const IntegrationScene      &in,
                                           const std::optional<double> &dt)
    {
      lumped::NewmarkOptions options;
      options.dt              = dt.value_or(0.0);
      options.duration        = in.duration.value_or(0.0);
      options.output_interval = in.output_interval;
      return options;
    }

    Integration integration_of(const IntegrationScene &in, const std::optional<double> &dt)
    {
      Integration integration;
      integration.method                 = in.method;
      integration.variable               = variable_time_step(in);
      integration.cdm                    = cdm_options(in, dt);
      integration.adaptive.contact_steps = in.contact_steps;
      integration.newmark                = newmark_options(in, dt);
      return integration;
    }

    Integration companion_integration(Integration integration, const lumped::Response &main)
    {
      if (integration.method == IntegrationMethod::cdm && !integration.variable)
        integration.cdm.dt = main.dt;
      return integration;
    }

    double planned_step(const lumped::PoundingModel &model,
                        const Integration           &integration,
                        double                       record_dt)
    {
      if (integration.method == IntegrationMethod::newmark)
        return integration.newmark.dt > 0.0 ? integration.newmark.dt : record_dt;
      if (integration.variable)
        return lumped::AdaptiveCentralDifference(model, integration.cdm, integration.adaptive)
          .large_step(record_dt);
      return lumped::CentralDifference(model, integration.cdm).time_step(record_dt);
    }

    Integrated integrate(const lumped::PoundingModel &model,
                         const Integration           &integration,
                         const lumped::GroundMotion  &motion)
    {
      Integrated run;
      if (integration.method == IntegrationMethod::newmark)
        run.response = lumped::NewmarkIntegrator(model, integration.newmark).run(motion);
      else if (integration.variable)
      {
        lumped::AdaptiveStepReport report;
        run.response =
          lumped::AdaptiveCentralDifference(model, integration.cdm, integration.adaptive)
            .run(motion, &report);
        run.adaptive = report;
      }
      else
        run.response = lumped::CentralDifference(model, integration.cdm).run(motion);
      return run;
    }

    RunEstimate make_estimate(double                      dt,
                              const IntegrationScene     &in,
                              const lumped::GroundMotion &motion,
                              std::size_t                 n_dofs)
    {
      RunEstimate e;
      e.dt = dt;
      e.duration =
        in.duration.value_or(motion.dt * static_cast<double>(motion.acceleration.size()));
      e.n_steps = dt > 0.0 ? std::round(e.duration / dt) : 0.0;
      e.n_dofs  = n_dofs;
      // A fixed step records every round(interval/dt)-th step; `dt: auto` interpolates a row
      // every output_interval, also between steps.
      const double rows =
        in.output_interval > 0.0 ? std::round(e.duration / in.output_interval) : 0.0;
      e.history_rows        = variable_time_step(in) ? rows : std::min(e.n_steps, rows);
      const double per_step = in.method == IntegrationMethod::cdm ? cdm_seconds_per_dof_step :
                                                                    newmark_seconds_per_dof_step;
      e.seconds             = static_cast<double>(n_dofs) *
                  (e.n_steps * per_step + e.history_rows * history_seconds_per_dof_row);
      return e;
    }
  } // namespace lumped_internal

  std::string RunEstimate::text() const
  {
    return fmt::format("{:.3g} steps of {:.3g} s over {:.4g} s x {} DoFs = {:.3g} DoF-steps, "
                       "{:.3g} history rows, ~{:.2g} s",
                       n_steps,
                       dt,
                       duration,
                       n_dofs,
                       n_steps * static_cast<double>(n_dofs),
                       history_rows,
                       seconds);
  }

  RunEstimate estimate_lumped_case(const LumpedScene &scene, const lumped::GroundMotion &motion)
  {
    const lumped::PoundingModel model(make_pounding_scene(scene));
    const IntegrationScene     &in = scene.integration;
    const std::optional<double> dt = requested_time_step(in);
    return lumped_internal::make_estimate(
      lumped_internal::planned_step(model, lumped_internal::integration_of(in, dt), motion.dt),
      in,
      motion,
      model.n_dofs());
  }

  void check_run_budget(const std::string      &name,
                        const RunEstimate      &estimate,
                        const IntegrationScene &integration)
  {
    if (!(estimate.n_steps <= integration.max_steps))
      throw std::runtime_error(fmt::format(
        "case {}: {} exceeds the step budget integration.max_steps = {:.3g} (expected fewer "
        "steps: a shorter integration.duration, a larger integration.dt or safety, or a larger "
        "max_steps if the run is intended)",
        name,
        estimate.text(),
        integration.max_steps));
    const double bytes = 3.0 * estimate.history_rows *
                         (3.0 * static_cast<double>(estimate.n_dofs) + 8.0) * sizeof(double);
    if (!(bytes <= history_memory_budget))
      throw std::runtime_error(fmt::format(
        "case {}: {:.3g} history rows (integration.output_interval = {:.3g} s over {:.4g} s) need "
        "~{:.3g} GB of memory, above the budget of {:.3g} GB (a larger output_interval)",
        name,
        estimate.history_rows,
        integration.output_interval,
        estimate.duration,
        bytes / 1e9,
        history_memory_budget / 1e9));
  }

  std::string implausibility(const lumped::Response &r, const IntegrationScene &in)
  {
    const auto worst = [](const std::vector<double> &values)
    {
      std::size_t at = 0;
      for (std::size_t i = 1; i < values.size(); ++i)
        if (std::abs(values[i]) > std::abs(values[at]) || std::isnan(values[i]))
          at = i;
      return at;
    };
    // A peak, its limit, and how the message names and shows them.
    struct Check
    {
      const std::vector<double> &peaks;
      double                     limit;
      const char                *quantity;
      const char                *key;
      double                     unit;
      const char                *unit_name;
    };
    const Check checks[] = {
      {r.peak_displacement, in.plausible_displacement, "displacement", "displacement", 1.0, "m"},
      {r.peak_absolute_acceleration,
       in.plausible_acceleration,
       "absolute acceleration",
       "acceleration",
       standard_gravity,
       "g"}};
    for (const Check &c : checks)
    {
      if (c.peaks.empty())
        continue;
      const std::size_t i     = worst(c.peaks);
      const double      value = std::abs(c.peaks[i]);
      if (!(value <= c.limit))
        return fmt::format("peak |{}| = {:.4g} {} at DoF {} exceeds integration.plausible_{} = "
                           "{:.4g} {} (a wrong unit or scale of the ground motion?)",
                           c.quantity,
                           value / c.unit,
                           c.unit_name,
                           i,
                           c.key,
                           c.limit / c.unit,
                           c.unit_name);
    }
    return "";
  }
} // namespace kimp::app
