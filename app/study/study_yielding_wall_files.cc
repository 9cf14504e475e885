// Writers of `kimp study`'s yielding walls: yielding_wall_element.csv (per height),
// yielding_wall_envelope.csv (the hull points each element runs on), yielding_wall.csv (per
// height and record), study.h5 /yielding_wall and the report section.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>

#include "app/study/study_columns.h"
#include "app/study/study_internal.h"
#include "base/format.h"
#include "io/results_file.h"
#include "io/table.h"

namespace kimp::app::study_internal
{
  namespace
  {
    /// A display unit of the CSV files: its name, the factor from SI to it and the SI unit.
    struct DisplayUnit
    {
      const char *name;
      double      factor;
      const char *si;
    };

    /// The display units of the yielding-wall tables.
    namespace display_unit
    {
      constexpr DisplayUnit kn_per_mm_per_m{"kN/mm/m", 1e-6, "N/m/m"};
      constexpr DisplayUnit kn_per_m{"kN/m", 1e-3, "N/m"};
      constexpr DisplayUnit kn{"kN", 1e-3, "N"};
      constexpr DisplayUnit kj{"kJ", 1e-3, "J"};
      constexpr DisplayUnit mm{"mm", 1e3, "m"};
      constexpr DisplayUnit cm{"cm", 100.0, "m"};
      constexpr DisplayUnit kn_s_per_m2{"kN*s/m^2", 1e-3, "N*s/m^2"};
      constexpr DisplayUnit t_per_m{"t/m", 1e-3, "kg/m"};

      /// An SI unit shown as it is.
      constexpr DisplayUnit si(const char *unit)
      {
        return {unit, 1.0, unit};
      }
    } // namespace display_unit

    /// A number column in short: its name, its display unit and its SI value of a row.
    template <class Row>
    struct Scaled
    {
      const char                        *name;
      DisplayUnit                        unit;
      std::function<double(const Row &)> value;
    };

    /// Appends `scaled` to `columns`, each NaN in a row that `ok` refuses.
    template <class Row>
    void append_scaled(std::vector<StudyColumn<Row>>   &columns,
                       const std::vector<Scaled<Row>>  &scaled,
                       std::function<bool(const Row &)> ok)
    {
      for (const Scaled<Row> &c : scaled)
        columns.push_back(number_column<Row>({c.name, c.unit.si},
                                             {c.name, c.unit.name},
                                             times(c.unit.factor),
                                             [ok, value = c.value](const Row &row)
                                             { return ok(row) ? value(row) : nan; }));
    }

    /// True when the element runs on a curve envelope (a pushover's concave hull).
    bool runs_on_curve(const StudyYieldingWall &w)
    {
      return !w.element.backfill.curve.empty();
    }

    /// The largest force of the element's envelope, N/m: the curve's last force, or the
    /// bilinear's cap (+inf without one).
    double element_envelope_force(const StudyYieldingWall &w)
    {
      if (runs_on_curve(w))
        return w.element.backfill.curve.back().force;
      return w.inputs.ultimate_capacity;
    }

    /// Where the element's envelope turns flat, m: the curve's last point, or the bilinear's w_u.
    double element_envelope_displacement(const StudyYieldingWall &w)
    {
      if (runs_on_curve(w))
        return w.element.backfill.curve.back().displacement;
      const YieldingWallInputs &in  = w.inputs;
      const double              w_y = in.capacity / in.stiffness;
      if (!std::isfinite(in.ultimate_capacity))
        return std::numeric_limits<double>::infinity();
      if (in.ultimate_capacity <= in.capacity || in.hardening_ratio == 0.0)
        return w_y;
      return w_y + (in.ultimate_capacity - in.capacity) / (in.hardening_ratio * in.stiffness);
    }

