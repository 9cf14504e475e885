// Writers of `kimp study`: report.md (k table beside thesis Table 2.1, building response, extra
// studies, cost) and the charts (scripts/study_charts.py).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "app/helper_programs.h"
#include "app/study/study_internal.h"
#include "app/study/study_velocity.h"
#include "base/format.h"
#include "base/logging.h"
#include "base/version.h"
#include "io/table.h"

namespace kimp::app::study_internal
{
  namespace
  {
    /// k of `law` in `k` (SI, per study law) in kN/mm^n per metre; NaN when missing.
    double law_k_display(const std::vector<double> &k, const StudyLaw &law)
    {
      const std::size_t i = study_law_index(law);
      return i < k.size() ? stiffness_to_kn_per_mm(k[i], law.exponent()) : nan;
    }

    /// The "Accuracy against cost: FEM" section: k against mesh, penalty and implicit solver. Empty
    /// without its points.
    std::string fem_accuracy_markdown(const StudyScene &scene, const StudyExtras &e)
    {
      std::string md;
      if (e.fem_accuracy.empty())
        return md;
      md += fmt::format("## Accuracy against cost: FEM (H = {} m)\n\nError of k against the finest "
                        "explicit mesh level; seconds are the FEM wall time of each run.\n\n",
                        scene.accuracy.wall_height);
      md += law_table_header("| series | h_contact (cm) | penalty | FEM s |",
                             4,
                             2,
                             [](const StudyLaw &law) {
                               return fmt::format(" k_{} {} | error {} |",
                                                  law.symbol,
                                                  law.per_metre_unit(),
                                                  law.symbol);
                             });
      for (const FemAccuracyPoint &p : e.fem_accuracy)
      {
        md += fmt::format("| {} | {:g} | {:g} | {} |",
                          p.series,
                          p.h_contact * 100,
                          p.penalty_factor,
                          readable(p.seconds));
        for (const StudyLaw &law : study_laws())
        {
          const std::size_t i = study_law_index(law);
          md += fmt::format(" {} | {} |",
                            readable(p.ok ? law_k_display(p.k, law) : nan),
                            p.ok && i < p.error.size() ? fmt::format("{:.3g} %", 100 * p.error[i]) :
                                                         "");
        }
        md += fmt::format(" {} |\n", p.status);
      }
      return md;
    }

    /// The "Accuracy against cost: building time step" section. Empty without its points.
    std::string lumped_accuracy_markdown(const StudyScene &scene, const StudyExtras &e)
    {
      std::string md;
      if (e.lumped_accuracy.empty())
        return md;
      md += fmt::format("## Accuracy against cost: building time step (thesis Figs 3.3-3.4)\n\n"
                        "Record {}, walls at {:.4g} cm, modified Kelvin-Voigt k = {:.5g} kN/mm; "
                        "errors against central difference at {:g} s.\n\n"
                        "| method | dt (s) | s | peak impact force (kN) | error | peak base acc. "
                        "(m/s²) | error | status |\n|---|---|---|---|---|---|---|---|\n",
                        e.lumped_record,
                        e.lumped_gap * 100,
                        stiffness_to_kn_per_mm(e.lumped_k_total, 1.0),
                        scene.accuracy.lumped_reference_dt);
      for (const LumpedAccuracyPoint &p : e.lumped_accuracy)
        md += fmt::format("| {} | {:g} | {} | {} | {} | {} | {} | {} |\n",
                          p.method,
                          p.dt,
                          readable(p.seconds),
                          readable(p.ok ? p.peak_impact_force / 1e3 : nan),
                          p.ok ? fmt::format("{:.3g} %", 100 * p.error_force) : "",
                          readable(p.ok ? p.base_acceleration : nan),
                          p.ok ? fmt::format("{:.3g} %", 100 * p.error_acceleration) : "",
                          p.status);
      return md;
    }

