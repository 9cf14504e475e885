// Writers of `kimp study`'s yielding walls: yielding_wall_element.csv (per height),
// yielding_wall.csv (per height and record), study.h5 /yielding_wall and the report section.
#include <fmt/format.h>

#include "app/study/study_internal.h"
#include "base/format.h"
#include "io/results_file.h"
#include "io/table.h"

namespace kimp::app::study_internal
{
  namespace
  {
    /// Per height: the element and what it was derived from (per metre, display units).
    Table element_table(const std::vector<StudyYieldingWall> &walls)
    {
      Table t;
      t.number("wall_height", "m")
        .number("capacity", "kN/m")
        .number("stiffness", "kN/mm/m")
        .number("unloading_stiffness", "kN/mm/m")
        .number("hardening_ratio", "1")
        .number("failure_displacement", "cm")
        .number("soil_density", "kg/m^3")
        .number("soil_wave_speed", "m/s")
        .number("loaded_height", "m")
        .number("radiation_damping", "kN*s/m^2")
        .number("slab_impedance", "kN*s/m^2")
        .number("wall_impedance", "kN*s/m^2")
        .number("contact_impedance", "kN*s/m^2")
        .number("wall_mass", "t/m")
        .number("striker_mass", "t/m")
        .number("contact_stiffness", "kN/mm/m")
        .number("width", "m")
        .text("status");
      for (const StudyYieldingWall &w : walls)
      {
        const auto                 v  = [&](double x) { return Cell(w.ok() ? x : nan); };
        const YieldingWallInputs  &in = w.inputs;
        const YieldingWallElement &e  = w.element;
        t.add_row({w.wall_height,
                   v(in.capacity / 1e3),
                   v(in.stiffness / 1e6),
                   v(in.unloading_stiffness / 1e6),
                   v(in.hardening_ratio),
                   v(100.0 * e.backfill.resolved().failure_displacement),
                   v(in.soil_density),
                   v(in.soil_wave_speed),
                   v(in.loaded_height),
                   v(e.radiation_damping / 1e3),
                   v(in.slab_impedance / 1e3),
                   v(in.wall_impedance / 1e3),
                   v(e.contact_impedance / 1e3),
                   v(e.wall_mass / 1e3),
                   v(in.striker_mass / 1e3),
                   v(e.contact_stiffness / 1e6),
                   v(e.width),
                   w.status});
      }
      return t;
    }

    /// Per height and record: the walls against their capacity (display units).
    Table runs_table(const std::vector<StudyBuildingRun> &runs)
    {
      Table t;
      t.text("record")
        .number("wall_height", "m")
        .number("gap", "cm")
        .number("peak_wall_resistance", "kN")
        .number("wall_capacity", "kN")
        .number("resistance_over_capacity", "1")
        .number("peak_contact_force", "kN")
        .number("peak_wall_displacement", "cm")
        .number("residual_wall_displacement", "cm")
        .integer("failed")
        .number("failure_time", "s")
        .number("wall_plastic_work", "kJ")
        .number("wall_radiated_work", "kJ")
        .number("energy_input", "kJ")
        .number("energy_error", "1")
        .number("peak_top_acceleration", "m/s^2")
        .number("peak_interstorey_drift", "cm")
        .integer("n_impacts")
        .number("wall_time", "s")
        .text("status");
      for (const StudyBuildingRun &r : runs)
      {
        if (!r.yielding_wall)
          continue;
        const bool ok = r.status == "ok";
        const auto v  = [&](double x) { return Cell(ok ? x : nan); };
        t.add_row({r.record,
                   r.wall_height,
                   r.gap * 100,
                   v(r.wall_peak_resistance / 1e3),
                   r.wall_capacity / 1e3,
                   v(r.wall_capacity > 0 ? r.wall_peak_resistance / r.wall_capacity : nan),
                   v(r.peak_impact_force / 1e3),
                   v(100.0 * r.peak_wall_displacement),
                   v(100.0 * r.wall_residual_displacement),
                   static_cast<std::int64_t>(r.wall_failed ? 1 : 0),
                   r.wall_failed ? r.wall_failure_time : nan,
                   v(r.wall_plastic_work / 1e3),
                   v(r.wall_radiated_work / 1e3),
                   v(r.energy_input / 1e3),
                   v(r.energy_error),
                   v(r.top_acceleration),
                   v(100.0 * r.max_interstorey_drift),
                   static_cast<std::int64_t>(r.n_impacts),
                   r.wall_seconds,
                   r.status});
      }
      return t;
    }
  } // namespace