    /// Per height: the element, what it was derived from and where its resistance comes from.
    std::vector<Scaled<StudyYieldingWall>> element_quantities()
    {
      using W = StudyYieldingWall;
      using namespace display_unit;
      // A value of the pushover's fit, NaN unless the element comes from a pushover.
      const auto of_pushover = [](double PushoverFit::*value)
      { return [value](const W &w) { return w.source == "pushover" ? w.fit.*value : nan; }; };
      return {
        // The envelope the element runs on: the hull's first slope, its last force and where
        // it turns flat (the bilinear's k, F_y and its cap or +inf without a curve).
        {"envelope_stiffness",
         kn_per_mm_per_m,
         [](const W &w) { return w.element.backfill.resolved().stiffness / w.element.width; }},
        {"envelope_force", kn_per_m, [](const W &w) { return element_envelope_force(w); }},
        {"envelope_displacement", mm, [](const W &w) { return element_envelope_displacement(w); }},
        {"unloading_stiffness",
         kn_per_mm_per_m,
         [](const W &w) { return w.inputs.unloading_stiffness; }},
        // The equal-energy bilinear of the pushover: the element's envelope only without a hull
        // (source estimate), else the comparison (ASCE 41 / FEMA 356).
        {"bilinear_capacity", kn_per_m, [](const W &w) { return w.inputs.capacity; }},
        {"bilinear_stiffness", kn_per_mm_per_m, [](const W &w) { return w.inputs.stiffness; }},
        {"bilinear_hardening_ratio", si("1"), [](const W &w) { return w.inputs.hardening_ratio; }},
        {"failure_displacement",
         cm,
         [](const W &w) { return w.element.backfill.resolved().failure_displacement; }},
        {"estimate_capacity", kn_per_m, [](const W &w) { return w.estimate_capacity; }},
        {"pushover_force", kn_per_m, of_pushover(&PushoverFit::target_force)},
        {"pushover_displacement", mm, of_pushover(&PushoverFit::target_displacement)},
        {"pushover_permanent_set", mm, of_pushover(&PushoverFit::pushover_permanent_set)},
        {"element_permanent_set", mm, of_pushover(&PushoverFit::permanent_set)},
        {"pushover_time", si("s"), [](const W &w) { return w.pushover_seconds; }},
        {"soil_density", si("kg/m^3"), [](const W &w) { return w.inputs.soil_density; }},
        {"soil_wave_speed", si("m/s"), [](const W &w) { return w.inputs.soil_wave_speed; }},
        {"loaded_height", si("m"), [](const W &w) { return w.inputs.loaded_height; }},
        {"radiation_damping", kn_s_per_m2, [](const W &w) { return w.element.radiation_damping; }},
        {"slab_impedance", kn_s_per_m2, [](const W &w) { return w.inputs.slab_impedance; }},
        {"wall_impedance", kn_s_per_m2, [](const W &w) { return w.inputs.wall_impedance; }},
        {"contact_impedance", kn_s_per_m2, [](const W &w) { return w.element.contact_impedance; }},
        {"wall_mass", t_per_m, [](const W &w) { return w.element.wall_mass; }},
        {"striker_mass", t_per_m, [](const W &w) { return w.inputs.striker_mass; }},
        {"contact_stiffness",
         kn_per_mm_per_m,
         [](const W &w) { return w.element.contact_stiffness; }},
        {"width", si("m"), [](const W &w) { return w.element.width; }},
      };
    }

    /// The element table: the height and source, the quantities, why that source, the status.
    std::vector<StudyColumn<StudyYieldingWall>> element_columns()
    {
      using W = StudyYieldingWall;
      std::vector<StudyColumn<W>> columns{
        same_column<W>("wall_height", "m", [](const W &w) { return w.wall_height; }),
        text_column<W>("source", [](const W &w) { return w.source; }),
        text_column<W>("envelope",
                       [](const W &w) {
                         return !w.ok() ? "" : runs_on_curve(w) ? "hull" : "bilinear";
                       }),
        integer_column<W>("envelope_points",
                          true,
                          true,
                          [](const W &w)
                          { return std::int64_t(w.ok() ? w.element.backfill.curve.size() : 0); })};
      append_scaled<W>(columns, element_quantities(), [](const W &w) { return w.ok(); });
      columns.push_back(
        text_column<W>("source_reason", [](const W &w) { return w.source_reason; }));
      columns.push_back(text_column<W>("status", [](const W &w) { return w.status; }));
      return columns;
    }

