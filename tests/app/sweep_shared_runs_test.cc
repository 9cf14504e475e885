// Sweeps whose cases share contact-free runs (FreeRunCache) give bitwise the rows of sweeps that
// run every case alone: gaps, separations, neighbour storeys, walls present or not, dt auto.
#include <cstring>
#include <gtest/gtest.h>
#include <string>

#include "app/sweep/sweep_engine.h"
#include "base/logging.h"
#include "tests/app/lumped_sweeps.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::app::SweepPlan;
  using kimp::app::SweepTable;

  void expect_same_rows(const SweepPlan &plan, const std::string &what)
  {
    const kimp::testing::TempDir temp_dir("sweep_shared_runs");
    const SweepTable             alone =
      kimp::testing::run_lumped_sweep(plan, temp_dir.path() / "alone", false, 1);
    const SweepTable shared =
      kimp::testing::run_lumped_sweep(plan, temp_dir.path() / "shared", true, 2);
    ASSERT_EQ(alone.rows.size(), plan.cases().size()) << what;
    ASSERT_EQ(shared.rows.size(), alone.rows.size()) << what;
    ASSERT_EQ(shared.metric_names, alone.metric_names) << what;
    std::size_t pounding = 0;
    for (std::size_t r = 0; r < alone.rows.size(); ++r)
    {
      ASSERT_EQ(alone.rows[r].status, "ok") << what << " row " << r;
      EXPECT_EQ(shared.rows[r].status, "ok") << what << " row " << r;
      ASSERT_EQ(shared.rows[r].metrics.size(), alone.rows[r].metrics.size());
      for (std::size_t m = 0; m < alone.rows[r].metrics.size(); ++m)
      {
        const double a = alone.rows[r].metrics[m], b = shared.rows[r].metrics[m];
        // Bit for bit (NaN for a metric a row does not have).
        EXPECT_TRUE(std::memcmp(&a, &b, sizeof a) == 0)
          << what << " row " << r << " " << alone.metric_names[m] << ": " << a << " vs " << b;
        if (alone.metric_names[m] == "n_impacts" && a > 0.0)
          ++pounding;
      }
    }
    EXPECT_GT(pounding, 0U) << what << ": some cases must pound";
    EXPECT_LT(pounding, alone.rows.size()) << what << ": some cases must not";
  }
} // namespace

TEST(SweepSharedRuns, WallGapsStoreysAndWallsPresentGiveTheSameRows)
{
  kimp::base::set_verbosity(kimp::base::Verbosity::quiet);
  const std::string scene = kimp::testing::pulse_sweep_scene(4, "8 cm", "", "6 s", "2e-4 s");
  const SweepPlan   plan =
    SweepPlan::parse("scene: base.yaml\n"
                     "parameters:\n"
                     "  building.n_storeys: [3, 4]\n"
                     "  walls.right.present: [true, false]\n"
                     "  integration.dt: [2e-4 s, auto]\n"
                     "  walls.left.gap, walls.right.gap: {from: 2 cm, to: 60 cm, step: 6 cm}\n",
                     "walls.yaml",
                     scene,
                     "base.yaml");
  expect_same_rows(plan, "walls");
}

TEST(SweepSharedRuns, AdjacentBuildingCasesGiveTheSameRows)
{
  // A sample of the adjacent-building study's topologies: the any-size kernel (up to 17 DOFs).
  kimp::base::set_verbosity(kimp::base::Verbosity::quiet);
  const std::string scene =
    kimp::testing::pulse_sweep_scene(4,
                                     "15 cm",
                                     "neighbours:\n"
                                     "  left: {present: true, n_storeys: 4, separation: 15 cm}\n"
                                     "  right: {present: true, n_storeys: 4, separation: 15 cm}\n",
                                     "5 s",
                                     "2e-4 s");
  const SweepPlan plan =
    SweepPlan::parse("scene: base.yaml\n"
                     "parameters:\n"
                     "  neighbour_side:\n"
                     "    - {label: left, neighbours.right.present: false}\n"
                     "    - {label: both, neighbours.right.present: true}\n"
                     "  neighbours.left.n_storeys, neighbours.right.n_storeys: [2, 6]\n"
                     "  gap_and_separation:\n"
                     "    - {label: a, walls.left.gap: 3 cm, walls.right.gap: 3 cm, "
                     "neighbours.left.separation: 3 cm, neighbours.right.separation: 3 cm}\n"
                     "    - {label: b, walls.left.gap: 10 cm, walls.right.gap: 10 cm, "
                     "neighbours.left.separation: 15 cm, neighbours.right.separation: 15 cm}\n"
                     "    - {label: c, walls.left.gap: 80 cm, walls.right.gap: 80 cm, "
                     "neighbours.left.separation: 90 cm, neighbours.right.separation: 90 cm}\n",
                     "neighbours.yaml",
                     scene,
                     "base.yaml");
  expect_same_rows(plan, "neighbours");
}
