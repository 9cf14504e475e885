// Writers of `kimp study`: k_table.csv, fidelity_levels.csv, building_response.csv, study.h5 and
// summary.json (docs/architecture.md "Results files").
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "app/laws/fit_run.h"
#include "app/study/study_columns.h"
#include "app/study/study_internal.h"
#include "app/study/study_velocity.h"
#include "base/format.h"
#include "io/results_file.h"
#include "io/summary.h"
#include "io/table.h"

namespace kimp::app::study_internal
{
  namespace
  {
    /// building_response.csv: one row per building run; k_total in the unit of its law's
    /// exponent (k_total_unit beside it).
    Table building_table(const std::vector<StudyBuildingRun> &runs)
    {
      Table t;
      t.text("record")
        .number("wall_height", "m")
        .text("law")
        .number("k_total", "1")
        .text("k_total_unit")
        .number("gap", "cm")
        .number("pga", "m/s^2")
        .number("peak_base_displacement", "cm")
        .number("peak_top_displacement", "cm")
        .number("peak_base_acceleration", "m/s^2")
        .number("peak_top_acceleration", "m/s^2")
        .number("peak_floor_acceleration", "m/s^2")
        .number("peak_interstorey_drift", "cm")
        .number("peak_impact_force", "kN")
        .number("wall_capacity_estimate", "kN")
        .number("peak_force_over_capacity", "1")
        .integer("n_impacts")
        .number("permanent_indentation", "mm")
        .number("amplification_base_acceleration", "1")
        .number("amplification_top_acceleration", "1")
        .number("amplification_interstorey_drift", "1")
        .number("wall_time", "s")
        .text("status");
      for (const StudyBuildingRun &r : runs)
      {
        const bool walls = r.law != "none";
        // A yielding wall: its own resistance (the contact part's peak is the local wave).
        const double force = r.yielding_wall ? r.wall_peak_resistance : r.peak_impact_force;
        t.add_row({r.record,
                   walls ? r.wall_height : nan,
                   r.law,
                   walls ? stiffness_to_kn_per_mm(r.k_total, r.exponent) : nan,
                   walls ? stiffness_display_unit(r.exponent) : std::string(),
                   walls ? r.gap * 100 : nan,
                   r.pga,
                   r.base_displacement * 100,
                   r.top_displacement * 100,
                   r.base_acceleration,
                   r.top_acceleration,
                   r.max_floor_acceleration,
                   r.max_interstorey_drift * 100,
                   r.peak_impact_force / 1e3,
                   r.wall_capacity > 0.0 ? r.wall_capacity / 1e3 : nan,
                   r.wall_capacity > 0.0 ? force / r.wall_capacity : nan,
                   static_cast<std::int64_t>(r.n_impacts),
                   r.permanent_indentation * 1e3,
                   r.amplification_base_acc,
                   r.amplification_top_acc,
                   r.amplification_drift,
                   r.wall_seconds,
                   r.status});
      }
      return t;
    }
  } // namespace