    /// The "Stability map of the central difference method" section. Empty without its points.
    std::string lumped_stability_markdown(const StudyScene &scene, const StudyExtras &e)
    {
      std::string md;
      if (e.stability.empty())
        return md;
      std::size_t n_stable = 0, n_accurate = 0, stable_above = 0, unstable_below = 0;
      for (const StabilityPoint &p : e.stability)
      {
        n_stable += p.stable;
        n_accurate += p.accurate;
        stable_above += p.stable && p.dt > p.dt_limit_damped;
        unstable_below += !p.stable && p.dt < p.dt_limit_damped;
      }
      md +=
        fmt::format("## Stability map of the central difference method\n\nTwo-body "
                    "collisions (isolation level {:.0f} t against the wall {:.0f} t, m_eff = "
                    "{:.4g} t, modified Kelvin-Voigt at COR {}), no stability guard: {} runs, "
                    "{} stable (energy gain < 0.1 %), {} of them accurate (effective COR within "
                    "5 % of nominal); {} stable above the damped limit "
                    "2(sqrt(1+ξ²)−ξ)/ω_imp, {} unstable below it.\n",
                    scene.building.isolation_mass / 1e3,
                    scene.walls.mass / 1e3,
                    e.stability_effective_mass / 1e3,
                    scene.fit.cor,
                    e.stability.size(),
                    n_stable,
                    n_accurate,
                    stable_above,
                    unstable_below);
      return md;
    }

    /// The "Stability map of the explicit FEM" section. Empty without its points.
    std::string fem_stability_markdown(const StudyScene &scene, const StudyExtras &e)
    {
      std::string md;
      if (e.fem_stability.empty())
        return md;
      std::size_t stable_above = 0, unstable_below = 0, n_stable = 0;
      for (const FemStabilityPoint &p : e.fem_stability)
      {
        n_stable += p.stable;
        stable_above += p.stable && p.dt_factor > 1;
        unstable_below += !p.stable && p.dt_factor < 1;
      }
      md += fmt::format(
        "## Stability map of the explicit FEM\n\nH = {} m, contact elements {:g} cm, the "
        "first {:g} ms of the impact, Δt = factor × the computed limit 2(sqrt(1+ξ²)−ξ)/ω "
        "(ω from the mesh's CFL bound and the penalty spring, ξ its contact damping), no "
        "refusal; unstable: diverged, or energy error above 1 %: {} runs, {} stable; {} stable above the limit (the bound is conservative "
        "there), {} unstable below it.\n\n| penalty factor | Δt limit (µs) | "
        "stable at Δt / limit |\n|---|---|---|\n",
        scene.accuracy.wall_height,
        e.fem_stability_h_contact * 100,
        e.fem_stability_end_time * 1e3,
        e.fem_stability.size(),
        n_stable,
        stable_above,
        unstable_below);
      std::map<double, std::pair<double, std::string>> rows;
      for (const FemStabilityPoint &p : e.fem_stability)
      {
        auto &row = rows[p.penalty_factor];
        row.first = p.dt_limit;
        row.second += fmt::format("{}{:g}: {}",
                                  row.second.empty() ? "" : ", ",
                                  p.dt_factor,
                                  p.stable ? "yes" : "no");
      }
      for (const auto &[penalty, row] : rows)
        md += fmt::format("| {:g} | {:.4g} | {} |\n", penalty, row.first * 1e6, row.second);
      return md;
    }

    /// The "Sensitivity of k" section. Empty without its points.
    std::string sensitivity_markdown(const StudyScene &scene, const StudyExtras &e)
    {
      std::string md;
      if (e.sensitivity.empty())
        return md;
      md += fmt::format("## Sensitivity of k (H = {} m, ±{:g} %)\n\n",
                        scene.sensitivity_study.wall_height,
                        scene.sensitivity_study.variation * 100);
      md += law_table_header("| parameter | factor |",
                             2,
                             1,
                             [](const StudyLaw &law) {
                               return fmt::format(" k_{} {} |", law.symbol, law.per_metre_unit());
                             });
      for (const SensitivityPoint &p : e.sensitivity)
      {
        md += fmt::format("| {} | {:g} |", p.parameter, p.factor);
        for (const StudyLaw &law : study_laws())
          md += fmt::format(" {} |", readable(p.ok ? law_k_display(p.k, law) : nan));
        md += fmt::format(" {} |\n", p.status);
      }
      return md;
    }

