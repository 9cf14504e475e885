// `kimp lumped`: one pounding analysis per case (central difference or Newmark), results in
// HDF5 (/lumped/<case>/...), summary.json and peaks.csv; failed cases are recorded, not fatal.
#include "app/lumped_run.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "base/errors.h"
#include "base/format.h"
#include "base/logging.h"
#include "base/version.h"
#include "fit/fitter.h"
#include "io/results_file.h"
#include "io/units.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  namespace
  {
    using Clock = std::chrono::steady_clock;

    /// AdaptiveStepReport::text() with a few significant figures.
    std::string variable_step_text(const lumped::AdaptiveStepReport &r)
    {
      return fmt::format("variable step: {} s, {} s approaching, {} s at contacts ({} windows, "
                         "{} steps of which {} below the large step, +{} for the estimate); "
                         "estimated errors: peak force {} %, peak acceleration {} %, peak "
                         "displacement {} %",
                         base::sig(r.dt_large, 3),
                         base::sig(r.dt_approach, 3),
                         base::sig(r.dt_contact, 3),
                         r.windows,
                         r.steps,
                         r.contact_steps_taken,
                         r.estimate_steps,
                         base::sig(100.0 * r.force_error, 2),
                         base::sig(100.0 * r.acceleration_error, 2),
                         base::sig(100.0 * r.displacement_error, 2));
    }

    double seconds_since(const Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }

    /// The k a case takes from a study's k table (impact.k_table at impact.wall_height): the
    /// table, the height, k in SI with its unit and in the display unit; nullopt when the case
    /// gives k itself or cannot resolve it (run_lumped_case() then records why).
    std::optional<nlohmann::json> k_from_table(const ImpactScene &impact)
    {
      if (impact.k_table.empty() || impact.k_si || impact.law == "bumper" || !impact.wall_height)
        return std::nullopt;
      try
      {
        const double k        = impact_stiffness(impact);
        const double exponent = impact_exponent(impact);
        return nlohmann::json{{"k_table", impact.k_table},
                              {"wall_height", *impact.wall_height},
                              {"k", k},
                              {"unit", fit::stiffness_si_unit(exponent)},
                              {"k_display", fit::stiffness_to_kn_per_mm(k, exponent)},
                              {"display_unit", fit::stiffness_display_unit(exponent)}};
      }
      catch (const std::exception &)
      {
        return std::nullopt;
      }
    }

    /// "<building> isolation level" for DOF 0 of an isolated main building, the wall's name for
    /// a flexible moat wall, else "<building> floor j" (floors above the ground numbered from 1).
    std::vector<std::string> dof_labels(const lumped::PoundingModel &model)
    {
      std::vector<std::string> labels(model.n_dofs());
      for (std::size_t b = 0; b < model.buildings().size(); ++b)
      {
        const lumped::BuildingBlock &block    = model.buildings()[b];
        const bool                   isolated = b == 0 && model.isolator() != nullptr;
        // A flexible moat wall is a block of one DOF named after the wall ("left_wall").
        const bool wall =
          block.name.size() > 5 && block.name.compare(block.name.size() - 5, 5, "_wall") == 0;
        if (wall && block.n_dofs == 1)
        {
          labels[static_cast<std::size_t>(block.first_dof)] = block.name;
          continue;
        }
        for (int i = 0; i < block.n_dofs; ++i)
          labels[static_cast<std::size_t>(block.first_dof + i)] =
            block.name + (isolated && i == 0 ? std::string(" isolation level") :
                                               " floor " + std::to_string(isolated ? i : i + 1));
      }
      return labels;
    }

    /// The storey below a floor takes its number: "building floor 2" -> "building storey 2".
    std::string storey_label(const std::string &upper_dof_label)
    {
      const std::size_t at = upper_dof_label.rfind(" floor ");
      return at == std::string::npos ?
               upper_dof_label + " storey" :
               upper_dof_label.substr(0, at) + " storey " + upper_dof_label.substr(at + 7);
    }

    /// Column labels of a history quantity: a string dataset `labels` and the same list,
    /// comma-separated, as attribute `labels`.
    void write_labels(ResultsGroup &&g, const std::vector<std::string> &labels)
    {
      g.write("labels", labels);
      std::string list;
      for (const std::string &l : labels)
        list += (list.empty() ? "" : ",") + l;
      g.set_attribute("labels", list);
    }

    std::vector<std::int64_t> history_steps(const lumped::Response &r)
    {
      std::vector<std::int64_t> steps;
      steps.reserve(r.history.time.size());
      for (const double t : r.history.time)
        steps.push_back(r.dt > 0.0 ? static_cast<std::int64_t>(std::llround(t / r.dt)) : 0);
      return steps;
    }

    void write_peaks(ResultsGroup &&g, const lumped::Response &r)
    {
      g.write("displacement", r.peak_displacement, "m");
      g.write("absolute_acceleration", r.peak_absolute_acceleration, "m/s^2");
      g.write("interstorey_drift", r.peak_interstorey_drift, "m");
    }

    void write_history(ResultsGroup &&g, const LumpedCaseResult &result)
    {
      const lumped::Response        &r = result.response;
      const lumped::ResponseHistory &h = r.history;
      const std::size_t              n = h.time.size();
      if (n == 0)
        return;
      struct Column
      {
        const char                     *name;
        const std::vector<double>      *values;
        const char                     *units;
        const std::vector<std::string> *labels;
      };
      std::vector<std::string> contact_labels;
      for (const std::string &name : result.contact_names)
        contact_labels.push_back("contact " + name);
      const std::vector<double> no_isolator;
      std::vector<Column>       columns = {
              {"displacement", &h.displacement, "m", &result.dof_labels},
              {"absolute_acceleration", &h.absolute_acceleration, "m/s^2", &result.dof_labels},
              {"interstorey_drift", &h.interstorey_drift, "m", &result.storey_labels},
              {"contact_force", &h.contact_force, "N", &contact_labels},
              {"energy_input", &h.energy_input, "J", nullptr},
              {"energy_error", &h.energy_error, "1", nullptr}};
      if (!result.isolator.empty())
      {
        columns.push_back({"isolator_force", &h.isolator_force, "N", nullptr});
        columns.push_back({"hysteretic_energy", &h.hysteretic_energy, "J", nullptr});
      }
      std::vector<SeriesSpec>     specs;
      std::vector<const Column *> used;
      for (const Column &c : columns)
        if (!c.values->empty() && c.values->size() % n == 0)
        {
          specs.push_back({c.name, c.values->size() / n, c.units});
          used.push_back(&c);
        }
      TimeSeriesSet                   set   = g.time_series_set(specs);
      const std::vector<std::int64_t> steps = history_steps(r);
      std::vector<double>             row(set.row_width());
      for (std::size_t i = 0; i < n; ++i)
      {
        std::size_t k = 0;
        for (std::size_t q = 0; q < used.size(); ++q)
          for (std::size_t j = 0; j < specs[q].width; ++j)
            row[k++] = (*used[q]->values)[i * specs[q].width + j];
        set.append(steps[i], h.time[i], row);
      }
      set.flush();
      for (const Column *column : used)
        if (column->labels && column->labels->size() == column->values->size() / n)
          write_labels(g.group(column->name), *column->labels);
    }

    void write_case(ResultsGroup &lumped_group, const LumpedCaseResult &c)
    {
      ResultsGroup g = lumped_group.case_group(c.name);
      g.set_attribute("wall_time", c.wall_time);
      g.write_scalar("wall_time", c.wall_time, "s");
      for (const BuildingModes &b : c.buildings)
      {
        ResultsGroup m = g.group("modal/" + b.name);
        m.write("period", b.periods, "s");
        m.write_scalar("rayleigh_a", b.rayleigh_a, "1/s");
        m.write_scalar("rayleigh_b", b.rayleigh_b, "s");
        m.write_scalar("c_iso", b.c_iso, "N*s/m");
      }
      if (!c.ok())
      {
        g.set_status(c.status);
        return;
      }
      const lumped::Response &r = c.response;
      g.write_scalar("dt", r.dt, "s");
      g.write_scalar("dt_critical", c.dt_critical, "s");
      g.set_attribute("dt_governing", c.governing);
      g.set_attribute("dt_policy", c.dt_policy);
      if (c.adaptive)
      {
        // Variable steps (dt: auto): dt above is the large step.
        const lumped::AdaptiveStepReport &a = *c.adaptive;
        g.set_attribute("dt_approach", a.dt_approach);
        g.set_attribute("dt_contact", a.dt_contact);
        g.set_attribute("dt_min", a.dt_min);
        g.set_attribute("windows", static_cast<std::int64_t>(a.windows));
        g.set_attribute("estimate_steps", static_cast<std::int64_t>(a.estimate_steps));
        g.set_attribute("estimated_error_peak_force", a.force_error);
        g.set_attribute("estimated_error_peak_acceleration", a.acceleration_error);
        g.set_attribute("estimated_error_peak_displacement", a.displacement_error);
      }
      g.write("n_steps", std::vector<std::int64_t>{static_cast<std::int64_t>(r.n_steps)}, "1");
      g.set_attribute("n_steps", static_cast<std::int64_t>(r.n_steps));
      g.write_scalar("duration", r.duration, "s");
      g.write_scalar("pga", c.pga, "m/s^2");
      write_peaks(g.group("peaks"), r);
      g.write_scalar("max_interstorey_drift", r.max_interstorey_drift(), "m");
      write_history(g.group("history"), c);
      if (!c.isolator.empty())
      {
        ResultsGroup ig = g.group("isolator");
        ig.write_text("kind", c.isolator);
        ig.write_scalar("peak_force", r.peak_isolator_force, "N");
        ig.write_scalar("dissipated_energy", r.energy.hysteretic, "J");
      }
      for (const lumped::ContactResult &contact : r.contacts)
      {
        ResultsGroup        cg = g.group("contacts/" + contact.name);
        std::vector<double> times, velocities;
        for (const lumped::ImpactEvent &e : contact.impacts)
        {
          times.push_back(e.time);
          velocities.push_back(e.velocity);
        }
        cg.write("impact_time", times, "s");
        cg.write("impact_velocity", velocities, "m/s");
        cg.set_attribute("n_impacts", static_cast<std::int64_t>(contact.impacts.size()));
        cg.write_scalar("peak_force", contact.peak_force, "N");
        cg.write_scalar("permanent_indentation", contact.permanent_indentation, "m");
        cg.write_scalar("dissipated_energy", contact.dissipated_energy, "J");
        // Every step with a non-zero force: the impact pulses at full rate.
        std::vector<std::int64_t> pulse_steps;
        pulse_steps.reserve(contact.pulse_time.size());
        for (const double t : contact.pulse_time)
          pulse_steps.push_back(static_cast<std::int64_t>(std::llround(t / r.dt)));
        cg.write_time_series("force_full_rate",
                             pulse_steps,
                             contact.pulse_time,
                             contact.pulse_force,
                             1,
                             "N");
      }
      const lumped::EnergyBalance &e  = r.energy;
      ResultsGroup                 eg = g.group("energy");
      eg.write_scalar("initial", e.initial, "J");
      eg.write_scalar("input", e.input, "J");
      eg.write_scalar("kinetic", e.kinetic, "J");
      eg.write_scalar("strain", e.strain, "J");
      eg.write_scalar("viscous", e.viscous, "J");
      eg.write_scalar("hysteretic", e.hysteretic, "J");
      eg.write_scalar("contact_work", e.contact_work, "J");
      eg.write_scalar("impact_dissipated", e.impact_dissipated, "J");
      eg.write_scalar("relative_error", e.relative_error, "1");
      eg.write_scalar("max_relative_error", e.max_relative_error, "1");
      if (c.companion)
      {
        write_peaks(g.group("companion/peaks"), *c.companion);
        const lumped::Amplification a  = lumped::amplification_factors(r, *c.companion);
        ResultsGroup                ag = g.group("amplification");
        ag.write("displacement", a.displacement, "1");
        ag.write("absolute_acceleration", a.absolute_acceleration, "1");
        ag.write("interstorey_drift", a.interstorey_drift, "1");
      }
      g.set_status("ok");
    }

    nlohmann::json case_summary(const LumpedCaseResult &c)
    {
      nlohmann::json j;
      j["name"]      = c.name;
      j["status"]    = c.status;
      j["wall_time"] = c.wall_time;
      for (const BuildingModes &b : c.buildings)
        j["periods"][b.name] = b.periods;
      if (!c.ok())
        return j;
      const lumped::Response &r = c.response;
      j["dt"]                   = r.dt;
      j["dt_critical"]          = c.dt_critical;
      j["dt_policy"]            = c.dt_policy;
      if (c.adaptive)
      {
        const lumped::AdaptiveStepReport &a = *c.adaptive;
        j["variable_step"]                  = {{"dt_large", a.dt_large},
                                               {"dt_approach", a.dt_approach},
                                               {"dt_contact", a.dt_contact},
                                               {"dt_min", a.dt_min},
                                               {"windows", a.windows},
                                               {"small_steps", a.contact_steps_taken},
                                               {"estimate_steps", a.estimate_steps},
                                               {"estimated_error",
                                                {{"peak_force", a.force_error},
                                                 {"peak_acceleration", a.acceleration_error},
                                                 {"peak_displacement", a.displacement_error}}}};
      }
      j["n_steps"]                        = r.n_steps;
      j["duration"]                       = r.duration;
      j["pga"]                            = c.pga;
      j["peaks"]["displacement"]          = r.peak_displacement;
      j["peaks"]["absolute_acceleration"] = r.peak_absolute_acceleration;
      j["peaks"]["interstorey_drift"]     = r.peak_interstorey_drift;
      j["max_interstorey_drift"]          = r.max_interstorey_drift();
      j["n_impacts"]                      = r.n_impacts();
      if (!c.isolator.empty())
        j["isolator"] = {{"kind", c.isolator},
                         {"peak_force", r.peak_isolator_force},
                         {"dissipated_energy", r.energy.hysteretic}};
      j["contacts"] = nlohmann::json::array();
      for (const lumped::ContactResult &contact : r.contacts)
      {
        nlohmann::json cj;
        cj["name"]                  = contact.name;
        cj["n_impacts"]             = contact.impacts.size();
        cj["peak_force"]            = contact.peak_force;
        cj["permanent_indentation"] = contact.permanent_indentation;
        cj["impacts"]               = nlohmann::json::array();
        for (const lumped::ImpactEvent &e : contact.impacts)
          cj["impacts"].push_back({{"time", e.time}, {"velocity", e.velocity}});
        j["contacts"].push_back(cj);
      }
      j["energy"] = {{"relative_error", r.energy.relative_error},
                     {"max_relative_error", r.energy.max_relative_error},
                     {"input", r.energy.input},
                     {"impact_dissipated", r.energy.impact_dissipated}};
      if (c.companion)
      {
        j["companion_peaks"]["displacement"]          = c.companion->peak_displacement;
        j["companion_peaks"]["absolute_acceleration"] = c.companion->peak_absolute_acceleration;
        j["companion_peaks"]["interstorey_drift"]     = c.companion->peak_interstorey_drift;
      }
      return j;
    }

    std::string number_text(const double value)
    {
      return format_quantity(value, "");
    }

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

    /// The estimate for a step `dt` chosen by the integrator (the integrators' own rule for N).
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

    /// `dt: auto` warns when its estimated error of the peak impact force exceeds this (the
    /// estimate is pessimistic: 0.09-0.87 % on Table 4.3 for true errors of 0.001-0.23 %).
    constexpr double variable_step_warning = 0.01;

    /// Cases may scale the record further: an absurd peak is worth a warning before the run.
    constexpr double warning_pga = 5.0 * standard_gravity;
  } // namespace

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
    if (in.method == IntegrationMethod::cdm)
    {
      if (variable_time_step(in))
        return make_estimate(
          lumped::AdaptiveCentralDifference(model, cdm_options(in, dt)).large_step(motion.dt),
          in,
          motion,
          model.n_dofs());
      const lumped::CentralDifference integrator(model, cdm_options(in, dt));
      return make_estimate(integrator.time_step(motion.dt), in, motion, model.n_dofs());
    }
    return make_estimate(dt.value_or(motion.dt), in, motion, model.n_dofs());
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
    if (!r.peak_displacement.empty())
    {
      const std::size_t i = worst(r.peak_displacement);
      const double      u = std::abs(r.peak_displacement[i]);
      if (!(u <= in.plausible_displacement))
        return fmt::format("peak |displacement| = {:.4g} m at DoF {} exceeds "
                           "integration.plausible_displacement = {:.4g} m (a wrong unit or "
                           "scale of the ground motion?)",
                           u,
                           i,
                           in.plausible_displacement);
    }
    if (!r.peak_absolute_acceleration.empty())
    {
      const std::size_t i = worst(r.peak_absolute_acceleration);
      const double      a = std::abs(r.peak_absolute_acceleration[i]);
      if (!(a <= in.plausible_acceleration))
        return fmt::format("peak |absolute acceleration| = {:.4g} g at DoF {} exceeds "
                           "integration.plausible_acceleration = {:.4g} g (a wrong unit or "
                           "scale of the ground motion?)",
                           a / standard_gravity,
                           i,
                           in.plausible_acceleration / standard_gravity);
    }
    return "";
  }

  LumpedCaseResult run_lumped_case(const std::string          &name,
                                   const LumpedScene          &scene,
                                   const lumped::GroundMotion &motion,
                                   const double                base_scale)
  {
    return run_lumped_case(name, scene, motion, base_scale, FreeRunSource());
  }

  LumpedCaseResult run_lumped_case(const std::string          &name,
                                   const LumpedScene          &scene,
                                   const lumped::GroundMotion &motion,
                                   const double                base_scale,
                                   const FreeRunSource        &free_runs)
  {
    LumpedCaseResult        result;
    const Clock::time_point start = Clock::now();
    result.name                   = name;
    try
    {
      const lumped::PoundingModel model(make_pounding_scene(scene));
      for (const lumped::BuildingBlock &block : model.buildings())
      {
        BuildingModes b;
        b.name = block.name;
        for (Eigen::Index i = 0; i < block.damping.modes.period.size(); ++i)
          b.periods.push_back(block.damping.modes.period[i]);
        b.rayleigh_a = block.damping.rayleigh.a;
        b.rayleigh_b = block.damping.rayleigh.b;
        b.c_iso      = block.damping.c_iso;
        result.buildings.push_back(std::move(b));
      }
      for (const lumped::ContactPair &c : model.contacts())
        result.contact_names.push_back(c.name);
      for (const lumped::Storey &s : model.storeys())
        result.storey_upper_dofs.push_back(s.upper_dof);
      result.dof_labels = dof_labels(model);
      for (const lumped::Storey &s : model.storeys())
        result.storey_labels.push_back(
          storey_label(result.dof_labels[static_cast<std::size_t>(s.upper_dof)]));
      if (model.isolator())
        result.isolator = model.isolator()->name();

      const double         factor = scene.ground_motion.scale / base_scale;
      lumped::GroundMotion used   = factor != 1.0 ? lumped::scaled(motion, factor) : motion;
      result.pga                  = used.pga();
      if (factor != 1.0 && result.pga > warning_pga)
        logger().warn("case {}: ground motion scaled by {:.4g} to a PGA of {:.4g} g, above {} g "
                      "(beyond any recorded motion): is the scale intended?",
                      name,
                      factor,
                      result.pga / standard_gravity,
                      warning_pga / standard_gravity);

      const IntegrationScene     &in = scene.integration;
      const std::optional<double> dt = requested_time_step(in);
      if (in.method == IntegrationMethod::cdm)
      {
        lumped::CentralDifferenceOptions options = cdm_options(in, dt);
        const lumped::CentralDifference  integrator(model, options);
        result.dt_critical = integrator.stability().dt_critical;
        result.governing   = integrator.stability().governing;
        result.dt_policy   = dt ? "fixed" : variable_time_step(in) ? "variable" : "stable";
        logger().debug("case {}: dt_cr = {} s ({})", name, result.dt_critical, result.governing);
        if (variable_time_step(in))
        {
          lumped::AdaptiveStepOptions adaptive_options;
          adaptive_options.contact_steps = in.contact_steps;
          const lumped::AdaptiveCentralDifference adaptive(model, options, adaptive_options);
          const RunEstimate                       estimate =
            make_estimate(adaptive.large_step(used.dt), in, used, model.n_dofs());
          result.estimated_steps = estimate.n_steps;
          if (logger().should_log(spdlog::level::debug))
            logger().debug("case {}: {}", name, estimate.text());
          check_run_budget(name, estimate, in);
          lumped::AdaptiveStepReport report;
          result.response = adaptive.run(used, &report);
          result.adaptive = report;
          if (in.companion)
          {
            // The companion chooses its own steps (independent of the walls). A run in which no
            // contact closed is the companion run (its steps differ only where a gap approached),
            // so that amplification factors are then exactly 1.
            result.companion =
              lumped::AdaptiveCentralDifference(model.without_contacts(), options, adaptive_options)
                .run(used);
            bool touched = result.response.n_impacts() > 0;
            for (const lumped::ContactResult &c : result.response.contacts)
              touched = touched || c.peak_force != 0.0;
            if (!touched)
            {
              lumped::Response same      = *result.companion;
              same.contacts              = result.response.contacts;
              same.history.contact_force = result.response.history.contact_force;
              result.response            = std::move(same);
            }
          }
          // Per case at -v; the study and the summary.json give the largest errors.
          logger().debug("case {}: {}", name, variable_step_text(report));
          if (report.force_error > variable_step_warning)
            logger().warn("case {}: dt auto estimates the peak impact force within {:.2g} %, "
                          "above {:.2g} %: raise integration.contact_steps or use a fixed dt",
                          name,
                          100.0 * report.force_error,
                          100.0 * variable_step_warning);
        }
        else
        {
          const RunEstimate estimate =
            make_estimate(integrator.time_step(used.dt), in, used, model.n_dofs());
          result.estimated_steps = estimate.n_steps;
          if (logger().should_log(spdlog::level::debug))
            logger().debug("case {}: {}", name, estimate.text());
          check_run_budget(name, estimate, in);
          std::shared_ptr<const lumped::FreeRunPrefix> prefix;
          if (free_runs && !(options.output_interval > 0.0))
          {
            lumped::CentralDifferenceOptions free_options = options;
            free_options.dt                               = integrator.time_step(used.dt);
            prefix = free_runs(lumped::CentralDifference(model.without_contacts(), free_options),
                               free_options.dt,
                               used);
          }
          if (prefix)
          {
            result.response = prefix->run(integrator, used);
            if (in.companion)
              result.companion = prefix->response();
          }
          else
          {
            result.response = integrator.run(used);
            if (in.companion)
            {
              options.dt = result.response.dt;
              result.companion =
                lumped::CentralDifference(model.without_contacts(), options).run(used);
            }
          }
        }
      }
      else
      {
        const lumped::NewmarkOptions options = newmark_options(in, dt);
        result.dt_policy                     = dt ? "fixed" : "record";
        const RunEstimate estimate =
          make_estimate(options.dt > 0.0 ? options.dt : used.dt, in, used, model.n_dofs());
        result.estimated_steps = estimate.n_steps;
        if (logger().should_log(spdlog::level::debug))
          logger().debug("case {}: {}", name, estimate.text());
        check_run_budget(name, estimate, in);
        result.response = lumped::NewmarkIntegrator(model, options).run(used);
        if (in.companion)
          result.companion = lumped::NewmarkIntegrator(model.without_contacts(), options).run(used);
      }
      if (const std::string why = implausibility(result.response, in); !why.empty())
        throw std::runtime_error("implausible result: " + why);
    }
    catch (const std::exception &error)
    {
      result.status   = "failed: " + base::error_text(error);
      result.response = lumped::Response{};
      result.companion.reset();
    }
    result.wall_time = seconds_since(start);
    return result;
  }

  LumpedCasesRun run_lumped_cases(const LumpedScene                          &scene,
                                  const std::string                          &file_name,
                                  const std::string                          &scene_text,
                                  const std::optional<std::filesystem::path> &records_dir_override,
                                  const std::optional<std::string>           &only_case,
                                  const SyntheticMotionSource                &synthetic)
  {
    const auto load = [&](const GroundMotionScene &section, const std::string &key_path)
    {
      if (!section.is_record() && synthetic)
        return synthetic(section);
      return std::make_shared<const lumped::GroundMotion>(
        load_ground_motion_at(section, records_dir_override, file_name, scene_text, key_path));
    };

    // The cases to run, with their index in `cases` (which names their keys in messages).
    const auto               cases = resolve_cases(scene);
    std::vector<std::size_t> chosen;
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (!only_case || cases[i].first == *only_case)
        chosen.push_back(i);
    if (chosen.empty())
    {
      std::string known;
      for (const auto &c : cases)
        known += (known.empty() ? "" : ", ") + c.first;
      throw std::invalid_argument("no case '" + only_case.value_or("") + "' in " + file_name +
                                  " (cases: " + known + ")");
    }

    LumpedCasesRun run;
    run.motion                         = load(scene.ground_motion, "ground_motion");
    const lumped::GroundMotion &motion = *run.motion;
    logger().info("ground motion {}: {} samples at {:.4g} s, PGA {:.4g} g",
                  motion.name,
                  motion.acceleration.size(),
                  motion.dt,
                  motion.pga() / lumped::standard_gravity);

    // Which k each case takes from a study's k table (summary.json "impact_k" too).
    for (const std::size_t i : chosen)
      if (const std::optional<nlohmann::json> k = k_from_table(cases[i].second.impact))
        logger().info("case {}: impact k = {} {} from the k table {} at wall height {} m",
                      cases[i].first,
                      base::sig(k->at("k_display").get<double>()),
                      k->at("display_unit").get<std::string>(),
                      k->at("k_table").get<std::string>(),
                      base::sig(k->at("wall_height").get<double>()));
    // The cases' own records (cases[i].record) before any run, so that a missing one is an error
    // at its key rather than a run stopped half-way.
    std::vector<std::shared_ptr<const lumped::GroundMotion>> own_motions(cases.size());
    for (const std::size_t i : chosen)
      if (cases[i].second.ground_motion.record != scene.ground_motion.record)
        own_motions[i] = load(cases[i].second.ground_motion, "cases[" + std::to_string(i) + "]");
    // Every case's cost first, so that a run over budget is refused before anything is computed
    // (an invalid case is left to run_lumped_case(), which records why it fails).
    for (const std::size_t i : chosen)
    {
      const auto &[name, case_scene] = cases[i];
      RunEstimate estimate;
      try
      {
        const double factor = case_scene.ground_motion.scale / scene.ground_motion.scale;
        estimate            = own_motions[i] ?
                                estimate_lumped_case(case_scene, *own_motions[i]) :
                                estimate_lumped_case(case_scene,
                                          factor != 1.0 ? lumped::scaled(motion, factor) : motion);
      }
      catch (const std::exception &)
      {
        continue;
      }
      if (logger().should_log(spdlog::level::info))
        logger().info("case {}: estimated {}", name, estimate.text());
      check_run_budget(name, estimate, case_scene.integration);
    }

    Progress progress(chosen.size(), static_cast<double>(chosen.size()));
    for (std::size_t done = 0; done < chosen.size(); ++done)
    {
      const std::size_t i = chosen[done];
      logger().info("case {}/{}: {}", i + 1, cases.size(), cases[i].first);
      if (!own_motions[i])
        run.results.push_back(
          run_lumped_case(cases[i].first, cases[i].second, motion, scene.ground_motion.scale));
      else
      {
        // A case with its own record (cases[i].record), loaded above.
        logger().info("case {}: ground motion {}", cases[i].first, own_motions[i]->name);
        run.results.push_back(run_lumped_case(cases[i].first,
                                              cases[i].second,
                                              *own_motions[i],
                                              cases[i].second.ground_motion.scale));
        own_motions[i].reset();
      }
      const LumpedCaseResult &r = run.results.back();
      if (r.ok() && logger().should_log(spdlog::level::info))
        logger().info("case {}: {} steps of {:.4g} s, {} impacts, peak base {} m, wall time {} s",
                      r.name,
                      r.response.n_steps,
                      r.response.dt,
                      r.response.n_impacts(),
                      base::sig(r.response.peak_displacement.empty() ?
                                  0.0 :
                                  r.response.peak_displacement[0]),
                      base::sig(r.wall_time, 3));
      else if (!r.ok())
        logger().error("case {}: {}", r.name, r.status);
      progress.update(done + 1, static_cast<double>(done + 1));
    }
    progress.finish();
    return run;
  }

  std::vector<LumpedCaseResult>
  run_lumped(const LoadedScene<LumpedScene>             &loaded,
             const OutputDir                            &output,
             const std::optional<std::filesystem::path> &records_dir_override)
  {
    const Clock::time_point start = Clock::now();
    LumpedCasesRun          run =
      run_lumped_cases(loaded.scene, loaded.file_name, loaded.text, records_dir_override);
    const lumped::GroundMotion    &motion  = *run.motion;
    std::vector<LumpedCaseResult> &results = run.results;

    ResultsFile  file(output.file("lumped.h5"), loaded.text, loaded.resolved_json);
    ResultsGroup root = file.root();
    root.group("input").set_attribute("ground_motion", motion.name);
    ResultsGroup lumped_group = root.group("lumped");
    for (const LumpedCaseResult &r : results)
      write_case(lumped_group, r);
    file.commit();

    nlohmann::json summary;
    summary["command"]       = "lumped";
    summary["kimp"]          = base::version_line();
    summary["scene"]         = loaded.file_name;
    summary["wall_time"]     = seconds_since(start);
    summary["ground_motion"] = {{"name", motion.name},
                                {"dt", motion.dt},
                                {"duration", motion.duration()},
                                {"pga", motion.pga()}};
    summary["units"]         = {{"displacement", "m"},
                                {"absolute_acceleration", "m/s^2"},
                                {"force", "N"},
                                {"time", "s"},
                                {"velocity", "m/s"},
                                {"energy", "J"},
                                {"wall_time", "s"}};
    summary["cases"]         = nlohmann::json::array();
    const auto cases         = resolve_cases(loaded.scene);
    for (std::size_t i = 0; i < results.size(); ++i)
    {
      summary["cases"].push_back(case_summary(results[i]));
      if (i < cases.size())
        if (std::optional<nlohmann::json> k = k_from_table(cases[i].second.impact))
        {
          k->erase("k_display");
          k->erase("display_unit");
          summary["cases"].back()["impact_k"] = *k;
        }
    }
    write_json_atomic(output.file("summary.json"), summary);

    std::vector<std::vector<std::string>> rows;
    for (const LumpedCaseResult &r : results)
    {
      if (!r.ok())
        continue;
      const lumped::Response &resp = r.response;
      for (std::size_t dof = 0; dof < resp.peak_displacement.size(); ++dof)
      {
        std::string drift;
        for (std::size_t s = 0; s < r.storey_upper_dofs.size(); ++s)
          if (r.storey_upper_dofs[s] == static_cast<int>(dof) &&
              s < resp.peak_interstorey_drift.size())
            drift = number_text(resp.peak_interstorey_drift[s]);
        rows.push_back({r.name,
                        std::to_string(dof),
                        number_text(resp.peak_displacement[dof]),
                        number_text(resp.peak_absolute_acceleration[dof]),
                        drift});
      }
    }
    write_csv_atomic(output.file("peaks.csv"),
                     {"case",
                      "dof",
                      "peak_displacement_m",
                      "peak_absolute_acceleration_m_per_s2",
                      "peak_interstorey_drift_m"},
                     rows);
    // Failed cases are recorded in these files: the command's failure for them keeps the files.
    output.keep_written();
    return std::move(run.results);
  }

} // namespace kimp::app
