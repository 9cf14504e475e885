// End-to-end paths and records of scenes: impact.k_table and record files relative to the scene
// file's directory (and to the sweep file for values it sets), whatever the working directory;
// a missing table or record refused at the scene's file:line:key with a did-you-mean, before any
// output (kimp lumped, kimp sweep).
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <initializer_list>
#include <string>

#include "tests/support/csv.h"
#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/messages.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  using kimp::testing::expect_contains;

  void write_file(const fs::path &file, const std::string &text)
  {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
  }

  /// A k table of `kimp study` (two heights) and a 4 s square-wave AT2 record.
  void write_site(const fs::path &site)
  {
    write_file(site / "k_table.csv",
               "wall_height_m,kelvin_voigt_total_kN_per_mm,jankowski_total_kN_per_mm1.5\n"
               "1,4634.45,2141.86\n"
               "2,714.031,208.796\n");
    std::string at2 = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS OF G\n"
                      "NPTS= 400, DT= .0100 SEC\n";
    for (int i = 0; i < 400; ++i)
      at2 += (i / 100) % 2 == 0 ? " 0.30\n" : " -0.30\n";
    write_file(site / "records/RSN1106_KOBE_KJM000.AT2", at2);
  }

  /// A short lumped scene whose walls take k from `k_table` at 1.5 m.
  std::string site_scene(const std::string &k_table, const std::string &record)
  {
    return "walls: {left: {gap: 4 cm}, right: {gap: 4 cm}}\n"
           "impact:\n"
           "  law: kelvin_voigt\n"
           "  k_table: " +
           k_table +
           "\n"
           "  wall_height: 1.5 m\n"
           "ground_motion:\n"
           "  record: " +
           record +
           "\n"
           "  duration: 3 s\n"
           "integration: {dt: 1e-4 s, output_interval: 0.02 s}\n";
  }

  TEST(ScenePathsCli, KTableAndRecordFileAreRelativeToTheScene)
  {
    const TempDir  temp("scene_paths");
    const fs::path site = temp.path() / "site";
    write_site(site);
    write_file(site / "scene.yaml",
               site_scene("k_table.csv", "records/RSN1106_KOBE_KJM000.AT2") +
                 "cases:\n  - {name: table}\n  - {name: synthetic, record: synthetic}\n");
    // Run from another directory, which holds no k_table.csv.
    fs::create_directories(temp.path() / "elsewhere");
    const KimpRun run = run_kimp("lumped ../site/scene.yaml -o out", temp.path() / "elsewhere");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(fs::exists(temp.path() / "elsewhere/out/lumped.h5"));
  }

  TEST(ScenePathsCli, MissingTableAndRecordsNameTheSceneKeyAndSuggest)
  {
    const TempDir  temp("scene_paths_bad");
    const fs::path site = temp.path() / "site";
    write_site(site);
    fs::create_directories(temp.path() / "elsewhere");
    const auto refused = [&](const std::string &scene, std::initializer_list<std::string> parts)
    {
      write_file(site / "scene.yaml", scene);
      const KimpRun run = run_kimp("lumped ../site/scene.yaml --records-dir ../site/records -o out",
                                   temp.path() / "elsewhere");
      EXPECT_EQ(run.exit_code, 1) << scene << run.err;
      expect_contains(run.err, parts);
      EXPECT_FALSE(fs::exists(temp.path() / "elsewhere/out/lumped.h5")) << scene;
      fs::remove_all(temp.path() / "elsewhere/out");
    };
    // A table that is not beside the scene: the key as written, the file looked for.
    refused(site_scene("missing.csv", "synthetic"),
            {"site/scene.yaml:4: impact.k_table = missing.csv",
             "../site/missing.csv: cannot read",
             "cannot read the k table"});
    // A misspelt record name: the records directory's name suggested.
    refused(site_scene("k_table.csv", "RSN1106_KOBE_KJM00"),
            {"site/scene.yaml:7: ground_motion.record = 'RSN1106_KOBE_KJM00': not found",
             "did you mean 'RSN1106_KOBE_KJM000'?"});
    // A case's misspelt built-in name, refused before any case runs.
    refused(site_scene("k_table.csv", "synthetic") +
              "cases:\n  - {name: a}\n  - {name: b, record: synthtic}\n",
            {"site/scene.yaml:12: cases[1].record = 'synthtic'", "did you mean 'synthetic'?"});
    // A record path that does not exist: the file beside it suggested, as a path.
    refused(site_scene("k_table.csv", "records/RSN1106_KOBE_KJM00.AT2"),
            {"site/scene.yaml:7: ground_motion.record = '../site/records/RSN1106_KOBE_KJM00.AT2'",
             "no such file",
             "did you mean '../site/records/RSN1106_KOBE_KJM000.AT2'?"});
  }

  TEST(ScenePathsCli, SweepValuesAreRelativeToTheSweepFileAndRecordsAreCheckedFirst)
  {
    const TempDir  temp("scene_paths_sweep");
    const fs::path site = temp.path() / "site";
    write_site(site);
    write_file(site / "scene.yaml", site_scene("k_table.csv", "synthetic"));
    // The sweep file in another directory, with its own k table beside it.
    write_file(temp.path() / "sweeps/k_table.csv", read_text(site / "k_table.csv"));
    write_file(temp.path() / "sweeps/tables.yaml",
               "scene: ../site/scene.yaml\n"
               "parameters:\n"
               "  impact.k_table: [k_table.csv, ../site/k_table.csv]\n");
    fs::create_directories(temp.path() / "elsewhere");
    const KimpRun ok = run_kimp("sweep ../sweeps/tables.yaml -o out", temp.path() / "elsewhere");
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    const CsvTable csv = read_csv(temp.path() / "elsewhere/out/sweep.csv");
    ASSERT_EQ(csv.rows.size(), 2u);
    for (const auto &row : csv.rows)
      EXPECT_EQ(row[csv.column("status")], "ok");

    // A misspelt record among a parameter's values: the sweep file's line, before any output.
    write_file(temp.path() / "sweeps/records.yaml",
               "scene: ../site/scene.yaml\n"
               "parameters:\n"
               "  walls.left.gap: [4 cm, 8 cm]\n"
               "  ground_motion.record: [synthetic, kobe]\n");
    // `kimp sweep ../sweeps/<name>.yaml` from elsewhere into <name>, refused before any output.
    const auto refused_sweep =
      [&](const std::string &name, std::initializer_list<std::string> parts)
    {
      const KimpRun run =
        run_kimp("sweep ../sweeps/" + name + ".yaml --records-dir ../site/records -o " + name,
                 temp.path() / "elsewhere");
      EXPECT_EQ(run.exit_code, 1) << run.err;
      expect_contains(run.err, parts);
      EXPECT_FALSE(fs::exists(temp.path() / "elsewhere" / name / "sweep.csv"));
    };
    refused_sweep("records",
                  {"records.yaml:4: parameters.ground_motion.record = kobe",
                   "did you mean 'RSN1106_KOBE_KJM000'?"});

    // The base scene's own record, not set by the sweep: the base scene's line.
    write_file(site / "typo.yaml", site_scene("k_table.csv", "synthetik"));
    write_file(temp.path() / "sweeps/typo.yaml",
               "scene: ../site/typo.yaml\nparameters:\n  walls.left.gap: [4 cm, 8 cm]\n");
    refused_sweep("typo",
                  {"site/typo.yaml:7: ground_motion.record = 'synthetik'",
                   "did you mean 'synthetic'?"});
  }
} // namespace
