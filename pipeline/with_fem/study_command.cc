// `kimp study`: FEM per wall height -> k fitted with laws 2 and 4 at COR 0.7 (PHYSICS.md §4)
// -> k_total = k_per_m·W -> isolated building pounding on moat walls (PHYSICS.md §2-3).
#include "pipeline/with_fem/study_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>
#include <unistd.h>

#include "lumped/response.h"
#include "pipeline/cli.h"
#include "pipeline/helper_programs.h"
#include "pipeline/logging.h"
#include "pipeline/lumped_command.h"
#include "pipeline/results_file.h"
#include "pipeline/with_fem/study_fem.h"

extern char **environ;

namespace kimp::pipeline
{
  namespace
  {
    using Clock = std::chrono::steady_clock;

    double seconds_since(Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }

    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    std::optional<ThesisStiffness> thesis_row(double wall_height)
    {
      for (const ThesisStiffness &row : thesis_table_2_1())
        if (std::abs(row.wall_height - wall_height) < 1e-9)
          return row;
      return std::nullopt;
    }

    /// k of a fit in kN/mm^n per metre (or NaN), and its confidence interval.
    double per_metre(const std::optional<FitResult> &fit)
    {
      return fit ? fit->stiffness_per_metre_display() : nan;
    }
    double per_metre_bound(const std::optional<FitResult> &fit, bool upper)
    {
      return fit ? stiffness_to_kn_per_mm(upper ? fit->stiffness.upper : fit->stiffness.lower,
                                          fit->exponent.value) :
                   nan;
    }

    std::string number(double value)
    {
      return std::isfinite(value) ? fmt::format("{:.6g}", value) : "";
    }

    // ---------------------------------------------------------------- stage 1: FEM and fits

    std::optional<FitResult> fit_variant(const FemCase       &fem_case,
                                         const FitVariant    &variant,
                                         const StudyFitScene &settings,
                                         std::string         &status)
    {
      try
      {
        ForceHistory history = force_history(fem_case, !settings.raw_force);
        if (settings.force_only_contact)
          history.indentation.clear();
        FitOptions options          = variant.options;
        options.separation_fraction = settings.separation_fraction;
        const FitResult fit         = fit_impact_law(history,
                                             fem_case.slab_mass,
                                             fem_case.impact_velocity,
                                             variant.law,
                                             options);
        status                      = "ok";
        return fit;
      }
      catch (const std::exception &error)
      {
        status = std::string("failed: ") + error.what();
        logger().warn("{} {}: fit {}", fem_case.name, variant.name, status);
        return std::nullopt;
      }
    }

    StudyHeight run_height(const StudyScene &scene, double wall_height, const OutputDir &output)
    {
      StudyHeight h;
      h.wall_height              = wall_height;
      h.name                     = fem_case_name(wall_height);
      StudyFemCase fem           = study_fem_case(scene.fem, wall_height, output);
      h.fem_case                 = std::move(fem.fem_case);
      h.fem_from_cache           = fem.from_cache;
      h.fem_seconds              = fem.wall_seconds;
      const Clock::time_point t0 = Clock::now();
      for (const FitVariant &variant : standard_fit_variants({}, scene.fit.cor))
      {
        if (variant.name == "kelvin_voigt_cor_fixed")
          h.kelvin_voigt = fit_variant(h.fem_case, variant, scene.fit, h.kelvin_voigt_status);
        else if (variant.name == "jankowski_cor_fixed")
          h.jankowski = fit_variant(h.fem_case, variant, scene.fit, h.jankowski_status);
      }
      h.fit_seconds = seconds_since(t0);
      return h;
    }

    void log_k_table(const StudyScene &scene, const std::vector<StudyHeight> &heights)
    {
      logger().info("k table (per metre of wall; total = x {} m), beside thesis Table 2.1:",
                    scene.fit.width);
      logger().info("  H [m] | KV kN/mm/m [95 % CI]        | Table 2.1 | KV total kN/mm | "
                    "Jankowski kN/mm^1.5/m [95 % CI] | Table 2.1 | J total kN/mm^1.5");
      for (const StudyHeight &h : heights)
      {
        const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
        logger().info("  {:5.2f} | {:8.4g} [{:.4g}, {:.4g}] | {:>9} | {:14.5g} | {:8.4g} [{:.4g}, "
                      "{:.4g}] | {:>9} | {:.5g}",
                      h.wall_height,
                      per_metre(h.kelvin_voigt),
                      per_metre_bound(h.kelvin_voigt, false),
                      per_metre_bound(h.kelvin_voigt, true),
                      thesis ? number(thesis->kelvin_voigt) : "-",
                      per_metre(h.kelvin_voigt) * scene.fit.width,
                      per_metre(h.jankowski),
                      per_metre_bound(h.jankowski, false),
                      per_metre_bound(h.jankowski, true),
                      thesis ? number(thesis->jankowski) : "-",
                      per_metre(h.jankowski) * scene.fit.width);
      }
    }