  void write_yielding_wall_csv(const OutputDir &output, const StudyResult &result)
  {
    if (result.yielding_walls.empty())
      return;
    element_table(result.yielding_walls).write_csv(output.file("yielding_wall_element.csv"));
    runs_table(result.building).write_csv(output.file("yielding_wall.csv"));
  }

  void write_yielding_wall_h5(ResultsGroup &root, const StudyResult &result)
  {
    if (result.yielding_walls.empty())
      return;
    ResultsGroup g = root.group("yielding_wall");
    element_table(result.yielding_walls).write_hdf5(g, "element");
    runs_table(result.building).write_hdf5(g, "runs");
  }

  nlohmann::ordered_json yielding_wall_json(const StudyResult &result)
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
                                    {"status", r.status}};
      if (r.status == "ok")
      {
        row["peak_wall_resistance"]       = r.wall_peak_resistance;
        row["wall_capacity"]              = r.wall_capacity;
        row["peak_wall_displacement"]     = r.peak_wall_displacement;
        row["residual_wall_displacement"] = r.wall_residual_displacement;
        row["failed"]                     = r.wall_failed;
        if (r.wall_failed)
          row["failure_time"] = r.wall_failure_time;
      }
      runs.push_back(row);
    }
    return {{"units", {{"force", "N"}, {"displacement", "m"}, {"wall_height", "m"}, {"time", "s"}}},
            {"n_runs", runs.size()},
            {"n_failed", n_failed},
            {"runs", runs}};
  }

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
    std::string md = fmt::format(
      "## Yielding moat walls: capacity and permanent displacement\n\n"
      "**{} of {} building runs push a wall past its failure limit (10 % of H).** With inelastic "
      "materials every building run hits each height's yielding wall element (docs/physics.md "
      "§2 \"Yielding moat wall\", element of a study): a contact spring with the first peak of "
      "the slab-wall impedance, in series with the cracked wall capped at its collapse load "
      "estimate (M_p + P_p H/3)/h_c and the backfill's radiation dashpot rho c h; W = {} m. The "
      "equivalent k of the k table is the comparison with Table 2.1 only.\n\n"
      "| record | H (m) | gap (cm) | peak wall resistance (kN) | capacity (kN) | resistance / "
      "capacity | peak contact force (kN) | peak wall displacement (cm) | residual (cm) | failed "
      "| status |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
      n_failed,
      n,
      scene.fit.width);
    for (const StudyBuildingRun &r : result.building)
    {
      if (!r.yielding_wall)
        continue;
      const bool ok = r.status == "ok";
      const auto s  = [&](double x) { return ok ? base::sig(x) : std::string("-"); };
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                        r.record,
                        base::sig(r.wall_height),
                        base::sig(r.gap * 100),
                        s(r.wall_peak_resistance / 1e3),
                        base::sig(r.wall_capacity / 1e3),
                        s(r.wall_peak_resistance / r.wall_capacity),
                        s(r.peak_impact_force / 1e3),
                        s(100.0 * r.peak_wall_displacement),
                        s(100.0 * r.wall_residual_displacement),
                        !ok ? std::string("-") :
                        r.wall_failed ?
                              fmt::format("**yes** (t = {} s)", base::sig(r.wall_failure_time)) :
                              std::string("no"),
                        r.status);
    }
    md += "\nThe element per height (capacity, cracked stiffness, dashpot, contact part): "
          "[yielding_wall_element.csv](yielding_wall_element.csv); per run: "
          "[yielding_wall.csv](yielding_wall.csv), study.h5 `/yielding_wall`.\n\n";
    return md;
  }
} // namespace kimp::app::study_internal
