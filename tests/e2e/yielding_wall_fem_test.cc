// The yielding wall element, its parameters frozen as an inelastic study derives them
// (app/study/yielding_wall_element.h: the resistance from the scene's static pushover where it
// runs, else the estimate; app/study/pushover_fit.h), against the dynamic FEM (`kimp fem`, H =
// 1.25 m, geostatic Mohr-Coulomb backfill, coarse 5 cm mesh): peak contact force, the slab's peak
// displacement, its time to stop and the wall's residual displacement. The test runs the
// reinforced 0.25 m wall with the FEM's own slab at 0.5 m/s; KIMP_YIELDING_WALL_FULL=1 runs the
// eight cases of docs/validation.md (the reinforced wall and an elastic wall with the contact
// interface; 0.5 and 1 m/s; the FEM's elastic slab and a rigid slab carrying the building's
// 55 t/m) and prints their table with each element's source. docs/validation.md "Yielding wall
// element against the dynamic FEM" has the numbers and where the element does not hold.
#ifdef KIMP_WITH_FEM

#  include <algorithm>
#  include <cmath>
#  include <cstdlib>
#  include <filesystem>
#  include <fmt/format.h>
#  include <gtest/gtest.h>
#  include <iostream>
#  include <limits>
#  include <stdexcept>
#  include <string>

#  include "app/fem/fem_scene.h"
#  include "app/study/pushover_fit.h"
#  include "app/study/yielding_wall_element.h"
#  include "app/study/yielding_wall_impact.h"
#  include "io/scene_io.h"
#  include "tests/support/csv.h"
#  include "tests/support/files.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp;
  using namespace kimp::testing;

  /// The reinforced moat wall of docs/validation.md (data/scenes/fem_reinforced_wall.yaml):
  /// damaged concrete with bars, geostatic Mohr-Coulomb sand.
  /// Throws when the file cannot be read (run from the repository root or under ctest), so that
  /// a missing scene never turns into a comparison of the elastic defaults.
  std::string reinforced_scene()
  {
    const auto        file = source_dir() / "data/scenes/fem_reinforced_wall.yaml";
    const std::string text = read_text(file);
    if (text.find("damage_plasticity") == std::string::npos)
      throw std::runtime_error(file.string() + ": cannot read the reinforced wall's scene (run "
                                               "from the repository root or set KIMP_SOURCE_DIR)");
    return text;
  }

  /// An elastic wall against the same sand with the contact interface.
  constexpr const char *elastic_wall = R"(wall_heights: ["1.25 m"]
interface: {model: contact}
materials:
  concrete: {model: elastic}
  soil: {model: mohr_coulomb, preset: medium_dense_sand}
)";

  /// The scene at the coarse mesh: `materials` (wall height and materials), then `slab` the slab
  /// line.
  std::string
  fem_scene(const std::string &slab, const std::string &end_time, const std::string &materials)
  {
    return materials + "\nmesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n" + slab +
           "\ndynamics: {end_time: \"" + end_time + "\"}\n";
  }

  /// The four compared quantities, per metre of wall.
  struct Impact
  {
    double peak_force   = 0.0; ///< N/m (FEM: of the smoothed force)
    double slab_peak    = 0.0; ///< m from the touch
    double time_to_stop = 0.0; ///< s from the touch
    double wall_end     = 0.0; ///< the wall's displacement at the end, m
  };

  /// From `kimp fem`'s histories: the slab displacement integrates its velocity from the touch.
  Impact fem_impact(const std::filesystem::path &histories)
  {
    const auto rows = read_csv_records(histories);
    Impact     r;
    double     x = 0.0, t_touch = -1.0, t_prev = 0.0, v_prev = 0.0;
    bool       stopped = false;
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
      r.peak_force = std::max(r.peak_force, f);
      r.slab_peak  = std::max(r.slab_peak, x);
      r.wall_end   = std::stod(row.at("wall_displacement_m"));
      t_prev       = t;
      v_prev       = v;
    }
    if (!stopped)
      r.time_to_stop = std::numeric_limits<double>::infinity();
    return r;
  }

  /// The element of the scene, parameters frozen: the study's derivation (the resistance from
  /// the scene's pushover where it runs, else the estimate), with the slab's own impedance
  /// (infinite for the rigid slab) and mass; `source` is set to where the resistance came from.
  Impact element_impact(const std::filesystem::path &scene_file,
                        double                       slab_mass,
                        double                       velocity,
                        bool                         rigid,
                        std::string                 &source)
  {
    const app::FemScene           scene = io::load_scene<app::FemScene>(scene_file);
    app::YieldingWallInputs       in    = app::yielding_wall_inputs(scene, 1.25, slab_mass);
    const app::PushoverResistance r     = app::pushover_resistance(scene, 1.25, in);
    source = r.source + (r.reason.empty() ? "" : " (" + r.reason + ")");
    std::cout << fmt::format("element: {}: F_y {:.4g} kN/m, k {:.4g} kN/mm/m, alpha {:.4g}, "
                             "k_ur {:.4g} kN/mm/m\n",
                             source,
                             in.capacity / 1e3,
                             in.stiffness / 1e6,
                             in.hardening_ratio,
                             in.unloading_stiffness / 1e6);
    if (rigid)
      in.slab_impedance = std::numeric_limits<double>::infinity();
    const app::YieldingWallElement e = app::derive_yielding_wall(in, 1.0);
    const app::SlabImpactResult    s = app::slab_impact(e, slab_mass, velocity, 1.0, 1e-6);
    return {s.peak_contact_force, s.slab_peak_displacement, s.time_to_stop, s.wall_residual};
  }

  struct Comparison
  {
    Impact      fem, element;
    std::string source; ///< of the element's wall-and-backfill part
    double      error(double Impact::*q) const { return element.*q / fem.*q - 1.0; }
  };

  Comparison compare(const std::string &name,
                     const std::string &slab,
                     const std::string &end_time,
                     double             slab_mass,
                     double             velocity,
                     bool               rigid,
                     const std::string &materials = reinforced_scene())
  {
    const TempDir dir("yielding_wall_fem_" + name);
    write_text(dir.path() / "scene.yaml", fem_scene(slab, end_time, materials));
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
    EXPECT_EQ(run.exit_code, 0) << run.output();
    Comparison c;
    c.fem     = fem_impact(dir.path() / "out" / "fem_histories.csv");
    c.element = element_impact(dir.path() / "scene.yaml", slab_mass, velocity, rigid, c.source);
    std::cout << fmt::format(
      "{}: FEM / element: peak force {:.4g} / {:.4g} kN/m ({:+.1f} %), slab peak {:.4g} / {:.4g} "
      "mm ({:+.1f} %), time to stop {:.4g} / {:.4g} ms ({:+.1f} %), wall at the end {:.4g} / "
      "{:.4g} mm ({:+.1f} %)\n",
      name,
      c.fem.peak_force / 1e3,
      c.element.peak_force / 1e3,
      100 * c.error(&Impact::peak_force),
      1e3 * c.fem.slab_peak,
      1e3 * c.element.slab_peak,
      100 * c.error(&Impact::slab_peak),
      1e3 * c.fem.time_to_stop,
      1e3 * c.element.time_to_stop,
      100 * c.error(&Impact::time_to_stop),
      1e3 * c.fem.wall_end,
      1e3 * c.element.wall_end,
      100 * c.error(&Impact::wall_end));
    return c;
  }
} // namespace

