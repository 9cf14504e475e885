// Inputs that cannot be silently wrong, at the app layer: sweep ranges counted before any cast,
// two-column records with ground_motion.record_unit, record errors at the scene's file:line:key
// with a did-you-mean, the step budget refused with the estimate, implausible peaks failed with
// the numbers, and (with the FEM engine) the study's warning for requested records not found.
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <initializer_list>
#include <string>
#include <utility>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_run.h"
#include "app/lumped/lumped_scene.h"
#include "app/sweep/sweep_plan.h"
#include "io/records.h"
#include "io/scene_io.h"
#include "io/units.h"
#include "tests/support/messages.h"
#include "tests/support/temp_dir.h"
#ifdef KIMP_WITH_FEM
#  include "app/study/study_scene.h"
#endif

namespace
{
  using namespace kimp::app;
  using kimp::io::SceneError;

  using kimp::testing::expect_contains;

  template <class F>
  std::string message_of(F &&f)
  {
    return kimp::testing::thrown_message(std::forward<F>(f));
  }

  /// A minimal AT2 file of `n` samples at 0.01 s, all `value_g`.
  std::string at2(std::size_t n, double value_g)
  {
    std::string text = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS OF G\n"
                       "NPTS= " +
                       std::to_string(n) + ", DT= .0100 SEC\n";
    for (std::size_t i = 0; i < n; ++i)
      text += " " + std::to_string(value_g) + "\n";
    return text;
  }

  /// Writes at2(100, `value_g`) (1 s, the shortest record admitted) to `file` inside `dir`,
  /// creating the folders of its path.
  void write_record(const kimp::testing::TempDir &dir, const std::string &file, double value_g)
  {
    std::filesystem::create_directories((dir.path() / file).parent_path());
    dir.write(file, at2(100, value_g));
  }

  TEST(SweepRange, TinyStepIsRefusedWithTheCountBeforeAnyCast)
  {
    // 10 cm .. 20 cm step 1e-20 cm: 1e21 values, beyond size_t; it used to run one case.
    const std::string message =
      message_of([] { expand_range("10 cm", "20 cm", "1e-20 cm", "sweep.yaml:4: parameters.g"); });
    expect_contains(message,
                    {"sweep.yaml:4: parameters.g", "gives 1e+21 values", "at most 10000000"});
    EXPECT_EQ(expand_range("10 cm", "20 cm", "5 cm", "w").size(), 3u);
    // One value above the admitted count.
    expect_contains(message_of([] { expand_range("0", "10000000", "1", "w"); }),
                    {"gives 1e+07 values"});
  }

  TEST(GroundMotionRecords, TwoColumnFileUsesTheSceneUnit)
  {
    const kimp::testing::TempDir dir;
    // 1 s of samples at 0.01 s (a shorter record is refused).
    std::string rows = "# t a\n0 0\n0.01 100\n0.02 -50\n";
    for (int i = 3; i < 100; ++i)
      rows += std::to_string(0.01 * i) + " 0\n";
    const auto        file = dir.write("motion.txt", rows);
    const std::string scene_text =
      "ground_motion:\n  record: " + file.string() + "\n  record_unit: cm/s^2\n";
    const auto loaded = kimp::io::read_scene_text<LumpedScene>(scene_text, "scene.yaml");
    const kimp::lumped::GroundMotion motion = load_ground_motion_at(loaded.scene.ground_motion,
                                                                    {},
                                                                    loaded.file_name,
                                                                    loaded.text,
                                                                    "ground_motion");
    ASSERT_EQ(motion.acceleration.size(), 100u);
    EXPECT_DOUBLE_EQ(motion.acceleration[1], 1.0); // 100 cm/s² = 1 m/s²
    EXPECT_DOUBLE_EQ(motion.acceleration[2], -0.5);
    EXPECT_DOUBLE_EQ(motion.dt, 0.01);

    // Without the key: refused at the scene's key, with the file's line and the key to add.
    const std::string without = "ground_motion:\n  record: " + file.string() + "\n";
    const auto        bare    = kimp::io::read_scene_text<LumpedScene>(without, "scene.yaml");
    expect_contains(message_of(
                      [&] {
                        load_ground_motion_at(bare.scene.ground_motion,
                                              {},
                                              "scene.yaml",
                                              without,
                                              "ground_motion");
                      }),
                    {"scene.yaml:2: ground_motion.record = '" + file.string() + "'",
                     "motion.txt:2:",
                     "does not state its unit",
                     "record_unit"});

    // Not an acceleration unit: a validation error at the key.
    expect_contains(message_of(
                      [&] {
                        kimp::io::read_scene_text<LumpedScene>(without + "  record_unit: cm\n",
                                                               "scene.yaml");
                      }),
                    {"scene.yaml:3: ground_motion.record_unit = 'cm'", "acceleration unit"});
  }

