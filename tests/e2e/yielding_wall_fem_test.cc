// The yielding wall element, its parameters frozen as an inelastic study derives them
// (app/study/yielding_wall_element.h: the resistance and its cap from the scene's static pushover
// where it runs, else the estimate; app/study/pushover_fit.h), against the dynamic FEM (`kimp
// fem`, H = 1.25 m, the reinforced 0.25 m wall, geostatic Mohr-Coulomb backfill; 5 cm at the
// contact graded to 25 cm, the wall's cells no taller than wide; absorbing far side, and the
// thesis' rollered block for comparison): peak contact force, the slab's peak displacement, its
// time to stop (to 95 % of its travel) and the wall's residual displacement, against the criterion
// (peak force <= 10 %, the others <= 15 %) on every row. The radiation dashpot is the
// one parameter fitted to the dynamic FEM (app::fit_radiation_damping(), on the FEM's slab at 1
// m/s), then frozen. The test fits it and runs the slab carrying the building's 55 t/m at 0.5 m/s;
// KIMP_YIELDING_WALL_FULL=1 runs the four rows of docs/validation.md (the FEM's slab and the heavy
// slab, 0.5 and 1 m/s) against both far sides and checks the absorbing ones;
// KIMP_YIELDING_WALL_FEM_DIR=DIR keeps each FEM run in DIR/<row>_<far side> (with VTU fields every
// 50 ms) and reuses a finished one there; KIMP_YIELDING_WALL_SCENE=FILE runs the scene FILE's wall
// (default: the shipped reinforced wall's materials with perfectly bonded bars). docs/validation.md
// "Yielding wall element against the dynamic FEM" has the numbers.
#ifdef KIMP_WITH_FEM

#  include <algorithm>
#  include <cmath>
#  include <cstdlib>
#  include <filesystem>
#  include <fmt/format.h>
#  include <gtest/gtest.h>
#  include <iostream>
#  include <limits>
#  include <optional>
#  include <sstream>
#  include <stdexcept>
#  include <string>
#  include <utility>
#  include <vector>

