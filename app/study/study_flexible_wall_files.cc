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

    /// The compared quantities: name, SI unit, display unit and the factor from SI to it, value.
    struct Quantity
    {
      const char *name;
      const char *unit;
      const char *display_unit;
      double      factor;
      double StudyBuildingRun::*value;
    };
    using R                     = StudyBuildingRun;
    const Quantity quantities[] = {
      {"peak_base_acceleration", "m/s^2", "m/s^2", 1.0, &R::base_acceleration},
      {"peak_top_acceleration", "m/s^2", "m/s^2", 1.0, &R::top_acceleration},
      {"peak_impact_force", "N", "kN", 1e-3, &R::peak_impact_force},
      {"peak_interstorey_drift", "m", "cm", 100.0, &R::max_interstorey_drift},
    };

    /// One flexible run with its rigid twin and its wall's SDOF (each may be missing).
    struct FlexibleRow
    {
      const StudyBuildingRun *flexible;
      const StudyBuildingRun *rigid;
      const StudyWallSdof    *sdof;

      bool flexible_ok() const { return flexible->status == "ok"; }
      bool rigid_ok() const { return rigid && rigid->status == "ok"; }
      bool sdof_ok() const { return sdof && sdof->ok(); }
      /// The run of `side` ("rigid" or "flexible") if it is ok, else null.
      const StudyBuildingRun *ok_run(const std::string &side) const
      {
        return side == "rigid" ? (rigid_ok() ? rigid : nullptr) :
                                 (flexible_ok() ? flexible : nullptr);
      }
    };

    /// The rows of `runs` (flexible runs of `result`).
    std::vector<FlexibleRow> flexible_rows(const StudyResult                           &result,
                                           const std::vector<const StudyBuildingRun *> &runs)
    {
      std::vector<FlexibleRow> rows;
      for (const StudyBuildingRun *f : runs)
        rows.push_back({f, rigid_twin(result, *f), sdof_of(result, f->wall_height)});
      return rows;
    }

    /// SIDE_amplification_QUANTITY of the CSV file: a peak against the run without walls.
    void append_amplification_columns(std::vector<StudyColumn<FlexibleRow>> &columns)
    {
      const std::pair<const char *, double StudyBuildingRun::*> amplifications[] = {
        {"base_acceleration", &StudyBuildingRun::amplification_base_acc},
        {"top_acceleration", &StudyBuildingRun::amplification_top_acc},
        {"interstorey_drift", &StudyBuildingRun::amplification_drift}};
      for (const std::string side : {"rigid", "flexible"})
        for (const auto &[name, amplification] : amplifications)
          columns.push_back(
            number_column<FlexibleRow>({},
                                       {side + "_amplification_" + name, "1"},
                                       {},
                                       [side, amplification = amplification](const FlexibleRow &x)
                                       {
                                         const StudyBuildingRun *run = x.ok_run(side);
                                         return run ? run->*amplification : nan;
                                       }));
    }

    /// Rigid beside flexible per run: the wall's SDOF, each quantity on both sides and their
    /// ratio, the amplifications against the run without walls, the wall's displacement.
    std::vector<StudyColumn<FlexibleRow>> flexible_wall_columns()
    {
      using F = FlexibleRow;
      std::vector<StudyColumn<F>> columns{
        csv_text_column<F>("record", [](const F &x) { return x.flexible->record; }),
        same_column<F>("wall_height", "m", [](const F &x) { return x.flexible->wall_height; }),
        csv_text_column<F>("law", [](const F &x) { return x.flexible->law; }),
        number_column<F>({"wall_stiffness", "N/m"},
                         {"wall_stiffness", "MN/m"},
                         divided_by(1e6),
                         [](const F &x) { return x.sdof_ok() ? x.sdof->stiffness : nan; }),
        number_column<F>({"wall_mass", "kg"},
                         {"wall_mass", "t"},
                         divided_by(1e3),
                         [](const F &x) { return x.sdof_ok() ? x.sdof->mass : nan; }),
        number_column<F>({},
                         {"wall_frequency", "Hz"},
                         {},
                         [](const F &x) { return x.sdof_ok() ? x.sdof->frequency : nan; })};
      for (const Quantity &q : quantities)
        for (const std::string side : {"rigid", "flexible"})
          columns.push_back(number_column<F>({side + "_" + q.name, q.unit},
                                             {side + "_" + q.name, q.display_unit},
                                             times(q.factor),
                                             [side, value = q.value](const F &x)
                                             {
                                               const StudyBuildingRun *run = x.ok_run(side);
                                               return run ? run->*value : nan;
                                             }));
      for (const Quantity &q : quantities)
        columns.push_back(number_column<F>({},
                                           {std::string("ratio_") + q.name, "1"},
                                           {},
                                           [value = q.value](const F &x) {
                                             return ratio(x.rigid,
                                                          *x.flexible,
                                                          x.rigid_ok() ? x.rigid->*value : nan,
                                                          x.flexible->*value);
                                           }));
      append_amplification_columns(columns);
      columns.push_back(
        number_column<F>({"peak_wall_displacement", "m"},
                         {"peak_wall_displacement", "mm"},
                         times(1e3),
                         [](const F &x)
                         { return x.flexible_ok() ? x.flexible->peak_wall_displacement : nan; }));
      columns.push_back(same_column<F>("energy_error",
                                       "1",
                                       [](const F &x) {
                                         return x.flexible_ok() ? x.flexible->energy_error : nan;
                                       }));
      for (const std::string side : {"rigid", "flexible"})
        columns.push_back(csv_text_column<F>(side + "_n_impacts",
                                             [side](const F &x)
                                             {
                                               const StudyBuildingRun *run = x.ok_run(side);
                                               return run ? std::to_string(run->n_impacts) : "";
                                             }));
      columns.push_back(
        csv_text_column<F>("status", [](const F &x) { return x.flexible->status; }));
      return columns;
    }

    /// A quantity of a computed SDOF (NaN where it failed).
    std::function<double(const StudyWallSdof &)> computed(double StudyWallSdof::*quantity)
    {
      return [quantity](const StudyWallSdof &s) { return s.ok() ? s.*quantity : nan; };
    }

    /// A mass per metre of wall: NAME_per_metre in kg/m in study.h5, NAME in t/m in the CSV.
    StudyColumn<StudyWallSdof> mass_per_metre_column(const std::string &name,
                                                     double StudyWallSdof::*quantity)
    {
      return number_column<StudyWallSdof>({name + "_per_metre", "kg/m"},
                                          {name, "t/m"},
                                          divided_by(1e3),
                                          computed(quantity));
    }

    std::vector<StudyColumn<StudyWallSdof>> wall_sdof_columns()
    {
      using S = StudyWallSdof;
      return {
        same_column<S>("wall_height", "m", [](const S &s) { return s.wall_height; }),
        number_column<S>({"stiffness_per_metre", "N/m/m"},
                         {"stiffness", "MN/m/m"},
                         divided_by(1e6),
                         computed(&S::stiffness_per_metre)),
        mass_per_metre_column("mass", &S::mass_per_metre),
        same_column<S>("frequency", "Hz", computed(&S::frequency)),
        mass_per_metre_column("participation_mass", &S::participation_mass_per_metre),
        mass_per_metre_column("modal_sum_mass", &S::modal_sum_mass_per_metre),
        csv_text_column<S>("mode",
                           [](const S &s) { return s.ok() ? std::to_string(s.mode + 1) : ""; }),
        same_column<S>("mode_frequency", "Hz", computed(&S::mode_frequency)),
        same_column<S>("mode_share", "1", computed(&S::mode_share)),
        mass_per_metre_column("mode_mass", &S::mode_mass_per_metre),
        mass_per_metre_column("wall_and_backfill_mass", &S::total_mass_per_metre),
        number_column<S>({"stiffness", "N/m"},
                         {"stiffness_total", "MN/m"},
                         divided_by(1e6),
                         computed(&S::stiffness)),
        number_column<S>({"mass", "kg"}, {"mass_total", "t"}, divided_by(1e3), computed(&S::mass)),
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

  } // namespace

  void write_flexible_wall_csv(const OutputDir &output, const StudyResult &result)
  {
    study_table(wall_sdof_columns(), result.wall_sdofs, StudyFile::csv)
      .write_csv(output.file("wall_sdof.csv"));

    std::vector<const StudyBuildingRun *> runs;
    for (const StudyBuildingRun &f : result.flexible_building)
      runs.push_back(&f);
    study_table(flexible_wall_columns(), flexible_rows(result, runs), StudyFile::csv)
      .write_csv(output.file("flexible_wall.csv"));
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
      ResultsGroup record = root.group("flexible_wall").group(key.first);
      study_table(flexible_wall_columns(), flexible_rows(result, runs), StudyFile::hdf5)
        .write_hdf5(record, key.second);
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
        const double x = ratio(r, f, r ? r->*q.value : nan, f.*q.value);
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
        const double    x = ratio(r, f, ok ? r->*q.value : nan, f.*q.value);
        cells += fmt::format(" {} / {} | {} |",
                             readable(ok ? r->*q.value * q.factor : nan),
                             readable(ok ? f.*q.value * q.factor : nan),
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
