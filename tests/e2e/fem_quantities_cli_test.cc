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
    EXPECT_FALSE(s.max_bar_strain_ratio.has_value()) << "linear materials have no bars";

    // summary.json: the quantities, their units and the check's verdict.
    std::ifstream        in(dir.path() / "out/summary.json");
    const nlohmann::json j     = nlohmann::json::parse(in);
    const auto          &entry = j.at("cases").at(0);
    EXPECT_NEAR(entry.at("impulse_momentum_ratio").get<double>(), ratio, 1e-12);
    EXPECT_EQ(entry.at("impulse_momentum").get<std::string>(), "ok");
    EXPECT_EQ(j.at("units").at("energy_equivalent_resistance").get<std::string>(), "N/m");
    EXPECT_EQ(j.at("units").at("first_peak_impulse").get<std::string>(), "N*s/m");
    // fem_quantities.csv: a header and one row per case.
    std::ifstream csv(dir.path() / "out/fem_quantities.csv");
    std::string   header, row;
    ASSERT_TRUE(std::getline(csv, header));
    ASSERT_TRUE(std::getline(csv, row));
    EXPECT_NE(header.find("energy_equivalent_resistance_N_per_m"), std::string::npos);
    EXPECT_EQ(row.rfind("H1.25,", 0), 0u) << row;
    EXPECT_NE(row.find(",ok"), std::string::npos) << row;
  }
} // namespace

#endif
