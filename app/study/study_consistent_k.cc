// Consistent k of `kimp study` (docs/physics.md §4 "Consistent k"): each building run is repeated
// with k(H, v_imp) of its own impact velocity until k changes by less than the tolerance; and the
// files, results groups and report sections of the k(H, v) table and of these iterations.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <set>

#include "app/lumped/lumped_run.h"
#include "app/study/study_columns.h"
#include "app/study/study_internal.h"
#include "app/study/study_velocity.h"
#include "base/errors.h"
#include "base/format.h"
#include "base/logging.h"
#include "io/table.h"
#include "lumped/integrators/response.h"

namespace kimp::app::study_internal
{
  namespace
  {
    /// The gap run_building() used for `record` (NaN if its run without walls failed).
    double record_gap(const StudyScene &scene, const StudyResult &result, const std::string &record)
    {
      for (const StudyBuildingRun &r : result.building)
        if (r.record == record && r.law == "none" && r.status == "ok")
          return wall_gap(scene, r.base_displacement);
      return nan;
    }

    double final_k(const ConsistentKRun &run)
    {
      return run.iterations.empty() ? nan : run.iterations.back().k_total;
    }

    double k_display(double k, double exponent)
    {
      return std::isfinite(k) ? stiffness_to_kn_per_mm(k, exponent) : nan;
    }

    /// What the consistent-k runs of one record share.
    struct RecordRuns
    {
      const StudyScene           &scene;
      const KTable               &table;
      const std::vector<double>  &velocities; ///< of `table`, m/s
      const LumpedScene          &base;       ///< the study's building for the record
      const lumped::GroundMotion &motion;
      double                      scale; ///< of the record
    };

    /// Repeats the building run of `run` (record, height, law, gap and reference k set) with
    /// k(H, v_imp) of its own impact velocity until k changes by less than the tolerance; each run
    /// is an iteration of `run`, a failure its status.
    void
    iterate_consistent_k(ConsistentKRun &run, const RecordRuns &in, const std::string &height_name)
    {
      double k = run.k_reference;
      for (unsigned int i = 0; i < in.scene.consistent_k.max_iterations; ++i)
      {
        const LumpedCaseResult done =
          run_lumped_case(fmt::format("{}_{}_consistent_{}", height_name, run.law, i + 1),
                          walled_scene(in.base, run.gap, run.law, k, in.scene.fit.cor),
                          in.motion,
                          in.scale);
        if (!done.ok())
        {
          run.status = "failed: building run " + std::to_string(i + 1) + ": " + done.status;
          break;
        }
        ConsistentKIteration it;
        it.k_total   = k;
        it.n_impacts = done.response.n_impacts();
        for (const lumped::ContactResult &c : done.response.contacts)
        {
          it.impact_velocity   = std::max(it.impact_velocity, c.largest_impact_velocity());
          it.peak_impact_force = std::max(it.peak_impact_force, c.peak_force);
        }
        if (it.n_impacts == 0)
        {
          // Nothing to be consistent with: the reference k stands.
          it.velocity_used = nan;
          it.k_next        = k;
          run.iterations.push_back(it);
          run.converged = true;
          run.status    = "ok: no impact";
          break;
        }
        // k is not extrapolated: a velocity outside the table takes its nearest end.
        it.velocity_used =
          in.velocities.empty() ?
            it.impact_velocity :
            std::clamp(it.impact_velocity, in.velocities.front(), in.velocities.back());
        try
        {
          it.k_next = in.table.stiffness(run.wall_height, run.exponent, it.velocity_used);
        }
        catch (const std::exception &error)
        {
          run.status = std::string("failed: ") + error.what();
          run.iterations.push_back(it);
          break;
        }
        it.change = relative_change(it.k_next, k);
        run.iterations.push_back(it);
        if (it.change < in.scene.consistent_k.tolerance)
        {
          run.converged = true;
          break;
        }
        k = it.k_next;
      }
      if (!run.converged && run.status == "ok")
        run.status = fmt::format("not converged: k changed by {:.3g} % in run {} of {} "
                                 "(tolerance {:.3g} %)",
                                 100.0 * run.iterations.back().change,
                                 run.iterations.size(),
                                 in.scene.consistent_k.max_iterations,
                                 100.0 * in.scene.consistent_k.tolerance);
    }

