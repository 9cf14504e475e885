// `kimp study` with an impact-velocity axis and consistent k, end to end on a quick scene (coarse
// rigid-slab FEM, one short synthetic record): the k(H, v) table of a linear FEM obeys the exact
// velocity scaling of a linear contact (k_KV independent of v, k_Jankowski ∝ v^-1/2), the
// consistent-k building runs converge to the k of their own impact velocity, a table with one
// velocity converges in one run, and a soil law that never yields is recognised as linear by
// fidelity: auto.
#ifdef KIMP_WITH_FEM

#  include <cmath>
#  include <filesystem>
#  include <fstream>
#  include <gtest/gtest.h>
#  include <map>
#  include <string>

#  include "tests/e2e/fem_scenes.h"
#  include "tests/support/csv.h"
#  include "tests/support/files.h"
#  include "tests/support/hdf5_reader.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  /// Linear-elastic concrete and soil, whatever the study's default materials.
  constexpr const char *linear_materials = R"(  materials:
    concrete:
      model: elastic
    soil:
      model: elastic
)";

  /// The quick study: the reduced study with `heights`, the `velocities` axis and `materials`.
  std::string quick_study(const std::string &heights,
                          const std::string &velocities,
                          const std::string &materials = linear_materials)
  {
    return reduced_study(heights, materials + "  velocities: " + velocities + "\n");
  }

  int run_study(const std::string &scene, const std::filesystem::path &dir, std::string &log)
  {
    const KimpRun run = kimp::testing::run_study(scene, dir);
    log               = run.output();
    return run.exit_code;
  }

  /// The rows of consistent_k_iterations.csv of one run (record, height, law).
  std::vector<std::map<std::string, std::string>>
  iterations_of(const std::vector<std::map<std::string, std::string>> &rows,
                const std::map<std::string, std::string>              &run)
  {
    std::vector<std::map<std::string, std::string>> mine;
    for (const auto &row : rows)
      if (row.at("record") == run.at("record") &&
          row.at("wall_height_m") == run.at("wall_height_m") && row.at("law") == run.at("law"))
        mine.push_back(row);
    return mine;
  }
} // namespace

TEST(StudyVelocityCli, LinearKTableScalesExactlyWithVelocityAndConsistentKConverges)
{
  const TempDir dir("study_velocity");
  std::string   log;
  ASSERT_EQ(run_study(quick_study(R"(["1.0 m", "2.0 m"])", R"(["0.5 m/s", "2 m/s"])"),
                      dir.path(),
                      log),
            0)
    << log;
  const std::filesystem::path out = dir.path() / "out";

  // k(H, v): 2 heights x {0.5, 1, 2} m/s, 1 m/s (slab.velocity) the reference.
  const auto rows = read_csv_records(out / "k_table.csv");
  ASSERT_EQ(rows.size(), 6u) << read_text(out / "k_table.csv");
  std::map<std::pair<std::string, double>, std::map<std::string, std::string>> by_case;
  for (const auto &row : rows)
  {
    const double v = std::stod(row.at("impact_velocity_m_per_s"));
    EXPECT_EQ(row.at("reference_velocity"), v == 1.0 ? "yes" : "no") << v;
    EXPECT_EQ(row.at("material"), "linear");
    // ok, or only the honest peak warning (the least-squares law misses the FEM's wave peak).
    for (const char *law : {"kelvin_voigt", "jankowski"})
    {
      const std::string status = row.at(std::string(law) + "_status");
      EXPECT_TRUE(status == "ok" || (status.rfind("warning: the fitted peak force is", 0) == 0 &&
                                     status.find(';') == std::string::npos))
        << v << " " << law << ": " << status;
    }
    by_case[{row.at("wall_height_m"), v}] = row;
  }
  // A linear FE model scales force and indentation with v: the fixed-COR Kelvin-Voigt fit keeps
  // k, a Hertz law fitted to it gives k ∝ v^-1/2, so k_J(0.5) / k_J(2) = 2. The fits stop at a
  // relative step of about 1e-8; 0.5 % allows for the 6 digits of the CSV and the rigid slab's
  // chatter whose smoothing window is fixed in time.
  constexpr double scaling_tolerance = 5e-3;
  for (const char *height : {"1", "2"})
  {
    const auto k = [&](double v, const char *column) {
      return std::stod(by_case.at({height, v}).at(column));
    };
    EXPECT_NEAR(k(0.5, "kelvin_voigt_kN_per_mm_per_m") / k(2.0, "kelvin_voigt_kN_per_mm_per_m"),
                1.0,
                scaling_tolerance)
      << "H = " << height;
    EXPECT_NEAR(k(0.5, "jankowski_kN_per_mm1.5_per_m") / k(2.0, "jankowski_kN_per_mm1.5_per_m"),
                2.0,
                2.0 * scaling_tolerance)
      << "H = " << height;
    EXPECT_NEAR(k(0.5, "jankowski_kN_per_mm1.5_per_m") / k(1.0, "jankowski_kN_per_mm1.5_per_m"),
                std::sqrt(2.0),
                std::sqrt(2.0) * scaling_tolerance)
      << "H = " << height;
  }

  // Consistent k: every run (2 heights x 3 laws) converged; its last run changed k by less than
  // the 2 % tolerance, and the k it used is the table's k at the velocity of the previous run.
  const auto runs       = read_csv_records(out / "consistent_k.csv");
  const auto iterations = read_csv_records(out / "consistent_k_iterations.csv");
  ASSERT_EQ(runs.size(), 6u) << read_text(out / "consistent_k.csv");
  for (const auto &run : runs)
  {
    const std::string what = run.at("law") + " H = " + run.at("wall_height_m");
    EXPECT_EQ(run.at("status"), "ok") << what;
    EXPECT_EQ(run.at("converged"), "yes") << what;
    const auto mine = iterations_of(iterations, run);
    ASSERT_EQ(mine.size(), std::stoul(run.at("iterations"))) << what;
    EXPECT_LT(std::stod(mine.back().at("change_percent")), 2.0) << what;
    for (std::size_t i = 1; i < mine.size(); ++i)
      EXPECT_EQ(mine[i].at("k_total"), mine[i - 1].at("k_next")) << what << " run " << i + 1;
    const double v = std::stod(mine.back().at("velocity_used_m_per_s"));
    EXPECT_GE(v, 0.5) << what;
    EXPECT_LE(v, 2.0) << what;
    // Kelvin-Voigt k does not depend on v (above): one run is enough.
    if (run.at("law") == "modified_kelvin_voigt")
    {
      EXPECT_EQ(run.at("iterations"), "1") << what;
    }
  }
  Hdf5Reader h5(out / "study.h5");
  EXPECT_EQ(h5.units("/k_table_velocity/impact_velocity"), "m/s");
  EXPECT_EQ(h5.units("/consistent_k/synthetic/jankowski/impact_velocity"), "m/s");
  const auto summary = read_json(out / "summary.json");
  EXPECT_EQ(summary.at("k_table_velocity").size(), 6u);
  EXPECT_EQ(summary.at("consistent_k").at("runs").size(), 6u);
  const std::string report = read_text(out / "report.md");
  for (const char *needle : {"k(H, v)", "Consistent k", "consistent_k.csv", "(reference)"})
    EXPECT_NE(report.find(needle), std::string::npos) << needle;
}

