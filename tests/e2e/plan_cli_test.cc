// End-to-end `kimp lumped` of scenes in plan: the shipped data/scenes/plan_4storey_moat.yaml
// through the built binary (files, peaks within the moat, energy balance with friction work),
// bad plan input refused at FILE:LINE: key with no output written, and the plan keys in
// --print-defaults.
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/files.h"
#include "tests/support/hdf5_reader.h"
#include "tests/support/kimp_run.h"
#include "tests/support/scene_texts.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  /// The PEER records: $KIMP_RECORDS_DIR, else ../shared/data/records beside the source tree.
  fs::path records_dir()
  {
    const char *env = std::getenv("KIMP_RECORDS_DIR");
    return env != nullptr ? fs::path(env) : source_dir() / ".." / "shared" / "data" / "records";
  }

  /// A small plan scene: the default building in a moat at 4 cm, 6 s of the synthetic motion at
  /// 30 degrees, mass 1 m off the centroid, mu = 0.3; `plan_extra` is appended to the plan section.
  std::string small_plan_scene(const std::string &plan_extra = "")
  {
    return "ground_motion:\n"
           "  duration: \"6 s\"\n"
           "integration:\n"
           "  dt: stable\n"
           "  output_interval: \"0.01 s\"\n"
           "plan:\n"
           "  eccentricity_x: \"1 m\"\n"
           "  angle: 30\n"
           "  moat:\n"
           "    gap: \"4 cm\"\n"
           "    friction: 0.3\n" +
           plan_extra;
  }

  KimpRun run_scene(const TempDir &dir, const std::string &scene)
  {
    const fs::path file = dir.write("scene.yaml", scene);
    return run_kimp("lumped " + file.string() + " -o " + (dir.path() / "out").string() +
                      " --records-dir " + records_dir().string(),
                    dir.path());
  }
} // namespace

TEST(PlanCli, ShippedMoatSceneRunsWithinTheMoatAndBalancesEnergy)
{
  if (!fs::exists(records_dir() / "RSN1106_KOBE_KJM000.AT2"))
    GTEST_SKIP() << "Kobe record not in " << records_dir();
  const TempDir dir("e2e_plan_shipped");
  // The shipped scene, shortened to the strong part of Kobe (the first 12 s).
  const std::string scene = replaced(read_text(source_dir() / "data/scenes/plan_4storey_moat.yaml"),
                                     "  output_interval: \"0.01 s\"\n",
                                     "  output_interval: \"0.01 s\"\n  duration: \"12 s\"\n");
  const KimpRun     run   = run_scene(dir, scene);
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const fs::path out = dir.path() / "out";
  for (const char *f : {"lumped.h5", "summary.json", "peaks.csv"})
    EXPECT_TRUE(fs::exists(out / f)) << f;

  const nlohmann::json summary = read_json(out / "summary.json");
  EXPECT_TRUE(summary.at("plan").get<bool>());
  const nlohmann::json &c = summary.at("cases").at(0);
  EXPECT_EQ(c.at("status"), "ok");
  const nlohmann::json &peaks = c.at("peaks");
  // Kobe at 30 degrees drives the base into the moat: corners reach the 15 cm gap, and the
  // walls stop them within a few cm (2500 kN/mm against a 1530 t building at ~1 m/s).
  EXPECT_GT(c.at("n_impacts").get<int>(), 0);
  EXPECT_GT(peaks.at("base_corner_displacement").get<double>(), 0.15);
  EXPECT_LT(peaks.at("base_corner_displacement").get<double>(), 0.15 + 0.05);
  EXPECT_GT(peaks.at("corner_impact_force").get<double>(), 1e6);
  // The eccentric mass turns the building; friction at the wall does work.
  EXPECT_GT(peaks.at("rotation").get<double>(), 1e-5);
  const nlohmann::json &energy = c.at("energy");
  EXPECT_GT(energy.at("friction").get<double>(), 0.0);
  EXPECT_LT(energy.at("max_relative_error").get<double>(), 1e-3);
  // 5 levels x (x, y, theta)
  EXPECT_EQ(peaks.at("displacement").size(), 15u);

  const Hdf5Reader h5(out / "lumped.h5");
  ASSERT_TRUE(h5.ok());
  EXPECT_EQ(h5.attribute("/lumped/default", "status"), "ok");
  EXPECT_TRUE(h5.exists("/lumped/default/history/displacement/value"));
  EXPECT_TRUE(h5.exists("/lumped/default/history/corner_displacement/value"));
  EXPECT_TRUE(h5.exists("/lumped/default/history/contact_force/value"));
  EXPECT_TRUE(h5.exists("/lumped/default/energy/friction"));
  EXPECT_EQ(h5.doubles("/lumped/default/peaks/displacement").size(), 15u);
  EXPECT_EQ(read_lines(out / "peaks.csv").size(), 1u + 15u);
}