    /// Per height and record: the walls against their capacity.
    std::vector<Scaled<StudyBuildingRun>> run_quantities()
    {
      using R = StudyBuildingRun;
      using namespace display_unit;
      return {
        {"gap", cm, [](const R &r) { return r.gap; }},
        {"peak_wall_resistance", kn, [](const R &r) { return r.wall_peak_resistance; }},
        {"resistance_over_capacity",
         si("1"),
         [](const R &r)
         { return r.wall_capacity > 0 ? r.wall_peak_resistance / r.wall_capacity : nan; }},
        {"peak_contact_force", kn, [](const R &r) { return r.peak_impact_force; }},
        {"peak_wall_displacement", cm, [](const R &r) { return r.peak_wall_displacement; }},
        {"residual_wall_displacement", cm, [](const R &r) { return r.wall_residual_displacement; }},
        {"wall_plastic_work", kj, [](const R &r) { return r.wall_plastic_work; }},
        {"wall_radiated_work", kj, [](const R &r) { return r.wall_radiated_work; }},
        {"energy_input", kj, [](const R &r) { return r.energy_input; }},
        {"energy_error", si("1"), [](const R &r) { return r.energy_error; }},
        {"peak_top_acceleration", si("m/s^2"), [](const R &r) { return r.top_acceleration; }},
        {"peak_interstorey_drift", cm, [](const R &r) { return r.max_interstorey_drift; }},
      };
    }

    /// The runs table: record, height and capacity, the quantities, failure, impacts, status.
    std::vector<StudyColumn<StudyBuildingRun>> run_columns()
    {
      using R = StudyBuildingRun;
      std::vector<StudyColumn<R>> columns{
        text_column<R>("record", [](const R &r) { return r.record; }),
        same_column<R>("wall_height", "m", [](const R &r) { return r.wall_height; }),
        text_column<R>("source", [](const R &r) { return r.wall_source; }),
        number_column<R>({"wall_capacity_per_metre", "N/m"},
                         {"wall_capacity_per_metre", "kN/m"},
                         times(1e-3),
                         [](const R &r) { return r.wall_capacity_per_metre; }),
        number_column<R>({"wall_capacity", "N"},
                         {"wall_capacity", "kN"},
                         times(1e-3),
                         [](const R &r) { return r.wall_capacity; })};
      append_scaled<R>(columns, run_quantities(), [](const R &r) { return r.status == "ok"; });
      columns.push_back(integer_column<R>("failed",
                                          true,
                                          true,
                                          [](const R &r)
                                          { return std::int64_t(r.wall_failed ? 1 : 0); }));
      columns.push_back(same_column<R>("failure_time",
                                       "s",
                                       [](const R &r)
                                       { return r.wall_failed ? r.wall_failure_time : nan; }));
      columns.push_back(integer_column<R>("n_impacts",
                                          true,
                                          true,
                                          [](const R &r) { return std::int64_t(r.n_impacts); }));
      columns.push_back(
        same_column<R>("wall_time", "s", [](const R &r) { return r.wall_seconds; }));
      columns.push_back(text_column<R>("status", [](const R &r) { return r.status; }));
      return columns;
    }

    /// The runs of a yielding wall.
    bool yielding(const StudyBuildingRun &r)
    {
      return r.yielding_wall;
    }
  } // namespace

  namespace
  {
    /// The points of the curve envelope each element runs on (its pushover's concave hull), per
    /// metre: with the height (`with_height`, one table of every height) or without (one table
    /// per height); SI in HDF5, mm and kN/m in the CSV.
    Table envelope_table(const std::vector<StudyYieldingWall> &walls,
                         const bool                            with_height,
                         const StudyYieldingWall              *only = nullptr)
    {
      Table t;
      if (with_height)
        t.number("wall_height", "m")
          .integer("point")
          .number("displacement", "mm")
          .number("force", "kN/m");
      else
        t.integer("point").number("displacement", "m").number("force", "N/m");
      for (const StudyYieldingWall &w : walls)
      {
        if ((only && &w != only) || !w.ok() || !runs_on_curve(w))
          continue;
        const auto &curve = w.element.backfill.curve;
        for (std::size_t i = 0; i < curve.size(); ++i)
        {
          if (with_height)
            t.add_row(
              {w.wall_height, std::int64_t(i), curve[i].displacement * 1e3, curve[i].force * 1e-3});
          else
            t.add_row({std::int64_t(i), curve[i].displacement, curve[i].force});
        }
      }
      return t;
    }
  } // namespace

