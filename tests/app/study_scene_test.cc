// `kimp study` scene: embedded defaults (docs/physics.md §3-4), validation messages with
// file:line:key, the lumped scene of the building runs and the FEM cache key.
#ifdef KIMP_WITH_FEM

#  include <filesystem>
#  include <gtest/gtest.h>
#  include <string>

#  include "app/study/study_fem.h"
#  include "app/study/study_run.h"
#  include "app/study/study_scene.h"
#  include "tests/support/messages.h"
#  include "tests/support/scene_errors.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using kimp::app::StudyScene;
  using kimp::testing::expect_contains;

  constexpr double exact = 1e-12; ///< values copied or parsed, relative

  /// The scene error message of `text` (empty if it loads).
  std::string scene_error(const std::string &text)
  {
    return kimp::testing::scene_error<StudyScene>(text, "study.yaml");
  }
} // namespace

TEST(StudyScene, EmptyDocumentIsTheDefaultStudy)
{
  const StudyScene scene = kimp::io::read_scene_text<StudyScene>("", "(default study scene)").scene;
  const std::vector<double> heights{1.00, 1.25, 1.50, 2.00};
  EXPECT_EQ(scene.fem.wall_heights, heights);
  EXPECT_NEAR(scene.fit.cor, 0.7, exact);
  EXPECT_NEAR(scene.fit.width, 27.78, exact);
  EXPECT_NEAR(scene.walls.gap_reduction, 0.10, exact);
  EXPECT_NEAR(scene.walls.mass, 500e3, exact * 500e3);
  EXPECT_FALSE(scene.walls.gap.has_value());
  EXPECT_EQ(scene.building.n_storeys, 4u);
  EXPECT_EQ(scene.building.kind, kimp::app::BuildingKind::isolated);
  EXPECT_EQ(scene.isolator.kind, kimp::app::IsolatorKind::bilinear);
  ASSERT_EQ(scene.records.size(), 1u);
  EXPECT_EQ(scene.records.front().record, "synthetic");
  // fidelity: auto on the 5 / 2.5 / 1.25 cm ladder at 1 %; the sensitivity study is off.
  EXPECT_EQ(scene.fem.fidelity, kimp::app::Fidelity::auto_ladder);
  EXPECT_NEAR(scene.fem.fidelity_tolerance, 0.01, exact);
  ASSERT_EQ(scene.fem.fidelity_h_contact.size(), 3u);
  EXPECT_NEAR(scene.fem.fidelity_h_contact[0], 0.05, exact);
  EXPECT_NEAR(scene.fem.fidelity_h_contact[1], 0.025, exact);
  EXPECT_NEAR(scene.fem.fidelity_h_contact[2], 0.0125, exact);
  EXPECT_EQ(scene.fem.fidelity_penalty_factors, std::vector<double>{1.0});
  EXPECT_TRUE(scene.accuracy_study);
  EXPECT_TRUE(scene.accuracy.implicit);
  EXPECT_NEAR(scene.accuracy.wall_height, 1.25, exact);
  EXPECT_FALSE(scene.sensitivity);
  EXPECT_TRUE(scene.stability_map);
}

TEST(StudyScene, FidelityLadderIsValidatedWithKeyAndValue)
{
  const std::string message = scene_error("fem:\n"
                                          "  fidelity: auto\n"
                                          "  fidelity_tolerance: \"0 %\"\n"
                                          "  fidelity_h_contact: [\"2.5 cm\", \"5 cm\"]\n"
                                          "  fidelity_penalty_factors: [10, 1]\n"
                                          "accuracy:\n"
                                          "  lumped_reference_dt: \"1 s\"\n");
  expect_contains(message,
                  {"fem.fidelity_tolerance = 0 %",
                   "fem.fidelity_h_contact[1] = 5 cm",
                   "fem.fidelity_penalty_factors[1] = 1",
                   "accuracy.lumped_reference_dt"});
  expect_contains(scene_error("fem:\n  fidelity: sometimes\n"), {"fem.fidelity"});
  expect_contains(scene_error("fem:\n  fidelity_h_contact: [\"20 cm\"]\n"), {"h_max"});
  // The study's levels set the penalty factor: a penalty scaled to the step is refused there.
  expect_contains(scene_error("fem:\n  contact: {penalty_step_ratio: 0.7}\n"),
                  {"study.yaml:2", "fem.contact.penalty_step_ratio = 0.7", "must be 0 in a study"});
}

