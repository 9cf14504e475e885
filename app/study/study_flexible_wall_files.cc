// Writers of `kimp study`'s flexible wall: wall_sdof.csv, flexible_wall.csv (rigid beside
// flexible per run), study.h5 /wall_sdof and /flexible_wall, summary.json and report.md.
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

#include "app/study/study_columns.h"
#include "app/study/study_internal.h"
#include "base/format.h"
#include "io/results_file.h"
#include "io/table.h"

namespace kimp::app::study_internal
{
  namespace
  {
    /// The rigid run of `r`'s record, height and law (or null).
    const StudyBuildingRun *rigid_twin(const StudyResult &result, const StudyBuildingRun &r)
    {
      for (const StudyBuildingRun &b : result.building)
        if (b.record == r.record && b.law == r.law && b.wall_height == r.wall_height)
          return &b;
      return nullptr;
    }

    /// The SDOF of `wall_height` (or null).
    const StudyWallSdof *sdof_of(const StudyResult &result, double wall_height)
    {
      for (const StudyWallSdof &s : result.wall_sdofs)
        if (s.wall_height == wall_height)
          return &s;
      return nullptr;
    }

    /// flexible / rigid, NaN unless both runs are ok.
    double
    ratio(const StudyBuildingRun *rigid, const StudyBuildingRun &flexible, double a, double b)
    {
      return rigid && rigid->status == "ok" && flexible.status == "ok" && a > 0 ? b / a : nan;
    }

    /// The compared quantities: name, unit, scale to the CSV unit, value.
    struct Quantity
    {
      const char *name;
      const char *csv_unit;
      double      scale;
      double (*value)(const StudyBuildingRun &);
    };
    const Quantity quantities[] = {
      {"peak_base_acceleration",
       "m_per_s2",
       1.0,
       [](const StudyBuildingRun &r) { return r.base_acceleration; }},
      {"peak_top_acceleration",
       "m_per_s2",
       1.0,
       [](const StudyBuildingRun &r) { return r.top_acceleration; }},
      {"peak_impact_force",
       "kN",
       1e-3,
       [](const StudyBuildingRun &r) { return r.peak_impact_force; }},
      {"peak_interstorey_drift",
       "cm",
       100.0,
       [](const StudyBuildingRun &r) { return r.max_interstorey_drift; }},
    };

    /// The wall's SDOF per height: its stiffness and mass (per metre and for the wall's width),
    /// the dominant mode, and the FEM model it came from.
    std::vector<StudyColumn<StudyWallSdof>> wall_sdof_columns()
    {
      using S = StudyWallSdof;
      return {
        same_column<S>("wall_height", "m", [](const S &s) { return s.wall_height; }),
        number_column<S>({"stiffness_per_metre", "N/m/m"},
                         {"stiffness", "MN/m/m"},
                         divided_by(1e6),
                         [](const S &s) { return s.ok() ? s.stiffness_per_metre : nan; }),
        number_column<S>({"mass_per_metre", "kg/m"},
                         {"mass", "t/m"},
                         divided_by(1e3),
                         [](const S &s) { return s.ok() ? s.mass_per_metre : nan; }),
        same_column<S>("frequency", "Hz", [](const S &s) { return s.ok() ? s.frequency : nan; }),
        number_column<S>({"participation_mass_per_metre", "kg/m"},
                         {"participation_mass", "t/m"},
                         divided_by(1e3),
                         [](const S &s) { return s.ok() ? s.participation_mass_per_metre : nan; }),
        number_column<S>({"modal_sum_mass_per_metre", "kg/m"},
                         {"modal_sum_mass", "t/m"},
                         divided_by(1e3),
                         [](const S &s) { return s.ok() ? s.modal_sum_mass_per_metre : nan; }),
        csv_text_column<S>("mode",
                           [](const S &s) { return s.ok() ? std::to_string(s.mode + 1) : ""; }),
        same_column<S>("mode_frequency",
                       "Hz",
                       [](const S &s) { return s.ok() ? s.mode_frequency : nan; }),
        same_column<S>("mode_share", "1", [](const S &s) { return s.ok() ? s.mode_share : nan; }),
        number_column<S>({"mode_mass_per_metre", "kg/m"},
                         {"mode_mass", "t/m"},
                         divided_by(1e3),
                         [](const S &s) { return s.ok() ? s.mode_mass_per_metre : nan; }),
        number_column<S>({"wall_and_backfill_mass_per_metre", "kg/m"},
                         {"wall_and_backfill_mass", "t/m"},
                         divided_by(1e3),
                         [](const S &s) { return s.ok() ? s.total_mass_per_metre : nan; }),
        number_column<S>({"stiffness", "N/m"},
                         {"stiffness_total", "MN/m"},
                         divided_by(1e6),
                         [](const S &s) { return s.ok() ? s.stiffness : nan; }),
        number_column<S>({"mass", "kg"},
                         {"mass_total", "t"},
                         divided_by(1e3),
                         [](const S &s) { return s.ok() ? s.mass : nan; }),
        same_column<S>("damping_ratio", "1", [](const S &s) { return s.damping_ratio; }),
        number_column<S>({"h_contact", "m"},
                         {"h_contact", "cm"},
                         times(100),
                         [](const S &s) { return s.h_contact; }),
        hdf5_column<S>("ok", "1", [](const S &s) { return flag(s.ok()); }),
        integer_column<S>("n_dofs", false, true, [](const S &s) { return std::int64_t(s.n_dofs); }),
        number_column<S>({}, {"wall_time", "s"}, {}, [](const S &s) { return s.seconds; }),
        csv_text_column<S>("status", [](const S &s) { return s.status; })};
    }