TEST(PlanCli, SyntheticTwoComponentsRun)
{
  const TempDir dir("e2e_plan_two");
  const KimpRun run = run_scene(dir, small_plan_scene("  second_component: synthetic\n"));
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const nlohmann::json c = read_json(dir.path() / "out" / "summary.json").at("cases").at(0);
  EXPECT_GT(c.at("n_impacts").get<int>(), 0);
  EXPECT_LT(c.at("energy").at("max_relative_error").get<double>(), 1e-3);
}

TEST(PlanCli, YieldingFacesAndModalDampingRun)
{
  // Faces 0 and 1 yield (a weak wall-and-backfill part: 5 kN/mm per m, 20 kN per m, failure at
  // 2 mm), modal damping: the run closes its energy balance with the walls' work and reports
  // the struck face's set and failure with its time.
  const TempDir dir("e2e_plan_yielding");
  const KimpRun run = run_scene(dir,
                                small_plan_scene("    yielding:\n"
                                                 "      - {face: 0, stiffness: \"5 kN/mm/m\", "
                                                 "capacity: \"20 kN/m\", failure_displacement: "
                                                 "\"0.2 cm\"}\n"
                                                 "      - {face: 1, mass: \"50 t\"}\n"
                                                 "  damping: modal\n"));
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const nlohmann::json c = read_json(dir.path() / "out" / "summary.json").at("cases").at(0);
  EXPECT_GT(c.at("n_impacts").get<int>(), 0);
  EXPECT_LT(c.at("energy").at("max_relative_error").get<double>(), 1e-3);
  const nlohmann::json &y = c.at("yielding_walls");
  ASSERT_EQ(y.size(), 2u);
  EXPECT_EQ(y.at(0).at("face").get<int>(), 0);
  EXPECT_GE(c.at("energy").at("wall_work").get<double>(),
            c.at("energy").at("wall_plastic").get<double>());
  bool failed = false;
  for (const nlohmann::json &f : y)
    if (f.at("failed").get<bool>())
    {
      failed = true;
      EXPECT_GT(f.at("failure_time").get<double>(), 0.0);
      EXPECT_GT(f.at("residual_displacement").get<double>(), 0.0);
    }
  EXPECT_TRUE(failed) << y.dump();
}

namespace
{
  struct BadPlan
  {
    const char *what;
    std::string plan_extra;
    std::string expected; ///< in the message, after "scene.yaml:"
  };
} // namespace