    // ---------------------------------------------------------------- stage 2: building runs

    std::string k_text(double k_total_si, double exponent)
    {
      return fmt::format("{:.12g} {}",
                         stiffness_to_kn_per_mm(k_total_si, exponent),
                         stiffness_display_unit(exponent));
    }

    void fill_peaks(StudyBuildingRun       &run,
                    const LumpedCaseResult &result,
                    unsigned int            top_dof,
                    const lumped::Response *without_walls)
    {
      run.status       = result.status;
      run.wall_seconds = result.wall_time;
      run.pga          = result.pga;
      if (!result.ok())
        return;
      const lumped::Response &r = result.response;
      run.base_displacement     = r.peak_displacement.at(0);
      run.top_displacement      = r.peak_displacement.at(top_dof);
      run.base_acceleration     = r.peak_absolute_acceleration.at(0);
      run.top_acceleration      = r.peak_absolute_acceleration.at(top_dof);
      run.max_floor_acceleration =
        *std::max_element(r.peak_absolute_acceleration.begin() + 1,
                          r.peak_absolute_acceleration.begin() + top_dof + 1);
      run.max_interstorey_drift = r.max_interstorey_drift();
      run.n_impacts             = r.n_impacts();
      for (const lumped::ContactResult &c : r.contacts)
      {
        run.peak_impact_force     = std::max(run.peak_impact_force, c.peak_force);
        run.permanent_indentation = std::max(run.permanent_indentation, c.permanent_indentation);
      }
      if (without_walls)
      {
        const lumped::Amplification a = lumped::amplification_factors(r, *without_walls);
        run.amplification_base_acc    = a.absolute_acceleration.at(0);
        run.amplification_top_acc     = a.absolute_acceleration.at(top_dof);
        run.amplification_drift =
          run.max_interstorey_drift / std::max(without_walls->max_interstorey_drift(), 1e-300);
      }
    }

    std::string record_label(const GroundMotionScene &record, std::set<std::string> &used)
    {
      std::string label = record.record;
      for (int i = 2; !used.insert(label).second; ++i)
        label = fmt::format("{}_{}", record.record, i);
      return label;
    }

    std::vector<StudyBuildingRun> run_building(const StudyScene               &scene,
                                               const std::vector<StudyHeight> &heights)
    {
      std::vector<StudyBuildingRun> runs;
      std::set<std::string>         labels;
      const unsigned int            top_dof = scene.building.n_storeys;
      for (const GroundMotionScene &record : study_records(scene))
      {
        const std::string label = record_label(record, labels);
        StudyBuildingRun  bare;
        bare.record = label;
        bare.law    = "none";
        lumped::GroundMotion motion;
        try
        {
          motion = load_ground_motion(record);
        }
        catch (const std::exception &error)
        {
          bare.status = std::string("failed: ") + error.what();
          logger().warn("record {}: {}", label, bare.status);
          runs.push_back(bare);
          continue;
        }
        const LumpedScene      base = study_lumped_scene(scene, record);
        const LumpedCaseResult none = run_lumped_case("no_walls", base, motion, record.scale);
        fill_peaks(bare, none, top_dof, nullptr);
        runs.push_back(bare);
        if (!none.ok())
        {
          logger().warn("record {}: run without walls {}", label, none.status);
          continue;
        }
        const double gap =
          scene.walls.gap.value_or((1.0 - scene.walls.gap_reduction) * bare.base_displacement);
        logger().info("record {} (PGA {:.3f} g): no walls: peak isolation displacement {:.4g} cm, "
                      "top acceleration {:.4g} m/s^2 -> wall gap {:.4g} cm",
                      label,
                      none.pga / lumped::standard_gravity,
                      bare.base_displacement * 100,
                      bare.top_acceleration,
                      gap * 100);

        for (const StudyHeight &h : heights)
        {
          const std::vector<std::pair<std::string, const std::optional<FitResult> *>> laws = {
            {"modified_kelvin_voigt", &h.kelvin_voigt},
            {"jankowski", &h.jankowski},
            {"hysteretic", &h.jankowski}};
          for (const auto &[law, fit] : laws)
          {
            StudyBuildingRun run;
            run.record      = label;
            run.wall_height = h.wall_height;
            run.law         = law;
            run.gap         = gap;
            if (!*fit)
            {
              run.status = "skipped: no fitted k for " + h.name;
              runs.push_back(run);
              continue;
            }
            run.exponent          = (*fit)->exponent.value;
            run.k_total           = (*fit)->stiffness.value * scene.fit.width;
            LumpedScene s         = base;
            s.walls.left.present  = true;
            s.walls.right.present = true;
            s.walls.left.gap      = gap;
            s.walls.right.gap     = gap;
            s.impact.law          = law;
            s.impact.k            = k_text(run.k_total, run.exponent);
            s.impact.exponent     = std::nullopt;
            s.impact.cor          = scene.fit.cor;
            const LumpedCaseResult done =
              run_lumped_case(h.name + "_" + law, s, motion, record.scale);
            fill_peaks(run, done, top_dof, &none.response);
            if (!done.ok())
              logger().warn("record {} {} {}: {}", label, h.name, law, done.status);
            runs.push_back(run);
          }
        }
      }
      return runs;
    }