TEST(StudyScene, VelocityAxisAndConsistentKDefaultsAndRules)
{
  const StudyScene scene = kimp::io::read_scene_text<StudyScene>("", "(default study scene)").scene;
  EXPECT_EQ(scene.fem.velocities, (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_TRUE(scene.consistent_k.enabled);
  EXPECT_NEAR(scene.consistent_k.tolerance, 0.02, exact);
  EXPECT_EQ(scene.consistent_k.max_iterations, 10u);
  const StudyScene none =
    kimp::io::read_scene_text<StudyScene>("fem:\n  velocities: []\n", "study.yaml").scene;
  EXPECT_TRUE(none.fem.velocities.empty());
  const std::string message = scene_error("fem:\n"
                                          "  velocities: [\"2 m/s\", \"1 m/s\"]\n"
                                          "consistent_k:\n"
                                          "  tolerance: \"0 %\"\n");
  EXPECT_NE(message.find("fem.velocities[1] = 1 m/s"), std::string::npos) << message;
  EXPECT_NE(message.find("must be above the previous level"), std::string::npos) << message;
  EXPECT_NE(message.find("consistent_k.tolerance = 0 %"), std::string::npos) << message;
  EXPECT_NE(scene_error("fem:\n  velocities: [\"-1 m/s\"]\n").find("fem.velocities"),
            std::string::npos);
}

TEST(StudyScene, ShippedSceneFileEqualsTheDefaults)
{
  const auto shipped  = kimp::io::read_scene<StudyScene>("data/scenes/wall_height_study.yaml");
  const auto defaults = kimp::io::read_scene_text<StudyScene>("", "(defaults)");
  EXPECT_EQ(shipped.resolved_json, defaults.resolved_json);
}

TEST(StudyScene, ValidationNamesFileLineKeyAndValue)
{
  const std::string message = scene_error("fit:\n"
                                          "  cor: 1.5\n"
                                          "walls:\n"
                                          "  gap_reduction: \"120 %\"\n"
                                          "isolator:\n"
                                          "  K2: \"300 MN/m\"\n");
  expect_contains(message,
                  {"study.yaml:2: fit.cor = 1.5",
                   "study.yaml:4: walls.gap_reduction = 120 %",
                   "study.yaml:6: isolator.K2"});
}

TEST(StudyScene, RejectsUnknownKeysAndFixedBaseBuildings)
{
  expect_contains(scene_error("fit:\n  corr: 0.5\n"), {"corr"});
  expect_contains(scene_error("building:\n  kind: fixed_base\n"), {"building.kind"});
  expect_contains(scene_error("fem:\n  wall_heights: [\"1 m\", \"1.00 m\"]\n"),
                  {"fem.wall_heights[1]"});
}

TEST(StudyScene, LumpedSceneCarriesBuildingAndWallMassWithoutWalls)
{
  StudyScene scene;
  scene.building.n_storeys = 3;
  scene.walls.mass         = 700e3;
  scene.walls.gap          = 0.12;
  kimp::app::GroundMotionScene record;
  record.scale                        = 0.5;
  const kimp::app::LumpedScene lumped = kimp::app::study_lumped_scene(scene, record);
  EXPECT_EQ(lumped.building.n_storeys, 3u);
  EXPECT_FALSE(lumped.walls.left.present);
  EXPECT_FALSE(lumped.walls.right.present);
  EXPECT_NEAR(lumped.walls.left.mass, 700e3, exact * 700e3);
  EXPECT_NEAR(lumped.walls.right.gap, 0.12, exact);
  EXPECT_NEAR(lumped.ground_motion.scale, 0.5, exact);
}

TEST(StudyScene, PeerRecordsAreOptional)
{
  StudyScene scene;
  scene.peer_records = false;
  EXPECT_EQ(kimp::app::study_records(scene).size(), 1u);
  scene.peer_records = true;
  scene.records_dir  = "/nonexistent-kimp-records";
  EXPECT_THROW(kimp::app::study_records(scene), std::invalid_argument);
}

TEST(StudyScene, ThesisTable21TimesWidthGivesTable22)
{
  // docs/physics.md §4: Table 2.2 = Table 2.1 x 27.78 m (KV totals, kN/mm).
  constexpr double          table_rounding = 1e-3; // Table 2.2 is printed to 0.01 kN/mm
  const std::vector<double> kv_total{4166.67, 2500, 1250, 694.44};
  const auto               &table = kimp::app::thesis_table_2_1();
  ASSERT_EQ(table.size(), kv_total.size());
  for (std::size_t i = 0; i < table.size(); ++i)
    EXPECT_NEAR(table[i].kelvin_voigt * kimp::fit::thesis_building_width,
                kv_total[i],
                table_rounding * kv_total[i])
      << "H = " << table[i].wall_height;
}

TEST(StudyScene, ThesisTable21ErrorsNameTheFile)
{
  const kimp::testing::TempDir dir("thesis_table");
  const auto                   error_of = [](const std::filesystem::path &file)
  {
    try
    {
      kimp::app::read_thesis_table_2_1(file);
    }
    catch (const std::exception &error)
    {
      return std::string(error.what());
    }
    return std::string();
  };
  const std::filesystem::path missing = dir.file("missing.csv");
  EXPECT_NE(error_of(missing).find(missing.string()), std::string::npos) << error_of(missing);
  const std::filesystem::path bad =
    dir.write("bad.csv",
              "wall_height_m,kelvin_voigt_kN_per_mm_per_m,jankowski_kN_per_mm1.5_per_m\n"
              "1.00,150,fifty\n");
  EXPECT_NE(error_of(bad).find(bad.string() + ":2: 'fifty'"), std::string::npos) << error_of(bad);
  dir.write("bad.csv", "height,k\n1,2\n");
  EXPECT_NE(error_of(bad).find(bad.string() + ":1: header"), std::string::npos) << error_of(bad);
}

TEST(StudyFemCache, KeyDependsOnHeightAndEveryParameter)
{
  const kimp::app::FemScene scene = kimp::app::default_study_fem_scene();
  const std::string         key   = kimp::app::study_fem_cache_key(scene, 1.25);
  EXPECT_EQ(key, kimp::app::study_fem_cache_key(scene, 1.25));
  EXPECT_NE(key, kimp::app::study_fem_cache_key(scene, 1.50));
  kimp::app::FemScene other = scene;
  other.materials.soil.youngs_modulus *= 1.0 + 1e-9;
  EXPECT_NE(key, kimp::app::study_fem_cache_key(other, 1.25));
  // The other heights of the list do not matter: a study with more heights reuses its cases.
  other              = scene;
  other.wall_heights = {1.25};
  EXPECT_EQ(key, kimp::app::study_fem_cache_key(other, 1.25));
}

#endif