    /// The sections of the study's extra parts: the markdown of each (empty without its points)
    /// and where its data stand (CSV file and study.h5 path) and its chart.
    struct ExtraSection
    {
      std::string (*markdown)(const StudyScene &, const StudyExtras &);
      const char *csv;
      const char *hdf5;
      const char *chart_title;
      const char *chart;
    };

    std::string extras_markdown(const StudyScene &scene, const StudyExtras &e, bool charts)
    {
      static const ExtraSection sections[] = {{fem_accuracy_markdown,
                                               "accuracy_fem.csv",
                                               "/accuracy/fem",
                                               "FEM accuracy against cost",
                                               "accuracy_fem.png"},
                                              {lumped_accuracy_markdown,
                                               "accuracy_lumped.csv",
                                               "/accuracy/lumped",
                                               "building time step accuracy against cost",
                                               "accuracy_lumped.png"},
                                              {lumped_stability_markdown,
                                               "stability_lumped.csv",
                                               "/stability/lumped",
                                               "stability map",
                                               "stability_map.png"},
                                              {fem_stability_markdown,
                                               "stability_fem.csv",
                                               "/stability/fem",
                                               "FEM stability map",
                                               "stability_map_fem.png"},
                                              {sensitivity_markdown,
                                               "sensitivity.csv",
                                               "/sensitivity",
                                               "sensitivity of k",
                                               "sensitivity.png"}};
      std::string               md;
      for (const ExtraSection &s : sections)
      {
        const std::string section = s.markdown(scene, e);
        if (section.empty())
          continue;
        md += section + fmt::format("\nData: [{0}]({0}), study.h5 `{1}`.\n\n", s.csv, s.hdf5);
        if (charts)
          md += fmt::format("![{}](charts/{})\n\n", s.chart_title, s.chart);
      }
      return md;
    }
  } // namespace

  std::string k_table_markdown(const StudyScene &scene, const std::vector<StudyHeight> &heights)
  {
    // The k table of k_table.csv and study.h5 /k_table: a value with its 95 % interval and the
    // FEM's numerical error in one cell.
    const auto with_interval = [](const std::vector<std::string> &t)
    {
      if (t[0].empty())
        return std::string("-");
      return t[0] + " [" + t[1] + ", " + t[2] + "]" + (t[3].empty() ? "" : " ± " + t[3]);
    };
    const auto or_dash = [](const std::vector<std::string> &t)
    { return t[0].empty() ? std::string("-") : t[0]; };
    const auto fem_level = [](const std::vector<std::string> &t)
    {
      const std::string state =
        t[2] == "auto" ? (t[3] == "yes" ? "" : " (not converged)") : " (fixed)";
      return t[0] + " cm, " + t[1] + state;
    };
    // Per law its cells joined: "a, b" and "ok", or "KV: ...; J: ...".
    const auto peak_ratios = [](const std::vector<std::string> &t)
    {
      std::string text;
      for (const std::string &cell : t)
        text += (text.empty() ? "" : ", ") + (cell.empty() ? std::string("-") : cell);
      return text;
    };
    const auto fit_status = [](const std::vector<std::string> &t)
    {
      if (std::all_of(t.begin(), t.end(), [](const std::string &cell) { return cell == "ok"; }))
        return std::string("ok");
      std::string text;
      for (std::size_t i = 0; i < t.size(); ++i)
        text += fmt::format("{}{}: {}", i ? "; " : "", study_laws()[i].symbol, t[i]);
      return text;
    };
    std::vector<const StudyHeight *> cases;
    for (const StudyHeight &h : heights)
      cases.push_back(&h);
    std::vector<io::MarkdownColumn> view = {{"H (m)", {"wall_height"}, {}}};
    std::vector<std::string>        symbols, ratios, statuses;
    for (const StudyLaw &law : study_laws())
    {
      const std::string name = law.name();
      view.push_back(
        {fmt::format("{} {} [95 % CI] ± numerical", law.short_name, law.per_metre_unit()),
         {name, name + "_lower", name + "_upper", name + "_numerical_error"},
         with_interval});
      view.push_back({"Table 2.1", {"thesis_" + name}, or_dash});
      view.push_back(
        {fmt::format("{} total {}", law.symbol, law.total_unit()), {name + "_total"}, or_dash});
      symbols.emplace_back(law.symbol);
      ratios.push_back(name + "_peak_force_ratio");
      statuses.push_back(name + "_status");
    }
    view.push_back(
      {fmt::format("fit/FEM peak force {}", fmt::join(symbols, ", ")), ratios, peak_ratios});
    view.push_back({"fit status", statuses, fit_status});
    view.insert(view.end(),
                {{"FEM level (h_contact, penalty)",
                  {"fem_h_contact", "fem_penalty_factor", "fidelity", "fidelity_converged"},
                  fem_level},
                 {"FEM from cache", {"fem_from_cache"}, {}}});
    return k_table(scene, cases).markdown(view);
  }