  Table k_table(const StudyScene &scene, const std::vector<const StudyHeight *> &cases)
  {
    const io::ColumnFormat error_format{2, {}, false};
    const io::ColumnFormat short_format{3, {}, true};
    Table                  t;
    // The answer first: height, velocity (reference or not), k, its fit's honesty; the FEM and
    // fidelity details after.
    t.number("wall_height", "m", io::ColumnFormat{3, {}, false})
      .number("impact_velocity", "m/s")
      .text("reference_velocity")
      .number("slab_mass", "kg/m")
      .number("fem_peak_force", "kN/m")
      .number("fem_contact_duration", "ms");
    for (const StudyLaw &law : study_laws())
    {
      const std::string name = law.name();
      add_k_columns(t, law);
      t.number(name + "_total", law.total_unit())
        .number(name + "_normalised_rms", "1")
        .number(name + "_peak_force_ratio", "1", short_format)
        .number(name + "_impulse_ratio", "1", short_format)
        .number(name + "_contact_duration_ratio", "1", short_format)
        .number("thesis_" + name, law.per_metre_unit());
    }
    for (const StudyLaw &law : study_laws())
      t.number(law.name() + "_numerical_error", law.per_metre_unit(), error_format);
    for (const StudyLaw &law : study_laws())
      t.number(law.name() + "_total_numerical_error", law.total_unit(), error_format);
    t.text("fidelity")
      .number("fem_h_contact", "cm", short_format)
      .number("fem_penalty_factor", "1", short_format)
      .text("fidelity_converged");
    for (const StudyLaw &law : study_laws())
      t.text(law.name() + "_status");
    t.text("material");
    for (const StudyLaw &law : study_laws())
      t.number("linear_" + law.name(), law.per_metre_unit());
    t.text("fem_from_cache");
    for (const StudyHeight *h : cases)
    {
      const std::optional<ThesisStiffness> thesis = thesis_row(h->wall_height);
      const io::FemSummary                &fem    = h->fem_case.summary;
      const double                         width  = scene.fit.width;
      // The cells in the order of the columns above.
      std::vector<Cell> row = number_cells({h->wall_height, h->fem_case.impact_velocity});
      row.push_back(std::string(h->reference_velocity ? "yes" : "no"));
      append_numbers(row,
                     {h->fem_case.slab_mass,
                      fem.peak_force.value_or(nan) / 1e3,
                      fem.contact_duration.value_or(nan) * 1e3});
      for (const StudyLawFit &law : h->laws)
      {
        const std::optional<FitResult> &fit = law.fit;
        add_k_cells(row, fit);
        append_numbers(row,
                       {per_metre(fit) * width,
                        fit ? fit->normalised_rms : nan,
                        fit ? fit->peak_force_ratio() : nan,
                        fit ? fit->impulse_ratio() : nan,
                        fit ? fit->contact_duration_ratio() : nan,
                        thesis_k(thesis, *law.law)});
      }
      for (const StudyLaw &law : study_laws())
        row.push_back(numerical_error(*h, law));
      for (const StudyLaw &law : study_laws())
        row.push_back(total_stiffness_error(0.0, numerical_error(*h, law), width));
      row.insert(row.end(),
                 {std::string(h->auto_fidelity ? "auto" : "fixed"),
                  used_h_contact(scene, *h) * 100.0,
                  used_penalty(scene, *h),
                  std::string(h->auto_fidelity ? (h->ladder.converged ? "yes" : "no") : "")});
      for (const StudyLawFit &law : h->laws)
        row.push_back(law.status);
      row.push_back(std::string(h->inelastic ? "inelastic" : "linear"));
      for (const StudyLawFit &law : h->laws)
        row.push_back(per_metre(law.linear));
      row.push_back(std::string(h->fem_from_cache ? "yes" : "no"));
      t.add_row(std::move(row));
    }
    return t;
  }

  namespace
  {
    /// One level of a height's fidelity ladder.
    struct FidelityRow
    {
      const StudyHeight *h     = nullptr;
      std::size_t        level = 0;

      const LevelOutcome  &outcome() const { return h->ladder.outcomes[level]; }
      const FidelityLevel &fem_level() const { return h->ladder.levels[level]; }
      bool                 used() const { return level == h->ladder.used; }
    };

    /// The columns of fidelity_levels.csv (every height) and study.h5 /fidelity/<H> (one
    /// height): the level, k of each study law, cost, state and (CSV) its engineer's quantities.
    std::vector<StudyColumn<FidelityRow>> fidelity_columns()
    {
      using R           = FidelityRow;
      const auto yes_no = [](bool value) { return std::string(value ? "yes" : "no"); };
      std::vector<StudyColumn<R>> columns = {
        number_column<R>({}, {"wall_height", "m"}, {}, [](const R &r) { return r.h->wall_height; }),
        number_column<R>({"h_contact", "m"},
                         {"h_contact", "cm"},
                         times(100),
                         [](const R &r) { return r.fem_level().h_contact; }),
        same_column<R>("penalty_factor",
                       "1",
                       [](const R &r) { return r.fem_level().penalty_factor; })};
      for (const StudyLaw &law : study_laws())
        columns.push_back(same_column<R>(law.name(),
                                         law.per_metre_unit(),
                                         [i = study_law_index(law), n = law.exponent()](const R &r)
                                         {
                                           const std::vector<double> &k = r.outcome().k;
                                           return stiffness_to_kn_per_mm(i < k.size() ? k[i] : nan,
                                                                         n);
                                         }));
      columns.insert(
        columns.end(),
        {number_column<R>({"seconds", "s"},
                          {"wall_time", "s"},
                          {},
                          [](const R &r) { return r.outcome().seconds; }),
         hdf5_column<R>("ok", "1", [](const R &r) { return flag(r.outcome().ok); }),
         hdf5_column<R>("from_cache", "1", [](const R &r) { return flag(r.outcome().from_cache); }),
         csv_text_column<R>("fem_from_cache",
                            [yes_no](const R &r) { return yes_no(r.outcome().from_cache); }),
         hdf5_column<R>("used", "1", [](const R &r) { return flag(r.used()); }),
         csv_text_column<R>("used", [yes_no](const R &r) { return yes_no(r.used()); }),
         csv_text_column<R>("status", [](const R &r) { return r.outcome().status; })});
      // The engineer's quantities of the level's record (SI; empty: not shown).
      for (const LadderQuantity &q : ladder_quantities())
        columns.push_back(number_column<R>({},
                                           {q.key, q.unit},
                                           {},
                                           [key = q.key](const R &r)
                                           {
                                             const auto &values = r.outcome().quantities;
                                             const auto  it     = values.find(key);
                                             return it == values.end() ? nan : it->second;
                                           }));
      return columns;
    }

