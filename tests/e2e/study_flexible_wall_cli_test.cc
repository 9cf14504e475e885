// `kimp study` with the flexible wall (walls.flexible, the default) end to end on a reduced study:
// the wall SDOF per height (a taller wall is softer and slower), the building run against it
// beside the rigid wall, with its energy balance closed, in the CSV, HDF5, JSON and report; and
// walls.flexible: false writes none of it.
#ifdef KIMP_WITH_FEM

#  include <cmath>
#  include <filesystem>
#  include <fstream>
#  include <gtest/gtest.h>
#  include <string>

#  include "tests/e2e/fem_scenes.h"
#  include "tests/support/csv.h"
#  include "tests/support/files.h"
#  include "tests/support/hdf5_reader.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

using namespace kimp::testing;

TEST(StudyFlexibleWallCli, WallSdofPerHeightAndRigidBesideFlexible)
{
  const TempDir dir("study_flexible_wall_cli");
  const KimpRun run = run_study(reduced_study(), dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const std::filesystem::path out = dir.path() / "out";

  const auto sdof = read_csv_records(out / "wall_sdof.csv");
  ASSERT_EQ(sdof.size(), 2u) << read_text(out / "wall_sdof.csv");
  for (const auto &row : sdof)
  {
    ASSERT_EQ(row.at("status"), "ok");
    EXPECT_GT(std::stod(row.at("mode_share")), 0.0) << row.at("wall_height_m");
    // The participation mass is a part of the wall and backfill's mass, and the computed modes
    // carry most of it.
    const double m = std::stod(row.at("mass_t_per_m"));
    EXPECT_LT(m, std::stod(row.at("wall_and_backfill_mass_t_per_m")));
    EXPECT_LE(std::stod(row.at("modal_sum_mass_t_per_m")), m * (1 + 1e-5));
    EXPECT_GT(std::stod(row.at("modal_sum_mass_t_per_m")), 0.5 * m);
    EXPECT_NEAR(std::stod(row.at("stiffness_total_MN_per_m")),
                std::stod(row.at("stiffness_MN_per_m_per_m")) * 27.78,
                1e-5 * std::stod(row.at("stiffness_total_MN_per_m")));
  }
  EXPECT_GT(std::stod(sdof[0].at("stiffness_MN_per_m_per_m")),
            std::stod(sdof[1].at("stiffness_MN_per_m_per_m")));
  EXPECT_GT(std::stod(sdof[0].at("frequency_Hz")), std::stod(sdof[1].at("frequency_Hz")));

  // One flexible run per rigid run with walls (2 heights x 3 laws), each beside its rigid twin.
  constexpr double energy_tolerance = 0.01;
  const auto       flexible         = read_csv_records(out / "flexible_wall.csv");
  ASSERT_EQ(flexible.size(), 6u) << read_text(out / "flexible_wall.csv");
  for (const auto &row : flexible)
  {
    ASSERT_EQ(row.at("status"), "ok") << row.at("law") << " H = " << row.at("wall_height_m");
    EXPECT_GT(std::stoi(row.at("flexible_n_impacts")), 0);
    EXPECT_GT(std::stod(row.at("peak_wall_displacement_mm")), 0.0);
    EXPECT_LT(std::stod(row.at("energy_error")), energy_tolerance);
    for (const char *q : {"peak_base_acceleration",
                          "peak_top_acceleration",
                          "peak_impact_force",
                          "peak_interstorey_drift"})
    {
      const double ratio = std::stod(row.at(std::string("ratio_") + q));
      EXPECT_TRUE(std::isfinite(ratio) && ratio > 0) << q;
    }
  }
  // The rigid columns are the rigid runs of building_response.csv (beside them per height the
  // estimate element's run, which has no flexible counterpart).
  const auto building = read_csv_records(out / "building_response.csv");
  ASSERT_EQ(building.size(), 9u);
  EXPECT_EQ(flexible[0].at("rigid_peak_impact_force_kN"), building[1].at("peak_impact_force_kN"));

  EXPECT_EQ(Hdf5Reader(out / "study.h5").units("/wall_sdof/stiffness"), "N/m");
  EXPECT_EQ(Hdf5Reader(out / "study.h5")
              .units("/flexible_wall/synthetic/jankowski/flexible_peak_impact_force"),
            "N");
  const auto summary = read_json(out / "summary.json");
  EXPECT_EQ(summary.at("flexible_wall").at("wall_sdof").size(), 2u);
  EXPECT_EQ(summary.at("flexible_wall").at("runs").size(), 6u);
  EXPECT_NE(read_text(out / "report.md").find("## Flexible moat wall"), std::string::npos);

  // walls.flexible: false: the rigid study only.
  std::ofstream(dir.path() / "rigid.yaml") << reduced_study() << "walls:\n  flexible: false\n";
  const KimpRun rigid = run_kimp("study rigid.yaml -o rigid", dir.path());
  ASSERT_EQ(rigid.exit_code, 0) << rigid.out << rigid.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "rigid" / "wall_sdof.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "rigid" / "flexible_wall.csv"));
  EXPECT_EQ(read_csv_records(dir.path() / "rigid" / "building_response.csv").size(), 9u);
}

#endif
