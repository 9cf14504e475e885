// `kimp collide`: effective COR table of the impact laws (two-body central difference runs,
// docs/physics.md §1) and the C_imp recalibration (thesis eqs. 2.18-2.23).
#include "app/lumped/collide_run.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "app/table_cells.h"
#include "base/errors.h"
#include "base/logging.h"
#include "io/results_file.h"
#include "io/summary.h"
#include "io/table.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  namespace
  {
    CollideLawScene make_law(const std::string &name,
                             const std::string &law,
                             const std::string &k,
                             const bool         ye = false)
    {
      CollideLawScene s;
      s.name         = name;
      s.law          = law;
      s.k            = k;
      s.hertzdamp_ye = ye;
      return s;
    }

    lumped::TwoBodySetup two_body_setup(const CollideScene &scene)
    {
      lumped::TwoBodySetup setup;
      setup.mass_1            = scene.mass_1;
      setup.mass_2            = scene.mass_2;
      setup.velocity_1        = scene.velocity;
      setup.velocity_2        = 0.0;
      setup.time_step         = scene.time_step;
      setup.velocity_estimate = scene.velocity_estimate;
      setup.record_history    = false;
      return setup;
    }

    lumped::ForceLawSpec spec_of(const CollideLawScene &law)
    {
      ImpactScene impact;
      static_cast<ImpactLawScene &>(impact) = law;
      return force_law_spec(impact);
    }

    std::string list_text(const std::vector<double> &values, const std::string &unit)
    {
      std::string out = "[";
      for (std::size_t i = 0; i < values.size(); ++i)
        out += (i ? ", " : "") + format_quantity(values[i], unit);
      return out + "]";
    }
  } // namespace

  std::vector<CollideLawScene> CollideScene::default_laws()
  {
    return {make_law("linear", "linear", "2500 kN/mm"),
            make_law("kelvin_voigt", "kelvin_voigt", "2500 kN/mm"),
            make_law("modified_kelvin_voigt", "modified_kelvin_voigt", "2500 kN/mm"),
            make_law("jankowski", "jankowski", "750 kN/mm^1.5"),
            make_law("hertzdamp", "hertzdamp", "750 kN/mm^1.5"),
            make_law("hertzdamp_ye", "hertzdamp", "750 kN/mm^1.5", true),
            make_law("hysteretic", "hysteretic", "750 kN/mm^1.5")};
  }

  void validate(const CollideScene &scene, ValidationContext &ctx)
  {
    // Single-key ranges (masses, velocity, time steps, grid values) are declared in visit().
    ctx.check(!scene.cor_grid.empty(), "cor_grid", "[]", "must list at least one value");
    ctx.check(!scene.laws.empty(), "laws", "[]", "must list at least one law");
    std::set<std::string> names;
    for (std::size_t i = 0; i < scene.laws.size(); ++i)
    {
      const CollideLawScene &law   = scene.laws[i];
      const auto             scope = ctx.section("laws[" + std::to_string(i) + "]");
      ctx.check(!law.name.empty() && names.insert(law.name).second,
                "name",
                "\"" + law.name + "\"",
                "must be non-empty and unique");
      const lumped::LawTraits *traits    = lumped::find_law_traits(law.law);
      const bool               wall_only = traits != nullptr && traits->moat_wall_only;
      ctx.check(!wall_only, "law", law.law, law.law + " is not part of the COR table");
      if (wall_only)
        continue;
      // The same law/k rules as a lumped scene's impact section.
      validate_law(law, ctx, false);
    }
    {
      const auto              scope = ctx.section("calibration");
      const CalibrationScene &c     = scene.calibration;
      const auto              two_or_more =
        [&](const char *key, const std::vector<double> &grid, const char *unit)
      { ctx.check(grid.size() >= 2, key, list_text(grid, unit), "needs >= 2 values"); };
      two_or_more("cor_grid", c.cor_grid, "");
      two_or_more("velocity_grid", c.velocity_grid, "m/s");
      two_or_more("mass_grid", c.mass_grid, "t");
    }
  }

  std::vector<CollideRow> collide_cor_table(const CollideScene &scene)
  {
    const lumped::TwoBodySetup setup = two_body_setup(scene);
    std::vector<CollideRow>    rows;
    for (const CollideLawScene &law : scene.laws)
    {
      const lumped::ForceLawSpec spec = spec_of(law);
      for (const double cor : scene.cor_grid)
      {
        CollideRow row;
        row.name = law.name;
        try
        {
          row.row = lumped::effective_cor_table({spec}, {cor}, setup).at(0);
        }
        catch (const std::exception &error)
        {
          constexpr double nan = std::numeric_limits<double>::quiet_NaN();
          row.row              = lumped::CorTableRow{law.law, cor, nan, nan, nan, nan, nan, nan};
          row.status           = "failed: " + base::error_text(error);
        }
        rows.push_back(std::move(row));
      }
    }
    return rows;
  }

  const std::vector<CorTableColumn> &cor_table_columns()
  {
    using R = lumped::CorTableRow;
    static const std::vector<CorTableColumn> columns{{"nominal_cor", "1", &R::nominal_cor},
                                                     {"effective_cor", "1", &R::effective_cor},
                                                     {"relative_error", "1", &R::relative_error},
                                                     {"peak_force", "N", &R::peak_force},
                                                     {"contact_duration",
                                                      "s",
                                                      &R::contact_duration},
                                                     {"max_penetration", "m", &R::max_penetration},
                                                     {"energy_error", "1", &R::energy_error}};
    return columns;
  }

  namespace
  {
    /// The recalibration of C_imp (`--calibrate`) over the scene's grids, logged beside the
    /// thesis' values.
    lumped::CalibrationResult calibrate_cimp(const CollideScene &scene)
    {
      lumped::CalibrationOptions options;
      options.cor_grid          = scene.calibration.cor_grid;
      options.velocity_grid     = scene.calibration.velocity_grid;
      options.mass_grid         = scene.calibration.mass_grid;
      options.other_mass        = scene.calibration.other_mass;
      options.stiffness         = scene.calibration.stiffness;
      options.time_step         = scene.calibration.time_step;
      options.tolerance         = scene.calibration.tolerance;
      options.velocity_estimate = scene.velocity_estimate;
      logger().info("calibrating C_imp over {} points",
                    options.cor_grid.size() * options.velocity_grid.size() *
                      options.mass_grid.size());
      lumped::CalibrationResult calibration = lumped::calibrate_impact_coefficient(options);
      logger().info("C_imp = c (1 - COR^2) / (COR^p1 m_eff^p2 v^p3), m_eff in kg, v in m/s:");
      logger().info("  c  = {:.4g} (thesis {})", calibration.c, ThesisCimp::c);
      logger().info("  p1 = {:.4f} (thesis {})", calibration.p1, ThesisCimp::p1);
      logger().info("  p2 = {:.4f} (thesis {})", calibration.p2, ThesisCimp::p2);
      logger().info("  p3 = {:.4f} (thesis {})", calibration.p3, ThesisCimp::p3);
      logger().info("  R^2 = {:.5f}; max COR error: thesis law {:.2f} %, refit {:.2f} %",
                    calibration.r_squared,
                    100.0 * calibration.max_cor_error_thesis,
                    100.0 * calibration.max_cor_error_fit);
      return calibration;
    }

    /// A quantity of the collision set-up: its name and unit in summary.json (`setup`, `units`)
    /// and collide.h5 (attributes of `/collide`), and its member of the scene.
    struct SetupQuantity
    {
      const char *name;
      const char *unit;
      double CollideScene::*value;
    };

    constexpr SetupQuantity setup_quantities[] = {{"mass_1", "kg", &CollideScene::mass_1},
                                                  {"mass_2", "kg", &CollideScene::mass_2},
                                                  {"velocity", "m/s", &CollideScene::velocity},
                                                  {"time_step", "s", &CollideScene::time_step}};

    /// collide.h5 `/collide/<law>`: the law's COR table and its status.
    void write_law_table(ResultsGroup                  &collide,
                         const CollideLawScene         &law,
                         const std::vector<CollideRow> &rows)
    {
      Table       t;
      std::string status = "ok";
      for (const CorTableColumn &c : cor_table_columns())
        t.number(c.name, c.unit);
      for (const CollideRow &r : rows)
      {
        if (r.name != law.name)
          continue;
        std::vector<Cell> cells;
        for (const CorTableColumn &c : cor_table_columns())
          cells.emplace_back(r.row.*c.value);
        t.add_row(std::move(cells));
        if (r.status != "ok")
          status = "failed: COR " + format_quantity(r.row.nominal_cor, "") + ": " + r.status;
      }
      ResultsGroup g = collide.case_group(law.name);
      g.set_attribute("law", law.law);
      t.write_hdf5(g, "cor_table");
      g.set_status(status);
    }

    /// collide.h5 `/collide/calibration`: the calibration points, the fit and the thesis' law.
    void write_calibration(ResultsGroup &collide, const lumped::CalibrationResult &calibration)
    {
      ResultsGroup g = collide.case_group("calibration");
      Table        t;
      t.number("cor", "1")
        .number("impact_velocity", "m/s")
        .number("mass", "kg")
        .number("effective_mass", "kg")
        .number("a1", "s/m")
        .number("a1_thesis", "s/m")
        .number("cor_thesis", "1")
        .number("cor_fit", "1");
      for (const lumped::CalibrationPoint &p : calibration.points)
        t.add_row(number_cells({p.cor,
                                p.impact_velocity,
                                p.mass,
                                p.effective_mass,
                                p.a1,
                                p.a1_thesis,
                                p.cor_thesis,
                                p.cor_fit}));
      t.write_hdf5(g, "points");
      g.write("fit",
              std::vector<double>{calibration.c, calibration.p1, calibration.p2, calibration.p3},
              "1");
      g.write("thesis",
              std::vector<double>{ThesisCimp::c, ThesisCimp::p1, ThesisCimp::p2, ThesisCimp::p3},
              "1");
      g.write_scalar("r_squared", calibration.r_squared, "1");
      g.write_scalar("max_cor_error_thesis", calibration.max_cor_error_thesis, "1");
      g.write_scalar("max_cor_error_fit", calibration.max_cor_error_fit, "1");
      g.set_status("ok");
    }

    /// collide.h5: the setup, one COR table per law and the calibration, if any.
    void write_collide_h5(const LoadedScene<CollideScene>                &loaded,
                          const OutputDir                                &output,
                          const std::vector<CollideRow>                  &rows,
                          const std::optional<lumped::CalibrationResult> &calibration)
    {
      const CollideScene &scene = loaded.scene;
      ResultsFile         file(output.file("collide.h5"), loaded.text, loaded.resolved_json);
      ResultsGroup        collide = file.root().group("collide");
      for (const SetupQuantity &q : setup_quantities)
        collide.set_attribute(q.name, scene.*q.value);
      for (const CollideLawScene &law : scene.laws)
        write_law_table(collide, law, rows);
      if (calibration)
        write_calibration(collide, *calibration);
      file.commit();
    }

    /// cor_table.csv: one row per law and COR.
    void write_cor_table_csv(const OutputDir &output, const std::vector<CollideRow> &rows)
    {
      std::vector<std::string> header{"law"};
      for (const CorTableColumn &c : cor_table_columns())
        header.push_back(csv_column(c.name, c.unit));
      header.push_back("status");
      std::vector<std::vector<std::string>> csv;
      for (const CollideRow &r : rows)
      {
        std::vector<std::string> line{r.name};
        for (const CorTableColumn &c : cor_table_columns())
          line.push_back(format_quantity(r.row.*c.value, ""));
        line.push_back(r.status);
        csv.push_back(std::move(line));
      }
      write_csv_atomic(output.file("cor_table.csv"), header, csv);
    }

    /// summary.json: the setup, one case per law and COR, the calibration.
    nlohmann::json collide_summary(const LoadedScene<CollideScene>                &loaded,
                                   const std::vector<CollideRow>                  &rows,
                                   const std::optional<lumped::CalibrationResult> &calibration,
                                   double                                          wall_time)
    {
      const CollideScene &scene   = loaded.scene;
      nlohmann::json      summary = io::summary_preamble("collide");
      summary["scene"]            = loaded.file_name;
      summary["wall_time"]        = wall_time;
      summary["units"]            = {{"peak_force", "N"}, {"wall_time", "s"}};
      for (const SetupQuantity &q : setup_quantities)
      {
        summary["units"][q.name] = q.unit;
        summary["setup"][q.name] = scene.*q.value;
      }
      // One case per law, in the shape of every command's summary.json (name, status).
      summary["cases"] = nlohmann::json::array();
      for (const CollideRow &r : rows)
        summary["cases"].push_back({{"name", r.name},
                                    {"nominal_cor", r.row.nominal_cor},
                                    {"effective_cor", r.row.effective_cor},
                                    {"relative_error", r.row.relative_error},
                                    {"peak_force", r.row.peak_force},
                                    {"status", r.status}});
      if (calibration)
        summary["calibration"] = {{"fit",
                                   {{"c", calibration->c},
                                    {"p1", calibration->p1},
                                    {"p2", calibration->p2},
                                    {"p3", calibration->p3}}},
                                  {"thesis",
                                   {{"c", ThesisCimp::c},
                                    {"p1", ThesisCimp::p1},
                                    {"p2", ThesisCimp::p2},
                                    {"p3", ThesisCimp::p3}}},
                                  {"r_squared", calibration->r_squared},
                                  {"max_cor_error_thesis", calibration->max_cor_error_thesis},
                                  {"max_cor_error_fit", calibration->max_cor_error_fit},
                                  {"n_points", calibration->points.size()}};
      return summary;
    }
  } // namespace

  void run_collide(const LoadedScene<CollideScene> &loaded,
                   const OutputDir                 &output,
                   const bool                       calibrate)
  {
    const auto                               start = std::chrono::steady_clock::now();
    const std::vector<CollideRow>            rows  = collide_cor_table(loaded.scene);
    std::optional<lumped::CalibrationResult> calibration;
    if (calibrate)
      calibration = calibrate_cimp(loaded.scene);
    const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    write_collide_h5(loaded, output, rows, calibration);
    write_cor_table_csv(output, rows);
    write_json_atomic(output.file("summary.json"),
                      collide_summary(loaded, rows, calibration, wall_time));

    for (const CollideRow &r : rows)
      if (r.status != "ok")
        throw std::runtime_error("collide: law " + r.name + " at COR " +
                                 format_quantity(r.row.nominal_cor, "") + " " + r.status +
                                 " (the table is written to " + output.path().string() + ")");
  }

} // namespace kimp::app