  TEST(GroundMotionRecords, MistypedRecordNamesTheKeyAndSuggests)
  {
    const kimp::testing::TempDir dir;
    write_record(dir, "RSN1106_KOBE_KJM000.AT2", 0.1);
    write_record(dir, "SCS142.AT2", 0.2);
    const std::string text    = "# my building\nground_motion:\n  record: RSN1106_KOBE_KJM00\n";
    const auto        loaded  = kimp::io::read_scene_text<LumpedScene>(text, "scene.yaml");
    const std::string message = message_of(
      [&]
      {
        load_ground_motion_at(loaded.scene.ground_motion,
                              dir.path(),
                              "scene.yaml",
                              text,
                              "ground_motion");
      });
    expect_contains(message,
                    {"scene.yaml:3: ground_motion.record = 'RSN1106_KOBE_KJM00': not found",
                     "did you mean 'RSN1106_KOBE_KJM000'?"});
    // A part of the name is enough for the hint; nothing close gives none.
    EXPECT_EQ(kimp::io::closest_record_name("kobe", {"SCS142", "RSN1106_KOBE_KJM000"}),
              "RSN1106_KOBE_KJM000");
    EXPECT_EQ(kimp::io::closest_record_name("scs124.AT2", {"SCS142", "RSN1106_KOBE_KJM000"}),
              "SCS142");
    EXPECT_FALSE(kimp::io::closest_record_name("elcentro", {"SCS142"}).has_value());
    // The right name loads, in g.
    const std::string good = "ground_motion:\n  record: SCS142\n";
    const auto        ok   = kimp::io::read_scene_text<LumpedScene>(good, "scene.yaml");
    const kimp::lumped::GroundMotion motion = load_ground_motion_at(ok.scene.ground_motion,
                                                                    dir.path(),
                                                                    "scene.yaml",
                                                                    good,
                                                                    "ground_motion");
    EXPECT_DOUBLE_EQ(motion.acceleration[0], 0.2 * kimp::io::standard_gravity);
  }

