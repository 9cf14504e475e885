// `kimp sweep` end to end: a gap sweep of the lumped engine whose rows obey the physics
// (no impacts beyond the free peak displacement), resume of an interrupted sweep through the CLI,
// failing cases recorded, malformed sweep files named by file:line:key, and 1 vs 2 MPI ranks.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <string>
#include <vector>

#include "tests/support/csv.h"
#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;
  namespace fs = std::filesystem;

  using Csv = CsvTable;

  const std::string kimp = kimp_executable();

  /// Rows without the wall time (last column), which differs between runs.
  std::vector<std::vector<std::string>> rows_without_wall_time(const fs::path &csv_file)
  {
    std::vector<std::vector<std::string>> rows = read_csv(csv_file).rows;
    for (auto &row : rows)
      row.pop_back();
    return rows;
  }

  /// A sweep of data/studies/scenes/quick_scene.yaml written into `dir`.
  fs::path write_sweep(const fs::path &dir, const std::string &body)
  {
    const fs::path file = dir / "sweep.yaml";
    std::ofstream(file) << "scene: "
                        << (source_dir() / "data/studies/scenes/quick_scene.yaml").string() << "\n"
                        << body;
    return file;
  }

  /// `kimp sweep <sweep><options> -o <out>` with its output in `log`: the exit code.
  int kimp_sweep(const fs::path    &sweep,
                 const fs::path    &out,
                 const fs::path    &log,
                 const std::string &options = "")
  {
    return run_command(kimp + " sweep " + sweep.string() + options + " -o " + out.string(), log);
  }

  const std::string gap_sweep = "parameters:\n"
                                "  walls.left.gap, walls.right.gap: {from: 4 cm, to: 34 cm, "
                                "step: 6 cm}\n"
                                "  impact.cor: [0.5, 0.9]\n";

  /// A temporary directory `dir` for the sweep file, its outputs and its logs.
  class SweepCli : public ::testing::Test
  {
  protected:
    const TempDir  temp_dir{"sweep_cli"};
    const fs::path dir = temp_dir.path();
  };

  class SweepCliMpi : public SweepCli
  {
  };

  TEST_F(SweepCli, GapSweepRowsFollowThePhysics)
  {
    const fs::path sweep = write_sweep(dir, gap_sweep);
    ASSERT_EQ(kimp_sweep(sweep, dir / "out", dir / "log.txt"), 0) << read_text(dir / "log.txt");
    const Csv csv = read_csv(dir / "out/sweep.csv");
    ASSERT_EQ(csv.rows.size(), 12U) << "6 gaps x 2 COR";
    const std::size_t gap_column    = csv.column("walls.left.gap+walls.right.gap_cm");
    const std::size_t status_column = csv.column("status");
    const std::size_t impacts       = csv.column("n_impacts");
    const std::size_t free_peak     = csv.column("free_peak_displacement_dof0_m");
    const std::size_t amplification = csv.column("amp_abs_acceleration_dof4");
    const double      free_base     = std::stod(csv.rows[0][free_peak]);
    std::size_t       n_pounding    = 0;
    std::size_t       n_free        = 0;
    constexpr double  tolerance     = 1e-12;
    for (const auto &row : csv.rows)
    {
      ASSERT_EQ(row[status_column], "ok") << row[0];
      // The companion run has no contacts: its peak cannot depend on gap or COR.
      EXPECT_EQ(std::stod(row[free_peak]), free_base) << "row " << row[0];
      const double gap = std::stod(row[gap_column]) * 0.01;
      if (gap > free_base)
      {
        ++n_free;
        EXPECT_EQ(row[impacts], "0") << "gap " << gap << " m > free peak " << free_base << " m";
        EXPECT_NEAR(std::stod(row[amplification]), 1.0, tolerance) << "gap " << gap;
      }
      else
      {
        ++n_pounding;
        EXPECT_GT(std::stod(row[impacts]), 0.0)
          << "gap " << gap << " m < free peak " << free_base << " m";
        EXPECT_GT(std::stod(row[amplification]), 1.0) << "gap " << gap;
      }
    }
    EXPECT_GT(n_pounding, 0U) << "free peak " << free_base;
    EXPECT_GT(n_free, 0U) << "free peak " << free_base;
    EXPECT_TRUE(fs::exists(dir / "out/sweep.h5"));
    fs::remove_all(dir);
  }

  TEST_F(SweepCli, InterruptedSweepResumesWithoutRecomputingFinishedCases)
  {
    const fs::path sweep = write_sweep(dir, gap_sweep);
    const fs::path out   = dir / "out";
    ASSERT_EQ(kimp_sweep(sweep, out, dir / "log1.txt"), 0) << read_text(dir / "log1.txt");
    const auto complete = rows_without_wall_time(out / "sweep.csv");

    // The state a SIGKILL leaves: 5 journaled cases, a torn sixth line, no results yet.
    const fs::path journal = out / "journal/rank-0.jsonl";
    std::ifstream  in(journal);
    std::string    kept, line;
    for (int i = 0; i < 5 && std::getline(in, line); ++i)
      kept += line + "\n";
    std::getline(in, line);
    in.close();
    std::ofstream(journal, std::ios::trunc) << kept << line.substr(0, line.size() / 3);
    fs::remove(out / "sweep.csv");
    fs::remove(out / "sweep.h5");

    ASSERT_EQ(kimp_sweep(sweep, out, dir / "log2.txt"), 0) << read_text(dir / "log2.txt");
    const std::string log = read_text(dir / "log2.txt");
    EXPECT_NE(log.find("12 cases, 5 already finished, 7 to run"), std::string::npos) << log;
    EXPECT_NE(log.find("ignored 1 incomplete journal line"), std::string::npos) << log;
    EXPECT_EQ(rows_without_wall_time(out / "sweep.csv"), complete);
    fs::remove_all(dir);
  }

  TEST_F(SweepCli, FailingCaseIsRecordedAndTheOthersComplete)
  {
    const fs::path sweep = write_sweep(dir,
                                       "parameters:\n"
                                       "  integration.dt: [auto, 0.05 s, auto]\n"
                                       "  walls.left.gap: [10 cm]\n");
    ASSERT_EQ(kimp_sweep(sweep, dir / "out", dir / "log.txt"), 0) << read_text(dir / "log.txt");
    const Csv csv = read_csv(dir / "out/sweep.csv");
    ASSERT_EQ(csv.rows.size(), 3U);
    const std::size_t status = csv.column("status");
    EXPECT_EQ(csv.rows[0][status], "ok");
    EXPECT_EQ(csv.rows[1][status].rfind("failed: ", 0), 0U) << csv.rows[1][status];
    EXPECT_NE(csv.rows[1][status].find("stability limit"), std::string::npos)
      << csv.rows[1][status];
    EXPECT_EQ(csv.rows[2][status], "ok");
    fs::remove_all(dir);
  }

  TEST_F(SweepCli, MalformedSweepFilesNameFileLineAndKey)
  {
    const std::map<std::string, std::vector<std::string>> cases = {
      {"parameters:\n  walls.left.gapp: [10 cm]\n", {"sweep.yaml:3", "walls.left.gapp"}},
      {"parameters:\n  impact.cor: [0.5, 2 cm]\n", {"sweep.yaml:3", "impact.cor = 2 cm"}},
      {"parameters:\n  walls.left.gap: {from: 10 cm, to: 5 cm, step: 1 cm}\n",
       {"sweep.yaml:3", "walls.left.gap", "must be >= from"}},
      {"combine: zip\nparameters:\n  impact.cor: [0.5, 0.7]\n  walls.left.gap: [1 cm]\n",
       {"sweep.yaml:5", "equal lengths"}},
      {"paramaters:\n  impact.cor: [0.5]\n", {"sweep.yaml:2", "paramaters", "unknown key"}},
    };
    int n = 0;
    for (const auto &[body, expected] : cases)
    {
      const fs::path sweep = write_sweep(dir, body);
      const fs::path log   = dir / ("log" + std::to_string(n++) + ".txt");
      EXPECT_EQ(kimp_sweep(sweep, dir / "out", log), 1) << body;
      const std::string text = read_text(log);
      for (const std::string &piece : expected)
        EXPECT_NE(text.find(piece), std::string::npos) << "sweep:\n"
                                                       << body << "output:\n"
                                                       << text << "expected: " << piece;
      EXPECT_FALSE(fs::exists(dir / "out/sweep.csv")) << body;
    }
    std::ofstream(dir / "missing.yaml") << "scene: no_such_scene.yaml\nparameters:\n  a: [1]\n";
    EXPECT_EQ(kimp_sweep(dir / "missing.yaml", dir / "out", dir / "log_missing.txt"), 1);
    EXPECT_NE(read_text(dir / "log_missing.txt").find("missing.yaml:1: scene"), std::string::npos)
      << read_text(dir / "log_missing.txt");
    fs::remove_all(dir);
  }

  /// Largest finite value of a CSV column over the main (non-companion) ok rows.
  double column_max(const Csv &csv, const std::string &name)
  {
    const std::size_t column = csv.column(name);
    const std::size_t status = csv.column("status");
    double            best   = -1.0;
    for (const auto &row : csv.rows)
      if (row[status] == "ok" && !row[column].empty())
        best = std::max(best, std::stod(row[column]));
    return best;
  }

  /// The number after "<label>: " in summary.md, or NaN.
  double summary_number(const std::string &summary, const std::string &label)
  {
    const std::size_t at = summary.find(label + ": ");
    if (at == std::string::npos)
      return std::nan("");
    return std::stod(summary.substr(at + label.size() + 2));
  }

  TEST_F(SweepCli, ReportWritesChartsSummaryAndRequiredGapTableThatMatchTheCsv)
  {
    const fs::path sweep =
      write_sweep(dir, "report: {kind: gap_study, title: Smoke gap study}\n" + gap_sweep);
    const fs::path out = dir / "out";
    ASSERT_EQ(kimp_sweep(sweep, out, dir / "log.txt"), 0) << read_text(dir / "log.txt");
    for (const char *chart : {"response_vs_gap", "amplification_vs_gap"})
      for (const char *ext : {".png", ".svg"})
      {
        const fs::path file = out / "charts" / (std::string(chart) + ext);
        EXPECT_TRUE(fs::exists(file) && fs::file_size(file) > 1000) << file;
      }
    const std::string summary = read_text(out / "summary.md");
    ASSERT_FALSE(summary.empty()) << read_text(out / "charts/charts.log");
    EXPECT_NE(summary.find("# Smoke gap study"), std::string::npos) << summary;
    EXPECT_NE(summary.find("12 cases (12 ok, 0 failed)"), std::string::npos) << summary;

    // Key numbers (4 significant digits) are the maxima of the CSV columns.
    const Csv        csv       = read_csv(out / "sweep.csv");
    constexpr double relative  = 1e-3;
    const auto       check_max = [&](const std::string &label, double expected)
    {
      const double shown = summary_number(summary, label);
      EXPECT_NEAR(shown, expected, relative * std::abs(expected)) << label << "\n" << summary;
    };
    check_max("largest amplification of the base acceleration",
              column_max(csv, "amp_abs_acceleration_dof0"));
    check_max("largest number of impacts", column_max(csv, "n_impacts"));
    check_max("largest max impact velocity",
              std::max(column_max(csv, "left_wall.max_impact_velocity_m_per_s"),
                       column_max(csv, "right_wall.max_impact_velocity_m_per_s")));

    // d_req per COR: the first swept gap beyond which no row pounds, and d_SRSS = free base peak.
    const Csv dsrss = read_csv(out / "dsrss_table.csv");
    ASSERT_EQ(dsrss.rows.size(), 2U) << "one configuration per COR";
    const double free_base = std::stod(csv.rows[0][csv.column("free_peak_displacement_dof0_m")]);
    for (const auto &row : dsrss.rows)
    {
      EXPECT_EQ(row[dsrss.column("d_req_status")], "reached");
      const double d_req = std::stod(row[dsrss.column("d_req_m")]);
      EXPECT_GT(d_req, free_base) << "no impact needs a gap above the free peak";
      EXPECT_LE(d_req - 0.06, free_base) << "one 6 cm step below d_req still pounds";
      EXPECT_NEAR(std::stod(row[dsrss.column("d_srss_m")]), free_base, 1e-12);
    }
    fs::remove_all(dir);
  }

  /// Occurrences of `piece` in `text`.
  std::size_t count_of(const std::string &text, const std::string &piece)
  {
    std::size_t n = 0;
    for (std::size_t at = text.find(piece); at != std::string::npos; at = text.find(piece, at + 1))
      ++n;
    return n;
  }

  TEST_F(SweepCli, GapChartsDrawOneLinePerRecordAndConfigurationWithItsRequiredGap)
  {
    const fs::path sweep = write_sweep(
      dir,
      "report: {kind: gap_study}\n" + gap_sweep +
        "  record:\n"
        "    - {label: full, ground_motion.record: synthetic}\n"
        "    - {label: half, ground_motion.record: synthetic, ground_motion.scale: 0.5}\n");
    const fs::path out = dir / "out";
    ASSERT_EQ(kimp_sweep(sweep, out, dir / "log.txt"), 0) << read_text(dir / "log.txt");
    const Csv dsrss = read_csv(out / "dsrss_table.csv");
    ASSERT_EQ(dsrss.rows.size(), 4U) << "2 records x 2 COR";
    const std::string svg = read_text(out / "charts/response_vs_gap.svg");
    // Four responses, each with one line per record and COR and that line's d_req mark (every
    // configuration has a d_req: reached, or below the smallest swept gap).
    EXPECT_EQ(count_of(svg, "id=\"series-"), 16U);
    EXPECT_EQ(count_of(svg, "id=\"d_req-"), 16U);
    for (const auto &row : dsrss.rows)
    {
      const std::string record = row[dsrss.column("record")];
      const std::string cor    = row[dsrss.column("impact.cor")] == "0.5" ? "0_5" : "0_9";
      EXPECT_NE(row[dsrss.column("d_req_status")], "not_reached");
      for (const char *response : {"floor_acc", "drift", "impact_velocity", "n_impacts"})
        for (const std::string kind : {"series-", "d_req-"})
        {
          const std::string id = "id=\"" + kind + record + "--" + cor + "--" + response + "\"";
          EXPECT_EQ(count_of(svg, id), 1U) << id;
        }
    }
    // Axes in words with units, records as panel titles; no key path on an axis.
    for (const char *words : {"gap to the moat wall [cm]", "record: full", "record: half"})
      EXPECT_NE(svg.find(words), std::string::npos) << words;
    fs::remove_all(dir);
  }

  TEST_F(SweepCli, NoChartsSkipsTheScriptAndAFailingScriptIsAnError)
  {
    const fs::path sweep = write_sweep(dir, "report: {kind: gap_study}\n" + gap_sweep);
    ASSERT_EQ(kimp_sweep(sweep, dir / "a", dir / "log_a.txt", " --no-charts"), 0)
      << read_text(dir / "log_a.txt");
    EXPECT_TRUE(fs::exists(dir / "a/sweep.csv"));
    EXPECT_FALSE(fs::exists(dir / "a/summary.md"));
    EXPECT_FALSE(fs::exists(dir / "a/charts"));

    // A chart script that fails: the sweep results stay, kimp exits with an error naming it.
    fs::create_directories(dir / "data/scripts");
    std::ofstream(dir / "data/scripts/sweep_charts.py") << "import sys\nsys.exit(3)\n";
    EXPECT_EQ(run_command("KIMP_DATA_DIR=" + (dir / "data").string() + " " + kimp + " sweep " +
                            sweep.string() + " -o " + (dir / "b").string(),
                          dir / "log_b.txt"),
              1);
    const std::string log = read_text(dir / "log_b.txt");
    EXPECT_NE(log.find("sweep_charts.py exited with status 3"), std::string::npos) << log;
    EXPECT_TRUE(fs::exists(dir / "b/sweep.csv"));
    EXPECT_FALSE(fs::exists(dir / "b/summary.md"));
    fs::remove_all(dir);
  }

  TEST_F(SweepCli, UnknownReportKindIsNamedWithFileAndLine)
  {
    const fs::path sweep = write_sweep(dir, "report:\n  kind: histogram\n" + gap_sweep);
    EXPECT_EQ(kimp_sweep(sweep, dir / "out", dir / "log.txt"), 1);
    const std::string log = read_text(dir / "log.txt");
    EXPECT_NE(log.find("sweep.yaml:3: report.kind: 'histogram' is not one of: gap_study"),
              std::string::npos)
      << log;
    fs::remove_all(dir);
  }

  // Run by the ctest entry e2e_sweep_cli_test.mpi (label mpi), which enables disabled tests.
  TEST_F(SweepCliMpi, DISABLED_OneAndTwoRanksGiveIdenticalRows)
  {
    const fs::path sweep = write_sweep(dir, gap_sweep);
    ASSERT_EQ(kimp_sweep(sweep, dir / "one", dir / "log1.txt", " -t 1"), 0)
      << read_text(dir / "log1.txt");
    ASSERT_EQ(run_command("mpirun --allow-run-as-root --oversubscribe -np 2 " + kimp + " sweep " +
                            sweep.string() + " -t 1 -o " + (dir / "two").string(),
                          dir / "log2.txt"),
              0)
      << read_text(dir / "log2.txt");
    EXPECT_TRUE(fs::exists(dir / "two/journal/rank-1.jsonl")) << read_text(dir / "log2.txt");
    const auto one = rows_without_wall_time(dir / "one/sweep.csv");
    EXPECT_EQ(one.size(), 12U);
    EXPECT_EQ(rows_without_wall_time(dir / "two/sweep.csv"), one);
    fs::remove_all(dir);
  }
} // namespace