  void write_yielding_wall_csv(const OutputDir &output, const StudyResult &result)
  {
    if (result.yielding_walls.empty())
      return;
    study_table(element_columns(), result.yielding_walls, StudyFile::csv)
      .write_csv(output.file("yielding_wall_element.csv"));
    study_table(run_columns(), result.building, StudyFile::csv, yielding)
      .write_csv(output.file("yielding_wall.csv"));
    const Table envelope = envelope_table(result.yielding_walls, true);
    if (envelope.n_rows() > 0)
      envelope.write_csv(output.file("yielding_wall_envelope.csv"));
  }

  std::string yielding_wall_route(const StudyScene &scene)
  {
    return has_inelastic_materials(scene.fem) ? "inelastic" : "linear";
  }

  void
  write_yielding_wall_h5(ResultsGroup &root, const StudyScene &scene, const StudyResult &result)
  {
    if (result.yielding_walls.empty())
      return;
    ResultsGroup g = root.group("yielding_wall");
    g.set_attribute("route", yielding_wall_route(scene));
    study_table(element_columns(), result.yielding_walls, StudyFile::hdf5).write_hdf5(g, "element");
    study_table(run_columns(), result.building, StudyFile::hdf5, yielding).write_hdf5(g, "runs");
    // The pushover curve each element was fitted to (source pushover).
    for (const StudyYieldingWall &w : result.yielding_walls)
    {
      if (w.source != "pushover")
        continue;
      Table curve;
      curve.number("displacement", "m").number("force", "N/m").integer("unloading");
      for (const fem::PushoverPoint &p : w.pushover_curve)
        curve.add_row({p.displacement, p.force, std::int64_t(p.unloading ? 1 : 0)});
      ResultsGroup pushover = g.group("pushover");
      curve.write_hdf5(pushover, w.name);
    }
    // The curve envelope each element runs on (its pushover's concave hull).
    for (const StudyYieldingWall &w : result.yielding_walls)
      if (w.ok() && runs_on_curve(w))
      {
        ResultsGroup envelope = g.group("envelope");
        envelope_table(result.yielding_walls, false, &w).write_hdf5(envelope, w.name);
      }
  }

  nlohmann::ordered_json yielding_wall_json(const StudyScene &scene, const StudyResult &result)
  {
    nlohmann::ordered_json runs     = nlohmann::ordered_json::array();
    std::size_t            n_failed = 0;
    for (const StudyBuildingRun &r : result.building)
    {
      if (!r.yielding_wall)
        continue;
      n_failed += r.status == "ok" && r.wall_failed;
      nlohmann::ordered_json row = {{"record", r.record},
                                    {"wall_height", r.wall_height},
                                    {"source", r.wall_source},
                                    {"status", r.status}};
      if (r.status == "ok")
      {
        row["peak_wall_resistance"]       = r.wall_peak_resistance;
        row["wall_capacity_per_metre"]    = r.wall_capacity_per_metre;
        row["wall_capacity"]              = r.wall_capacity;
        row["peak_wall_displacement"]     = r.peak_wall_displacement;
        row["residual_wall_displacement"] = r.wall_residual_displacement;
        row["failed"]                     = r.wall_failed;
        if (r.wall_failed)
          row["failure_time"] = r.wall_failure_time;
        row["energy_error"] = r.energy_error;
      }
      runs.push_back(row);
    }
    nlohmann::ordered_json elements = nlohmann::ordered_json::array();
    for (const StudyYieldingWall &w : result.yielding_walls)
    {
      nlohmann::ordered_json e = {{"wall_height", w.wall_height},
                                  {"status", w.status},
                                  {"source", w.source},
                                  {"source_reason", w.source_reason},
                                  {"estimate_capacity", w.estimate_capacity}};
      if (w.ok())
      {
        e["capacity"]            = w.inputs.capacity;
        e["stiffness"]           = w.inputs.stiffness;
        e["hardening_ratio"]     = w.inputs.hardening_ratio;
        e["unloading_stiffness"] = w.inputs.unloading_stiffness;
        e["radiation_damping"]   = w.element.radiation_damping;
        e["contact_stiffness"]   = w.element.contact_stiffness;
      }
      if (w.source == "pushover")
      {
        e["pushover_force"]        = w.fit.target_force;
        e["pushover_displacement"] = w.fit.target_displacement;
      }
      elements.push_back(e);
    }
    const bool linear = yielding_wall_route(scene) == "linear";
    return {{"route", yielding_wall_route(scene)},
            {"route_text",
             linear ?
               "linear study: each height's estimate element (capacity from the section and "
               "Rankine's passive resistance, cracked stiffness, radiation dashpot rho c; no "
               "FEM pushover), run beside the linear springs, which stay the comparison with "
               "Table 2.1" :
               "inelastic study: the walls of every building run, instead of the laws"},
            {"units",
             {{"force", "N"},
              {"displacement", "m"},
              {"wall_height", "m"},
              {"time", "s"},
              {"energy_error", "1"},
              {"per_metre",
               "capacity and forces of elements, wall_capacity_per_metre: N/m, stiffness: N/m per "
               "m, radiation_damping: N*s/m per m"}}},
            {"n_runs", runs.size()},
            {"n_failed", n_failed},
            {"elements", elements},
            {"runs", runs}};
  }