    /// The log line of one finished consistent-k run.
    void log_consistent_k(const ConsistentKRun &run, const std::string &height_name)
    {
      logger().info("consistent k, record {} {} {}: {} run(s), v_imp {} m/s, k {} -> {} {} "
                    "({})",
                    run.record,
                    height_name,
                    run.law,
                    run.iterations.size(),
                    base::sig(run.iterations.empty() ? nan : run.iterations.back().impact_velocity),
                    base::sig(k_display(run.k_reference, run.exponent)),
                    base::sig(k_display(final_k(run), run.exponent)),
                    stiffness_display_unit(run.exponent),
                    run.status);
    }
  } // namespace

  std::vector<ConsistentKRun> run_consistent_k(const StudyScene &scene, const StudyResult &result)
  {
    std::vector<ConsistentKRun> runs;
    if (!scene.consistent_k.enabled)
      return runs;
    const KTable table = study_k_table(scene, result);
    if (table.rows.empty())
    {
      logger().warn("consistent k skipped: no height has both fitted k");
      return runs;
    }
    const std::vector<double> velocities = table.velocities();
    for (const auto &[label, record] : labelled_records(scene))
    {
      const double gap = record_gap(scene, result, label);
      if (!std::isfinite(gap))
        continue;
      lumped::GroundMotion motion;
      try
      {
        motion = load_ground_motion(record);
      }
      catch (const std::exception &error)
      {
        logger().warn("consistent k, record {}: {}", label, base::error_text(error));
        continue;
      }
      const LumpedScene base = study_lumped_scene(scene, record);
      const RecordRuns  in{scene, table, velocities, base, motion, record.scale};
      for (const StudyHeight &h : result.heights)
        for (const auto &[law, fit_of_law] : building_laws(h))
        {
          const std::optional<FitResult> &fit = *fit_of_law;
          if (!fit)
            continue;
          ConsistentKRun run;
          run.record      = label;
          run.wall_height = h.wall_height;
          run.law         = law;
          run.exponent    = fit->exponent.value;
          run.gap         = gap;
          run.k_reference = fit->stiffness.value * scene.fit.width;
          iterate_consistent_k(run, in, h.name);
          log_consistent_k(run, h.name);
          runs.push_back(std::move(run));
        }
    }
    return runs;
  }

  namespace
  {
    /// One building run of a consistent-k iteration: the run and the iteration's index.
    struct ConsistentKStep
    {
      const ConsistentKRun *run   = nullptr;
      std::size_t           index = 0;

      const ConsistentKIteration &it() const { return run->iterations[index]; }
    };