    /// Every level climbed by the heights `heights`, in order.
    std::vector<FidelityRow> fidelity_rows(const std::vector<const StudyHeight *> &heights)
    {
      std::vector<FidelityRow> rows;
      for (const StudyHeight *h : heights)
        for (std::size_t i = 0; i < h->ladder.outcomes.size(); ++i)
          rows.push_back({h, i});
      return rows;
    }

    /// One engineer's quantity of a height against a comparison run.
    struct QuantityRow
    {
      double               wall_height = 0.0; ///< m
      std::string          comparison;        ///< "numerical error", "far side absorbing"
      const QuantityError *error = nullptr;
    };

    /// DIR/fidelity_quantities.csv: per height the engineer's quantities of the reported level
    /// against the second finest level ("numerical error") and against the other far side
    /// (fem.fidelity_far_side_spread), their change and the verdict against the 5 % target.
    void write_quantity_convergence_csv(const OutputDir                &output,
                                        const std::vector<StudyHeight> &heights)
    {
      std::vector<QuantityRow> rows;
      for (const StudyHeight &h : heights)
      {
        for (const QuantityError &e : h.ladder.quantity_errors)
          rows.push_back({h.wall_height, "numerical error", &e});
        for (const QuantityError &e : h.ladder.far_side_spread)
          rows.push_back({h.wall_height, "far side " + h.ladder.other_far_side, &e});
      }
      if (rows.empty())
        return;
      using R = QuantityRow;
      // "other": the second finest level, or the run with the other far side; "reported": the
      // reported level.
      const std::vector<StudyColumn<R>> columns = {
        same_column<R>("wall_height", "m", [](const R &r) { return r.wall_height; }),
        csv_text_column<R>("comparison", [](const R &r) { return r.comparison; }),
        csv_text_column<R>("quantity", [](const R &r) { return r.error->key; }),
        csv_text_column<R>("unit", [](const R &r) { return r.error->unit; }),
        same_column<R>("other", "", [](const R &r) { return r.error->coarse; }),
        same_column<R>("reported", "", [](const R &r) { return r.error->fine; }),
        same_column<R>("change_percent", "1", [](const R &r) { return 100.0 * r.error->relative; }),
        same_column<R>("target_percent",
                       "1",
                       [](const R &) { return 100.0 * ladder_quantity_tolerance; }),
        csv_text_column<R>("verdict", [](const R &r) { return r.error->verdict; })};
      study_table(columns, rows, StudyFile::csv).write_csv(output.file("fidelity_quantities.csv"));
    }
  } // namespace

  void write_k_table_csv(const OutputDir                &output,
                         const StudyScene               &scene,
                         const std::vector<StudyHeight> &heights,
                         const std::vector<StudyHeight> &velocity_cases)
  {
    StudyResult all; // rows by height, then impact velocity
    all.heights        = heights;
    all.velocity_cases = velocity_cases;
    // The reference velocity's rows first (the k of the building runs), then the other
    // velocities by height and velocity.
    std::vector<const StudyHeight *> cases = k_table_cases(all);
    std::stable_partition(cases.begin(),
                          cases.end(),
                          [](const StudyHeight *h) { return h->reference_velocity; });
    k_table(scene, cases).write_csv(output.file("k_table.csv"));
    std::vector<const StudyHeight *> climbed;
    for (const StudyHeight &h : heights)
      climbed.push_back(&h);
    const std::vector<FidelityRow> levels = fidelity_rows(climbed);
    if (levels.empty())
      return;
    study_table(fidelity_columns(), levels, StudyFile::csv)
      .write_csv(output.file("fidelity_levels.csv"));
    write_quantity_convergence_csv(output, heights);
  }