TEST(PlanCli, BadPlanInputNamesFileLineAndKeyAndWritesNothing)
{
  const std::vector<BadPlan> cases = {
    {"wall not enclosing the slab",
     "    wall: [{x: \"-10.1 m\", y: \"-10.1 m\"}, {x: \"10.1 m\", y: \"-10.1 m\"}, "
     "{x: \"10.1 m\", y: \"9 m\"}, {x: \"-10.1 m\", y: \"9 m\"}]\n",
     ":12: plan.moat.wall"},
    {"self-intersecting wall",
     "    wall: [{x: \"-11 m\", y: \"-11 m\"}, {x: \"11 m\", y: \"11 m\"}, "
     "{x: \"11 m\", y: \"-11 m\"}, {x: \"-11 m\", y: \"11 m\"}]\n",
     ":12: plan.moat.wall"},
    {"gap <= 0", "    gaps: [\"4 cm\", \"0 cm\", \"4 cm\", \"4 cm\"]\n", ":12: plan.moat.gaps[1]"},
    {"wrong number of gaps", "    gaps: [\"4 cm\", \"4 cm\"]\n", ":12: plan.moat.gaps"},
    {"missing second component", "  second_component: record\n", "plan.second_record"},
    {"yielding face outside the wall",
     "    yielding: [{face: 9}]\n",
     "moat.yielding[0].segment = 9"},
    {"yielding face twice",
     "    yielding: [{face: 1}, {face: 1}]\n",
     "already has a yielding wall"},
    {"yielding width in plan",
     "    yielding: [{face: 1, width: \"5 m\"}]\n",
     "moat.yielding[0].width does not apply"},
    {"convex curve envelope of a face",
     "    yielding: [{face: 1, envelope: curve, curve: [{displacement: 0 mm, force: 0 kN/m}, "
     "{displacement: 2 mm, force: 100 kN/m}, {displacement: 3 mm, force: 160 kN/m}]}]\n",
     "plan.moat.yielding[0].curve[2] = {3 mm, 160 kN/m}: the slope rises"},
  };
  for (const BadPlan &b : cases)
  {
    const TempDir dir("e2e_plan_bad");
    const KimpRun run = run_scene(dir, small_plan_scene(b.plan_extra));
    EXPECT_NE(run.exit_code, 0) << b.what;
    EXPECT_NE(run.err.find("scene.yaml"), std::string::npos) << b.what << ": " << run.err;
    EXPECT_NE(run.err.find(b.expected), std::string::npos) << b.what << ": " << run.err;
    EXPECT_FALSE(fs::exists(dir.path() / "out" / "lumped.h5")) << b.what;
    EXPECT_FALSE(fs::exists(dir.path() / "out" / "summary.json")) << b.what;
  }
}

TEST(PlanCli, PrintDefaultsAndSchemaDeclareThePlanKeys)
{
  const TempDir dir("e2e_plan_defaults");
  const KimpRun defaults = run_kimp("lumped --print-defaults", dir.path());
  ASSERT_EQ(defaults.exit_code, 0) << defaults.output();
  for (const char *key : {"plan:", "eccentricity_x", "second_component", "points_per_edge"})
    EXPECT_NE(defaults.out.find(key), std::string::npos) << key;
  const KimpRun schema = run_kimp("lumped --print-schema", dir.path());
  ASSERT_EQ(schema.exit_code, 0) << schema.output();
  const nlohmann::json json = nlohmann::json::parse(schema.out);
  EXPECT_NE(json.dump().find("k_length"), std::string::npos);
}

// `kimp sweep` of a scene in plan over the angle of incidence and the eccentricity with the
// directionality report: every case ok, the peaks in sweep.csv, the chart and the summary's
// largest peaks.
TEST(PlanCli, SweepDrawsTheDirectionalityChart)
{
  const TempDir dir("e2e_plan_sweep");
  dir.write("base.yaml", small_plan_scene());
  const fs::path sweep = dir.write("sweep.yaml",
                                   "scene: base.yaml\n"
                                   "report: {kind: directionality, title: Small moat}\n"
                                   "parameters:\n"
                                   "  plan.angle: {from: 0, to: 180, step: 45}\n"
                                   "  plan.eccentricity_x: [0 m, 2 m]\n");
  const KimpRun  run =
    run_kimp("sweep " + sweep.string() + " -o " + (dir.path() / "out").string() + " --threads 2",
             dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const std::string csv = read_text(dir.path() / "out" / "sweep.csv");
  EXPECT_NE(csv.find("base_corner_displacement"), std::string::npos);
  EXPECT_NE(csv.find("corner_impact_force"), std::string::npos);
  EXPECT_EQ(csv.find("failed"), std::string::npos) << csv;
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "charts" / "directionality.png"));
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "charts" / "directionality.svg"));
  const std::string summary = read_text(dir.path() / "out" / "summary.md");
  EXPECT_NE(summary.find("10 cases (10 ok, 0 failed)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("largest peak base corner displacement"), std::string::npos) << summary;
  EXPECT_NE(summary.find("largest peak rotation"), std::string::npos) << summary;
}