  namespace
  {
    /// "Engineer's quantities": per height the quantities of the reported FEM record and, with
    /// `fidelity: auto`, their change between the two finest levels against the 5 % target.
    std::string quantities_report_markdown(const StudyResult &result)
    {
      std::string md = "## Engineer's quantities of the FEM records\n\n"
                       "Per height, of the reported level (docs/physics.md \"Engineer's "
                       "quantities\"): the first peak force and the impulse of its pulse, the "
                       "energy-equivalent resistance E_0 / largest slab travel, the largest wall "
                       "displacement, the time to stop the slab (to 95 % of its travel; in "
                       "brackets the instant its velocity is zero, ill-conditioned when it "
                       "creeps to rest), the wall face at the end, the largest bar strain over "
                       "the yield strain (>= 1: the bars yield) at a point (mesh-dependent once "
                       "they yield) and over a gauge length (the vertical bars; the heights of "
                       "the point and of the gauge's centre above the ground) and the "
                       "impulse-momentum check of the record.\n\n"
                       "| H (m) | first peak (kN/m) | its impulse (N·s/m) | R_e (kN/m) | slab "
                       "travel (mm) | wall (mm) | time to stop (ms) | wall at the end (mm) | bar "
                       "strain / ε_y at a point (at y m) | over the gauge (at y m) | ∫F dt / "
                       "m(v_in + v_out) |\n"
                       "|---|---|---|---|---|---|---|---|---|---|---|\n";
      const auto  v  = [](const std::optional<double> &x, double scale)
      { return x ? base::sig(*x * scale, 4) : std::string("-"); };
      for (const StudyHeight &h : result.heights)
      {
        const io::FemSummary &s     = h.fem_case.summary;
        const auto            check = h.fem_case.labels.find("impulse_momentum");
        const std::string     flag  = check != h.fem_case.labels.end() && check->second != "ok" ?
                                        " **" + check->second + "**" :
                                        std::string();
        md +=
          fmt::format("| {} | {} | {} | {} | {} | {} | {} ({}) | {} | {} | {} | {}{} |\n",
                      base::sig(h.wall_height, 3),
                      v(s.first_peak_force, 1e-3),
                      v(s.first_peak_impulse, 1.0),
                      v(s.energy_equivalent_resistance, 1e-3),
                      v(s.max_slab_displacement, 1e3),
                      v(s.max_wall_displacement, 1e3),
                      v(s.time_to_95_travel, 1e3),
                      v(s.time_to_stop, 1e3),
                      v(s.wall_residual_displacement, 1e3),
                      s.max_bar_strain_ratio ? v(s.max_bar_strain_ratio, 1.0) + " (" +
                                                 v(s.max_bar_strain_height, 1.0) + ")" :
                                               std::string("no bars"),
                      s.max_bar_gauge_strain_ratio ? v(s.max_bar_gauge_strain_ratio, 1.0) + " (" +
                                                       v(s.max_bar_gauge_strain_height, 1.0) + ")" :
                                                     std::string("-"),
                      v(s.impulse_momentum_ratio, 1.0),
                      flag);
      }
      bool any = false;
      for (const StudyHeight &h : result.heights)
        any = any || !h.ladder.quantity_errors.empty() || !h.ladder.far_side_spread.empty();
      if (!any)
        return md + "\n";
      md += fmt::format("\nNumerical error: the change between the two finest levels of the "
                        "fidelity ladder; far side: the change to a run of the reported level "
                        "with the other far side (`fem.fidelity_far_side_spread`). Target <= "
                        "{:.3g} % (a change within a quantity's resolution passes too), "
                        "[fidelity_quantities.csv](fidelity_quantities.csv):\n\n"
                        "| H (m) | comparison | quantity | other | reported | change (%) | "
                        "verdict |\n|---|---|---|---|---|---|---|\n",
                        100.0 * ladder_quantity_tolerance);
      const auto row = [&](double height, const std::string &what, const QuantityError &e)
      {
        md += fmt::format("| {} | {} | {} ({}) | {} | {} | {} | {} |\n",
                          base::sig(height, 3),
                          what,
                          e.key,
                          e.unit,
                          base::sig(e.coarse, 4),
                          base::sig(e.fine, 4),
                          base::sig(100.0 * e.relative, 3),
                          e.verdict == "pass" ? e.verdict : "**" + e.verdict + "**");
      };
      for (const StudyHeight &h : result.heights)
      {
        for (const QuantityError &e : h.ladder.quantity_errors)
          row(h.wall_height, "numerical error", e);
        for (const QuantityError &e : h.ladder.far_side_spread)
          row(h.wall_height, "far side " + h.ladder.other_far_side, e);
      }
      return md + "\n";
    }
  } // namespace