    /// The columns of consistent_k.csv: one row per record, height and law.
    std::vector<StudyColumn<ConsistentKRun>> consistent_k_columns()
    {
      using R = ConsistentKRun;
      // The last (first) iteration's value, NaN without iterations.
      const auto last = [](double ConsistentKIteration::*value) {
        return [value](const R &r)
        { return r.iterations.empty() ? nan : r.iterations.back().*value; };
      };
      const auto first_force = [](const R &r)
      { return r.iterations.empty() ? nan : r.iterations.front().peak_impact_force; };
      return {
        csv_text_column<R>("record", [](const R &r) { return r.record; }),
        same_column<R>("wall_height", "m", [](const R &r) { return r.wall_height; }),
        csv_text_column<R>("law", [](const R &r) { return r.law; }),
        same_column<R>("k_reference",
                       "",
                       [](const R &r) { return k_display(r.k_reference, r.exponent); }),
        same_column<R>("k_consistent",
                       "",
                       [](const R &r) { return k_display(final_k(r), r.exponent); }),
        csv_text_column<R>("k_unit", [](const R &r) { return stiffness_display_unit(r.exponent); }),
        same_column<R>("change_percent",
                       "1",
                       [](const R &r) { return 100.0 * (final_k(r) / r.k_reference - 1.0); }),
        same_column<R>("impact_velocity", "m/s", last(&ConsistentKIteration::impact_velocity)),
        same_column<R>("velocity_used", "m/s", last(&ConsistentKIteration::velocity_used)),
        integer_column<R>("iterations",
                          false,
                          true,
                          [](const R &r)
                          { return static_cast<std::int64_t>(r.iterations.size()); }),
        csv_text_column<R>("converged",
                           [](const R &r) { return std::string(r.converged ? "yes" : "no"); }),
        number_column<R>({"peak_impact_force_reference", "N"},
                         {"peak_impact_force_reference", "kN"},
                         divided_by(1e3),
                         first_force),
        number_column<R>({"peak_impact_force_consistent", "N"},
                         {"peak_impact_force_consistent", "kN"},
                         divided_by(1e3),
                         last(&ConsistentKIteration::peak_impact_force)),
        csv_text_column<R>("status", [](const R &r) { return r.status; })};
    }

    /// The columns of consistent_k_iterations.csv and study.h5 /consistent_k/<record>/<law>
    /// (one row per building run; k in `k_si_unit`, the law's N/m^n, in study.h5).
    std::vector<StudyColumn<ConsistentKStep>>
    consistent_k_step_columns(const std::string &k_si_unit)
    {
      using S = ConsistentKStep;
      // k in the law's display unit in the CSV file (its unit in the column k_unit), SI in
      // study.h5.
      const auto k_columns = [&](const std::string &name, double ConsistentKIteration::*k)
      {
        return std::vector<StudyColumn<S>>{
          hdf5_column<S>(name, k_si_unit, [k](const S &s) { return s.it().*k; }),
          number_column<S>({},
                           {name, ""},
                           {},
                           [k](const S &s) { return k_display(s.it().*k, s.run->exponent); })};
      };
      const auto index = [](const S &s) { return static_cast<double>(s.index + 1); };
      const auto count = [](const S &s) { return static_cast<double>(s.it().n_impacts); };
      std::vector<StudyColumn<S>> columns = {
        csv_text_column<S>("record", [](const S &s) { return s.run->record; }),
        same_column<S>("wall_height", "m", [](const S &s) { return s.run->wall_height; }),
        csv_text_column<S>("law", [](const S &s) { return s.run->law; }),
        hdf5_column<S>("iteration", "1", index),
        integer_column<S>("iteration",
                          false,
                          true,
                          [](const S &s) { return static_cast<std::int64_t>(s.index + 1); })};
      for (StudyColumn<S> &c : k_columns("k_total", &ConsistentKIteration::k_total))
        columns.push_back(std::move(c));
      columns.push_back(csv_text_column<S>("k_unit",
                                           [](const S &s)
                                           { return stiffness_display_unit(s.run->exponent); }));
      columns.push_back(same_column<S>("impact_velocity",
                                       "m/s",
                                       [](const S &s) { return s.it().impact_velocity; }));
      columns.push_back(
        same_column<S>("velocity_used", "m/s", [](const S &s) { return s.it().velocity_used; }));
      for (StudyColumn<S> &c : k_columns("k_next", &ConsistentKIteration::k_next))
        columns.push_back(std::move(c));
      columns.push_back(number_column<S>({"change", "1"},
                                         {"change_percent", "1"},
                                         times(100),
                                         [](const S &s) { return s.it().change; }));
      columns.push_back(number_column<S>({"peak_impact_force", "N"},
                                         {"peak_impact_force", "kN"},
                                         divided_by(1e3),
                                         [](const S &s) { return s.it().peak_impact_force; }));
      columns.push_back(hdf5_column<S>("n_impacts", "1", count));
      columns.push_back(integer_column<S>("n_impacts",
                                          false,
                                          true,
                                          [](const S &s)
                                          { return static_cast<std::int64_t>(s.it().n_impacts); }));
      columns.push_back(
        hdf5_column<S>("converged", "1", [](const S &s) { return flag(s.run->converged); }));
      return columns;
    }