#  include "app/fem/fem_quantities.h"
#  include "app/fem/fem_scene.h"
#  include "app/study/pushover_fit.h"
#  include "app/study/yielding_wall_element.h"
#  include "app/study/yielding_wall_impact.h"
#  include "io/scene_io.h"
#  include "tests/support/csv.h"
#  include "tests/support/files.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/reinforced_wall_scene.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp;
  using namespace kimp::testing;

  /// The reinforced moat wall of docs/validation.md with its bars perfectly bonded: the
  /// materials of data/scenes/fem_reinforced_wall.yaml without the bars' strain penetration,
  /// crack spacing and tension stiffening (the FEM this test's numbers were measured against).
  /// KIMP_YIELDING_WALL_SCENE=FILE takes the scene FILE instead, e.g. the shipped one, whose
  /// table docs/validation.md "Yielding wall element against the dynamic FEM" gives (its heavy
  /// slab at 0.5 m/s misses the peak-force criterion by 0.4 points). Throws when FILE cannot be
  /// read, so that a missing scene never turns into a comparison of the elastic defaults. The
  /// file's `slab` line is dropped: each row brings its own slab.
  std::string reinforced_scene()
  {
    if (const char *file = std::getenv("KIMP_YIELDING_WALL_SCENE"))
    {
      const std::string text = read_text(file);
      if (text.find("damage_plasticity") == std::string::npos)
        throw std::runtime_error(std::string(file) + ": not a reinforced wall's scene (no "
                                                     "damage_plasticity concrete)");
      // The rows set the slab: the file's own one-line `slab: {...}` (the shipped scene's
      // damping, which a rigid slab refuses) gives way to theirs.
      std::istringstream in(text);
      std::string        kept, line;
      while (std::getline(in, line))
        if (line.rfind("slab:", 0) != 0)
          kept += line + "\n";
      return kept;
    }
    return perfectly_bonded_wall_scene();
  }

  /// The scene at the coarse mesh whose wall cells do not lock: 5 cm at the contact graded to
  /// 25 cm, the wall's rows no taller than its 5 cm columns; `slab` the slab line. With `hold`
  /// the stop rule is off and the run goes on to `end_time`, so that the wall at the end is the
  /// settled set, not a wall still springing back when the slab has left.
  std::string
  fem_scene(const std::string &slab, const std::string &end_time, const bool hold, const bool keep)
  {
    const std::string held = hold ? ", separation_hold_time: \"" + end_time + "\"" : "";
    return reinforced_scene() +
           "\nmesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5, wall_aspect_max: 1}\n" +
           slab + "\ndynamics: {end_time: \"" + end_time + "\"" + held + "}\n" +
           (keep ? "output: {vtu_interval: \"50 ms\"}\n" : "");
  }

  /// The four compared quantities, per metre of wall.
  struct Impact
  {
    double peak_force   = 0.0; ///< N/m (FEM: of the smoothed force)
    double slab_peak    = 0.0; ///< m from the touch
    double time_to_stop = 0.0; ///< s from the touch to the slab's velocity zero
    double wall_end     = 0.0; ///< the wall's displacement at the end, m
    double wall_peak    = 0.0; ///< the wall's largest displacement, m
    /// s from the touch to 95 % of the slab's largest travel (app::stop_travel_fraction)
    double time_to_95_travel = 0.0;
  };

  /// The first time at which `x` reaches app::stop_travel_fraction of its largest value,
  /// interpolated between the samples `t`.
  double time_to_travel_fraction(const std::vector<double> &t, const std::vector<double> &x)
  {
    const double target = app::stop_travel_fraction * *std::max_element(x.begin(), x.end());
    for (std::size_t i = 1; i < x.size(); ++i)
      if (x[i] >= target)
        return t[i - 1] + (t[i] - t[i - 1]) * (target - x[i - 1]) / (x[i] - x[i - 1]);
    return std::numeric_limits<double>::infinity();
  }

  /// From `kimp fem`'s histories: the slab displacement integrates its velocity from the touch.
  Impact fem_impact(const std::filesystem::path &histories)
  {
    const auto          rows = read_csv_records(histories);
    Impact              r;
    double              x = 0.0, t_touch = -1.0, t_prev = 0.0, v_prev = 0.0;
    bool                stopped = false;
    std::vector<double> since_touch, travel; // from the touch
    for (const auto &row : rows)
    {
      const double t = std::stod(row.at("time_s"));
      // The peak of the smoothed force, as `kimp fem` and the study report it.
      const double f = std::stod(row.at("smoothed_contact_force_N_per_m"));
      const double v = std::stod(row.at("slab_velocity_m_per_s"));
      if (t_touch >= 0.0)
        x += 0.5 * (v + v_prev) * (t - t_prev);
      else if (f > 0.0)
        t_touch = t;
      if (t_touch >= 0.0 && !stopped && v <= 0.0)
      {
        stopped        = true;
        r.time_to_stop = t - t_touch;
      }
      if (t_touch >= 0.0)
      {
        since_touch.push_back(t - t_touch);
        travel.push_back(x);
      }
      r.peak_force = std::max(r.peak_force, f);
      r.slab_peak  = std::max(r.slab_peak, x);
      r.wall_end   = std::stod(row.at("wall_displacement_m"));
      r.wall_peak  = std::max(r.wall_peak, r.wall_end);
      t_prev       = t;
      v_prev       = v;
    }
    if (!stopped)
      r.time_to_stop = std::numeric_limits<double>::infinity();
    r.time_to_95_travel = time_to_travel_fraction(since_touch, travel);
    return r;
  }

  /// One row of the comparison: the slab line of the FEM scene, its mass (kg/m) and speed.
  struct Row
  {
    std::string name, slab, end_time;
    double      slab_mass = 0.0, velocity = 0.0;
    bool        rigid = false;
    bool        hold  = false; ///< run to end_time with the stop rule off
  };

  /// The four rows of docs/validation.md: the FEM's elastic slab (8 m x 0.20 m of concrete,
  /// 3.84 t/m) and a rigid slab carrying the building's 55 t/m (1,530 t over 27.78 m), at 0.5 and
  /// 1 m/s.
  Row row(const bool heavy, const double v)
  {
    const std::string speed = fmt::format("{} m/s", v);
    if (heavy)
      return {fmt::format("rigid_55t_{}", v),
              "slab: {velocity: \"" + speed + "\", rigid: true, mass: \"55 t/m\"}",
              "400 ms",
              55e3,
              v,
              true,
              false};
    // The light slab leaves while the wall still springs back (at 0.5 m/s from 4.9 mm through
    // 1.9 mm when the stop rule would end the run, to rest at 0.0 mm): held for 300 ms.
    return {fmt::format("fem_slab_{}", v),
            "slab: {velocity: \"" + speed + "\"}",
            "300 ms",
            3840.0,
            v,
            false,
            true};
  }

  /// The element of the scene for the slab of `r`, as the study derives it (the resistance and
  /// its cap from the scene's pushover where it runs, else the estimate), with the slab's own
  /// impedance (infinite for the rigid slab) and mass; `source` is set to where the resistance
  /// came from.
  app::YieldingWallElement
  element_of(const std::filesystem::path &scene_file, const Row &r, std::string &source)
  {
    // The pushover does not depend on the slab: run it once for all rows.
    static std::optional<std::pair<app::YieldingWallInputs, std::string>> resistance;
    const app::FemScene     scene = io::load_scene<app::FemScene>(scene_file);
    app::YieldingWallInputs in    = app::yielding_wall_inputs(scene, 1.25, r.slab_mass);
    if (!resistance)
    {
      app::YieldingWallInputs       pushed = in;
      const app::PushoverResistance p      = app::pushover_resistance(scene, 1.25, pushed);
      resistance.emplace(pushed, p.source + (p.reason.empty() ? "" : " (" + p.reason + ")"));
    }
    const app::YieldingWallInputs &p = resistance->first;
    source                           = resistance->second;
    in.capacity                      = p.capacity;
    in.stiffness                     = p.stiffness;
    in.hardening_ratio               = p.hardening_ratio;
    in.unloading_stiffness           = p.unloading_stiffness;
    in.ultimate_capacity             = p.ultimate_capacity;
    in.envelope_displacements        = p.envelope_displacements; // the curve's concave hull
    in.envelope_forces               = p.envelope_forces;
    if (r.rigid)
      in.slab_impedance = std::numeric_limits<double>::infinity();
    const app::YieldingWallElement e = app::derive_yielding_wall(in, 1.0);
    std::cout << fmt::format("element: {}: envelope the curve's concave hull ({} points, k {:.4g} "
                             "kN/mm/m); equal-energy bilinear F_y {:.4g} kN/m, cap {:.4g} kN/m, "
                             "k {:.4g} kN/mm/m, alpha {:.4g}; k_ur {:.4g} kN/mm/m, Z_c {:.4g} "
                             "kN*s/m^2\n",
                             source,
                             in.envelope_displacements.size(),
                             in.envelope_forces.size() > 1 ?
                               in.envelope_forces[1] / in.envelope_displacements[1] / 1e6 :
                               0.0,
                             in.capacity / 1e3,
                             in.ultimate_capacity / 1e3,
                             in.stiffness / 1e6,
                             in.hardening_ratio,
                             in.unloading_stiffness / 1e6,
                             e.contact_impedance / 1e3);
    return e;
  }

  struct Comparison
  {
    Impact      fem, element;
    std::string source;        ///< of the element's wall-and-backfill part
    double      damping = 0.0; ///< the element's c_r, N·s/m per m
    double      error(double Impact::*q) const { return element.*q / fem.*q - 1.0; }
    /// The residual's error over the FEM wall's largest displacement (where the FEM's residual
    /// is a small remainder of a wall that sprang back, its relative error says nothing).
    double residual_over_peak() const { return (element.wall_end - fem.wall_end) / fem.wall_peak; }
  };

  /// The FEM far side the element is compared with: absorbing (the site's backfill does not end
  /// 2 m behind the wall) or the thesis' rollered block.
  enum class Far
  {
    absorbing,
    rollers
  };

  /// Runs (or, with KIMP_YIELDING_WALL_FEM_DIR, reuses) the FEM of `r` and returns its
  /// directory's scene file and the FEM's quantities.
  std::pair<std::filesystem::path, Impact> fem_run(const Row &r, const Far far, const TempDir &temp)
  {
    const char       *kept = std::getenv("KIMP_YIELDING_WALL_FEM_DIR");
    const std::string tag  = r.name + (far == Far::absorbing ? "_absorbing" : "_rollers");
    const auto        dir  = kept ? std::filesystem::path(kept) / tag : temp.path() / tag;
    std::filesystem::create_directories(dir);
    write_text(dir / "scene.yaml",
               fem_scene(r.slab, r.end_time, r.hold, kept != nullptr) +
                 (far == Far::absorbing ? "boundary: {far: absorbing}\n" : ""));
    if (!kept || !std::filesystem::exists(dir / "out" / "summary.json"))
    {
      const KimpRun run = run_kimp("fem scene.yaml -o out", dir);
      EXPECT_EQ(run.exit_code, 0) << run.output();
    }
    return {dir / "scene.yaml", fem_impact(dir / "out" / "fem_histories.csv")};
  }

  /// "label FEM / element unit (error %)" of the quantity q, shown times `scale`.
  std::string compared(const Comparison &c,
                       const char       *label,
                       double Impact::*q,
                       double          scale,
                       const char     *unit)
  {
    return fmt::format("{} {:.4g} / {:.4g} {} ({:+.1f} %)",
                       label,
                       scale * (c.fem.*q),
                       scale * (c.element.*q),
                       unit,
                       100 * c.error(q));
  }

  void print(const std::string &name, const Comparison &c)
  {
    std::cout << fmt::format(
      "{} (c_r {:.4g} kN*s/m^2): FEM / element: {}, {}, {}, {}, wall at the end {:.4g} / {:.4g} "
      "mm ({:+.1f} %; {:+.1f} % of the FEM wall's largest {:.4g} mm)\n",
      name,
      c.damping / 1e3,
      compared(c, "peak force", &Impact::peak_force, 1e-3, "kN/m"),
      compared(c, "slab peak", &Impact::slab_peak, 1e3, "mm"),
      compared(c, "time to 95 % of the travel", &Impact::time_to_95_travel, 1e3, "ms"),
      compared(c, "slab velocity zero", &Impact::time_to_stop, 1e3, "ms"),
      1e3 * c.fem.wall_end,
      1e3 * c.element.wall_end,
      100 * c.error(&Impact::wall_end),
      100 * c.residual_over_peak(),
      1e3 * c.fem.wall_peak);
  }

  /// The element's radiation dashpot, fitted to the slab travel of the FEM's slab at 1 m/s (the
  /// study's reference record) against the `far` FEM: the one parameter of the element fitted to
  /// the dynamic FEM (docs/validation.md); that row's comparison in `fitted`.
  double fitted_dashpot(const Far far, const TempDir &temp, Comparison &fitted)
  {
    const Row r             = row(false, 1.0);
    const auto [scene, fem] = fem_run(r, far, temp);
    const auto e            = element_of(scene, r, fitted.source);
    const auto fit          = app::fit_radiation_damping(e,
                                                r.slab_mass,
                                                r.velocity,
                                                fem.slab_peak,
                                                e.radiation_damping,
                                                0.2,
                                                1e-6);
    std::cout << fmt::format("dashpot fitted to {} ({}): {:.4g} kN*s/m^2 (rho c_p H_b = {:.4g}) "
                             "{}\n",
                             r.name,
                             far == Far::absorbing ? "absorbing far side" : "rollers",
                             fit.damping / 1e3,
                             e.radiation_damping / 1e3,
                             fit.note);
    EXPECT_TRUE(fit.note.empty()) << fit.note;
    const auto s   = app::slab_impact(app::with_radiation_damping(e, fit.damping),
                                    r.slab_mass,
                                    r.velocity,
                                    1.0,
                                    1e-6);
    fitted.fem     = fem;
    fitted.damping = fit.damping;
    fitted.element = {s.peak_contact_force,
                      s.slab_peak_displacement,
                      s.time_to_stop,
                      s.wall_residual,
                      s.wall_peak_displacement,
                      s.time_to_95_travel};
    print(r.name, fitted);
    return fit.damping;
  }

  /// Row `r` against the `far` FEM with the dashpot `damping` frozen.
  Comparison compare(const Row &r, const Far far, const double damping, const TempDir &temp)
  {
    const auto [scene, fem] = fem_run(r, far, temp);
    Comparison c;
    c.fem        = fem;
    c.damping    = damping;
    const auto e = app::with_radiation_damping(element_of(scene, r, c.source), damping);
    const auto s = app::slab_impact(e, r.slab_mass, r.velocity, 1.0, 1e-6);
    c.element    = {s.peak_contact_force,
                    s.slab_peak_displacement,
                    s.time_to_stop,
                    s.wall_residual,
                    s.wall_peak_displacement,
                    s.time_to_95_travel};
    print(r.name, c);
    return c;
  }

  /// The dashpot that row `r` alone would need (fitted to its own FEM travel), printed: how far
  /// the one fitted at 1 m/s is from being a property of the wall (docs/validation.md).
  void print_own_dashpot(const Row &r, const Far far, const TempDir &temp)
  {
    const auto [scene, fem] = fem_run(r, far, temp);
    std::string source;
    const auto  e   = element_of(scene, r, source);
    const auto  fit = app::fit_radiation_damping(e,
                                                r.slab_mass,
                                                r.velocity,
                                                fem.slab_peak,
                                                4.0 * e.radiation_damping,
                                                1.0,
                                                1e-6);
    std::cout << fmt::format("{}: the dashpot fitted to this row alone: {:.4g} kN*s/m^2 {}\n",
                             r.name,
                             fit.damping / 1e3,
                             fit.note);
  }

  // The criterion of the wall-and-backfill element against the dynamic FEM.
  constexpr double force_tolerance  = 0.10; // peak force
  constexpr double motion_tolerance = 0.15; // slab travel, time to stop, wall residual


  /// |element / FEM − 1| <= tolerance for quantity `q` of `c`.
  void expect_within(const Comparison &c, double Impact::*q, double tolerance, const char *what)
  {
    EXPECT_LE(std::abs(c.error(q)), tolerance) << what << ": element / FEM - 1 = " << c.error(q);
  }

  /// The criterion on every row: peak force, slab travel (not on the fitted row), time to stop
  /// (to 95 % of the travel on both sides: the instant the slab's velocity is zero is
  /// ill-conditioned where the slab creeps to rest) and the wall's residual. Where the FEM wall
  /// comes back to rest (the FEM slab at 0.5 m/s: a set of a few micrometres) the residual's
  /// relative error says nothing; there its error over the FEM wall's largest displacement is
  /// checked instead (docs/validation.md says so).
  void expect_criterion(const Comparison &c, const bool fitted)
  {
    expect_within(c, &Impact::peak_force, force_tolerance, "peak force");
    if (!fitted)
      expect_within(c, &Impact::slab_peak, motion_tolerance, "slab travel");
    expect_within(c, &Impact::time_to_95_travel, motion_tolerance, "time to 95 % of the travel");
    if (std::abs(c.fem.wall_end) > 0.05 * c.fem.wall_peak)
      expect_within(c, &Impact::wall_end, motion_tolerance, "wall residual");
    else
      EXPECT_LE(std::abs(c.residual_over_peak()), motion_tolerance)
        << "wall residual over the FEM wall's largest displacement";
  }
} // namespace

