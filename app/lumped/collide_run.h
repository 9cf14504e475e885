// `kimp collide [SCENE.yaml] -o DIR [--calibrate]`: effective COR of every impact law against its
// nominal COR in a two-body collision (thesis: 280 t vs 300 t at 1 m/s, Δt = 2e-4 s,
// docs/physics.md §1), and the recalibration of C_imp of eq. 2.23 (1.55 / 0.7076 / 0.0025 /
// 0.9755).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "app/laws/cor_key.h"
#include "app/lumped/building_keys.h"
#include "app/lumped/lumped_scene.h"
#include "io/scene_io.h"
#include "io/summary.h"
#include "lumped/collision/cimp_calibration.h"
#include "lumped/collision/two_body.h"

namespace kimp::app
{
  /// One law of the COR table: a name for the row and its parameters (its `cor` is replaced by
  /// each value of the grid).
  struct CollideLawScene : ImpactLawScene
  {
    std::string name = "law";
  };

  template <class Io>
  void visit(Io &io, CollideLawScene &s)
  {
    io.text("name", s.name, "row label (letters, digits, _ - .)");
    visit_law(io, s);
  }

  /// The key `time_step`: the central difference step of a two-body collision (s, > 0); `doc`
  /// says whose.
  template <class Io>
  void visit_collision_time_step(Io &io, double &time_step, std::string_view doc)
  {
    io.quantity("time_step", time_step, "s", doc, io::Range::positive());
  }

  /// The C_imp calibration grid (lumped::CalibrationOptions; thesis set-up by default).
  struct CalibrationScene
  {
    std::vector<double> cor_grid =
      {0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95};
    std::vector<double> velocity_grid = {0.5, 1.0, 1.5, 2.0, 2.5};
    std::vector<double> mass_grid =
      {100e3, 200e3, 300e3, 400e3, 500e3, 600e3, 700e3, 800e3, 900e3, 1000e3};
    double other_mass = 300e3;
    double stiffness  = 2.3717e10;
    double time_step  = 2e-5;
    double tolerance  = 1e-7;
  };

  template <class Io>
  void visit(Io &io, CalibrationScene &s)
  {
    io.quantity_list("cor_grid", s.cor_grid, "", "nominal COR values (at least 2)", cor_range());
    io.quantity_list("velocity_grid",
                     s.velocity_grid,
                     "m/s",
                     "impact velocities v_imp (at least 2)",
                     io::Range::greater(0.0).and_at_most(1e3));
    io.quantity_list("mass_grid",
                     s.mass_grid,
                     "t",
                     "mass m1 of the striking body (at least 2)",
                     io::Range::greater(0.0).and_at_most(1e12));
    visit_mass(io, "other_mass", s.other_mass, "mass m2 of the struck body (at rest)");
    visit_hertz_stiffness(io, "stiffness", s.stiffness, "k of the hysteretic law (n = 1.5)");
    visit_collision_time_step(io, s.time_step, "time step of each collision");
    io.quantity("tolerance",
                s.tolerance,
                "",
                "relative tolerance of the energy balance root",
                io::Range::greater(0.0).and_less(0.1));
  }

  /// Scene of `kimp collide` (SI members).
  struct CollideScene
  {
    double                       mass_1            = 280e3;
    double                       mass_2            = 300e3;
    double                       velocity          = 1.0;
    double                       time_step         = 2e-4;
    lumped::VelocityEstimate     velocity_estimate = lumped::VelocityEstimate::backward_difference;
    std::vector<double>          cor_grid = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    std::vector<CollideLawScene> laws     = default_laws();
    CalibrationScene             calibration;

    /// The thesis' laws: linear, Kelvin-Voigt, modified KV (2500 kN/mm), Jankowski, Hertzdamp
    /// (and its Ye et al. variant), hysteretic (750 kN/mm^1.5).
    static std::vector<CollideLawScene> default_laws();
  };

  template <class Io>
  void visit(Io &io, CollideScene &s)
  {
    visit_mass(io, "mass_1", s.mass_1, "striking mass m1");
    visit_mass(io, "mass_2", s.mass_2, "struck mass m2 (at rest)");
    io.quantity("velocity", s.velocity, "m/s", "approach velocity of m1", io::Range::positive());
    visit_collision_time_step(io, s.time_step, "central difference time step");
    io.choice("velocity_estimate",
              s.velocity_estimate,
              {{"backward", lumped::VelocityEstimate::backward_difference},
               {"second_order", lumped::VelocityEstimate::second_order}},
              "rate given to the law: (d_n - d_n-1)/dt (thesis) or second order");
    io.quantity_list("cor_grid", s.cor_grid, "", "nominal COR values of the table", cor_range());
    io.list("laws", s.laws, "laws of the table (their cor is replaced by the grid)");
    io.section("calibration", s.calibration, "C_imp calibration (--calibrate)");
  }

  /// Ranges, law/k compatibility, unique law names.
  void validate(const CollideScene &scene, io::ValidationContext &ctx);

  /// The thesis' values of eq. 2.23: C_imp = 1.55(1 − COR²)/(COR^0.7076 m_eff^0.0025 v^0.9755).
  struct ThesisCimp
  {
    static constexpr double c  = 1.55;
    static constexpr double p1 = 0.7076;
    static constexpr double p2 = 0.0025;
    static constexpr double p3 = 0.9755;
  };

  /// One row of the COR table with the law's label (NaN values and a status when it failed).
  struct CollideRow
  {
    std::string         name;
    lumped::CorTableRow row;
    std::string         status = "ok";
  };

  /// The effective COR table of every law of the scene over its grid.
  std::vector<CollideRow> collide_cor_table(const CollideScene &scene);

  /// A number column of the COR table: its name, SI unit ("1": none) and value in a row.
  struct CorTableColumn
  {
    const char *name;
    const char *unit;
    double lumped::CorTableRow::*value;
  };

  /// The number columns of the COR table, in their order in collide.h5 (`cor_table`),
  /// cor_table.csv (the unit appended to the name) and the Python module's cor_table().
  const std::vector<CorTableColumn> &cor_table_columns();

  /// Run the table (and the calibration) and write collide.h5, cor_table.csv and summary.json.
  void run_collide(const io::LoadedScene<CollideScene> &scene,
                   const io::OutputDir                 &output,
                   bool                                 calibrate);

  /// Register `kimp collide` (scene optional: the thesis set-up by default).
} // namespace kimp::app
