// End-to-end `kimp collide`: the thesis two-body set-up (280 t vs 300 t at 1 m/s, dt 2e-4 s);
// the Kelvin-Voigt row reproduces its nominal COR, the linear law is elastic (COR 1), the
// hysteretic law stays close to nominal; collide.h5 / cor_table.csv / summary.json written.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace
{
  namespace fs = std::filesystem;

  constexpr double kelvin_voigt_tolerance = 0.01; ///< |COR_eff − COR|/COR (< 1 %)
  constexpr double hysteretic_tolerance   = 0.05; ///< same, hysteretic law at COR >= 0.3
  constexpr double elastic_tolerance      = 0.01; ///< linear law: COR_eff = 1

  std::string slurp(const fs::path &file)
  {
    std::ifstream      in(file);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  int kimp(const std::string &arguments, const fs::path &dir, std::string &err)
  {
    const std::string cmd = std::string(KIMP_BINARY_DIR) + "/kimp " + arguments + " >" +
                            (dir / "stdout.txt").string() + " 2>" + (dir / "stderr.txt").string();
    const int status = std::system(cmd.c_str());
    err              = slurp(dir / "stderr.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  std::vector<std::string> split(const std::string &line)
  {
    std::vector<std::string> fields;
    std::stringstream        s(line);
    std::string              field;
    while (std::getline(s, field, ','))
      fields.push_back(field);
    return fields;
  }
} // namespace

TEST(CollideCli, CorTableKelvinVoigtEqualsNominal)
{
  const fs::path dir = fs::temp_directory_path() / ("kimp_e2e_collide_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string err;
  ASSERT_EQ(kimp("collide -o " + (dir / "out").string(), dir, err), 0) << err;
  EXPECT_TRUE(fs::exists(dir / "out" / "collide.h5"));
  const nlohmann::json summary = nlohmann::json::parse(slurp(dir / "out" / "summary.json"));
  EXPECT_DOUBLE_EQ(summary["setup"]["mass_1"].get<double>(), 280e3);
  EXPECT_DOUBLE_EQ(summary["setup"]["time_step"].get<double>(), 2e-4);

  std::ifstream csv(dir / "out" / "cor_table.csv");
  std::string   line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line.rfind("law,nominal_cor,effective_cor", 0), 0u) << line;
  std::size_t n_kv = 0;
  while (std::getline(csv, line))
  {
    const std::vector<std::string> f = split(line);
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
  fs::remove_all(dir);
}

TEST(CollideCli, SceneChangesTheSetUpAndBadSceneIsRejected)
{
  const fs::path dir =
    fs::temp_directory_path() / ("kimp_e2e_collide_scene_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "c.yaml") << "velocity: \"2 m/s\"\ncor_grid: [0.5, 0.9]\nlaws:\n"
                                   "  - name: kv\n    law: kelvin_voigt\n    k: \"2500 kN/mm\"\n";
  std::string err;
  ASSERT_EQ(kimp("collide " + (dir / "c.yaml").string() + " -o " + (dir / "out").string(),
                 dir,
                 err),
            0)
    << err;
  const nlohmann::json summary = nlohmann::json::parse(slurp(dir / "out" / "summary.json"));
  ASSERT_EQ(summary["cor_table"].size(), 2u);
  EXPECT_DOUBLE_EQ(summary["setup"]["velocity"].get<double>(), 2.0);
  for (const auto &row : summary["cor_table"])
    EXPECT_NEAR(row["effective_cor"].get<double>(),
                row["nominal_cor"].get<double>(),
                kelvin_voigt_tolerance * row["nominal_cor"].get<double>());

  std::ofstream(dir / "bad.yaml")
    << "laws:\n  - name: j\n    law: jankowski\n    k: \"2500 kN/mm\"\n";
  EXPECT_NE(kimp("collide " + (dir / "bad.yaml").string() + " -o " + (dir / "bad").string(),
                 dir,
                 err),
            0);
  EXPECT_NE(err.find("bad.yaml:4: laws[0].k = 2500 kN/mm"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "bad" / "cor_table.csv"));
  fs::remove_all(dir);
}