    std::string readable(double value)
    {
      return std::isfinite(value) ? base::sig(value) : std::string();
    }
  } // namespace

  void write_flexible_wall_csv(const OutputDir &output, const StudyResult &result)
  {
    study_table(wall_sdof_columns(), result.wall_sdofs, StudyFile::csv)
      .write_csv(output.file("wall_sdof.csv"));

    std::vector<std::string> header = {"record",
                                       "wall_height_m",
                                       "law",
                                       "wall_stiffness_MN_per_m",
                                       "wall_mass_t",
                                       "wall_frequency_Hz"};
    for (const Quantity &q : quantities)
      for (const char *which : {"rigid", "flexible"})
        header.push_back(fmt::format("{}_{}_{}", which, q.name, q.csv_unit));
    for (const Quantity &q : quantities)
      header.push_back(fmt::format("ratio_{}", q.name));
    for (const char *which : {"rigid", "flexible"})
      for (const char *a : {"base_acceleration", "top_acceleration", "interstorey_drift"})
        header.push_back(fmt::format("{}_amplification_{}", which, a));
    for (const std::string column :
         {"peak_wall_displacement_mm", "energy_error", "rigid_n_impacts", "flexible_n_impacts"})
      header.push_back(column);
    header.push_back("status");

    std::vector<std::vector<std::string>> rows;
    for (const StudyBuildingRun &f : result.flexible_building)
    {
      const StudyBuildingRun  *r   = rigid_twin(result, f);
      const StudyWallSdof     *s   = sdof_of(result, f.wall_height);
      const bool               sok = s && s->ok();
      const bool               rok = r && r->status == "ok";
      const bool               fok = f.status == "ok";
      std::vector<std::string> row = {f.record,
                                      number(f.wall_height),
                                      f.law,
                                      number(sok ? s->stiffness / 1e6 : nan),
                                      number(sok ? s->mass / 1e3 : nan),
                                      number(sok ? s->frequency : nan)};
      for (const Quantity &q : quantities)
      {
        row.push_back(number(rok ? q.value(*r) * q.scale : nan));
        row.push_back(number(fok ? q.value(f) * q.scale : nan));
      }
      for (const Quantity &q : quantities)
        row.push_back(number(ratio(r, f, rok ? q.value(*r) : nan, q.value(f))));
      for (const StudyBuildingRun *run : {r, static_cast<const StudyBuildingRun *>(&f)})
      {
        const bool ok = run && run->status == "ok";
        row.push_back(number(ok ? run->amplification_base_acc : nan));
        row.push_back(number(ok ? run->amplification_top_acc : nan));
        row.push_back(number(ok ? run->amplification_drift : nan));
      }
      row.push_back(number(fok ? f.peak_wall_displacement * 1e3 : nan));
      row.push_back(number(fok ? f.energy_error : nan));
      row.push_back(rok ? std::to_string(r->n_impacts) : "");
      row.push_back(fok ? std::to_string(f.n_impacts) : "");
      row.push_back(f.status);
      rows.push_back(row);
    }
    write_csv_atomic(output.file("flexible_wall.csv"), header, rows);
  }