  std::string report_markdown(const StudyScene &scene, const StudyResult &result, bool charts)
  {
    std::string md = "# kimp wall-height study\n\n" + base::version_line() + "\n\n";
    for (const std::string &warning : result.warnings)
      md += "**Warning:** " + warning + ".\n\n";
    md += yielding_wall_markdown(scene, result);
    md += fmt::format("## Impact stiffness per wall height (fitted at COR {}, W = {} m, impact "
                      "velocity {} m/s)\n\n",
                      scene.fit.cor,
                      scene.fit.width,
                      scene.fem.solver.initial_velocity);
    md += k_table_markdown(scene, result.heights);
    md += fmt::format("\n\"fit/FEM peak force\" is the fitted law's peak force over the FEM's: "
                      "k reproduces the whole pulse (least squares), so the peak may differ; a "
                      "fit whose peak misses the FEM's by more than {:.3g} % "
                      "(`fit.peak_tolerance`) has the status warning. Impulse and contact "
                      "duration ratios: k_table.csv, summary.json.\n",
                      100.0 * scene.fit.peak_tolerance);
    md += "\nThe intervals are the fits' own (law misfit). The ± values are the FEM's numerical "
          "error of k with `fem.fidelity: auto`: the change of k from the previous level of the "
          "mesh ladder (and of the penalty ladder, added in quadrature); the climb stops when "
          "both laws change by less than `fem.fidelity_tolerance`. ";
    for (const StudyHeight &h : result.heights)
      md += fmt::format("{}: {}. ", h.name, h.fidelity_reason);
    md += "The thesis used non-linear materials in ADINA and did not state its slab mass, so "
          "the trend with H and the order of magnitude are what should agree.\n\n"
          "Data: [k_table.csv](k_table.csv), [study.h5](study.h5) (`/k_table`, `/fit/<H>`, "
          "`/fem/<H>`, `/fidelity/<H>`).\n\n";
    if (charts)
      md += "![FEM force histories with the fitted laws](charts/force_histories.png)\n\n";
    if (charts && result.heights.size() > 1) // one height: one point, the table says it
      md += "![k against wall height](charts/k_vs_height.png)\n\n";
    md += quantities_report_markdown(result);
    md += velocity_report_markdown(scene, result, charts);

    md += "## Building response\n\n"
          "Isolated building of docs/physics.md §3 with moat walls on both sides, gap "
          "from the no-wall peak isolation displacement; ";
    md += yielding_wall_route(scene) == "linear" ?
            "linear route: modified Kelvin-Voigt with k_KV, Jankowski and the hysteretic law "
            "with k_Jankowski.\n\n"
            "The walls are linear: the impact force is read against the wall's static collapse "
            "load estimate (M_p + P_p H/3)/h_c × W (docs/physics.md §2 \"Yielding moat wall\", "
            "capacity estimate); a ratio above 1 (**bold**) is a force the wall cannot carry. "
            "The rows `yielding_wall` are the same runs against each height's estimate element "
            "(first section): their impact force is the contact part's (the local wave), the "
            "ratio the wall-and-backfill part's peak resistance over its cap.\n\n" :
            "inelastic materials: yielding wall elements (section above); the impact force is "
            "the contact part's (the local wave), the ratio the wall-and-backfill part's peak "
            "resistance over its cap.\n\n";
    md += "| record | H (m) | law | gap (cm) | base acc. (m/s²) | top acc. (m/s²) | drift (cm) | "
          "impact force (kN) | wall capacity est. (kN) | force / capacity | impacts | top acc. "
          "amplification | status |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const StudyBuildingRun &r : result.building)
    {
      const bool capacity = r.wall_capacity > 0.0;
      // A yielding wall: its own resistance (the contact part's peak is the local wave).
      const double      wall_force = r.yielding_wall ? r.wall_peak_resistance : r.peak_impact_force;
      const double      ratio      = capacity ? wall_force / r.wall_capacity : 0.0;
      const std::string ratio_text = !capacity   ? "-" :
                                     ratio > 1.0 ? "**" + readable(ratio) + "**" :
                                                   readable(ratio);
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                        r.record,
                        r.law == "none" ? "-" : readable(r.wall_height),
                        r.law,
                        r.law == "none" ? "-" : readable(r.gap * 100),
                        readable(r.base_acceleration),
                        readable(r.top_acceleration),
                        readable(r.max_interstorey_drift * 100),
                        readable(r.peak_impact_force / 1e3),
                        capacity ? readable(r.wall_capacity / 1e3) : std::string("-"),
                        ratio_text,
                        r.n_impacts,
                        readable(r.amplification_top_acc),
                        r.status);
    }
    md += "\nData: [building_response.csv](building_response.csv), study.h5 "
          "`/building/<record>/<law>`.\n\n";
    if (charts)
      md += "![building response against wall height](charts/building_response.png)\n\n";
    md += flexible_wall_markdown(scene, result);
    md += consistent_k_report_markdown(scene, result);
    md += extras_markdown(scene, result.extras, charts);
    md += "## Cost\n\n" + cost_text(result) + " (wall time; see summary.json).\n";
    return md;
  }

  /// Draw the charts; false (with a warning) if they could not be drawn.
  bool draw_charts(const OutputDir &output)
  {
    if (!draw_optional_charts("study_charts.py", output.path(), "charts"))
      return false;
    logger().info("charts written to {}", output.file("charts").string());
    return true;
  }
} // namespace kimp::app::study_internal