  TEST(GroundMotionRecords, RecordPathsAreRelativeToTheSceneAndMissingOnesSuggest)
  {
    const kimp::testing::TempDir dir;
    write_record(dir, "records/RSN1106_KOBE_KJM000.AT2", 0.1);
    const auto scene  = dir.write("scene.yaml",
                                 "ground_motion:\n  record: records/RSN1106_KOBE_KJM000.AT2\n"
                                  "  records_dir: records\n");
    const auto loaded = kimp::io::read_scene<LumpedScene>(scene);
    EXPECT_EQ(loaded.scene.ground_motion.record,
              (dir.path() / "records/RSN1106_KOBE_KJM000.AT2").string());
    EXPECT_EQ(loaded.scene.ground_motion.records_dir, (dir.path() / "records").string());
    EXPECT_DOUBLE_EQ(load_ground_motion(loaded.scene.ground_motion).acceleration[0],
                     0.1 * kimp::io::standard_gravity);
    // A bare name stays a name (looked up in the records directory, also relative to the scene).
    const auto named   = dir.write("named.yaml",
                                 "ground_motion:\n  record: RSN1106_KOBE_KJM000\n"
                                   "  records_dir: records\n");
    const auto by_name = kimp::io::read_scene<LumpedScene>(named);
    EXPECT_EQ(by_name.scene.ground_motion.record, "RSN1106_KOBE_KJM000");
    EXPECT_EQ(load_ground_motion(by_name.scene.ground_motion).acceleration.size(), 100u);
    // A misspelt file: "no such file" and the file beside it.
    const std::string typo = "ground_motion:\n  record: records/RSN1106_KOBE_KJM00.AT2\n";
    const auto        bad  = kimp::io::read_scene_text<LumpedScene>(typo, "s.yaml", dir.path());
    expect_contains(
      message_of(
        [&]
        { load_ground_motion_at(bad.scene.ground_motion, {}, "s.yaml", typo, "ground_motion"); }),
      {"s.yaml:2: ground_motion.record = '" +
         (dir.path() / "records/RSN1106_KOBE_KJM00.AT2").string() + "'",
       "no such file",
       "did you mean '" + (dir.path() / "records/RSN1106_KOBE_KJM000.AT2").string() + "'?"});
    // The built-in name misspelt, with or without a records directory.
    const std::string synthetic = "ground_motion:\n  record: synthetc\n";
    const auto        s         = kimp::io::read_scene_text<LumpedScene>(synthetic, "s.yaml");
    for (const auto &records : {std::optional<std::filesystem::path>(),
                                std::optional<std::filesystem::path>(dir.path() / "records")})
      expect_contains(message_of(
                        [&] {
                          load_ground_motion_at(s.scene.ground_motion,
                                                records,
                                                "s.yaml",
                                                synthetic,
                                                "ground_motion");
                        }),
                      {"s.yaml:2: ground_motion.record = 'synthetc'", "did you mean 'synthetic'?"});
  }

  TEST(RunBudget, EstimateBeforeTheRunAndRefusalAboveTheBudget)
  {
    // The default scene (synthetic motion, no walls) with a 1e7 s analysis: 2e9 steps of the
    // record's 5 ms (the isolated building's own limit is far larger).
    const auto scene =
      kimp::io::load_scene_text<LumpedScene>("integration:\n  duration: 1e7 s\n", "long.yaml");
    const kimp::lumped::GroundMotion motion   = load_ground_motion(scene.ground_motion);
    const RunEstimate                estimate = estimate_lumped_case(scene, motion);
    EXPECT_DOUBLE_EQ(estimate.dt, 0.005);
    EXPECT_DOUBLE_EQ(estimate.n_steps, 2e9);
    EXPECT_EQ(estimate.n_dofs, 5u);
    EXPECT_DOUBLE_EQ(estimate.history_rows, 1e9); // every output_interval = 10 ms
    EXPECT_DOUBLE_EQ(estimate.seconds,
                     5 * (2e9 * cdm_seconds_per_dof_step + 1e9 * history_seconds_per_dof_row));

    const LumpedCaseResult result =
      run_lumped_case("long", scene, motion, scene.ground_motion.scale);
    EXPECT_FALSE(result.ok());
    expect_contains(result.status,
                    {"failed: case long: 2e+09 steps of 0.005 s over 1e+07 s x 5 DoFs",
                     "exceeds the step budget integration.max_steps = 2e+08"});

    // A budget from the scene: the default 20 s record (4000 steps) is refused below 4000.
    const auto small =
      kimp::io::load_scene_text<LumpedScene>("integration:\n  max_steps: 3999\n", "small.yaml");
    expect_contains(run_lumped_case("small", small, motion, 1.0).status,
                    {"4e+03 steps", "max_steps = 4e+03"});
    const auto enough =
      kimp::io::load_scene_text<LumpedScene>("integration:\n  max_steps: 4000\n", "enough.yaml");
    EXPECT_EQ(run_lumped_case("enough", enough, motion, 1.0).status, "ok");
  }

