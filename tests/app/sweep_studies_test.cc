// The shipped sweep studies (data/studies): every file parses, every varied key exists in
// the lumped scene schema, every case is a valid scene, and the case counts are those of the
// studies' designs (e.g. study 1: 3 buildings x 3 records x 3 scalings x 71 gaps).
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <string>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_scene.h"
#include "app/sweep/sweep_plan.h"
#include "tests/support/files.h"

namespace
{
  namespace fs = std::filesystem;

  fs::path studies_dir()
  {
    return kimp::testing::source_dir() / "data/studies";
  }

  TEST(SweepStudies, EveryShippedStudyIsValidWithItsDesignedCaseCount)
  {
    const std::map<std::string, std::size_t> expected_cases = {
      {"quick_gap_sweep.yaml", 4 * 3},
      {"study1_gap_records_storeys.yaml", 3 * 3 * 3 * 71},
      {"study2_isolation_flexibility.yaml", 13 * 2 * 3 * 2},
      {"study3_wall_location.yaml", 3 * 36 * 3},
      {"study4_impact_parameters.yaml", 10 * 10},
      {"study5_adjacent_buildings.yaml", 4 * 5 * (36 * 3) * 3},
      {"study6_bumpers_gap.yaml", 2 * 3 * 31 * 3},
      {"study6_bumper_properties.yaml", 4 * 3 * 2 * 3},
      {"study6_bumper_cor.yaml", 8 * 3 * 2},
      {"plan_directionality.yaml", 13 * 3},
    };
    std::set<std::string> seen;
    for (const auto &item : fs::directory_iterator(studies_dir()))
    {
      if (item.path().extension() != ".yaml")
        continue;
      const std::string name = item.path().filename().string();
      seen.insert(name);
      SCOPED_TRACE(name);
      const kimp::app::SweepPlan plan  = kimp::app::SweepPlan::from_file(item.path());
      const auto                 found = expected_cases.find(name);
      ASSERT_NE(found, expected_cases.end()) << "add the case count of the new study " << name;
      EXPECT_EQ(plan.cases().size(), found->second);
      EXPECT_NO_THROW(plan.check_key_paths(
        [](const std::string &text, const std::string &scene_name)
        { kimp::io::read_scene_text<kimp::app::PlanLumpedScene>(text, scene_name); }));
      // Every case of the small studies, a regular sample of the large ones (test time).
      constexpr std::size_t max_loaded = 1000;
      const std::size_t     stride     = 1 + plan.cases().size() / max_loaded;
      std::set<std::string> ids;
      for (const kimp::app::SweepCase &c : plan.cases())
      {
        ids.insert(c.id);
        if (c.index % stride != 0)
          continue;
        try
        {
          kimp::io::read_scene_text<kimp::app::PlanLumpedScene>(c.scene_text, c.scene_name);
        }
        catch (const std::exception &error)
        {
          ADD_FAILURE() << error.what();
          break;
        }
      }
      EXPECT_EQ(ids.size(), plan.cases().size()) << "case ids must be unique";
    }
    EXPECT_EQ(seen.size(), expected_cases.size());
  }

  TEST(SweepStudies, RecordsOfTheStudiesExistInTheRecordsDirectory)
  {
    const kimp::app::LumpedScene base =
      kimp::io::load_scene<kimp::app::LumpedScene>(studies_dir() / "scenes/isolated_walls.yaml");
    const auto records = kimp::app::scene_records_directory(base.ground_motion);
    if (!records || !fs::is_directory(*records))
      GTEST_SKIP() << "no records directory (../shared/data/records or KIMP_RECORDS_DIR)";
    for (const char *record : {"RSN1106_KOBE_KJM000", "SCS142", "RSN77_SFERN_PUL164"})
    {
      kimp::app::GroundMotionScene scene = base.ground_motion;
      scene.record                       = record;
      scene.duration.reset();
      EXPECT_NO_THROW(kimp::app::load_ground_motion(scene)) << record;
    }
  }
} // namespace
