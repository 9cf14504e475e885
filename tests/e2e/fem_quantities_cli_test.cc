// `kimp fem` writes the engineer's quantities of every record (summary.json with units, fem.h5,
// fem_quantities.csv) and checks impulse against momentum: a small elastic case (elastic slab on
// the quick scene) passes within 2 %.
#ifdef KIMP_WITH_FEM

#  include <cmath>
#  include <filesystem>
#  include <fstream>
#  include <gtest/gtest.h>
#  include <iostream>
#  include <nlohmann/json.hpp>
#  include <string>

#  include "io/fem_results.h"
#  include "tests/e2e/fem_scenes.h"
#  include "tests/support/files.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  TEST(FemQuantitiesCli, ElasticRecordPassesImpulseMomentumAndReportsQuantities)
  {
    const TempDir dir("fem_quantities_cli");
    write_text(dir.path() / "scene.yaml",
               quick_fem_scene("dynamics: {end_time: \"40 ms\"}\n", /*rigid=*/false));
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
    ASSERT_EQ(run.exit_code, 0) << run.err;

    const auto cases = kimp::io::read_fem_cases(dir.path() / "out/fem.h5");
    ASSERT_EQ(cases.size(), 1u);
    const kimp::io::FemCase &c     = cases[0];
    const auto              &s     = c.summary;
    const double             ratio = s.impulse_momentum_ratio.value();
    std::cout << "elastic slab, quick scene: impulse / m (v_in + v_out) = " << ratio
              << ", first peak " << s.first_peak_force.value() / 1e3 << " kN/m (peak "
              << s.peak_force.value() / 1e3 << "), first-pulse impulse "
              << s.first_peak_impulse.value() << " N s/m, slab travel "
              << s.max_slab_displacement.value() * 1e3 << " mm, R_e "
              << s.energy_equivalent_resistance.value() / 1e3 << " kN/m, time to stop "
              << s.time_to_stop.value() * 1e3 << " ms\n";
    EXPECT_NEAR(ratio, 1.0, 0.02);
    EXPECT_EQ(c.labels.at("impulse_momentum"), "ok");
    // An elastic wall: the first pulse is the peak of the record, the slab stops once.
    EXPECT_LE(s.first_peak_force.value(), s.peak_force.value() * (1 + 1e-12));
    EXPECT_GT(s.first_peak_force.value(), 0.5 * s.peak_force.value());
    const double e0 = 0.5 * c.slab_mass * c.impact_velocity * c.impact_velocity;
    EXPECT_NEAR(s.energy_equivalent_resistance.value() * s.max_slab_displacement.value(),
                e0,
                1e-9 * e0);
    EXPECT_GT(s.time_to_stop.value(), 0.0);
    EXPECT_LT(s.time_to_stop.value(), s.contact_duration.value());
    // An elastic wall stops the slab like a spring: 95 % of the travel at about asin(0.95) /
    // (pi / 2) = 0.80 of the zero-velocity time.
    EXPECT_GT(s.time_to_95_travel.value(), 0.6 * s.time_to_stop.value());
    EXPECT_LT(s.time_to_95_travel.value(), s.time_to_stop.value());
    EXPECT_FALSE(s.max_bar_gauge_strain_ratio.has_value()) << "no bars, no gauge";
    EXPECT_FALSE(s.max_bar_strain_ratio.has_value()) << "linear materials have no bars";

    // summary.json: the quantities, their units and the check's verdict.
    std::ifstream        in(dir.path() / "out/summary.json");
    const nlohmann::json j     = nlohmann::json::parse(in);
    const auto          &entry = j.at("cases").at(0);
    EXPECT_NEAR(entry.at("impulse_momentum_ratio").get<double>(), ratio, 1e-12);
    EXPECT_EQ(entry.at("impulse_momentum").get<std::string>(), "ok");
    EXPECT_EQ(j.at("units").at("energy_equivalent_resistance").get<std::string>(), "N/m");
    EXPECT_EQ(j.at("units").at("first_peak_impulse").get<std::string>(), "N*s/m");
    EXPECT_EQ(j.at("units").at("time_to_95_travel").get<std::string>(), "s");
    EXPECT_NEAR(entry.at("time_to_95_travel").get<double>(), s.time_to_95_travel.value(), 1e-15);
    // fem_quantities.csv: a header and one row per case.
    std::ifstream csv(dir.path() / "out/fem_quantities.csv");
    std::string   header, row;
    ASSERT_TRUE(std::getline(csv, header));
    ASSERT_TRUE(std::getline(csv, row));
    EXPECT_NE(header.find("energy_equivalent_resistance_N_per_m"), std::string::npos);
    EXPECT_EQ(row.rfind("H1.25,", 0), 0u) << row;
    EXPECT_NE(row.find(",ok"), std::string::npos) << row;
    EXPECT_NE(header.find("time_to_95_travel_s"), std::string::npos);
  }

  /// The reinforced moat wall (data/scenes/fem_reinforced_wall.yaml) on a coarse mesh for the
  /// first 15 ms of its impact, with the bars' gauge `gauge` long; its record.
  kimp::io::FemCase
  reinforced_record(const TempDir &dir, const std::string &tag, const std::string &gauge)
  {
    std::filesystem::create_directories(dir.path() / tag);
    write_text(dir.path() / tag / "scene.yaml",
               read_text(source_dir() / "data/scenes/fem_reinforced_wall.yaml") +
                 "\nmesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5, "
                 "wall_aspect_max: 1}\ndynamics: {end_time: \"15 ms\", bar_gauge_length: \"" +
                 gauge + "\"}\noutput: {frame_interval: \"0 ms\"}\n");
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path() / tag);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const auto cases = kimp::io::read_fem_cases(dir.path() / tag / "out/fem.h5");
    EXPECT_EQ(cases.size(), 1u);
    return cases.at(0);
  }

  // The bars' strain over a gauge through `kimp fem`: a gauge shorter than any half cell reads
  // the largest vertical bar strain of a Gauss point (the point measure, whose largest strain is
  // the vertical bars' in the bending wall); the default gauge (half the 0.25 m wall's
  // thickness) averages it down near the base, where the wall bends most.
  TEST(FemQuantitiesCli, BarGaugeReadsThePointStrainWhenShortAndAveragesWhenLong)
  {
    const TempDir           dir("fem_quantities_gauge");
    const kimp::io::FemCase point = reinforced_record(dir, "short", "0.1 mm");
    const kimp::io::FemCase gauge = reinforced_record(dir, "default", "0 cm");
    const auto             &p = point.summary, &g = gauge.summary;
    std::cout << "reinforced wall, 5 cm, 15 ms: point bar strain / eps_y "
              << p.max_bar_strain_ratio.value() << " at " << p.max_bar_strain_height.value()
              << " m; 0.1 mm gauge " << p.max_bar_gauge_strain_ratio.value() << " at "
              << p.max_bar_gauge_strain_height.value() << " m; default gauge "
              << g.bar_gauge_length.value() << " m: " << g.max_bar_gauge_strain_ratio.value()
              << " centred at " << g.max_bar_gauge_strain_height.value() << " m\n";
    EXPECT_NEAR(p.bar_gauge_length.value(), 1e-4, 1e-12);
    EXPECT_NEAR(g.bar_gauge_length.value(), 0.125, 1e-9) << "half the wall's thickness";
    EXPECT_NEAR(p.max_bar_gauge_strain_ratio.value(),
                p.max_bar_strain_ratio.value(),
                1e-9 * p.max_bar_strain_ratio.value());
    EXPECT_NEAR(p.max_bar_gauge_strain_height.value(), p.max_bar_strain_height.value(), 0.05);
    EXPECT_LT(g.max_bar_gauge_strain_ratio.value(), p.max_bar_strain_ratio.value());
    EXPECT_GT(g.max_bar_gauge_strain_ratio.value(), 0.0);
    EXPECT_LT(g.max_bar_gauge_strain_height.value(), 0.5) << "near the base";
    // The same run otherwise: the gauge only reads.
    EXPECT_EQ(p.max_bar_strain_ratio.value(), g.max_bar_strain_ratio.value());
    EXPECT_TRUE(gauge.labels.count("bars_yield_over_gauge"));
  }
} // namespace

#endif
