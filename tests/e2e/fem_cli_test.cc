// `kimp fem` end to end: fem.h5 readable by read_fem_cases with the physics of a rigid-slab
// impact (momentum balance, COR in (0, 1.2)), summary.json and CSV consistent with it, refused
// scenes (overlap, dt above the stability limit) leaving no result files, and 1 vs 2 MPI ranks.
#ifdef KIMP_WITH_FEM

#  include <algorithm>
#  include <cmath>
#  include <cstdlib>
#  include <filesystem>
#  include <fstream>
#  include <gtest/gtest.h>
#  include <nlohmann/json.hpp>
#  include <sstream>
#  include <string>
#  include <vector>

#  include "io/fem_results.h"
#  include "tests/e2e/fem_scenes.h"
#  include "tests/support/files.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  constexpr double momentum_tolerance = 2e-3;  ///< relative: impulse vs slab momentum change
  constexpr double rank_tolerance     = 1e-10; ///< relative: 1 vs 2 MPI ranks

  /// quick_fem_scene(extra, rigid) written to `dir`/scene.yaml: a coarse scene, seconds of run
  /// time.
  void write_quick_scene(const std::filesystem::path &dir,
                         const std::string           &extra = "",
                         bool                         rigid = true)
  {
    write_text(dir / "scene.yaml", quick_fem_scene(extra, rigid));
  }

  /// The log of `kimp fem` on quick_fem_scene(extra) in `dir`, a run that must fail and write
  /// neither fem.h5 nor summary.json.
  std::string refused_scene_log(const TempDir &dir, const std::string &extra)
  {
    write_quick_scene(dir.path(), extra);
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
    EXPECT_NE(run.exit_code, 0);
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out/fem.h5"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out/summary.json"));
    return run.err;
  }

  TEST(FemCli, RigidSlabImpactConservesMomentumAndRebounds)
  {
    const TempDir dir("fem_cli");
    write_quick_scene(dir.path(), "dynamics: {end_time: \"40 ms\"}\n");
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
    ASSERT_EQ(run.exit_code, 0) << run.err;

    const std::vector<kimp::io::FemCase> cases =
      kimp::io::read_fem_cases(dir.path() / "out/fem.h5");
    ASSERT_EQ(cases.size(), 1u);
    const kimp::io::FemCase &c = cases[0];
    EXPECT_EQ(c.name, "H1.25");
    EXPECT_EQ(c.status, "ok");
    const double peak  = c.summary.peak_force.value();
    const double cor   = c.summary.apparent_cor.value();
    const double v_end = c.summary.rebound_velocity.value();
    const double pulse = c.summary.impulse.value();
    const double v0    = c.impact_velocity;
    EXPECT_GT(peak, 0.0);
    EXPECT_GT(cor, 0.0);
    EXPECT_LT(cor, 1.2);
    EXPECT_NEAR(c.slab_mass, 2400.0 * 8.0 * 0.2, 1e-9) << "rho L t of the default slab";
    // The contact force is the only force on a rigid slab: impulse = m (v0 - v_end).
    const double momentum_change = c.slab_mass * (v0 - v_end);
    EXPECT_NEAR(pulse, momentum_change, momentum_tolerance * momentum_change)
      << "impulse " << pulse << " N s/m, m " << c.slab_mass << " kg/m, v_end " << v_end;
    ASSERT_FALSE(c.time.empty());
    EXPECT_EQ(c.contact_force.size(), c.time.size());
    EXPECT_EQ(c.labels.at("slab"), "rigid");

    const nlohmann::json summary = read_json(dir.path() / "out/summary.json");
    // `cases` is a list of objects with "name", as in every command's summary.json.
    ASSERT_EQ(summary.at("cases").size(), 1u);
    EXPECT_EQ(summary.at("cases").at(0).at("name"), "H1.25");
    EXPECT_EQ(summary.at("cases").at(0).at("peak_force").get<double>(), peak);
    EXPECT_EQ(summary.at("n_ranks"), 1);

    // CSV: one row per sample, the raw force written with round-trip precision.
    std::ifstream csv(dir.path() / "out/fem_histories.csv");
    std::string   line;
    std::getline(csv, line);
    EXPECT_EQ(line.rfind("case,time_s,contact_force_N_per_m", 0), 0u) << line;
    std::size_t rows = 0;
    while (std::getline(csv, line))
    {
      std::istringstream fields(line);
      std::string        name, time, force;
      std::getline(fields, name, ',');
      std::getline(fields, time, ',');
      std::getline(fields, force, ',');
      ASSERT_LT(rows, c.time.size());
      EXPECT_EQ(std::stod(force), c.contact_force[rows]) << "row " << rows;
      ++rows;
    }
    EXPECT_EQ(rows, c.time.size());
  }

  TEST(FemCli, InelasticRunSplitsTheDissipationByBodyWithUnits)
  {
    // Mohr-Coulomb backfill and damaged concrete: the summary gives the plastic and damage
    // dissipation per body, they add up to the totals, and summary.json names their unit.
    const TempDir dir("fem_cli_inelastic");
    write_quick_scene(dir.path(),
                      "dynamics: {end_time: \"10 ms\"}\n"
                      "materials:\n"
                      "  concrete: {model: damage_plasticity, f_cm: \"38 MPa\"}\n"
                      "  soil: {model: mohr_coulomb, preset: medium_dense_sand, c: \"5 kPa\"}\n");
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const nlohmann::json  summary = read_json(dir.path() / "out/summary.json");
    const nlohmann::json &c       = summary.at("cases").at(0);
    for (const char *what : {"plastic", "damage"})
    {
      double sum = 0;
      for (const char *body : {"slab", "wall", "soil"})
      {
        const std::string key = std::string(what) + "_dissipation_" + body;
        ASSERT_TRUE(c.contains(key)) << key;
        EXPECT_EQ(summary.at("units").at(key), "J/m") << key;
        EXPECT_GE(c.at(key).get<double>(), 0.0) << key;
        sum += c.at(key).get<double>();
      }
      const double total = c.at(std::string(what) + "_dissipation").get<double>();
      EXPECT_NEAR(sum, total, 1e-9 * std::max(total, 1e-12)) << what;
    }
    EXPECT_GT(c.at("plastic_dissipation_soil").get<double>(), 0.0);
    EXPECT_EQ(c.at("damage_dissipation_soil").get<double>(), 0.0);
    EXPECT_EQ(summary.at("units").at("geostatic_weight"), "N/m");
  }

  TEST(FemCli, OverlappingSceneFailsWithTheKeyAndWritesNoResults)
  {
    const TempDir     dir("fem_cli_overlap");
    const std::string log = refused_scene_log(dir, "geometry:\n  gap: \"0 mm\"\n");
    EXPECT_NE(log.find("scene.yaml:5: geometry.gap = 0 mm"), std::string::npos) << log;
  }

  TEST(FemCli, TimeStepAboveTheStabilityLimitFailsAndWritesNoResults)
  {
    const TempDir     dir("fem_cli_dt");
    const std::string log = refused_scene_log(dir, "dynamics: {dt: \"1 ms\"}\n");
    EXPECT_NE(log.find("H1.25"), std::string::npos) << log;
    EXPECT_NE(log.find("dt"), std::string::npos) << log;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out/fem_histories.csv"));
    for (const auto &entry : std::filesystem::directory_iterator(dir.path() / "out"))
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
        << "temporary file left: " << entry.path();
  }

  /// Run by the ctest test e2e_fem_cli_mpi_two_ranks (label mpi), which sets KIMP_MPIEXEC.
  TEST(FemCliMpi, TwoRanksGiveTheSameForceHistoryAsOne)
  {
    const char *mpiexec = std::getenv("KIMP_MPIEXEC");
    if (mpiexec == nullptr || *mpiexec == 0)
      GTEST_SKIP() << "KIMP_MPIEXEC not set: run through ctest -L mpi";
    const TempDir dir("fem_cli_mpi");
    write_quick_scene(dir.path(), "dynamics: {end_time: \"3 ms\"}\n", false);
    const KimpRun one = run_kimp("-q fem scene.yaml -o one", dir.path());
    ASSERT_EQ(one.exit_code, 0) << one.err;
    const std::string command = "cd '" + dir.path().string() + "' && " + mpiexec +
                                " -np 2 --allow-run-as-root --oversubscribe " + kimp_executable() +
                                " -q fem scene.yaml -o two";
    ASSERT_EQ(run_command(command, dir.path() / "mpi.txt"), 0) << read_text(dir.path() / "mpi.txt");

    const auto a = kimp::io::read_fem_cases(dir.path() / "one/fem.h5");
    const auto b = kimp::io::read_fem_cases(dir.path() / "two/fem.h5");
    ASSERT_EQ(a.size(), 1u);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(b[0].summary.n_ranks.value(), 2.0);
    const double peak = a[0].summary.peak_force.value();
    EXPECT_GT(peak, 0.0);
    EXPECT_NEAR(b[0].summary.peak_force.value(), peak, rank_tolerance * peak);
    ASSERT_EQ(a[0].contact_force.size(), b[0].contact_force.size());
    for (std::size_t i = 0; i < a[0].contact_force.size(); ++i)
      ASSERT_NEAR(b[0].contact_force[i], a[0].contact_force[i], rank_tolerance * peak)
        << "sample " << i << ", t = " << a[0].time[i] << " s";
  }
} // namespace

#endif // KIMP_WITH_FEM
