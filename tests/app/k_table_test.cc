// A study's k_table.csv as the k source of a lumped scene (app/laws/k_table.h, impact.k_table):
// linear interpolation by wall height, refusal outside the table with file and key, per-case
// heights and records; a k(H, v) table interpolated in height at each velocity, then in velocity.
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "app/laws/k_table.h"
#include "app/lumped/lumped_scene.h"
#include "tests/support/files.h"
#include "tests/support/scene_errors.h"
#include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  constexpr double exact = 1e-12; // relative: the interpolation is one multiply-add

  /// The columns the reader uses, among others, as `kimp study` writes them (two heights and a
  /// failed row that must be skipped).
  const std::string height_table =
    "wall_height_m,kelvin_voigt_kN_per_mm_per_m,kelvin_voigt_total_kN_per_mm,"
    "jankowski_total_kN_per_mm1.5,kelvin_voigt_status\n"
    "1,166.827,4634.45,2141.86,ok\n"
    "2,25.7031,714.031,208.796,ok\n"
    "1.5,,,,\"failed: no contact\"\n";

  /// A k(H, v) table as `kimp study` writes it with fem.velocities: two heights at 0.5, 1 and
  /// 2 m/s, 1 m/s the reference velocity; rows deliberately out of order.
  const std::string velocity_table =
    "wall_height_m,impact_velocity_m_per_s,kelvin_voigt_total_kN_per_mm,"
    "jankowski_total_kN_per_mm1.5,reference_velocity\n"
    "1,1,4000,2000,yes\n"
    "1,0.5,3000,2400,no\n"
    "2,0.5,600,300,no\n"
    "1,2,5000,1600,no\n"
    "2,1,800,250,yes\n"
    "2,2,1000,200,no\n";

  /// `dir`/k_table.csv holding `csv`.
  std::filesystem::path write_k_table(const std::filesystem::path &dir,
                                      const std::string           &csv = height_table)
  {
    return write_text(dir / "k_table.csv", csv);
  }

  TEST(KTable, VelocityTableInterpolatesInHeightThenVelocityAndKeepsTheReference)
  {
    const TempDir           dir("k_table_velocity");
    const auto              file  = write_k_table(dir.path(), velocity_table);
    const kimp::app::KTable table = kimp::app::read_k_table(file);
    ASSERT_EQ(table.rows.size(), 6u);
    ASSERT_EQ(table.velocities(), (std::vector<double>{0.5, 1.0, 2.0}));
    const double kn_mm = 1e6; // kN/mm -> N/m
    // Without a velocity: the reference rows (1 m/s), as an old single-velocity table.
    EXPECT_NEAR(table.stiffness(1.0, 1.0), 4000 * kn_mm, exact * 4000 * kn_mm);
    EXPECT_NEAR(table.stiffness(1.5, 1.0), 2400 * kn_mm, exact * 2400 * kn_mm);
    // On the grid: the row itself.
    EXPECT_NEAR(table.stiffness(2.0, 1.0, 0.5), 600 * kn_mm, exact * 600 * kn_mm);
    // Bilinear: at H = 1.5 m the KV k is 1800 at 0.5 m/s and 2400 at 1 m/s; 0.75 m/s is halfway.
    EXPECT_NEAR(table.stiffness(1.5, 1.0, 0.75), 2100 * kn_mm, exact * 2100 * kn_mm);
    // 1.5 m/s between 1 and 2 m/s at H = 1 m: 4500.
    EXPECT_NEAR(table.stiffness(1.0, 1.0, 1.5), 4500 * kn_mm, exact * 4500 * kn_mm);
    // Jankowski column: H = 2 m, 1.5 m/s -> (250 + 200) / 2 kN/mm^1.5.
    const double j = 225e3 * std::pow(1e3, 1.5);
    EXPECT_NEAR(table.stiffness(2.0, 1.5, 1.5), j, exact * j);
    try
    {
      table.stiffness(1.0, 1.0, 3.0);
      FAIL() << "3 m/s is outside 0.5-2 m/s";
    }
    catch (const std::invalid_argument &error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find("impact velocity 3 m/s is outside the range of " + file.string()),
                std::string::npos)
        << message;
    }
  }

  TEST(KTable, TableWithoutVelocitiesGivesTheSameKAtEveryVelocity)
  {
    const TempDir           dir("k_table_no_velocity");
    const kimp::app::KTable table = kimp::app::read_k_table(write_k_table(dir.path()));
    EXPECT_TRUE(table.velocities().empty());
    for (const double v : {0.1, 1.0, 7.0})
      EXPECT_EQ(table.stiffness(1.25, 1.0, v), table.stiffness(1.25, 1.0)) << v << " m/s";
  }

  TEST(KTable, InterpolatesLinearlyInSiAndRefusesOutsideTheRange)
  {
    const TempDir           dir("k_table");
    const auto              file  = write_k_table(dir.path());
    const kimp::app::KTable table = kimp::app::read_k_table(dir.path()); // the study directory
    ASSERT_EQ(table.rows.size(), 2u);
    const double kv_1 = 4634.45e6, kv_2 = 714.031e6;   // N/m
    const double j_1 = 2141.86e3 * std::pow(1e3, 1.5); // N/m^1.5
    EXPECT_NEAR(table.stiffness(1.0, 1.0), kv_1, exact * kv_1);
    EXPECT_NEAR(table.stiffness(1.5, 1.0), 0.5 * (kv_1 + kv_2), exact * kv_1);
    EXPECT_NEAR(table.stiffness(1.25, 1.0), 0.75 * kv_1 + 0.25 * kv_2, exact * kv_1);
    EXPECT_NEAR(table.stiffness(1.0, 1.5), j_1, exact * j_1);
    try
    {
      table.stiffness(2.5, 1.0);
      FAIL() << "2.5 m is outside 1-2 m";
    }
    catch (const std::invalid_argument &error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find("outside the range of " + file.string()), std::string::npos)
        << message;
      EXPECT_NE(message.find("not extrapolated"), std::string::npos) << message;
    }
    EXPECT_THROW(table.stiffness(1.5, 2.65), std::invalid_argument);
    EXPECT_THROW(kimp::app::read_k_table(dir.path() / "missing.csv"), std::invalid_argument);
  }

  TEST(KTable, LumpedSceneTakesKFromTheTableByWallHeight)
  {
    const TempDir     dir("k_table_scene");
    const auto        file  = write_k_table(dir.path());
    const std::string scene = "impact:\n"
                              "  law: kelvin_voigt\n"
                              "  k_table: " +
                              file.string() +
                              "\n"
                              "  wall_height: 1.5 m\n"
                              "cases:\n"
                              "  - name: low\n"
                              "    wall_height: 1 m\n"
                              "  - name: jankowski\n"
                              "    law: jankowski\n"
                              "  - name: other_record\n"
                              "    record: RSN1106_KOBE_KJM000\n"
                              "  - name: own_k\n"
                              "    k: 100 kN/mm\n";
    const auto s     = kimp::io::load_scene_text<kimp::app::LumpedScene>(scene, "site.yaml");
    const auto cases = kimp::app::resolve_cases(s);
    ASSERT_EQ(cases.size(), 4u);
    const auto k = [&](std::size_t i)
    { return kimp::app::force_law_spec(cases[i].second.impact).stiffness; };
    EXPECT_NEAR(k(0), 4634.45e6, exact * 4634.45e6);
    EXPECT_NEAR(k(1), 0.5 * (2141.86e3 + 208.796e3) * std::pow(1e3, 1.5), 1e-9 * k(1));
    EXPECT_NEAR(k(2), 0.5 * (4634.45e6 + 714.031e6), exact * k(2));
    EXPECT_EQ(cases[2].second.ground_motion.record, "RSN1106_KOBE_KJM000");
    EXPECT_EQ(cases[0].second.ground_motion.record, "synthetic");
    EXPECT_NEAR(k(3), 100e6, exact * 100e6);
  }

  TEST(KTable, TablePathIsRelativeToTheSceneFile)
  {
    const TempDir dir("k_table_relative");
    write_k_table(dir.path());
    const auto scene = write_text(dir.path() / "site.yaml",
                                  "impact:\n  law: kelvin_voigt\n  k_table: k_table.csv\n"
                                  "  wall_height: 1 m\n");
    // The working directory (the test's) holds no k_table.csv: the scene's directory is used.
    ASSERT_FALSE(std::filesystem::exists("k_table.csv"));
    const auto loaded = kimp::io::read_scene<kimp::app::LumpedScene>(scene);
    EXPECT_EQ(loaded.scene.impact.k_table, (dir.path() / "k_table.csv").string());
    EXPECT_NEAR(kimp::app::impact_stiffness(loaded.scene.impact), 4634.45e6, exact * 4634.45e6);
    // An absolute path stays as it is.
    const auto absolute =
      write_text(dir.path() / "absolute.yaml",
                 "impact:\n  law: kelvin_voigt\n  k_table: " +
                   (dir.path() / "k_table.csv").string() + "\n  wall_height: 2 m\n");
    EXPECT_NEAR(kimp::app::impact_stiffness(
                  kimp::io::read_scene<kimp::app::LumpedScene>(absolute).scene.impact),
                714.031e6,
                exact * 714.031e6);
    // A table missing beside the scene: the key as written, the file looked for.
    const auto  missing = write_text(dir.path() / "missing.yaml",
                                    "impact:\n  law: kelvin_voigt\n  k_table: other.csv\n"
                                     "  wall_height: 1 m\n");
    std::string error;
    try
    {
      kimp::io::read_scene<kimp::app::LumpedScene>(missing);
    }
    catch (const kimp::io::SceneError &e)
    {
      error = e.what();
    }
    EXPECT_NE(error.find(missing.string() + ":3: impact.k_table = other.csv: " +
                         (dir.path() / "other.csv").string() + ": cannot read the k table"),
              std::string::npos)
      << error;
  }

  TEST(KTable, HeightOutsideTheTableIsRefusedWithFileAndKey)
  {
    const TempDir     dir("k_table_bad");
    const auto        file = write_k_table(dir.path());
    const std::string error =
      scene_error<kimp::app::LumpedScene>("impact:\n  law: kelvin_voigt\n  k_table: " +
                                            file.string() + "\n  wall_height: 3 m\n",
                                          "site.yaml");
    EXPECT_NE(error.find("site.yaml:4: impact.wall_height = 3 m"), std::string::npos) << error;
    EXPECT_NE(error.find(file.string()), std::string::npos) << error;

    const std::string missing = scene_error<kimp::app::LumpedScene>(
      "impact:\n  k_table: nowhere/k_table.csv\n  wall_height: 1 m\n",
      "site.yaml");
    EXPECT_NE(missing.find("site.yaml:2: impact.k_table = nowhere/k_table.csv"), std::string::npos)
      << missing;

    const std::string no_height =
      scene_error<kimp::app::LumpedScene>("impact:\n  law: kelvin_voigt\n  k_table: " +
                                            file.string() + "\n",
                                          "site.yaml");
    EXPECT_NE(no_height.find("impact.wall_height = null (default): must be given with k_table"),
              std::string::npos)
      << no_height;

    const std::string case_height = scene_error<kimp::app::LumpedScene>(
      "impact:\n  law: kelvin_voigt\n  k_table: " + file.string() +
        "\n  wall_height: 1 m\ncases:\n  - name: tall\n    wall_height: 2.5 m\n",
      "site.yaml");
    EXPECT_NE(case_height.find("cases[0].wall_height = 2.5 m"), std::string::npos) << case_height;
  }
} // namespace