    /// Every building run of `runs`, in order.
    std::vector<ConsistentKStep> consistent_k_steps(const std::vector<const ConsistentKRun *> &runs)
    {
      std::vector<ConsistentKStep> steps;
      for (const ConsistentKRun *r : runs)
        for (std::size_t i = 0; i < r->iterations.size(); ++i)
          steps.push_back({r, i});
      return steps;
    }
  } // namespace

  void write_consistent_k_csv(const OutputDir &output, const StudyResult &result)
  {
    if (result.consistent_k.empty())
      return;
    study_table(consistent_k_columns(), result.consistent_k, StudyFile::csv)
      .write_csv(output.file("consistent_k.csv"));
    std::vector<const ConsistentKRun *> runs;
    for (const ConsistentKRun &r : result.consistent_k)
      runs.push_back(&r);
    study_table(consistent_k_step_columns(""), consistent_k_steps(runs), StudyFile::csv)
      .write_csv(output.file("consistent_k_iterations.csv"));
  }


  void write_velocity_h5(ResultsGroup &root, const StudyScene &scene, const StudyResult &result)
  {
    // /fem/<H>_v<v> and /fit_velocity/<case>/<law>: the velocity cases.
    ResultsGroup fem_root = root.group("fem");
    for (const StudyHeight &h : result.velocity_cases)
    {
      if (h.fem_case.name.empty())
        continue; // the FEM failed: no case to write
      write_fem_case(fem_root, h.fem_case);
      ResultsGroup g = root.group("fit_velocity").group(h.name);
      g.write_scalar("wall_height", h.wall_height, "m");
      g.write_scalar("impact_velocity", h.impact_velocity, "m/s");
      write_study_fits(g, h, scene.fit.width);
    }

    // /k_table_velocity: every height and velocity, with the linear k beside.
    Table k;
    k.number("wall_height", "m")
      .number("impact_velocity", "m/s")
      .number("reference_velocity", "1")
      .number("inelastic", "1");
    for (const StudyLaw &law : study_laws())
    {
      const std::string name = law.name();
      add_k_columns(k, law);
      k.number(name + "_numerical_error", law.per_metre_unit())
        .number("linear_" + name, law.per_metre_unit());
    }
    for (const StudyHeight *h : k_table_cases(result))
    {
      std::vector<Cell> row = number_cells(
        {h->wall_height, h->impact_velocity, flag(h->reference_velocity), flag(h->inelastic)});
      for (const StudyLawFit &law : h->laws)
      {
        add_k_cells(row, law.fit);
        append_numbers(row, {numerical_error(*h, *law.law), per_metre(law.linear)});
      }
      k.add_row(std::move(row));
    }
    k.write_hdf5(root, "k_table_velocity");
    root.group("k_table_velocity")
      .set_attribute("reference_velocity_m_per_s", scene.fem.solver.initial_velocity);

    // /consistent_k/<record>/<law>: one row per building run of the iteration.
    for (const auto &[key, runs] : by_record_and_law(result.consistent_k, false))
    {
      const Table t =
        study_table(consistent_k_step_columns(stiffness_si_unit(runs.front()->exponent)),
                    consistent_k_steps(runs),
                    StudyFile::hdf5);
      ResultsGroup group = root.group("consistent_k").group(key.first);
      t.write_hdf5(group, key.second);
      group.group(key.second).set_attribute("tolerance", scene.consistent_k.tolerance);
    }
  }