    // ---------------------------------------------------------------- stage 3: files

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
              "kelvin_voigt_status",
              "jankowski_status"};
    }

    std::vector<std::string> k_table_row(const StudyScene &scene, const StudyHeight &h)
    {
      const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
      const auto                           value  = [&](const char *key)
      {
        const auto it = h.fem_case.summary.find(key);
        return it == h.fem_case.summary.end() ? nan : it->second;
      };
      return {number(h.wall_height),
              number(h.fem_case.slab_mass),
              number(h.fem_case.impact_velocity),
              number(value("peak_force") / 1e3),
              number(value("contact_duration") * 1e3),
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
              h.kelvin_voigt_status,
              h.jankowski_status};
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

    std::string si_stiffness_unit(double exponent, bool per_metre_of_wall)
    {
      const std::string n = exponent == 1.0 ? "" : fmt::format("^{}", exponent);
      return "N/m" + n + (per_metre_of_wall ? "/m" : "");
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
          const FitResult  &r    = **fit;
          const std::string unit = si_stiffness_unit(r.exponent.value, true);
          f.write_scalar("stiffness", r.stiffness.value, unit);
          f.write_scalar("stiffness_lower", r.stiffness.lower, unit);
          f.write_scalar("stiffness_upper", r.stiffness.upper, unit);
          f.write_scalar("stiffness_total",
                         r.stiffness.value * scene.fit.width,
                         si_stiffness_unit(r.exponent.value, false));
          f.write_scalar("cor", r.cor.value, "1");
          f.write_scalar("exponent", r.exponent.value, "1");
          f.write_scalar("normalised_rms", r.normalised_rms, "1");
          f.write_scalar("model_effective_cor", r.model_effective_cor, "1");
          f.write("time", r.time, "s");
          f.write("fem_force", r.fem_force, "N/m");
          f.write("model_force", r.model_force, "N/m");
        }
      }

      std::vector<TableColumn> k(11);
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
                                 thesis ? thesis->jankowski : nan};
        for (std::size_t i = 0; i < k.size(); ++i)
          k[i].values.push_back(values[i]);
      }
      root.write_table("k_table", k);
      root.group("k_table").set_attribute("building_width_m", scene.fit.width);

      // /building/<record>/<law>: one row per wall height (law "none": the run without walls).
      std::map<std::pair<std::string, std::string>, std::vector<const StudyBuildingRun *>> tables;
      for (const StudyBuildingRun &r : result.building)
        if (r.status == "ok")
          tables[{r.record, r.law}].push_back(&r);
      for (const auto &[key, rows] : tables)
      {
        const std::string        k_unit = si_stiffness_unit(rows.front()->exponent, false);
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
                                      {"charts", result.charts_seconds},
                                      {"total", result.wall_seconds}};
      nlohmann::ordered_json table = nlohmann::ordered_json::array();
      for (const StudyHeight &h : result.heights)
      {
        const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
        nlohmann::ordered_json               row;
        row["case"]           = h.name;
        row["wall_height"]    = h.wall_height;
        row["fem_from_cache"] = h.fem_from_cache;
        row["fem_seconds"]    = h.fem_seconds;
        row["fit_seconds"]    = h.fit_seconds;
        for (const char *key : {"n_dofs", "n_steps", "dt", "peak_force", "contact_duration"})
          if (const auto it = h.fem_case.summary.find(key); it != h.fem_case.summary.end())
            row[std::string("fem_") + key] = it->second;
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
      return j;
    }

    std::string report_markdown(const StudyScene &scene, const StudyResult &result, bool charts)
    {
      std::string md = "# kimp wall-height study\n\n" + version_line() + "\n\n";
      md += fmt::format("## Impact stiffness per wall height (fitted at COR {}, W = {} m)\n\n",
                        scene.fit.cor,
                        scene.fit.width);
      md += "| H (m) | KV kN/mm/m [95 % CI] | Table 2.1 | KV total kN/mm | Jankowski "
            "kN/mm^1.5/m [95 % CI] | Table 2.1 | J total kN/mm^1.5 | FEM from cache |\n"
            "|---|---|---|---|---|---|---|---|\n";
      for (const StudyHeight &h : result.heights)
      {
        const std::optional<ThesisStiffness> t = thesis_row(h.wall_height);
        md += fmt::format("| {:.2f} | {} [{}, {}] | {} | {} | {} [{}, {}] | {} | {} | {} |\n",
                          h.wall_height,
                          number(per_metre(h.kelvin_voigt)),
                          number(per_metre_bound(h.kelvin_voigt, false)),
                          number(per_metre_bound(h.kelvin_voigt, true)),
                          t ? number(t->kelvin_voigt) : "-",
                          number(per_metre(h.kelvin_voigt) * scene.fit.width),
                          number(per_metre(h.jankowski)),
                          number(per_metre_bound(h.jankowski, false)),
                          number(per_metre_bound(h.jankowski, true)),
                          t ? number(t->jankowski) : "-",
                          number(per_metre(h.jankowski) * scene.fit.width),
                          h.fem_from_cache ? "yes" : "no");
      }
      md += "\nThe intervals are the fits' own (law misfit), not the FEM discretisation error. "
            "The thesis used non-linear materials in ADINA and did not state its slab mass, so "
            "the trend with H and the order of magnitude are what should agree.\n\n"
            "Data: [k_table.csv](k_table.csv), [study.h5](study.h5) (`/k_table`, `/fit/<H>`, "
            "`/fem/<H>`).\n\n";
      if (charts)
        md += "![FEM force histories with the fitted laws](charts/force_histories.png)\n\n"
              "![k against wall height](charts/k_vs_height.png)\n\n";

      md += "## Building response\n\n"
            "Isolated building of PHYSICS.md §3 with moat walls on both sides, gap "
            "from the no-wall peak isolation displacement; modified Kelvin-Voigt with k_KV, "
            "Jankowski and the hysteretic law with k_Jankowski.\n\n"
            "| record | H (m) | law | gap (cm) | base acc. (m/s²) | top acc. (m/s²) | drift (cm) | "
            "impact force (kN) | impacts | top acc. amplification | status |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|\n";
      for (const StudyBuildingRun &r : result.building)
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                          r.record,
                          r.law == "none" ? "-" : number(r.wall_height),
                          r.law,
                          r.law == "none" ? "-" : number(r.gap * 100),
                          number(r.base_acceleration),
                          number(r.top_acceleration),
                          number(r.max_interstorey_drift * 100),
                          number(r.peak_impact_force / 1e3),
                          r.n_impacts,
                          number(r.amplification_top_acc),
                          r.status);
      md += "\nData: [building_response.csv](building_response.csv), study.h5 "
            "`/building/<record>/<law>`.\n\n";
      if (charts)
        md += "![building response against wall height](charts/building_response.png)\n\n";
      md += fmt::format("## Cost\n\nFEM {:.2f} s, fits {:.2f} s, building runs {:.2f} s, charts "
                        "{:.2f} s, total {:.2f} s (see summary.json).\n",
                        result.fem_seconds,
                        result.fit_seconds,
                        result.building_seconds,
                        result.charts_seconds,
                        result.wall_seconds);
      return md;
    }

    // ---------------------------------------------------------------- stage 4: charts

    /// Draw the charts; false (with a warning) if they could not be drawn.
    bool draw_charts(const OutputDir &output)
    {
      const std::filesystem::path script = find_helper_script("study_charts.py");
      if (script.empty())
      {
        logger().warn("charts skipped: scripts/study_charts.py not found (set KIMP_DATA_DIR to "
                      "the kimp source tree)");
        return false;
      }
      const std::filesystem::path log = output.file("charts/charts.log");
      std::filesystem::remove(log);
      const int status = run_program({"/usr/bin/python3", script.string(), output.path().string()},
                                     ProgramOutput::append,
                                     log);
      if (status != 0)
      {
        logger().warn("charts skipped: {} exited with {} (needs /usr/bin/python3 with matplotlib "
                      "and h5py; Debian python3-matplotlib python3-h5py); see {}",
                      script.string(),
                      status,
                      log.string());
        return false;
      }
      logger().info("charts written to {}", output.file("charts").string());
      return true;
    }
  } // namespace

  const std::vector<ThesisStiffness> &thesis_table_2_1()
  {
    static const std::vector<ThesisStiffness> table = {{1.00, 150, 50},
                                                       {1.25, 90, 27},
                                                       {1.50, 45, 10},
                                                       {2.00, 25, 5}};
    return table;
  }

  StudyResult run_study(const LoadedScene<StudyScene> &loaded, const OutputDir &output)
  {
    const Clock::time_point start = Clock::now();
    const StudyScene       &scene = loaded.scene;
    StudyResult             result;
    for (const double height : scene.fem.wall_heights)
    {
      result.heights.push_back(run_height(scene, height, output));
      result.fem_seconds += result.heights.back().fem_seconds;
      result.fit_seconds += result.heights.back().fit_seconds;
    }
    log_k_table(scene, result.heights);

    std::vector<std::vector<std::string>> k_rows;
    for (const StudyHeight &h : result.heights)
      k_rows.push_back(k_table_row(scene, h));
    write_csv_atomic(output.file("k_table.csv"), k_table_header(), k_rows);

    const Clock::time_point building_start = Clock::now();
    result.building                        = run_building(scene, result.heights);
    result.building_seconds                = seconds_since(building_start);
    std::vector<std::vector<std::string>> b_rows;
    for (const StudyBuildingRun &r : result.building)
      b_rows.push_back(building_row(r));
    write_csv_atomic(output.file("building_response.csv"), building_header(), b_rows);
    write_study_h5(loaded, result, output);

    bool charts = false;
    if (scene.charts)
    {
      const Clock::time_point charts_start = Clock::now();
      charts                               = draw_charts(output);
      result.charts_seconds                = seconds_since(charts_start);
    }
    result.wall_seconds = seconds_since(start);
    write_text_atomic(output.file("report.md"), report_markdown(scene, result, charts));
    write_text_atomic(output.file("summary.json"), summary_json(scene, result).dump(2) + "\n");
    logger().info("study done in {:.2f} s (FEM {:.2f} s, fits {:.2f} s, building {:.2f} s, "
                  "charts {:.2f} s): {}",
                  result.wall_seconds,
                  result.fem_seconds,
                  result.fit_seconds,
                  result.building_seconds,
                  result.charts_seconds,
                  output.file("report.md").string());
    return result;
  }

  void register_study_command(CLI::App &app)
  {
    struct Options
    {
      std::string scene;
      std::string output;
      bool        print_defaults = false;
    };
    auto      options = std::make_shared<Options>();
    CLI::App *command = app.add_subcommand(
      "study",
      "the wall-height study: FEM per height -> fitted k (Kelvin-Voigt, Jankowski) -> k table "
      "beside thesis Table 2.1 -> building pounding runs -> CSV, study.h5, charts, report.md");
    command->add_option("scene", options->scene, "study scene (YAML; none: the default study)")
      ->type_name("SCENE.yaml");
    command->add_option("-o,--output", options->output, "output directory (created if missing)")
      ->type_name("DIR");
    command->add_flag("--print-defaults",
                      options->print_defaults,
                      "print the annotated default study scene and exit");
    command->preparse_callback([options](std::size_t) { *options = Options{}; });
    command->callback(
      [options]()
      {
        if (options->print_defaults)
          throw PrintDefaults(default_scene_text<StudyScene>("kimp study scene (defaults)"));
        if (options->output.empty())
          throw CLI::RequiredError("the output directory -o/--output DIR");
        logger().info("{}: study {}",
                      version_line(),
                      options->scene.empty() ? "(default scene)" : options->scene);
        const LoadedScene<StudyScene> scene =
          options->scene.empty() ? read_scene_text<StudyScene>("", "(default study scene)") :
                                   read_scene<StudyScene>(options->scene);
        int mpi_initialized = 0, rank = 0;
        MPI_Initialized(&mpi_initialized);
        if (!mpi_initialized)
          throw std::logic_error("kimp study: MPI is not initialised (fem::MpiSession in main)");
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        if (rank != 0)
          return;
        const OutputDir output(options->output);
        run_study(scene, output);
      });
  }
} // namespace kimp::pipeline