  namespace
  {
    /// Per height: where the wall-and-backfill part comes from, the envelope it runs on and the
    /// equal-energy bilinear beside it.
    std::string element_markdown(const std::vector<StudyYieldingWall> &walls)
    {
      std::string md =
        "| H (m) | source | element envelope | k_ur (kN/mm/m) | dashpot c_r (kN*s/m^2) | "
        "bilinear (comparison): F_y (kN/m) | k (kN/mm/m) | alpha | estimate (kN/m) | pushover: "
        "largest force (kN/m) at (mm) | note |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
      for (const StudyYieldingWall &w : walls)
      {
        const bool  ok = w.ok(), po = ok && w.source == "pushover";
        const auto  s = [](bool show, double x) { return show ? base::sig(x) : std::string("-"); };
        std::string envelope = "-";
        if (ok && runs_on_curve(w))
          envelope =
            fmt::format("hull of {} points: k {} kN/mm/m, flat at {} kN/m from {} mm "
                        "(yielding_wall_envelope.csv)",
                        w.element.backfill.curve.size(),
                        base::sig(w.element.backfill.resolved().stiffness / w.element.width / 1e6),
                        base::sig(element_envelope_force(w) / 1e3),
                        base::sig(element_envelope_displacement(w) * 1e3));
        else if (ok)
          envelope = "the bilinear";
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                          base::sig(w.wall_height),
                          ok ? w.source : w.status,
                          envelope,
                          s(ok, w.inputs.unloading_stiffness / 1e6),
                          s(ok, w.element.radiation_damping / 1e3),
                          s(ok, w.inputs.capacity / 1e3),
                          s(ok, w.inputs.stiffness / 1e6),
                          s(ok, w.inputs.hardening_ratio),
                          s(true, w.estimate_capacity / 1e3),
                          po ? base::sig(w.fit.target_force / 1e3) + " at " +
                                 base::sig(w.fit.target_displacement * 1e3) :
                               std::string("-"),
                          w.source_reason.empty() ? std::string("-") : w.source_reason);
      }
      return md + "\n";
    }
  } // namespace

  namespace
  {
    /// The section's title and first paragraph: what the element is, by route.
    std::string yielding_wall_intro(const StudyScene &scene, std::size_t n_failed, std::size_t n)
    {
      const std::string failed =
        fmt::format("**{} of {} building runs push a wall past its failure limit (10 % of H).** ",
                    n_failed,
                    n);
      if (yielding_wall_route(scene) == "linear")
        return fmt::format(
          "## Moat walls as yielding elements (estimate, beside the linear springs): capacity "
          "and permanent displacement\n\n{}"
          "This study is linear: its building runs hit impact springs with the equivalent k "
          "(below, the comparison with Table 2.1), which never yield. Beside each of them the same "
          "building, record and gap hit each height's *estimate* element (docs/physics.md §2 "
          "\"Yielding moat wall\", element of a study): the wall and its backfill as the cracked "
          "cantilever 3(EI/2)/h_c^3 capped at the collapse load estimate (M_p + P_p H/3)/h_c (the "
          "wall's section and Rankine's passive resistance; no FEM pushover), the backfill's "
          "radiation dashpot rho c_p H_b, in series with a contact spring of the slab-wall "
          "impedance; W = {} m. The dashpot is the backfill's plane-wave bound: the dynamic FEM "
          "radiates 1/35-1/20 of it and the element meets the FEM with about 1/11 of it "
          "(docs/validation.md \"Yielding wall element against the dynamic FEM\"), so the wall "
          "displacements below are lower than with a fitted dashpot (docs/validation.md \"What "
          "the default study reads\": its effect on the default study). The peak contact force is "
          "the local wave against the wall's mass, not a force on the wall-and-backfill part. "
          "These are estimates: an inelastic study (`fem.materials`) derives each height's element "
          "from its static pushover and fits the dashpot to its FEM.\n\n",
          failed,
          scene.fit.width);
      return fmt::format(
        "## Yielding moat walls: capacity and permanent displacement\n\n{}"
        "With inelastic materials every building run hits each height's yielding wall element "
        "(docs/physics.md §2 \"Yielding moat wall\", element of a study): a contact spring with "
        "the first peak of the slab-wall impedance, in series with the wall and its backfill and "
        "the backfill's radiation dashpot rho c h; W = {} m. The wall-and-backfill part runs on "
        "the concave hull of the height's static pushover (source pushover; its equal-energy "
        "bilinear is shown beside it as the comparison) or, where the pushover fails, on the "
        "cracked cantilever capped at the collapse load estimate (M_p + P_p H/3)/h_c (source "
        "estimate). The equivalent k of the k table is the comparison with Table 2.1 only.\n\n",
        failed,
        scene.fit.width);
    }
  } // namespace

  std::string yielding_wall_markdown(const StudyScene &scene, const StudyResult &result)
  {
    if (result.yielding_walls.empty())
      return {};
    std::size_t n = 0, n_failed = 0;
    for (const StudyBuildingRun &r : result.building)
      if (r.yielding_wall && r.status == "ok")
      {
        ++n;
        n_failed += r.wall_failed ? 1 : 0;
      }
    std::string md = yielding_wall_intro(scene, n_failed, n) +
                     element_markdown(result.yielding_walls) +
                     "| record | H (m) | gap (cm) | capacity (kN/m) | capacity W (kN) | peak wall "
                     "resistance (kN) | resistance / capacity | peak contact force (kN) | peak "
                     "wall displacement (cm) | residual (cm) | failed | energy error | status "
                     "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const StudyBuildingRun &r : result.building)
    {
      if (!r.yielding_wall)
        continue;
      const bool ok = r.status == "ok";
      const auto s  = [&](double x) { return ok ? base::sig(x) : std::string("-"); };
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                        r.record,
                        base::sig(r.wall_height),
                        base::sig(r.gap * 100),
                        base::sig(r.wall_capacity_per_metre / 1e3),
                        base::sig(r.wall_capacity / 1e3),
                        s(r.wall_peak_resistance / 1e3),
                        s(r.wall_peak_resistance / r.wall_capacity),
                        s(r.peak_impact_force / 1e3),
                        s(100.0 * r.peak_wall_displacement),
                        s(100.0 * r.wall_residual_displacement),
                        !ok ? std::string("-") :
                        r.wall_failed ?
                              fmt::format("**yes** (t = {} s)", base::sig(r.wall_failure_time)) :
                              std::string("no"),
                        ok ? fmt::format("{:.2g}", r.energy_error) : std::string("-"),
                        r.status);
    }
    const bool any_hull =
      std::any_of(result.yielding_walls.begin(),
                  result.yielding_walls.end(),
                  [](const StudyYieldingWall &w) { return w.ok() && runs_on_curve(w); });
    md += "\nThe element per height (envelope, bilinear comparison, dashpot, contact part): "
          "[yielding_wall_element.csv](yielding_wall_element.csv); ";
    if (any_hull)
      md += "the hull points each element runs on: "
            "[yielding_wall_envelope.csv](yielding_wall_envelope.csv), study.h5 "
            "`/yielding_wall/envelope`; ";
    md += "per run: [yielding_wall.csv](yielding_wall.csv), study.h5 `/yielding_wall`.\n\n";
    return md;
  }
} // namespace kimp::app::study_internal