  void add_velocity_summary(nlohmann::ordered_json &j,
                            const StudyScene       &scene,
                            const StudyResult      &result)
  {
    nlohmann::ordered_json table = nlohmann::ordered_json::array();
    for (const StudyHeight *h : k_table_cases(result))
    {
      nlohmann::ordered_json row;
      row["case"]               = h->name;
      row["wall_height"]        = h->wall_height;
      row["impact_velocity"]    = h->impact_velocity;
      row["reference_velocity"] = h->reference_velocity;
      row["material"]           = h->inelastic ? "inelastic" : "linear";
      if (!h->material_reason.empty())
        row["material_reason"] = h->material_reason;
      for (const StudyLawFit &law : h->laws)
      {
        nlohmann::ordered_json f = law_json(*h, law);
        if (const std::optional<FitResult> &linear = law.linear)
          f["linear_k_per_metre"] = per_metre(linear);
        row[law.law->name()] = f;
      }
      table.push_back(row);
    }
    j["reference_velocity"]     = scene.fem.solver.initial_velocity;
    j["k_table_velocity"]       = table;
    nlohmann::ordered_json runs = nlohmann::ordered_json::array();
    for (const ConsistentKRun &r : result.consistent_k)
    {
      nlohmann::ordered_json row;
      row["record"]              = r.record;
      row["wall_height"]         = r.wall_height;
      row["law"]                 = r.law;
      row["unit"]                = stiffness_display_unit(r.exponent);
      row["k_reference"]         = k_display(r.k_reference, r.exponent);
      row["k_consistent"]        = k_display(final_k(r), r.exponent);
      row["iterations"]          = r.iterations.size();
      row["converged"]           = r.converged;
      row["status"]              = r.status;
      nlohmann::ordered_json its = nlohmann::ordered_json::array();
      for (const ConsistentKIteration &it : r.iterations)
        its.push_back({{"k_total", k_display(it.k_total, r.exponent)},
                       {"impact_velocity", it.impact_velocity},
                       {"k_next", k_display(it.k_next, r.exponent)},
                       {"change", it.change}});
      row["runs"] = its;
      runs.push_back(row);
    }
    j["consistent_k"] = {{"enabled", scene.consistent_k.enabled},
                         {"tolerance", scene.consistent_k.tolerance},
                         {"max_iterations", scene.consistent_k.max_iterations},
                         {"runs", runs}};
  }

  std::string
  velocity_report_markdown(const StudyScene &scene, const StudyResult &result, bool charts)
  {
    const bool any_inelastic = std::any_of(result.heights.begin(),
                                           result.heights.end(),
                                           [](const StudyHeight &h) { return h.inelastic; });
    if (result.velocity_cases.empty() && !any_inelastic && !has_inelastic_materials(scene.fem))
      return "";
    std::string md = fmt::format(
      "## Impact stiffness against impact velocity, k(H, v)\n\n"
      "One FEM case per wall height and slab velocity. The fidelity ladder runs once per height "
      "at the reference velocity {} m/s; the FEM level (and material model) it chose is reused "
      "at the other velocities, whose numerical error (±) is the reference's relative error "
      "times their k (carried over, not measured). The linear k is the same FEM case with "
      "linear-elastic materials of the same initial stiffness.\n\n",
      scene.fem.solver.initial_velocity);
    md += law_table_header("| H (m) | v (m/s) | materials |",
                           3,
                           3,
                           [](const StudyLaw &law)
                           {
                             return fmt::format(" {} {} [95 % CI] ± numerical | linear {} | "
                                                "Table 2.1 |",
                                                law.short_name,
                                                law.per_metre_unit(),
                                                law.symbol);
                           });
    const auto plus_minus = [](double error)
    { return std::isfinite(error) ? " ± " + base::sig(error, 2) : std::string(); };
    // Per height the reference velocity's row first (the k of the building runs).
    std::vector<const StudyHeight *> cases = k_table_cases(result);
    std::stable_sort(cases.begin(),
                     cases.end(),
                     [](const StudyHeight *a, const StudyHeight *b)
                     {
                       return a->wall_height < b->wall_height ||
                              (a->wall_height == b->wall_height && a->reference_velocity &&
                               !b->reference_velocity);
                     });
    for (const StudyHeight *h : cases)
    {
      const std::optional<ThesisStiffness> t = thesis_row(h->wall_height);
      md += fmt::format("| {:.2f} | {:g}{} | {} |",
                        h->wall_height,
                        h->impact_velocity,
                        h->reference_velocity ? " (reference)" : "",
                        h->inelastic ? "inelastic" : "linear");
      for (const StudyLawFit &law : h->laws)
      {
        const std::optional<FitResult> &fit = law.fit;
        const double thesis                 = h->reference_velocity ? thesis_k(t, *law.law) : nan;
        md += fmt::format(" {} [{}, {}]{} | {} | {} |",
                          readable(per_metre(fit)),
                          readable(per_metre_bound(fit, false)),
                          readable(per_metre_bound(fit, true)),
                          plus_minus(numerical_error(*h, *law.law)),
                          h->inelastic ? readable(per_metre(law.linear)) : "-",
                          std::isfinite(thesis) ? readable(thesis) : "-");
      }
      md += fmt::format(" {} |\n", all_ok(h->laws) ? std::string("ok") : joined_status(h->laws));
    }
    md += "\n";
    for (const StudyHeight &h : result.heights)
      if (has_inelastic_materials(scene.fem) && !h.material_reason.empty())
        md += fmt::format("Materials, {}: {}. ", h.name, h.material_reason);
    md += "\n\nData: [k_table.csv](k_table.csv) (one row per height and velocity, column "
          "`impact_velocity_m_per_s`), study.h5 `/k_table_velocity`, `/fit_velocity/<case>`.\n\n";
    if (charts && !result.velocity_cases.empty())
      md += "![k against impact velocity per wall height](charts/k_vs_velocity.png)\n\n";
    return md;
  }

