// End-to-end `kimp collide`: the thesis two-body set-up (280 t vs 300 t at 1 m/s, dt 2e-4 s);
// the Kelvin-Voigt row reproduces its nominal COR, the linear law is elastic (COR 1), the
// hysteretic law stays close to nominal; collide.h5 / cor_table.csv / summary.json written.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/csv.h"
#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  constexpr double kelvin_voigt_tolerance = 0.01; ///< |COR_eff − COR|/COR (< 1 %)
  constexpr double hysteretic_tolerance   = 0.05; ///< same, hysteretic law at COR >= 0.3
  constexpr double elastic_tolerance      = 0.01; ///< linear law: COR_eff = 1
} // namespace

TEST(CollideCli, CorTableKelvinVoigtEqualsNominal)
{
  const TempDir   temp_dir("e2e_collide");
  const fs::path &dir = temp_dir.path();
  const KimpRun   run = run_kimp("collide -o " + (dir / "out").string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "collide.h5"));
  const nlohmann::json summary = read_json(dir / "out" / "summary.json");
  EXPECT_DOUBLE_EQ(summary["setup"]["mass_1"].get<double>(), 280e3);
  EXPECT_DOUBLE_EQ(summary["setup"]["time_step"].get<double>(), 2e-4);

  std::ifstream csv(dir / "out" / "cor_table.csv");
  std::string   line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line.rfind("law,nominal_cor,effective_cor", 0), 0u) << line;
  std::size_t n_kv = 0;
  while (std::getline(csv, line))
  {
    const std::vector<std::string> f = split_csv_line(line);
    ASSERT_GE(f.size(), 9u) << line;
    const double nominal   = std::stod(f[1]);
    const double effective = std::stod(f[2]);
    EXPECT_EQ(f[8], "ok") << line;
    if (f[0] == "kelvin_voigt")
    {
      ++n_kv;
      EXPECT_NEAR(effective, nominal, kelvin_voigt_tolerance * nominal) << line;
    }
    if (f[0] == "linear")
    {
      EXPECT_NEAR(effective, 1.0, elastic_tolerance) << line;
    }
    if (f[0] == "hysteretic" && nominal >= 0.3)
    {
      EXPECT_NEAR(effective, nominal, hysteretic_tolerance * nominal) << line;
    }
  }
  EXPECT_EQ(n_kv, 10u) << "COR grid 0.1 ... 1.0";
}

TEST(CollideCli, SceneChangesTheSetUpAndBadSceneIsRejected)
{
  const TempDir   temp_dir("e2e_collide_scene");
  const fs::path &dir = temp_dir.path();
  std::ofstream(dir / "c.yaml") << "velocity: \"2 m/s\"\ncor_grid: [0.5, 0.9]\nlaws:\n"
                                   "  - name: kv\n    law: kelvin_voigt\n    k: \"2500 kN/mm\"\n";
  const KimpRun run =
    run_kimp("collide " + (dir / "c.yaml").string() + " -o " + (dir / "out").string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = read_json(dir / "out" / "summary.json");
  ASSERT_EQ(summary["cases"].size(), 2u);
  EXPECT_DOUBLE_EQ(summary["setup"]["velocity"].get<double>(), 2.0);
  for (const auto &row : summary["cases"])
    EXPECT_NEAR(row["effective_cor"].get<double>(),
                row["nominal_cor"].get<double>(),
                kelvin_voigt_tolerance * row["nominal_cor"].get<double>());

  std::ofstream(dir / "bad.yaml")
    << "laws:\n  - name: j\n    law: jankowski\n    k: \"2500 kN/mm\"\n";
  const KimpRun bad =
    run_kimp("collide " + (dir / "bad.yaml").string() + " -o " + (dir / "bad").string(), dir);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("bad.yaml:4: laws[0].k = 2500 kN/mm"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad" / "cor_table.csv"));
}

TEST(CollideCli, CalibrateFitsTheImpactCoefficientOnlyWhenAsked)
{
  // A 2 x 2 x 2 grid of the C_imp calibration (docs/physics.md, "Calibration of C_imp"): with an
  // elastic approach branch the loop area scales as v_imp² and m_eff hardly matters, so the fit
  // a1 = c/(COR^p1 m_eff^p2 v_imp^p3) gives p3 -> 1, p2 -> 0 and reproduces every point.
  const TempDir   temp_dir("e2e_collide_calibrate");
  const fs::path &dir = temp_dir.path();
  write_text(dir / "c.yaml",
             "laws:\n"
             "  - name: kv\n"
             "    law: kelvin_voigt\n"
             "calibration:\n"
             "  cor_grid: [0.5, 0.8]\n"
             "  velocity_grid: [\"0.5 m/s\", \"1.5 m/s\"]\n"
             "  mass_grid: [\"200 t\", \"600 t\"]\n");
  const KimpRun with = run_kimp("collide c.yaml -o with --calibrate", dir);
  ASSERT_EQ(with.exit_code, 0) << with.err;
  const nlohmann::json c = read_json(dir / "with" / "summary.json").at("calibration");
  EXPECT_EQ(c["n_points"].get<int>(), 8);
  EXPECT_GT(c["r_squared"].get<double>(), 0.9999);
  EXPECT_NEAR(c["fit"]["p3"].get<double>(), 1.0, 0.01);
  EXPECT_NEAR(c["fit"]["p2"].get<double>(), 0.0, 0.01);
  EXPECT_LT(c["max_cor_error_fit"].get<double>(), 1e-3);
  EXPECT_DOUBLE_EQ(c["thesis"]["c"].get<double>(), 1.55);

  const KimpRun without = run_kimp("collide c.yaml -o without", dir);
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_FALSE(read_json(dir / "without" / "summary.json").contains("calibration"));
}