  void write_flexible_wall_h5(ResultsGroup &root, const StudyResult &result)
  {
    if (result.wall_sdofs.empty())
      return;
    study_table(wall_sdof_columns(), result.wall_sdofs, StudyFile::hdf5)
      .write_hdf5(root, "wall_sdof");

    // /flexible_wall/<record>/<law>: one row per wall height, rigid and flexible side by side.
    for (const auto &[key, runs] : by_record_and_law(result.flexible_building, true))
    {
      Table t;
      t.number("wall_height", "m").number("wall_stiffness", "N/m").number("wall_mass", "kg");
      for (const Quantity &q : quantities)
      {
        const std::string unit = std::string(q.csv_unit) == "m_per_s2" ? "m/s^2" :
                                 std::string(q.csv_unit) == "kN"       ? "N" :
                                                                         "m";
        t.number(fmt::format("rigid_{}", q.name), unit)
          .number(fmt::format("flexible_{}", q.name), unit);
      }
      t.number("peak_wall_displacement", "m").number("energy_error", "1");
      for (const StudyBuildingRun *f : runs)
      {
        const StudyBuildingRun *r = rigid_twin(result, *f);
        const StudyWallSdof    *s = sdof_of(result, f->wall_height);
        std::vector<Cell>       v =
          number_cells({f->wall_height, s ? s->stiffness : nan, s ? s->mass : nan});
        for (const Quantity &q : quantities)
        {
          v.push_back(r && r->status == "ok" ? q.value(*r) : nan);
          v.push_back(q.value(*f));
        }
        v.push_back(f->peak_wall_displacement);
        v.push_back(f->energy_error);
        t.add_row(std::move(v));
      }
      ResultsGroup record = root.group("flexible_wall").group(key.first);
      t.write_hdf5(record, key.second);
    }
  }

  nlohmann::ordered_json flexible_wall_json(const StudyResult &result)
  {
    nlohmann::ordered_json j;
    j["units"]                   = {{"stiffness", "N/m"},
                                    {"mass", "kg"},
                                    {"per_metre", "of wall"},
                                    {"frequency", "Hz"},
                                    {"wall_time", "s"}};
    j["wall_time"]               = result.flexible_wall_seconds;
    nlohmann::ordered_json sdofs = nlohmann::ordered_json::array();
    for (const StudyWallSdof &s : result.wall_sdofs)
    {
      nlohmann::ordered_json row;
      row["case"]        = s.name;
      row["wall_height"] = s.wall_height;
      row["status"]      = s.status;
      if (s.ok())
      {
        row["stiffness_per_metre"]          = s.stiffness_per_metre;
        row["mass_per_metre"]               = s.mass_per_metre;
        row["frequency"]                    = s.frequency;
        row["participation_mass_per_metre"] = s.participation_mass_per_metre;
        row["mode"]                         = s.mode + 1;
        row["mode_frequency"]               = s.mode_frequency;
        row["mode_share"]                   = s.mode_share;
        row["mode_mass_per_metre"]          = s.mode_mass_per_metre;
        row["stiffness"]                    = s.stiffness;
        row["mass"]                         = s.mass;
        row["mode_frequencies"]             = s.mode_frequencies;
        row["mode_shares"]                  = s.mode_shares;
      }
      row["damping_ratio"] = s.damping_ratio;
      sdofs.push_back(row);
    }
    j["wall_sdof"]              = sdofs;
    nlohmann::ordered_json runs = nlohmann::ordered_json::array();
    for (const StudyBuildingRun &f : result.flexible_building)
    {
      const StudyBuildingRun *r = rigid_twin(result, f);
      nlohmann::ordered_json  row;
      row["record"]      = f.record;
      row["wall_height"] = f.wall_height;
      row["law"]         = f.law;
      row["status"]      = f.status;
      for (const Quantity &q : quantities)
      {
        const double x = ratio(r, f, r ? q.value(*r) : nan, q.value(f));
        if (std::isfinite(x))
          row[std::string("ratio_") + q.name] = x;
      }
      if (f.status == "ok")
      {
        row["amplification_top_acceleration"] = {{"rigid", r ? r->amplification_top_acc : nan},
                                                 {"flexible", f.amplification_top_acc}};
        row["peak_wall_displacement"]         = f.peak_wall_displacement;
        row["energy_error"]                   = f.energy_error;
      }
      runs.push_back(row);
    }
    j["runs"] = runs;
    return j;
  }