  std::string consistent_k_report_markdown(const StudyScene &scene, const StudyResult &result)
  {
    if (result.consistent_k.empty())
      return "";
    std::size_t n_converged = 0;
    for (const ConsistentKRun &r : result.consistent_k)
      n_converged += r.converged;
    std::string md = fmt::format(
      "## Consistent k: building runs with k(H, v_imp)\n\n"
      "Each building run is repeated with the k of its own impact velocity v_imp (the largest "
      "closing velocity at first contact over the impacts on both walls), interpolated in the "
      "k(H, v) table (clamped to its velocities, never extrapolated), until k changes by less "
      "than {:g} % (at most {} runs). {} of {} iterations converged.\n\n"
      "| record | H (m) | law | k at {} m/s | consistent k | unit | runs | v_imp (m/s) per run | "
      "k per run | peak force (kN), first / last | status |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n",
      100.0 * scene.consistent_k.tolerance,
      scene.consistent_k.max_iterations,
      n_converged,
      result.consistent_k.size(),
      scene.fem.solver.initial_velocity);
    for (const ConsistentKRun &r : result.consistent_k)
    {
      std::string velocities, ks;
      for (const ConsistentKIteration &it : r.iterations)
      {
        velocities += (velocities.empty() ? "" : ", ") + readable(it.impact_velocity);
        ks += (ks.empty() ? "" : ", ") + readable(k_display(it.k_total, r.exponent));
      }
      md += fmt::format(
        "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} / {} | {} |\n",
        r.record,
        readable(r.wall_height),
        r.law,
        readable(k_display(r.k_reference, r.exponent)),
        readable(k_display(final_k(r), r.exponent)),
        stiffness_display_unit(r.exponent),
        r.iterations.size(),
        velocities,
        ks,
        readable(r.iterations.empty() ? nan : r.iterations.front().peak_impact_force / 1e3),
        readable(r.iterations.empty() ? nan : r.iterations.back().peak_impact_force / 1e3),
        r.status);
    }
    md += "\nData: [consistent_k.csv](consistent_k.csv), "
          "[consistent_k_iterations.csv](consistent_k_iterations.csv), study.h5 "
          "`/consistent_k/<record>/<law>`.\n\n";
    return md;
  }
} // namespace kimp::app::study_internal