  void write_building_csv(const OutputDir &output, const std::vector<StudyBuildingRun> &runs)
  {
    building_table(runs).write_csv(output.file("building_response.csv"));
  }

  void write_study_fits(ResultsGroup &g, const StudyHeight &h, double width)
  {
    for (const StudyLawFit &law : h.laws)
    {
      ResultsGroup f = g.group(law.law->name());
      f.set_status(law.status);
      if (const std::optional<FitResult> &fit = law.fit)
        write_fit_result(f, *fit, width, FitResultLayout::study);
    }
  }

  void write_study_h5(const io::LoadedScene<StudyScene> &loaded,
                      const StudyResult                 &result,
                      const OutputDir                   &output)
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
      write_study_fits(g, h, scene.fit.width);
    }

    std::vector<const StudyHeight *> heights;
    for (const StudyHeight &h : result.heights)
      heights.push_back(&h);
    k_table(scene, heights).write_hdf5(root, "k_table");
    root.group("k_table").set_attribute("building_width_m", scene.fit.width);
    write_study_extras(root, result.extras);
    write_flexible_wall_h5(root, result);
    write_yielding_wall_h5(root, scene, result);
    write_velocity_h5(root, scene, result);

    // /fidelity/<H>: the levels climbed (fidelity: auto).
    for (const StudyHeight &h : result.heights)
    {
      if (!h.auto_fidelity)
        continue;
      const Table  levels   = study_table(fidelity_columns(), fidelity_rows({&h}), StudyFile::hdf5);
      ResultsGroup fidelity = root.group("fidelity");
      levels.write_hdf5(fidelity, h.name);
      ResultsGroup table = fidelity.group(h.name);
      table.set_attribute("reason", h.fidelity_reason);
      table.set_attribute("converged", h.ladder.converged ? 1.0 : 0.0);
      table.set_attribute("tolerance", scene.fem.fidelity_tolerance);
    }

    // /building/<record>/<law>: one row per wall height (law "none": the run without walls).
    for (const auto &[key, rows] : by_record_and_law(result.building, true))
    {
      Table t;
      t.number("wall_height", "m")
        .number("k_total", stiffness_si_unit(rows.front()->exponent))
        .number("gap", "m")
        .number("base_displacement", "m")
        .number("top_displacement", "m")
        .number("base_acceleration", "m/s^2")
        .number("top_acceleration", "m/s^2")
        .number("floor_acceleration", "m/s^2")
        .number("interstorey_drift", "m")
        .number("impact_force", "N")
        .number("wall_capacity_estimate", "N")
        .number("n_impacts", "1")
        .number("permanent_indentation", "m")
        .number("amplification_base_acceleration", "1")
        .number("amplification_top_acceleration", "1")
        .number("amplification_interstorey_drift", "1");
      for (const StudyBuildingRun *r : rows)
        t.add_row(number_cells({r->wall_height,
                                r->k_total,
                                r->gap,
                                r->base_displacement,
                                r->top_displacement,
                                r->base_acceleration,
                                r->top_acceleration,
                                r->max_floor_acceleration,
                                r->max_interstorey_drift,
                                r->peak_impact_force,
                                r->wall_capacity,
                                static_cast<double>(r->n_impacts),
                                r->permanent_indentation,
                                r->amplification_base_acc,
                                r->amplification_top_acc,
                                r->amplification_drift}));
      ResultsGroup record = root.group("building").group(key.first);
      t.write_hdf5(record, key.second);
    }
    file.commit();
  }

  std::vector<std::pair<std::string, double>> cost_by_stage(const StudyResult &result)
  {
    std::vector<std::pair<std::string, double>> stages = {{"fem", result.fem_seconds},
                                                          {"fit", result.fit_seconds},
                                                          {"building", result.building_seconds}};
    if (!result.wall_sdofs.empty())
      stages.emplace_back("flexible_wall", result.flexible_wall_seconds);
    const StudyExtras &e = result.extras;
    if (!e.fem_accuracy.empty() || !e.lumped_accuracy.empty() || !e.stability.empty() ||
        !e.fem_stability.empty() || !e.sensitivity.empty())
      stages.emplace_back("extras", e.seconds);
    if (result.charts_seconds > 0.0)
      stages.emplace_back("charts", result.charts_seconds);
    double sum = 0.0;
    for (const auto &stage : stages)
      sum += stage.second;
    stages.emplace_back("other", std::max(0.0, result.wall_seconds - sum));
    return stages;
  }

  std::string cost_text(const StudyResult &result)
  {
    static const std::map<std::string, std::string> names = {{"fem", "FEM"},
                                                             {"fit", "fits"},
                                                             {"building", "building runs"},
                                                             {"flexible_wall", "flexible walls"},
                                                             {"extras", "extra studies"},
                                                             {"charts", "charts"},
                                                             {"other", "files and the rest"}};
    std::string                                     text;
    for (const auto &[stage, seconds] : cost_by_stage(result))
      text += fmt::format("{} {} s, ", names.at(stage), base::sig(seconds, 3));
    return text + fmt::format("total {} s", base::sig(result.wall_seconds, 3));
  }

  namespace
  {
    /// summary.json's status of a height: "ok", else "warning: " or (a fit failed) "failed: "
    /// and each law's status ("Kelvin-Voigt: ...; Jankowski: ...").
    std::string height_status(const StudyHeight &h)
    {
      if (all_ok(h.laws))
        return "ok";
      bool        failed = false;
      std::string laws;
      for (const StudyLawFit &law : h.laws)
      {
        failed = failed || law.status.rfind("failed", 0) == 0;
        laws += fmt::format("{}{}: {}", laws.empty() ? "" : "; ", law.law->title, law.status);
      }
      return (failed ? "failed: " : "warning: ") + laws;
    }
  } // namespace

  nlohmann::ordered_json summary_json(const StudyScene &scene, const StudyResult &result)
  {
    nlohmann::ordered_json j = io::summary_preamble("study");
    j["units"]               = {{"wall_height", "m"},
                                {"k_per_metre", "kN/mm^n/m"},
                                {"k_total", "kN/mm^n"},
                                {"isolation_mass", "kg"},
                                {"wall_mass", "kg"},
                                {"effective_mass", "kg"},
                                {"wall_time", "s"}};
    j["building_width"]      = scene.fit.width;
    // The contact the impact laws describe (kimp export-opensees takes m_eff and the COR from
    // here): the building's isolation level against its wall.
    const double m_building = scene.building.isolation_mass, m_wall = scene.walls.mass;
    j["contact"]   = {{"isolation_mass", m_building},
                      {"wall_mass", m_wall},
                      {"effective_mass", m_building * m_wall / (m_building + m_wall)},
                      {"cor", scene.fit.cor},
                      {"peak_tolerance", scene.fit.peak_tolerance}};
    j["wall_time"] = result.wall_seconds;
    nlohmann::ordered_json stages;
    for (const auto &[stage, seconds] : cost_by_stage(result))
      stages[stage] = seconds;
    j["wall_time_by_stage"] = stages;
    // One case per wall height, in the shape of every command's summary.json (name, status).
    j["cases"] = nlohmann::ordered_json::array();
    for (const StudyHeight &h : result.heights)
    {
      j["cases"].push_back({{"name", h.name},
                            {"status", height_status(h)},
                            {"wall_height", h.wall_height},
                            {"wall_time", h.fem_seconds + h.fit_seconds}});
    }
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
      row["fidelity_reason"]    = h.fidelity_reason;
      const io::FemSummary &fem = h.fem_case.summary;
      if (fem.n_dofs)
        row["fem_n_dofs"] = *fem.n_dofs;
      if (fem.n_steps)
        row["fem_n_steps"] = *fem.n_steps;
      for (const auto &[key, value] : {std::pair{"dt", fem.dt},
                                       std::pair{"peak_force", fem.peak_force},
                                       std::pair{"contact_duration", fem.contact_duration}})
        if (value)
          row[std::string("fem_") + key] = *value;
      for (const StudyLawFit &law : h.laws)
      {
        nlohmann::ordered_json f         = law_json(h, law, scene.fit.width);
        const double           reference = thesis_k(thesis, *law.law);
        if (std::isfinite(reference))
          f["thesis_table_2_1"] = reference;
        row[law.law->name()] = f;
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
    if (!result.yielding_walls.empty())
      j["yielding_wall"] = yielding_wall_json(scene, result);
    add_velocity_summary(j, scene, result);
    return j;
  }
} // namespace kimp::app::study_internal