  std::string flexible_wall_markdown(const StudyScene &scene, const StudyResult &result)
  {
    if (result.wall_sdofs.empty())
      return "";
    const bool  mode_mass = scene.walls.flexible_mass == WallSdofMass::mode;
    std::string md        = fmt::format(
      "## Flexible moat wall (wall SDOF from the FEM)\n\n"
             "Each height's wall with its backfill (the FE mesh of the level used, without the slab) "
             "as a single-DOF oscillator at the slab level (docs/physics.md §4 \"Wall SDOF\"): k = "
             "static stiffness under a unit load spread over the slab's contact band; m = {}; f = "
             "sqrt(k/m)/2π; per metre of wall, times W = {} m for the building; damping ratio {:g} %. "
             "The modal analysis gives the mode with the largest share of the static deflection at "
             "the band. The impact laws keep the m_eff of the wall mass {:g} t in both the rigid and "
             "the flexible runs (the same dashpot constant), so the SDOF's mass acts only as the "
             "wall's inertia. For comparison, the thesis' bumper wall stiffness k_w is 1500 MN/m.\n\n"
             "| H (m) | k (MN/m/m) | m (t/m) | f (Hz) | largest share: mode, f (Hz), share | "
             "k/ω² of that mode (t/m) | wall + backfill (t/m) | k·W (MN/m) | m·W (t) | status |\n"
             "|---|---|---|---|---|---|---|---|---|---|\n",
      mode_mass ? "k/ω² of that mode (walls.flexible_mass: mode)" :
                         "the participation mass k²·uᵀMu of the static deflection u (Rayleigh; "
                         "every mode by its share of the deflection)",
      scene.fit.width,
      100 * scene.walls.damping_ratio,
      scene.walls.mass / 1e3);
    for (const StudyWallSdof &s : result.wall_sdofs)
    {
      const auto v = [&](double x) { return readable(s.ok() ? x : nan); };
      md += fmt::format("| {:.2f} | {} | {} | {} | {}, {}, {} % | {} | {} | {} | {} | {} |\n",
                        s.wall_height,
                        v(s.stiffness_per_metre / 1e6),
                        v(s.mass_per_metre / 1e3),
                        v(s.frequency),
                        s.ok() ? std::to_string(s.mode + 1) : "-",
                        v(s.mode_frequency),
                        v(100 * s.mode_share),
                        v(s.mode_mass_per_metre / 1e3),
                        v(s.total_mass_per_metre / 1e3),
                        v(s.stiffness / 1e6),
                        v(s.mass / 1e3),
                        s.status);
    }
    md += "\nThe building against the rigid and the flexible wall (same record, gap, law, k and "
          "m_eff); ratio = flexible / rigid.\n\n"
          "| record | H (m) | law | base acc. rigid / flexible (m/s²) | ratio | top acc. "
          "rigid / flexible (m/s²) | ratio | impact force rigid / flexible (kN) | ratio | drift "
          "rigid / flexible (cm) | ratio | wall displ. (mm) | status |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    double      log_sum[4] = {0, 0, 0, 0};
    std::size_t n_ratios   = 0;
    for (const StudyBuildingRun &f : result.flexible_building)
    {
      const StudyBuildingRun *r  = rigid_twin(result, f);
      const bool              ok = f.status == "ok" && r && r->status == "ok";
      std::string             cells;
      for (std::size_t i = 0; i < 4; ++i)
      {
        const Quantity &q = quantities[i];
        const double    x = ratio(r, f, ok ? q.value(*r) : nan, q.value(f));
        cells += fmt::format(" {} / {} | {} |",
                             readable(ok ? q.value(*r) * q.scale : nan),
                             readable(ok ? q.value(f) * q.scale : nan),
                             readable(x));
        if (ok && std::isfinite(x) && x > 0)
          log_sum[i] += std::log(x);
      }
      n_ratios += ok;
      md += fmt::format("| {} | {:.2f} | {} |{} {} | {} |\n",
                        f.record,
                        f.wall_height,
                        f.law,
                        cells,
                        readable(f.status == "ok" ? f.peak_wall_displacement * 1e3 : nan),
                        f.status);
    }
    if (n_ratios > 0)
      md += fmt::format("\nGeometric mean of the ratios over {} runs: base acceleration {}, top "
                        "acceleration {}, impact force {}, drift {}.\n",
                        n_ratios,
                        base::sig(std::exp(log_sum[0] / n_ratios)),
                        base::sig(std::exp(log_sum[1] / n_ratios)),
                        base::sig(std::exp(log_sum[2] / n_ratios)),
                        base::sig(std::exp(log_sum[3] / n_ratios)));
    md += "\nData: [wall_sdof.csv](wall_sdof.csv), [flexible_wall.csv](flexible_wall.csv), "
          "study.h5 `/wall_sdof`, `/flexible_wall/<record>/<law>`, summary.json "
          "`flexible_wall`.\n\n";
    return md;
  }
} // namespace kimp::app::study_internal
