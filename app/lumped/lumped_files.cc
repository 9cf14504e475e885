// The files of `kimp lumped`: DIR/lumped.h5 (/lumped/<case>/..., docs/architecture.md "Results
// files"), DIR/summary.json and DIR/peaks.csv, and the k a case takes from a study's k table.
#include <cmath>
#include <nlohmann/json.hpp>

#include "app/lumped/lumped_run_internal.h"
#include "fit/fitter.h"
#include "io/results_file.h"
#include "io/summary.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  namespace
  {
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
      // Chunks of the series' exact length (n rows): no padding rows in the file.
      TimeSeriesSet                   set   = g.time_series_set(specs, 4096, n);
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

    /// The step of the case: dt, the critical step, the policy and, with variable steps, the
    /// report of dt: auto.
    void write_step(ResultsGroup &g, const LumpedCaseResult &c)
    {
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
    }

    /// `contacts/<contact>`: its impacts, peak force, indentation, dissipation and the pulses at
    /// full rate (step size `dt`, s).
    void write_contact(ResultsGroup &g, const lumped::ContactResult &contact, double dt)
    {
      ResultsGroup cg = g.group("contacts/" + contact.name);
      cg.write("impact_time", contact.impact_column(&lumped::ImpactEvent::time), "s");
      cg.write("impact_velocity", contact.impact_column(&lumped::ImpactEvent::velocity), "m/s");
      cg.set_attribute("n_impacts", static_cast<std::int64_t>(contact.impacts.size()));
      cg.write_scalar("peak_force", contact.peak_force, "N");
      cg.write_scalar("permanent_indentation", contact.permanent_indentation, "m");
      cg.write_scalar("dissipated_energy", contact.dissipated_energy, "J");
      // Every step with a non-zero force: the impact pulses at full rate.
      std::vector<std::int64_t> pulse_steps;
      pulse_steps.reserve(contact.pulse_time.size());
      for (const double t : contact.pulse_time)
        pulse_steps.push_back(static_cast<std::int64_t>(std::llround(t / dt)));
      cg.write_time_series("force_full_rate",
                           pulse_steps,
                           contact.pulse_time,
                           contact.pulse_force,
                           1,
                           "N");
      // The deformation δ at the same steps: each impact's indentation.
      cg.write_time_series("deformation_full_rate",
                           pulse_steps,
                           contact.pulse_time,
                           contact.pulse_deformation,
                           1,
                           "m");
    }

    /// `energy`: the energy balance's terms (the walls' works with yielding walls).
    void write_energy(ResultsGroup &g, const LumpedCaseResult &c)
    {
      const lumped::Response      &r  = c.response;
      const lumped::EnergyBalance &e  = r.energy;
      ResultsGroup                 eg = g.group("energy");
      for (const EnergyTerm &t : energy_terms())
        if (!t.walls || !c.yielding_walls.empty())
          eg.write_scalar(t.name, e.*t.value, t.unit);
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
      write_step(g, c);
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
        write_contact(g, contact, r.dt);
      for (const YieldingWallLimits &w : c.yielding_walls)
      {
        ResultsGroup wg = g.group("walls/" + w.wall);
        lumped_internal::write_yielding_wall(wg, yielding_wall_record(w, r.contacts[w.contact]));
      }
      write_energy(g, c);
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
      if (!c.yielding_walls.empty())
      {
        j["energy"]["wall_plastic"]  = r.energy.wall_plastic;
        j["energy"]["wall_radiated"] = r.energy.wall_radiated;
        j["walls"]                   = nlohmann::json::array();
        for (const YieldingWallLimits &w : c.yielding_walls)
        {
          nlohmann::json wj =
            lumped_internal::yielding_wall_json(yielding_wall_record(w, r.contacts[w.contact]));
          wj["name"] = w.wall;
          j["walls"].push_back(wj);
        }
      }
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
  } // namespace

  YieldingWallRecord yielding_wall_record(const YieldingWallLimits    &w,
                                          const lumped::ContactResult &part)
  {
    return {part.peak_force,
            w.capacity,
            part.peak_resistance,
            part.peak_deformation,
            part.permanent_indentation,
            w.failure_displacement,
            part.failure_time,
            part.plastic_work,
            part.radiated_work};
  }

  const std::vector<EnergyTerm> &energy_terms()
  {
    using E = lumped::EnergyBalance;
    static const std::vector<EnergyTerm> terms{
      {"initial", "J", &E::initial},
      {"input", "J", &E::input},
      {"kinetic", "J", &E::kinetic},
      {"strain", "J", &E::strain},
      {"viscous", "J", &E::viscous},
      {"hysteretic", "J", &E::hysteretic},
      {"contact_work", "J", &E::contact_work},
      {"impact_dissipated", "J", &E::impact_dissipated},
      {"wall_plastic", "J", &E::wall_plastic, true},
      {"wall_radiated", "J", &E::wall_radiated, true},
      {"relative_error", "1", &E::relative_error},
      {"max_relative_error", "1", &E::max_relative_error},
    };
    return terms;
  }

  namespace lumped_internal
  {
    void write_yielding_wall(ResultsGroup &g, const YieldingWallRecord &w)
    {
      g.write_scalar("peak_force", w.peak_force, "N");
      g.write_scalar("capacity", w.capacity, "N");
      g.write_scalar("peak_resistance", w.peak_resistance, "N");
      g.write_scalar("peak_resistance_ratio", w.peak_resistance / w.capacity, "1");
      g.write_scalar("peak_displacement", w.peak_displacement, "m");
      g.write_scalar("residual_displacement", w.residual_displacement, "m");
      g.write_scalar("failure_displacement", w.failure_displacement, "m");
      g.set_attribute("failed", static_cast<std::int64_t>(w.failure_time ? 1 : 0));
      if (w.failure_time)
        g.write_scalar("failure_time", *w.failure_time, "s");
      g.write_scalar("plastic_work", w.plastic_work, "J");
      g.write_scalar("radiated_work", w.radiated_work, "J");
    }

    nlohmann::json yielding_wall_json(const YieldingWallRecord &w)
    {
      nlohmann::json j = {{"peak_resistance_ratio", w.peak_resistance / w.capacity},
                          {"failed", w.failure_time.has_value()}};
      for (const YieldingWallQuantity &q : yielding_wall_quantities)
        j[q.name] = w.*q.value;
      if (w.failure_time)
        j["failure_time"] = *w.failure_time;
      return j;
    }

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

    void write_lumped_files(const LoadedScene<LumpedScene> &loaded,
                            const OutputDir                &output,
                            const LumpedCasesRun           &run,
                            const Clock::time_point         start)
    {
      const lumped::GroundMotion          &motion  = *run.motion;
      const std::vector<LumpedCaseResult> &results = run.results;

      ResultsFile  file(output.file("lumped.h5"), loaded.text, loaded.resolved_json);
      ResultsGroup root = file.root();
      root.group("input").set_attribute("ground_motion", motion.name);
      ResultsGroup lumped_group = root.group("lumped");
      for (const LumpedCaseResult &r : results)
        write_case(lumped_group, r);
      file.commit();

      nlohmann::json summary   = io::summary_preamble("lumped");
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
    }
  } // namespace lumped_internal
} // namespace kimp::app