TEST(YieldingWallFem, ElementWithFrozenParametersAgainstTheFemSlabAtHalfAMetrePerSecond)
{
  // The FEM's elastic slab, 8 m x 0.20 m of concrete: 3.84 t/m.
  const Comparison c =
    compare("elastic_0.5", "slab: {velocity: \"0.5 m/s\"}", "100 ms", 3840.0, 0.5, false);
  // The reinforced wall is on its pushover: the implicit damage update stalls at the first
  // cracks, IMPL-EX at 0.25 mm steps runs (F_y 113.1 kN/m, k 86.85 kN/mm/m, alpha 0.023).
  EXPECT_EQ(c.source.rfind("pushover (IMPL-EX damage update", 0), 0u) << c.source;
  // What holds (docs/validation.md): the first peak, from the slab-wall impedance alone
  // (measured -8.3 %).
  EXPECT_LT(std::abs(c.error(&Impact::peak_force)), 0.10);
  // What does not hold (measured: slab peak -41.5 %, time to stop -32.6 %): the element, with the
  // pushover's secant at 0.6 F_y, is stiffer than the FEM's wall under the slab (the static push
  // spreads the band load that the slab's impact concentrates). Pinned so that a change shows,
  // either way; these are not the targets (15 %).
  EXPECT_NEAR(c.error(&Impact::slab_peak), -0.415, 0.07);
  EXPECT_NEAR(c.error(&Impact::time_to_stop), -0.326, 0.07);
  // 480 J/m push both walls past their yield: each keeps a set when the slab leaves, the
  // element's (0.89 mm) below the FEM's (1.1 mm, still moving back).
  EXPECT_GT(c.element.wall_end, 0.0);
  EXPECT_LT(c.element.wall_end, c.fem.wall_end);
}

TEST(YieldingWallFem, FullTableOfDocsValidation)
{
  if (!std::getenv("KIMP_YIELDING_WALL_FULL"))
    GTEST_SKIP() << "set KIMP_YIELDING_WALL_FULL=1 for the eight cases of docs/validation.md";
  for (const auto &[wall, materials] : {std::pair{"reinforced", reinforced_scene()},
                                        std::pair{"elastic_wall", std::string(elastic_wall)}})
    for (const double v : {0.5, 1.0})
    {
      const std::string speed = fmt::format("{} m/s", v);
      const std::string tag   = fmt::format("{}_{}", wall, v);
      compare("fem_slab_" + tag,
              "slab: {velocity: \"" + speed + "\"}",
              "100 ms",
              3840.0,
              v,
              false,
              materials);
      compare("rigid_55t_" + tag,
              "slab: {velocity: \"" + speed + "\", rigid: true, mass: \"55 t/m\"}",
              "400 ms",
              55e3,
              v,
              true,
              materials);
    }
}

#endif
