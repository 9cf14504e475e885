// Writers of `kimp study`: k_table.csv, fidelity_levels.csv, building_response.csv, study.h5 and
// summary.json (docs/architecture.md "Results files").
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <tuple>

#include "app/fit_run.h"
#include "app/study/study_internal.h"
#include "app/study/study_velocity.h"
#include "base/version.h"
#include "io/results_file.h"

namespace kimp::app::study_internal
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::fit;
  namespace
  {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    std::vector<std::string> k_table_header()
    {
      return {"wall_height_m",
              "slab_mass_kg_per_m",
              "impact_velocity_m_per_s",
              "fem_peak_force_kN_per_m",
              "fem_contact_duration_ms",
              "kelvin_voigt_kN_per_mm_per_m",
              "kelvin_voigt_lower_kN_per_mm_per_m",
              "kelvin_voigt_upper_kN_per_mm_per_m",
              "kelvin_voigt_total_kN_per_mm",
              "kelvin_voigt_normalised_rms",
              "thesis_kelvin_voigt_kN_per_mm_per_m",
              "jankowski_kN_per_mm1.5_per_m",
              "jankowski_lower_kN_per_mm1.5_per_m",
              "jankowski_upper_kN_per_mm1.5_per_m",
              "jankowski_total_kN_per_mm1.5",
              "jankowski_normalised_rms",
              "thesis_jankowski_kN_per_mm1.5_per_m",
              "kelvin_voigt_numerical_error_kN_per_mm_per_m",
              "jankowski_numerical_error_kN_per_mm1.5_per_m",
              "kelvin_voigt_total_numerical_error_kN_per_mm",
              "jankowski_total_numerical_error_kN_per_mm1.5",
              "fidelity",
              "fem_h_contact_cm",
              "fem_penalty_factor",
              "fidelity_converged",
              "kelvin_voigt_status",
              "jankowski_status",
              "reference_velocity",
              "material",
              "linear_kelvin_voigt_kN_per_mm_per_m",
              "linear_jankowski_kN_per_mm1.5_per_m"};
    }

    std::vector<std::string> k_table_row(const StudyScene &scene, const StudyHeight &h)
    {
      const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
      const FemSummary                    &fem    = h.fem_case.summary;
      return {number(h.wall_height),
              number(h.fem_case.slab_mass),
              number(h.fem_case.impact_velocity),
              number(fem.peak_force.value_or(nan) / 1e3),
              number(fem.contact_duration.value_or(nan) * 1e3),
              number(per_metre(h.kelvin_voigt)),
              number(per_metre_bound(h.kelvin_voigt, false)),
              number(per_metre_bound(h.kelvin_voigt, true)),
              number(per_metre(h.kelvin_voigt) * scene.fit.width),
              number(h.kelvin_voigt ? h.kelvin_voigt->normalised_rms : nan),
              number(thesis ? thesis->kelvin_voigt : nan),
              number(per_metre(h.jankowski)),
              number(per_metre_bound(h.jankowski, false)),
              number(per_metre_bound(h.jankowski, true)),
              number(per_metre(h.jankowski) * scene.fit.width),
              number(h.jankowski ? h.jankowski->normalised_rms : nan),
              number(thesis ? thesis->jankowski : nan),
              number(numerical_error(h, 1.0)),
              number(numerical_error(h, 1.5)),
              number(total_stiffness_error(0.0, numerical_error(h, 1.0), scene.fit.width)),
              number(total_stiffness_error(0.0, numerical_error(h, 1.5), scene.fit.width)),
              h.auto_fidelity ? "auto" : "fixed",
              number(used_h_contact(scene, h) * 100.0),
              number(used_penalty(scene, h)),
              h.auto_fidelity ? (h.ladder.converged ? "yes" : "no") : "",
              h.kelvin_voigt_status,
              h.jankowski_status,
              h.reference_velocity ? "yes" : "no",
              h.inelastic ? "inelastic" : "linear",
              number(per_metre(h.linear_kelvin_voigt)),
              number(per_metre(h.linear_jankowski))};
    }

    std::vector<std::string> building_header()
    {
      return {"record",
              "wall_height_m",
              "law",
              "k_total",
              "k_total_unit",
              "gap_cm",
              "pga_m_per_s2",
              "peak_base_displacement_cm",
              "peak_top_displacement_cm",
              "peak_base_acceleration_m_per_s2",
              "peak_top_acceleration_m_per_s2",
              "peak_floor_acceleration_m_per_s2",
              "peak_interstorey_drift_cm",
              "peak_impact_force_kN",
              "n_impacts",
              "permanent_indentation_mm",
              "amplification_base_acceleration",
              "amplification_top_acceleration",
              "amplification_interstorey_drift",
              "wall_seconds",
              "status"};
    }

    std::vector<std::string> building_row(const StudyBuildingRun &r)
    {
      const bool walls = r.law != "none";
      return {r.record,
              walls ? number(r.wall_height) : "",
              r.law,
              walls ? number(stiffness_to_kn_per_mm(r.k_total, r.exponent)) : "",
              walls ? stiffness_display_unit(r.exponent) : "",
              walls ? number(r.gap * 100) : "",
              number(r.pga),
              number(r.base_displacement * 100),
              number(r.top_displacement * 100),
              number(r.base_acceleration),
              number(r.top_acceleration),
              number(r.max_floor_acceleration),
              number(r.max_interstorey_drift * 100),
              number(r.peak_impact_force / 1e3),
              std::to_string(r.n_impacts),
              number(r.permanent_indentation * 1e3),
              number(r.amplification_base_acc),
              number(r.amplification_top_acc),
              number(r.amplification_drift),
              number(r.wall_seconds),
              r.status};
    }
  } // namespace

  void write_k_table_csv(const OutputDir                &output,
                         const StudyScene               &scene,
                         const std::vector<StudyHeight> &heights,
                         const std::vector<StudyHeight> &velocity_cases)
  {
    std::vector<std::vector<std::string>> k_rows;
    StudyResult                           all; // rows by height, then impact velocity
    all.heights        = heights;
    all.velocity_cases = velocity_cases;
    for (const StudyHeight *h : k_table_cases(all))
      k_rows.push_back(k_table_row(scene, *h));
    write_csv_atomic(output.file("k_table.csv"), k_table_header(), k_rows);
    std::vector<std::vector<std::string>> level_rows;
    for (const StudyHeight &h : heights)
      for (std::size_t i = 0; i < h.ladder.outcomes.size(); ++i)
      {
        const LevelOutcome &o = h.ladder.outcomes[i];
        level_rows.push_back({number(h.wall_height),
                              number(h.ladder.levels[i].h_contact * 100.0),
                              number(h.ladder.levels[i].penalty_factor),
                              number(stiffness_to_kn_per_mm(o.k_kelvin_voigt, 1.0)),
                              number(stiffness_to_kn_per_mm(o.k_jankowski, 1.5)),
                              number(o.seconds),
                              o.from_cache ? "yes" : "no",
                              i == h.ladder.used ? "yes" : "no",
                              o.status});
      }
    if (!level_rows.empty())
      write_csv_atomic(output.file("fidelity_levels.csv"),
                       {"wall_height_m",
                        "h_contact_cm",
                        "penalty_factor",
                        "kelvin_voigt_kN_per_mm_per_m",
                        "jankowski_kN_per_mm1.5_per_m",
                        "seconds",
                        "fem_from_cache",
                        "used",
                        "status"},
                       level_rows);
  }

  void write_building_csv(const OutputDir &output, const std::vector<StudyBuildingRun> &runs)
  {
    std::vector<std::vector<std::string>> b_rows;
    for (const StudyBuildingRun &r : runs)
      b_rows.push_back(building_row(r));
    write_csv_atomic(output.file("building_response.csv"), building_header(), b_rows);
  }

  void write_study_h5(const LoadedScene<StudyScene> &loaded,
                      const StudyResult             &result,
                      const OutputDir               &output)
  {
    const StudyScene &scene = loaded.scene;
    ResultsFile       file(output.file("study.h5"), loaded.text, loaded.resolved_json);
    ResultsGroup      root     = file.root();
    ResultsGroup      fem_root = root.group("fem");
    ResultsGroup      fit_root = root.group("fit");
    for (const StudyHeight &h : result.heights)
    {
      write_fem_case(fem_root, h.fem_case);
      ResultsGroup g = fit_root.group(h.name);
      g.write_scalar("wall_height", h.wall_height, "m");
      for (const auto &[law, fit, status] :
           {std::tuple{"kelvin_voigt", &h.kelvin_voigt, &h.kelvin_voigt_status},
            std::tuple{"jankowski", &h.jankowski, &h.jankowski_status}})
      {
        ResultsGroup f = g.group(law);
        f.set_status(*status);
        if (!*fit)
          continue;
        write_fit_result(f, **fit, scene.fit.width, FitResultLayout::study);
      }
    }

    std::vector<TableColumn> k(17);
    k[0]  = {"wall_height", "m", {}};
    k[1]  = {"kelvin_voigt", "kN/mm/m", {}};
    k[2]  = {"kelvin_voigt_lower", "kN/mm/m", {}};
    k[3]  = {"kelvin_voigt_upper", "kN/mm/m", {}};
    k[4]  = {"kelvin_voigt_total", "kN/mm", {}};
    k[5]  = {"thesis_kelvin_voigt", "kN/mm/m", {}};
    k[6]  = {"jankowski", "kN/mm^1.5/m", {}};
    k[7]  = {"jankowski_lower", "kN/mm^1.5/m", {}};
    k[8]  = {"jankowski_upper", "kN/mm^1.5/m", {}};
    k[9]  = {"jankowski_total", "kN/mm^1.5", {}};
    k[10] = {"thesis_jankowski", "kN/mm^1.5/m", {}};
    k[11] = {"kelvin_voigt_numerical_error", "kN/mm/m", {}};
    k[12] = {"jankowski_numerical_error", "kN/mm^1.5/m", {}};
    k[13] = {"h_contact", "m", {}};
    k[14] = {"penalty_factor", "1", {}};
    k[15] = {"fidelity_auto", "1", {}};
    k[16] = {"fidelity_converged", "1", {}};
    for (const StudyHeight &h : result.heights)
    {
      const std::optional<ThesisStiffness> thesis   = thesis_row(h.wall_height);
      const double                         values[] = {h.wall_height,
                                                       per_metre(h.kelvin_voigt),
                                                       per_metre_bound(h.kelvin_voigt, false),
                                                       per_metre_bound(h.kelvin_voigt, true),
                                                       per_metre(h.kelvin_voigt) * scene.fit.width,
                               thesis ? thesis->kelvin_voigt : nan,
                                                       per_metre(h.jankowski),
                                                       per_metre_bound(h.jankowski, false),
                                                       per_metre_bound(h.jankowski, true),
                                                       per_metre(h.jankowski) * scene.fit.width,
                               thesis ? thesis->jankowski : nan,
                                                       numerical_error(h, 1.0),
                                                       numerical_error(h, 1.5),
                                                       used_h_contact(scene, h),
                                                       used_penalty(scene, h),
                               h.auto_fidelity ? 1.0 : 0.0,
                               h.auto_fidelity && h.ladder.converged ? 1.0 : 0.0};
      for (std::size_t i = 0; i < k.size(); ++i)
        k[i].values.push_back(values[i]);
    }
    root.write_table("k_table", k);
    root.group("k_table").set_attribute("building_width_m", scene.fit.width);
    write_study_extras(root, result.extras);
    write_flexible_wall_h5(root, result);
    write_velocity_h5(root, scene, result);

    // /fidelity/<H>: the levels climbed (fidelity: auto).
    for (const StudyHeight &h : result.heights)
    {
      if (!h.auto_fidelity)
        continue;
      std::vector<TableColumn> levels = {{"h_contact", "m", {}},
                                         {"penalty_factor", "1", {}},
                                         {"kelvin_voigt", "kN/mm/m", {}},
                                         {"jankowski", "kN/mm^1.5/m", {}},
                                         {"seconds", "s", {}},
                                         {"ok", "1", {}},
                                         {"from_cache", "1", {}},
                                         {"used", "1", {}}};
      for (std::size_t i = 0; i < h.ladder.outcomes.size(); ++i)
      {
        const LevelOutcome &o   = h.ladder.outcomes[i];
        const double        v[] = {h.ladder.levels[i].h_contact,
                                   h.ladder.levels[i].penalty_factor,
                                   stiffness_to_kn_per_mm(o.k_kelvin_voigt, 1.0),
                                   stiffness_to_kn_per_mm(o.k_jankowski, 1.5),
                                   o.seconds,
                            o.ok ? 1.0 : 0.0,
                            o.from_cache ? 1.0 : 0.0,
                            i == h.ladder.used ? 1.0 : 0.0};
        for (std::size_t j = 0; j < levels.size(); ++j)
          levels[j].values.push_back(v[j]);
      }
      ResultsGroup fidelity = root.group("fidelity");
      fidelity.write_table(h.name, levels);
      ResultsGroup table = fidelity.group(h.name);
      table.set_attribute("reason", h.fidelity_reason);
      table.set_attribute("converged", h.ladder.converged ? 1.0 : 0.0);
      table.set_attribute("tolerance", scene.fem.fidelity_tolerance);
    }

    // /building/<record>/<law>: one row per wall height (law "none": the run without walls).
    std::map<std::pair<std::string, std::string>, std::vector<const StudyBuildingRun *>> tables;
    for (const StudyBuildingRun &r : result.building)
      if (r.status == "ok")
        tables[{r.record, r.law}].push_back(&r);
    for (const auto &[key, rows] : tables)
    {
      const std::string        k_unit = stiffness_si_unit(rows.front()->exponent);
      std::vector<TableColumn> c      = {{"wall_height", "m", {}},
                                         {"k_total", k_unit, {}},
                                         {"gap", "m", {}},
                                         {"base_displacement", "m", {}},
                                         {"top_displacement", "m", {}},
                                         {"base_acceleration", "m/s^2", {}},
                                         {"top_acceleration", "m/s^2", {}},
                                         {"floor_acceleration", "m/s^2", {}},
                                         {"interstorey_drift", "m", {}},
                                         {"impact_force", "N", {}},
                                         {"n_impacts", "1", {}},
                                         {"permanent_indentation", "m", {}},
                                         {"amplification_base_acceleration", "1", {}},
                                         {"amplification_top_acceleration", "1", {}},
                                         {"amplification_interstorey_drift", "1", {}}};
      for (const StudyBuildingRun *r : rows)
      {
        const double v[] = {r->wall_height,
                            r->k_total,
                            r->gap,
                            r->base_displacement,
                            r->top_displacement,
                            r->base_acceleration,
                            r->top_acceleration,
                            r->max_floor_acceleration,
                            r->max_interstorey_drift,
                            r->peak_impact_force,
                            static_cast<double>(r->n_impacts),
                            r->permanent_indentation,
                            r->amplification_base_acc,
                            r->amplification_top_acc,
                            r->amplification_drift};
        for (std::size_t i = 0; i < c.size(); ++i)
          c[i].values.push_back(v[i]);
      }
      root.group("building").group(key.first).write_table(key.second, c);
    }
    file.commit();
  }

  nlohmann::ordered_json summary_json(const StudyScene &scene, const StudyResult &result)
  {
    nlohmann::ordered_json j;
    j["command"]                 = "study";
    j["kimp"]                    = version_line();
    j["units"]                   = {{"wall_height", "m"},
                                    {"k_per_metre", "kN/mm^n/m"},
                                    {"k_total", "kN/mm^n"},
                                    {"seconds", "s"}};
    j["building_width"]          = scene.fit.width;
    j["wall_seconds"]            = {{"fem", result.fem_seconds},
                                    {"fit", result.fit_seconds},
                                    {"building", result.building_seconds},
                                    {"extras", result.extras.seconds},
                                    {"charts", result.charts_seconds},
                                    {"total", result.wall_seconds}};
    nlohmann::ordered_json table = nlohmann::ordered_json::array();
    for (const StudyHeight &h : result.heights)
    {
      const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
      nlohmann::ordered_json               row;
      row["case"]               = h.name;
      row["wall_height"]        = h.wall_height;
      row["fem_from_cache"]     = h.fem_from_cache;
      row["fem_seconds"]        = h.fem_seconds;
      row["fit_seconds"]        = h.fit_seconds;
      row["fidelity"]           = h.auto_fidelity ? "auto" : "fixed";
      row["fem_h_contact"]      = used_h_contact(scene, h);
      row["fem_penalty_factor"] = used_penalty(scene, h);
      if (h.auto_fidelity)
      {
        row["fidelity_converged"] = h.ladder.converged;
        row["fidelity_levels"]    = h.ladder.outcomes.size();
      }
      row["fidelity_reason"] = h.fidelity_reason;
      const FemSummary &fem  = h.fem_case.summary;
      for (const auto &[key, value] : {std::pair{"n_dofs", fem.n_dofs},
                                       std::pair{"n_steps", fem.n_steps},
                                       std::pair{"dt", fem.dt},
                                       std::pair{"peak_force", fem.peak_force},
                                       std::pair{"contact_duration", fem.contact_duration}})
        if (value)
          row[std::string("fem_") + key] = *value;
      for (const auto &[law, fit, status, reference] :
           {std::tuple{"kelvin_voigt",
                       &h.kelvin_voigt,
                       &h.kelvin_voigt_status,
                       thesis ? thesis->kelvin_voigt : nan},
            std::tuple{"jankowski",
                       &h.jankowski,
                       &h.jankowski_status,
                       thesis ? thesis->jankowski : nan}})
      {
        nlohmann::ordered_json f;
        f["status"] = *status;
        if (*fit)
        {
          f["k_per_metre"]    = per_metre(*fit);
          f["k_lower"]        = per_metre_bound(*fit, false);
          f["k_upper"]        = per_metre_bound(*fit, true);
          f["k_total"]        = per_metre(*fit) * scene.fit.width;
          f["unit"]           = (*fit)->per_metre_unit();
          f["normalised_rms"] = (*fit)->normalised_rms;
          const double error  = numerical_error(h, std::string(law) == "kelvin_voigt" ? 1.0 : 1.5);
          if (std::isfinite(error))
            f["k_numerical_error"] = error;
        }
        if (std::isfinite(reference))
          f["thesis_table_2_1"] = reference;
        row[law] = f;
      }
      table.push_back(row);
    }
    j["k_table"]         = table;
    j["n_building_runs"] = result.building.size();
    std::size_t n_failed = 0;
    for (const StudyBuildingRun &r : result.building)
      n_failed += r.status != "ok";
    j["n_building_runs_not_ok"] = n_failed;
    if (!result.wall_sdofs.empty())
      j["flexible_wall"] = flexible_wall_json(result);
    add_velocity_summary(j, scene, result);
    return j;
  }
} // namespace kimp::app::study_internal
