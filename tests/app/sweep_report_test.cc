// d_req against d_SRSS (docs/physics.md §2 last bullet): required gap on hand-made rows (monotone,
// non-monotone, not reached), the SRSS gap in closed form, grouping by configuration and record,
// and a small real sweep whose d_SRSS is sqrt(d_L² + d_R²) of the free peaks.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <random>
#include <string>
#include <vector>

#include "app/sweep/sweep_engine.h"
#include "app/sweep/sweep_lumped.h"
#include "app/sweep/sweep_report.h"
#include "base/logging.h"
#include "tests/app/lumped_sweeps.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::app;

  constexpr double exact     = 1e-15; ///< m, values copied, not computed
  constexpr double round_off = 1e-12; ///< m, a few operations on lengths of order 0.1 m

  std::vector<GapSample> samples(const std::vector<double> &gaps, const std::vector<int> &impacts)
  {
    std::vector<GapSample> out;
    for (std::size_t i = 0; i < gaps.size(); ++i)
      out.push_back({gaps[i], impacts[i] > 0, true});
    return out;
  }

  std::vector<double> gap_range(double from, double step, int n)
  {
    std::vector<double> gaps;
    for (int i = 0; i < n; ++i)
      gaps.push_back(from + step * i);
    return gaps;
  }

  TEST(RequiredGap, MonotoneImpactCountsGiveTheFirstGapWithoutImpact)
  {
    const std::vector<double> gaps = gap_range(0.10, 0.01, 11); // 10..20 cm
    const auto r = kimp::app::required_gap(samples(gaps, {9, 7, 5, 3, 1, 0, 0, 0, 0, 0, 0}));
    EXPECT_EQ(r.status, RequiredGapStatus::reached);
    EXPECT_NEAR(r.gap, 0.15, exact);
  }

  TEST(RequiredGap, NonMonotoneImpactCountsNeedEveryLargerGapFree)
  {
    // 12 and 13 cm free, 14 cm pounds again: d_req is 15 cm, not 12 cm.
    const std::vector<double> gaps = gap_range(0.10, 0.01, 8);
    const auto                r = kimp::app::required_gap(samples(gaps, {4, 2, 0, 0, 1, 0, 0, 0}));
    EXPECT_EQ(r.status, RequiredGapStatus::reached);
    EXPECT_NEAR(r.gap, 0.15, exact);
  }

  TEST(RequiredGap, ImpactAtTheLargestGapIsNotReached)
  {
    const std::vector<double> gaps = gap_range(0.10, 0.05, 4);
    const auto                r    = kimp::app::required_gap(samples(gaps, {3, 0, 0, 1}));
    EXPECT_EQ(r.status, RequiredGapStatus::not_reached);
    EXPECT_TRUE(std::isnan(r.gap));
  }

  TEST(RequiredGap, NoImpactAnywhereGivesTheSmallestGapAsUpperBound)
  {
    const std::vector<double> gaps = gap_range(0.20, 0.05, 3);
    const auto                r    = kimp::app::required_gap(samples(gaps, {0, 0, 0}));
    EXPECT_EQ(r.status, RequiredGapStatus::at_smallest_gap);
    EXPECT_NEAR(r.gap, 0.20, exact);
    EXPECT_EQ(kimp::app::required_gap({}).status, RequiredGapStatus::no_data);
  }

  TEST(RequiredGap, OrderDuplicatesAndFailedCasesDoNotMatter)
  {
    std::vector<GapSample> s = samples(gap_range(0.10, 0.01, 10), {5, 4, 3, 0, 2, 0, 0, 0, 0, 0});
    // A second record-less duplicate at 16 cm with an impact makes 16 cm a pounding gap, and a
    // failed case at 19 cm (its impact flag is meaningless) is ignored.
    s.push_back({0.16, true, true});
    s.push_back({0.19, true, false});
    std::mt19937 random(42);
    for (int trial = 0; trial < 5; ++trial)
    {
      std::shuffle(s.begin(), s.end(), random);
      const auto r = kimp::app::required_gap(s);
      EXPECT_EQ(r.status, RequiredGapStatus::reached) << "trial " << trial;
      EXPECT_NEAR(r.gap, 0.17, exact) << "trial " << trial;
    }
  }

  TEST(SrssGap, ClosedFormMaxOverContactsMinusClearanceOffset)
  {
    // Wall: g = gap, d_iso = 0.35 m. Neighbour floor: g = gap + 5 cm, d_L = 0.3, d_R = 0.4 m, so
    // sqrt(0.3² + 0.4²) − 0.05 = 0.45 m governs. Another floor: 0.2, 0.1 m, offset 0.05 m.
    const double                  gap = 0.12;
    const std::vector<ContactGap> contacts{
      {"left_wall", gap, 0.35},
      {"left_neighbour_floor1", gap + 0.05, std::hypot(0.3, 0.4)},
      {"left_neighbour_floor2", gap + 0.05, std::hypot(0.2, 0.1)}};
    const auto r = kimp::app::srss_required_gap(contacts, gap);
    EXPECT_NEAR(r.gap, 0.45, round_off);
    EXPECT_EQ(r.governing, "left_neighbour_floor1");
    // The result does not depend on the gap of the case when the offsets are kept.
    std::vector<ContactGap> shifted = contacts;
    for (ContactGap &c : shifted)
      c.clearance += 0.2;
    EXPECT_NEAR(kimp::app::srss_required_gap(shifted, gap + 0.2).gap, 0.45, round_off);
    EXPECT_THROW(kimp::app::srss_required_gap({}, gap), std::invalid_argument);
  }

  /// A hand-made sweep: gap 10-20 cm with separation = gap + 0 or + 5 cm, two records, plus one
  /// failed case; pounding while gap < threshold(record, offset).
  TEST(DsrssTable, GroupsByConfigurationRecordAndSeparationOffset)
  {
    std::string gap_values;
    for (int g = 10; g <= 20; ++g)
      for (int off : {0, 5})
        gap_values += "    - {label: \"gap " + std::to_string(g) + " +" + std::to_string(off) +
                      "\", walls.left.gap: \"" + std::to_string(g) +
                      " cm\", neighbours.left.separation: \"" + std::to_string(g + off) +
                      " cm\"}\n";
    const SweepPlan plan = SweepPlan::parse("scene: base.yaml\n"
                                            "report: {kind: adjacent_buildings}\n"
                                            "parameters:\n"
                                            "  record: [kobe, converter]\n"
                                            "  gap_and_separation:\n" +
                                              gap_values,
                                            "hand.yaml",
                                            "walls: {left: {gap: 15 cm}}\n"
                                            "neighbours: {left: {separation: 15 cm}}\n",
                                            "base.yaml");
    ASSERT_EQ(plan.cases().size(), 44U);
    ASSERT_TRUE(plan.report());
    EXPECT_EQ(plan.report()->gap_key, "walls.left.gap");

    SweepTable table;
    table.parameter_names = {"record", "gap_and_separation"};
    table.metric_names    = {"n_impacts",
                             "left_wall.clearance [m]",
                             "left_wall.srss_gap [m]",
                             "left_neighbour_floor1.clearance [m]",
                             "left_neighbour_floor1.srss_gap [m]"};
    const auto threshold  = [](const std::string &record, double offset)
    { return (record == "kobe" ? 0.16 : 0.13) - offset / 2; };
    const auto   d_iso   = [](const std::string &record) { return record == "kobe" ? 0.14 : 0.11; };
    const double d_fixed = 0.06;
    for (const auto &c : plan.cases())
    {
      SweepTableRow row;
      row.index        = c.index;
      row.id           = c.id;
      row.values       = c.values;
      const int    g   = std::stoi(c.values[1].substr(4));
      const int    off = std::stoi(c.values[1].substr(c.values[1].find('+') + 1));
      const double gap = g * 0.01, offset = off * 0.01;
      if (c.values[0] == "converter" && g == 18 && off == 5)
      {
        row.status = "failed: dt above the stability limit";
        row.metrics.assign(5, std::nan(""));
      }
      else
      {
        row.status  = "ok";
        row.metrics = {gap < threshold(c.values[0], offset) - 1e-9 ? 3.0 : 0.0,
                       gap,
                       d_iso(c.values[0]),
                       gap + offset,
                       std::hypot(d_iso(c.values[0]), d_fixed)};
      }
      table.rows.push_back(row);
    }

    const auto dsrss = kimp::app::dsrss_table(plan, table, "walls.left.gap");
    ASSERT_EQ(dsrss.parameter_names, std::vector<std::string>{"record"});
    ASSERT_EQ(dsrss.rows.size(), 4U) << "2 records x 2 separation offsets";
    for (const auto &r : dsrss.rows)
    {
      const std::string &record = r.values.at(0);
      const double       offset = r.clearance_offset;
      SCOPED_TRACE(record + " offset " + std::to_string(offset));
      EXPECT_TRUE(std::abs(offset) < round_off || std::abs(offset - 0.05) < round_off);
      const bool has_failed_gap = record == "converter" && offset > 0.01;
      EXPECT_EQ(r.n_gaps, has_failed_gap ? 10U : 11U);
      EXPECT_EQ(r.d_req.status, RequiredGapStatus::reached);
      const double expected_req = std::ceil(threshold(record, offset) * 100 - 1e-6) / 100;
      EXPECT_NEAR(r.d_req.gap, expected_req, round_off);
      const double expected_srss =
        std::max(d_iso(record), std::hypot(d_iso(record), d_fixed) - offset);
      EXPECT_NEAR(r.d_srss, expected_srss, round_off);
      EXPECT_NEAR(r.delta(), expected_srss - expected_req, round_off);
      EXPECT_LT(r.d_srss_spread, round_off);
    }
    // The failed case counts for both offset groups of its record (it has no metrics).
    EXPECT_EQ(std::count_if(dsrss.rows.begin(),
                            dsrss.rows.end(),
                            [](const auto &r) { return r.n_failed == 1; }),
              2);
    EXPECT_THROW(kimp::app::dsrss_table(plan, table, "walls.right.gap"), kimp::app::SweepError);
  }

  /// Value of a metric in a row, by name.
  double metric(const SweepTable &table, const SweepTableRow &row, const std::string &name)
  {
    const auto it = std::find(table.metric_names.begin(), table.metric_names.end(), name);
    if (it == table.metric_names.end())
      throw std::runtime_error("no metric " + name);
    return row.metrics.at(static_cast<std::size_t>(it - table.metric_names.begin()));
  }

  TEST(DsrssTable, RealSweepUsesTheFreePeaksOfTheFacingFloors)
  {
    kimp::base::set_verbosity(kimp::base::Verbosity::quiet);
    const std::string scene = kimp::testing::pulse_sweep_scene(
      3,
      "8 cm",
      "neighbours:\n  left: {present: true, n_storeys: 2, separation: 13 cm}\n",
      "4 s",
      "auto");
    const SweepPlan plan =
      SweepPlan::parse("scene: base.yaml\n"
                       "parameters:\n"
                       "  gap_and_separation:\n"
                       "    - {label: small, walls.left.gap: 2 cm, walls.right.gap: 2 cm, "
                       "neighbours.left.separation: 3 cm}\n"
                       "    - {label: large, walls.left.gap: 80 cm, walls.right.gap: 80 cm, "
                       "neighbours.left.separation: 81 cm}\n",
                       "real.yaml",
                       scene,
                       "base.yaml");
    const kimp::testing::TempDir temp_dir("sweep_report");
    const SweepTable             table =
      kimp::testing::run_lumped_sweep(plan, temp_dir.path() / "sweep", true, 1);
    ASSERT_EQ(table.rows.size(), 2U);
    for (const auto &row : table.rows)
      ASSERT_EQ(row.status, "ok");

    // Expected by hand from the free peaks: wall contacts sqrt(d_0² + 0²) − 0, neighbour floor j
    // sqrt(d_j² + d_(first + j − 1)²) − 1 cm (separation = gap + 1 cm).
    const SweepTableRow &small = table.rows[0];
    const auto           free  = [&](int dof)
    { return metric(table, small, "free_peak_displacement_dof" + std::to_string(dof) + " [m]"); };
    const int first = static_cast<int>(metric(table, small, "left_neighbour.first_dof"));
    EXPECT_EQ(first, 4) << "3-storey isolated building: DOFs 0-3, then the neighbour";
    double expected = free(0);
    for (int j = 1; j <= 2; ++j)
      expected = std::max(expected, std::hypot(free(j), free(first + j - 1)) - 0.01);
    EXPECT_GT(metric(table, small, "n_impacts"), 0.0) << "2 cm gap must pound";
    EXPECT_EQ(metric(table, table.rows[1], "n_impacts"), 0.0) << "80 cm gap must not pound";

    const auto dsrss = kimp::app::dsrss_table(plan, table, "walls.left.gap");
    ASSERT_EQ(dsrss.rows.size(), 1U);
    const auto &r = dsrss.rows[0];
    EXPECT_NEAR(r.d_srss, expected, round_off);
    EXPECT_LT(r.d_srss_spread, round_off) << "runs without contacts do not depend on the gap";
    EXPECT_NEAR(r.clearance_offset, 0.01, round_off);
    EXPECT_EQ(r.governing.rfind("left_neighbour_floor", 0), 0U)
      << "the superstructure floors move more than the isolation level: " << r.governing;
    EXPECT_EQ(r.d_req.status, RequiredGapStatus::reached);
    EXPECT_NEAR(r.d_req.gap, 0.80, round_off);
    EXPECT_NEAR(r.delta(), expected - 0.80, round_off);
    std::printf("real sweep: d_SRSS = %.6f m (%s), d_req = %.2f m, free base peak %.6f m\n",
                r.d_srss,
                r.governing.c_str(),
                r.d_req.gap,
                free(0));

    // The CSV has one line per configuration with the units in the header.
    const fs::path csv = temp_dir.file("dsrss.csv");
    kimp::app::write_dsrss_table(dsrss, csv);
    std::ifstream in(csv);
    std::string   header, line;
    std::getline(in, header);
    std::getline(in, line);
    fs::remove(csv);
    EXPECT_NE(header.find("d_srss_m"), std::string::npos) << header;
    EXPECT_NE(header.find("delta_d_m"), std::string::npos) << header;
    EXPECT_NE(line.find("reached"), std::string::npos) << line;
  }
} // namespace