// The dashpot fitted to the FEM's slab at 1 m/s, then frozen, against the slab carrying the
// building's mass per metre at 0.5 m/s; absorbing far side.
TEST(YieldingWallFem, ElementWithFrozenParametersAgainstTheFemAtTheBuildingsMass)
{
  const TempDir temp("yielding_wall_fem");
  Comparison    fitted;
  const double  c_r = fitted_dashpot(Far::absorbing, temp, fitted);
  // The reinforced wall is on its pushover: the implicit damage update stalls at the first
  // cracks, IMPL-EX at 0.25 mm steps runs; its cap is the curve's largest force.
  EXPECT_EQ(fitted.source.rfind("pushover (IMPL-EX damage update", 0), 0u) << fitted.source;
  // Measured 24.18 kN*s/m^2, 6 % of rho c_p H_b (394.5 kN*s/m^2); pinned so that a change
  // shows. (45.94 against the FEM with the fixed crack frame and the local compression curve,
  // whose wall was stiffer: its slab travelled 11.77 instead of 12.53 mm; 36.51 there with the
  // equal-energy bilinear as the envelope.)
  EXPECT_NEAR(c_r, 24.18e3, 0.1 * 24.18e3);
  expect_criterion(fitted, true);
  const Comparison heavy = compare(row(true, 0.5), Far::absorbing, c_r, temp);
  expect_criterion(heavy, false);
}

TEST(YieldingWallFem, FullTableOfDocsValidation)
{
  if (!std::getenv("KIMP_YIELDING_WALL_FULL"))
    GTEST_SKIP() << "set KIMP_YIELDING_WALL_FULL=1 for the four rows of docs/validation.md";
  const TempDir temp("yielding_wall_fem_full");
  for (const Far far : {Far::absorbing, Far::rollers})
  {
    Comparison   fitted;
    const double c_r = fitted_dashpot(far, temp, fitted);
    if (far == Far::absorbing)
      expect_criterion(fitted, true);
    for (const bool heavy : {false, true})
      for (const double v : {0.5, 1.0})
        if (heavy || v != 1.0)
        {
          const Comparison c = compare(row(heavy, v), far, c_r, temp);
          if (far == Far::absorbing) // the rollered block's rows are printed for comparison
          {
            expect_criterion(c, false);
            print_own_dashpot(row(heavy, v), far, temp);
          }
        }
  }
}

#endif