  TEST(Plausibility, AbsurdScaleFailsTheCaseWithTheNumbers)
  {
    // A record scaled by 1e6: kilometres of displacement are not a result.
    const auto scaled =
      kimp::io::load_scene_text<LumpedScene>("ground_motion:\n  scale: 1e6\n", "scaled.yaml");
    const kimp::lumped::GroundMotion motion = load_ground_motion(scaled.ground_motion);
    EXPECT_NEAR(motion.pga(), 0.8e6 * kimp::io::standard_gravity, 1.0);
    const LumpedCaseResult result = run_lumped_case("scaled", scaled, motion, 1e6);
    expect_contains(result.status,
                    {"failed: implausible result: peak |displacement| = ",
                     " m at DoF ",
                     "exceeds integration.plausible_displacement = 10 m"});

    // The unscaled motion is plausible: peaks of centimetres and below 1 g at the base.
    const auto plain = kimp::io::load_scene_text<LumpedScene>("", "plain.yaml");
    const kimp::lumped::GroundMotion plain_motion = load_ground_motion(plain.ground_motion);
    const LumpedCaseResult           ok = run_lumped_case("plain", plain, plain_motion, 1.0);
    ASSERT_TRUE(ok.ok()) << ok.status;
    EXPECT_EQ(implausibility(ok.response, plain.integration), "");

    // The limits are scene keys: a 1 mm displacement limit fails the same run.
    const auto strict =
      kimp::io::load_scene_text<LumpedScene>("integration:\n  plausible_displacement: 1 mm\n",
                                             "strict.yaml");
    expect_contains(implausibility(ok.response, strict.integration),
                    {"exceeds integration.plausible_displacement = 0.001 m"});
    const auto accel =
      kimp::io::load_scene_text<LumpedScene>("integration:\n  plausible_acceleration: 0.01 g\n",
                                             "accel.yaml");
    expect_contains(implausibility(ok.response, accel.integration),
                    {"peak |absolute acceleration| = ", "plausible_acceleration = 0.01 g"});
  }

#ifdef KIMP_WITH_FEM
  TEST(StudyRecords, RequestedRecordsNotFoundAreWarned)
  {
    const kimp::testing::TempDir dir;
    StudyScene                   scene;
    scene.records_dir                = dir.path().string();
    std::vector<std::string> missing = missing_study_records(scene);
    ASSERT_EQ(missing.size(), 2u);
    expect_contains(missing[0], {"RSN1106_KOBE_KJM000", "is not run", dir.path().string()});
    expect_contains(missing[1], {"SCS142.AT2 is not in"});
    write_record(dir, "SCS142.AT2", 0.2);
    missing = missing_study_records(scene);
    ASSERT_EQ(missing.size(), 1u);
    EXPECT_EQ(study_records(scene).size(), 2u); // the synthetic motion and SCS142
    scene.peer_records = false;
    EXPECT_TRUE(missing_study_records(scene).empty());
  }

  TEST(StudyRecords, MisspeltRecordIsAnErrorAtItsKeyBeforeAnyRun)
  {
    const kimp::testing::TempDir dir;
    write_record(dir, "records/SCS142.AT2", 0.2);
    const auto file   = dir.write("study.yaml",
                                "peer_records: false\n"
                                  "records:\n"
                                  "  - {record: synthetic}\n"
                                  "  - {record: records/SCS142.AT2}\n"
                                  "  - {record: SCS124, records_dir: records}\n");
    const auto loaded = kimp::io::read_scene<StudyScene>(file);
    expect_contains(message_of([&] { check_study_records(loaded); }),
                    {file.string() + ":5: records[2].record = 'SCS124': not found",
                     "did you mean 'SCS142'?"});
    // Fixed, every record loads (the path relative to the scene file).
    const auto fixed = dir.write("fixed.yaml",
                                 "peer_records: false\n"
                                 "records:\n"
                                 "  - {record: records/SCS142.AT2}\n"
                                 "  - {record: SCS142, records_dir: records}\n");
    EXPECT_NO_THROW(check_study_records(kimp::io::read_scene<StudyScene>(fixed)));
  }
#endif
} // namespace