TEST(StudyVelocityCli, VelocityIndependentTableConvergesInOneRun)
{
  const TempDir dir("study_velocity_one");
  std::string   log;
  ASSERT_EQ(run_study(quick_study(R"(["1.25 m"])", "[]"), dir.path(), log), 0) << log;
  const auto runs = read_csv_records(dir.path() / "out" / "consistent_k.csv");
  ASSERT_EQ(runs.size(), 3u) << read_text(dir.path() / "out" / "consistent_k.csv");
  for (const auto &run : runs)
  {
    EXPECT_EQ(run.at("iterations"), "1") << run.at("law");
    EXPECT_EQ(run.at("converged"), "yes") << run.at("law");
    EXPECT_EQ(run.at("k_consistent"), run.at("k_reference")) << run.at("law");
  }
}

TEST(StudyVelocityCli, AutoFidelityKeepsLinearWhenTheSoilNeverYields)
{
  // Mohr-Coulomb with 1 GPa of cohesion stays elastic: the inelastic k equals the linear one,
  // so fidelity: auto keeps the linear materials and says so.
  const TempDir     dir("study_velocity_material");
  std::string       scene = quick_study(R"(["1.25 m"])",
                                  "[]",
                                  "  materials:\n    concrete:\n      model: elastic\n    soil:\n"
                                        "      model: mohr_coulomb\n      c: \"1e6 kPa\"\n"
                                        "      tension_cutoff: \"1e6 kPa\"\n");
  const std::string fixed = "  fidelity: fixed\n";
  scene.replace(scene.find(fixed),
                fixed.size(),
                "  fidelity: auto\n  fidelity_h_contact: [\"10 cm\", \"5 cm\"]\n");
  std::string log;
  ASSERT_EQ(run_study(scene, dir.path(), log), 0) << log;
  const auto rows = read_csv_records(dir.path() / "out" / "k_table.csv");
  ASSERT_EQ(rows.size(), 1u) << read_text(dir.path() / "out" / "k_table.csv");
  EXPECT_EQ(rows[0].at("material"), "linear");
  EXPECT_NE(log.find("linear materials kept"), std::string::npos) << log;
  EXPECT_NE(read_text(dir.path() / "out" / "report.md").find("linear materials kept"),
            std::string::npos);
}

#endif
