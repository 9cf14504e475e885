// Sweep execution: resume after SIGKILL gives exactly the rows of an uninterrupted run
// without recomputing finished cases, failing cases are recorded, torn journal lines are ignored,
// duplicates merge to one row, and 1 vs 2 ranks give identical rows.
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <mutex>
#include <random>
#include <set>
#include <signal.h>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "app/sweep/sweep_engine.h"
#include "app/sweep/sweep_journal.h"
#include "base/logging.h"
#include "io/scene_io.h"
#include "io/summary.h"
#include "io/units.h"
#include "tests/support/files.h"
#include "tests/support/hdf5_reader.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::testing::Hdf5Reader;
  using kimp::testing::read_lines;
  using kimp::testing::TempDir;
  namespace fs = std::filesystem;
  using kimp::app::CaseRow;
  using kimp::app::SweepOptions;
  using kimp::app::SweepPlan;

  struct ToyScene
  {
    double      gap    = 0.15;
    double      cor    = 0.7;
    std::string record = "kobe";
  };
  template <class Io>
  void visit(Io &io, ToyScene &s)
  {
    io.quantity("gap", s.gap, "cm", "gap");
    io.quantity("cor", s.cor, "", "coefficient of restitution");
    io.text("record", s.record, "record");
  }

  /// A deterministic stand-in for a pounding run: metrics are closed-form functions of the scene;
  /// a gap of 13 cm fails like an unstable time step would.
  CaseRow toy_run(const std::string &text, const std::string &name)
  {
    const ToyScene s = kimp::io::load_scene_text<ToyScene>(text, name);
    if (std::abs(s.gap - 0.13) < 1e-9)
      throw std::runtime_error("time step above the stability limit (gap 13 cm)");
    const double peak = 1.0 / s.gap + s.cor + static_cast<double>(s.record.size());
    return {{{"peak_acceleration [m/s^2]", peak}, {"n_impacts", std::floor(10 * s.cor)}}, "ok"};
  }

  const std::string toy_base = "gap: 15 cm\ncor: 0.7\nrecord: kobe\n";

  SweepPlan toy_plan()
  {
    return SweepPlan::parse("scene: toy.yaml\n"
                            "parameters:\n"
                            "  gap: {from: 10 cm, to: 19 cm, step: 1 cm}\n"
                            "  record: [kobe, sylmar]\n"
                            "  cor: [0.3, 0.7]\n",
                            "toy_sweep.yaml",
                            toy_base,
                            "toy.yaml");
  }

  /// CSV rows without the last column (wall time differs between runs).
  std::vector<std::string> rows_without_wall_time(const fs::path &dir)
  {
    std::vector<std::string> rows = read_lines(dir / "sweep.csv");
    for (std::string &row : rows)
      row = row.substr(0, row.rfind(','));
    return rows;
  }

  std::size_t count_lines(const fs::path &file)
  {
    return read_lines(file).size();
  }

  SweepOptions options(unsigned int threads)
  {
    SweepOptions o;
    o.threads = threads;
    return o;
  }

  class SweepEngine : public ::testing::Test
  {
  protected:
    void SetUp() override { kimp::base::set_verbosity(kimp::base::Verbosity::quiet); }

    /// A fresh folder "sweep" in a temporary directory tagged `tag` that lives as long as the
    /// test: where one sweep writes.
    fs::path sweep_folder(const std::string &tag)
    {
      return temps.emplace_back(tag).path() / "sweep";
    }

    const SweepPlan     plan = toy_plan();
    std::deque<TempDir> temps;
  };

  TEST_F(SweepEngine, EveryCaseGivesOneRowSortedByIndexAndFailuresAreRecorded)
  {
    const fs::path dir     = sweep_folder("sweep_clean");
    const auto     summary = kimp::app::run_sweep(plan, toy_run, dir, options(2));
    ASSERT_EQ(plan.cases().size(), 40U);
    EXPECT_EQ(summary.n_run, 40U);
    EXPECT_EQ(summary.n_failed, 4U) << "gap 13 cm x 2 records x 2 COR fail";
    EXPECT_EQ(summary.n_rows, 40U);

    const auto table = kimp::app::collect_sweep_table(plan, dir);
    ASSERT_EQ(table.rows.size(), 40U);
    ASSERT_EQ(table.metric_names,
              (std::vector<std::string>{"peak_acceleration [m/s^2]", "n_impacts"}));
    constexpr double tolerance = 1e-12;
    for (std::size_t i = 0; i < table.rows.size(); ++i)
    {
      const auto &row = table.rows[i];
      EXPECT_EQ(row.index, i);
      EXPECT_EQ(row.id, plan.cases()[i].id);
      if (row.values[0] == "13 cm")
      {
        EXPECT_EQ(row.status.rfind("failed: ", 0), 0U) << row.status;
        EXPECT_NE(row.status.find("stability limit"), std::string::npos) << row.status;
        EXPECT_TRUE(std::isnan(row.metrics[0]));
        continue;
      }
      EXPECT_EQ(row.status, "ok");
      const double gap = kimp::io::parse_quantity_as(row.values[0], "m");
      const double cor = std::stod(row.values[2]);
      EXPECT_NEAR(row.metrics[0],
                  1.0 / gap + cor + static_cast<double>(row.values[1].size()),
                  tolerance)
        << "row " << i << " gap " << row.values[0];
    }
    const auto csv = read_lines(dir / "sweep.csv");
    ASSERT_EQ(csv.size(), 41U);
    EXPECT_EQ(csv[0],
              "index,id,companion,gap_cm,record,cor,status,peak_acceleration_m_per_s2,n_impacts,"
              "wall_time_s");
    // The gap in the unit of its values (numbers only in numeric columns).
    EXPECT_EQ(csv[1].rfind("0," + plan.cases()[0].id + ",,10,kobe,0.3,ok,", 0), 0U) << csv[1];
  }

  TEST_F(SweepEngine, Hdf5TableHasOneRowPerCaseWithUnits)
  {
    const fs::path dir = sweep_folder("sweep_h5");
    kimp::app::run_sweep(plan, toy_run, dir, options(1));
    const Hdf5Reader file(dir / "sweep.h5");
    ASSERT_GE(file.id(), 0);
    const auto n_rows_of = [&](const char *path)
    {
      EXPECT_TRUE(file.exists(path)) << path;
      return file.dims(path).at(0);
    };
    EXPECT_EQ(n_rows_of("/sweep/index"), 40U);
    EXPECT_EQ(n_rows_of("/sweep/status"), 40U);
    EXPECT_EQ(n_rows_of("/sweep/id"), 40U);
    EXPECT_EQ(n_rows_of("/sweep/parameters/record"), 40U);
    EXPECT_EQ(n_rows_of("/sweep/metrics/peak_acceleration"), 40U);

    // The gap parameter is also stored in SI with its unit; 10 cm = 0.1 m in the first row.
    const std::string gap = "/sweep/parameters_si/gap";
    ASSERT_TRUE(file.exists(gap));
    const std::vector<double> values    = file.doubles(gap);
    constexpr double          tolerance = 1e-15;
    EXPECT_NEAR(values[0], 0.1, tolerance);
    EXPECT_NEAR(values[39], 0.19, tolerance);
    const std::string units = file.units(gap);
    ASSERT_NE(units, "<missing>");
    EXPECT_STREQ(units.c_str(), "m");
    EXPECT_FALSE(fs::exists(dir / "sweep.h5.partial"));
  }

  TEST_F(SweepEngine, ResumeAfterSigkillGivesTheRowsOfAnUninterruptedRun)
  {
    const fs::path clean = sweep_folder("sweep_reference");
    kimp::app::run_sweep(plan, toy_run, clean, options(2));

    const fs::path killed  = sweep_folder("sweep_killed");
    const fs::path journal = kimp::app::SweepJournal::file_of(killed, 0);
    const pid_t    child   = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0)
    {
      // Slow enough (20 ms per case, 40 cases, 2 threads) to be killed mid-sweep.
      const auto slow = [](const std::string &text, const std::string &name)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return toy_run(text, name);
      };
      try
      {
        kimp::app::run_sweep(plan, slow, killed, options(2));
      }
      catch (...)
      {
        ::_exit(2);
      }
      ::_exit(0);
    }
    constexpr std::size_t min_lines_before_kill = 6;
    const auto            give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (count_lines(journal) < min_lines_before_kill &&
           std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child finished before it was killed";

    const auto            before = kimp::app::SweepJournal::read_all(killed);
    std::set<std::string> finished;
    for (const auto &entry : before.entries)
      finished.insert(entry.id);
    ASSERT_GE(finished.size(), min_lines_before_kill);
    ASSERT_LT(finished.size(), plan.cases().size());

    std::mutex               calls_mutex;
    std::vector<std::string> recomputed;
    std::atomic<std::size_t> n_calls{0};
    const auto               counting = [&](const std::string &text, const std::string &name)
    {
      ++n_calls;
      const ToyScene s = kimp::io::load_scene_text<ToyScene>(text, name);
      (void)s;
      for (const auto &c : plan.cases())
        if (c.scene_name == name && finished.count(c.id) > 0)
        {
          const std::lock_guard<std::mutex> lock(calls_mutex);
          recomputed.push_back(c.id);
        }
      return toy_run(text, name);
    };
    const auto summary = kimp::app::run_sweep(plan, counting, killed, options(2));
    EXPECT_EQ(n_calls.load(), plan.cases().size() - finished.size())
      << finished.size() << " cases were finished before the kill";
    EXPECT_TRUE(recomputed.empty()) << "recomputed " << recomputed.size() << " finished cases";
    EXPECT_EQ(summary.n_resumed, finished.size());
    EXPECT_EQ(rows_without_wall_time(killed), rows_without_wall_time(clean));

    // A third call finds everything finished and rewrites the same rows.
    n_calls = 0;
    kimp::app::run_sweep(plan, counting, killed, options(2));
    EXPECT_EQ(n_calls.load(), 0U);
    EXPECT_EQ(rows_without_wall_time(killed), rows_without_wall_time(clean));
  }

  TEST_F(SweepEngine, TornJournalLineIsIgnoredAndItsCaseRerun)
  {
    const fs::path          dir  = sweep_folder("sweep_torn");
    const fs::path          file = kimp::app::SweepJournal::file_of(dir, 0);
    kimp::app::JournalEntry first;
    first.index = 0;
    first.id    = plan.cases()[0].id;
    first.row   = toy_run(plan.cases()[0].scene_text, "first");
    {
      kimp::app::SweepJournal journal(file);
      journal.append(first);
    }
    kimp::app::JournalEntry second = first;
    second.index                   = 1;
    second.id                      = plan.cases()[1].id;
    const std::string line         = kimp::app::SweepJournal::to_line(second);
    {
      std::ofstream out(file, std::ios::app);
      out << line.substr(0, line.size() / 2); // crash in the middle of the write
    }
    const auto contents = kimp::app::SweepJournal::read_all(dir);
    ASSERT_EQ(contents.entries.size(), 1U);
    EXPECT_EQ(contents.n_torn_lines, 1U);

    std::atomic<std::size_t> n_calls{0};
    const auto               counting = [&](const std::string &text, const std::string &name)
    {
      ++n_calls;
      return toy_run(text, name);
    };
    const auto summary = kimp::app::run_sweep(plan, counting, dir, options(2));
    EXPECT_EQ(summary.n_torn_lines, 1U);
    EXPECT_EQ(summary.n_resumed, 1U);
    EXPECT_EQ(n_calls.load(), plan.cases().size() - 1);
    EXPECT_EQ(summary.n_rows, plan.cases().size());
    // The fragment stays on a line of its own; every later line is complete.
    const auto after = kimp::app::SweepJournal::read_all(dir);
    EXPECT_EQ(after.n_torn_lines, 1U);
    EXPECT_EQ(after.entries.size(), plan.cases().size());
  }

  TEST_F(SweepEngine, DuplicateEntriesMergeToOneRowPreferringOk)
  {
    const fs::path dir = sweep_folder("sweep_duplicates");
    kimp::app::run_sweep(plan, toy_run, dir, options(1));
    {
      // The same case journaled again by another rank, once failed and once ok.
      kimp::app::SweepJournal other(kimp::app::SweepJournal::file_of(dir, 7));
      kimp::app::JournalEntry entry;
      entry.index = 3;
      entry.id    = plan.cases()[3].id;
      entry.row   = CaseRow{{}, "failed: duplicate"};
      other.append(entry);
      entry.row = toy_run(plan.cases()[3].scene_text, "again");
      other.append(entry);
      entry.id = "3-0000000000000000"; // a case of another sweep file: ignored
      other.append(entry);
    }
    const auto table = kimp::app::collect_sweep_table(plan, dir);
    ASSERT_EQ(table.rows.size(), plan.cases().size());
    std::set<std::string> ids;
    for (const auto &row : table.rows)
      ids.insert(row.id);
    EXPECT_EQ(ids.size(), table.rows.size());
    EXPECT_EQ(table.rows[3].status, "ok");
  }

  TEST_F(SweepEngine, RetryFailedRerunsOnlyFailedCases)
  {
    const fs::path dir = sweep_folder("sweep_retry");
    kimp::app::run_sweep(plan, toy_run, dir, options(2));
    std::atomic<std::size_t> n_calls{0};
    const auto               healed = [&](const std::string &text, const std::string &name)
    {
      ++n_calls;
      ToyScene s = kimp::io::load_scene_text<ToyScene>(text, name);
      return CaseRow{{{"peak_acceleration [m/s^2]", 1.0 / s.gap}}, "ok"};
    };
    SweepOptions retry = options(2);
    retry.retry_failed = true;
    kimp::app::run_sweep(plan, healed, dir, retry);
    EXPECT_EQ(n_calls.load(), 4U);
    const auto table = kimp::app::collect_sweep_table(plan, dir);
    for (const auto &row : table.rows)
      EXPECT_EQ(row.status, "ok") << row.id;
  }

  /// Two "ranks" as threads of one process, meeting at a barrier before rank 0 merges.
  TEST_F(SweepEngine, OneAndTwoRanksGiveIdenticalRows)
  {
    const fs::path one = sweep_folder("sweep_one_rank");
    kimp::app::run_sweep(plan, toy_run, one, options(1));

    const fs::path          two = sweep_folder("sweep_two_ranks");
    std::mutex              mutex;
    std::condition_variable arrived;
    int                     n_arrived = 0;
    const auto              barrier   = [&]()
    {
      std::unique_lock<std::mutex> lock(mutex);
      if (++n_arrived == 2)
        arrived.notify_all();
      arrived.wait(lock, [&] { return n_arrived == 2; });
    };
    std::vector<kimp::app::SweepSummary> summaries(2);
    std::vector<std::thread>             ranks;
    for (int rank = 0; rank < 2; ++rank)
      ranks.emplace_back(
        [&, rank]()
        {
          SweepOptions o                            = options(1);
          o.rank                                    = rank;
          o.n_ranks                                 = 2;
          o.barrier                                 = barrier;
          summaries[static_cast<std::size_t>(rank)] = kimp::app::run_sweep(plan, toy_run, two, o);
        });
    for (std::thread &rank : ranks)
      rank.join();
    EXPECT_EQ(summaries[0].n_run, 20U);
    EXPECT_EQ(summaries[1].n_run, 20U);
    EXPECT_EQ(summaries[0].n_rows, 40U);
    EXPECT_TRUE(fs::exists(kimp::app::SweepJournal::file_of(two, 1)));
    EXPECT_EQ(rows_without_wall_time(two), rows_without_wall_time(one));
  }

  TEST_F(SweepEngine, MergeWithoutFinishedCasesWritesEmptyTables)
  {
    const fs::path dir   = sweep_folder("sweep_empty");
    const auto     table = kimp::app::collect_sweep_table(plan, dir);
    EXPECT_TRUE(table.rows.empty());
    ASSERT_NO_THROW(kimp::app::write_sweep_results(plan, table, dir));
    EXPECT_EQ(read_lines(dir / "sweep.csv").size(), 1U) << "header only";
    EXPECT_TRUE(fs::exists(dir / "sweep.h5"));
  }

  TEST(SweepMetricUnit, NameAndUnitAreSplitAtTheLastBracket)
  {
    EXPECT_EQ(kimp::app::split_metric_unit("v [m/s]"),
              (std::pair<std::string, std::string>{"v", "m/s"}));
    EXPECT_EQ(kimp::app::split_metric_unit("n_impacts"),
              (std::pair<std::string, std::string>{"n_impacts", "1"}));
  }

  TEST(SweepJournalLine, UnreadableJournalIsNamedInTheError)
  {
    const TempDir  temp_dir("journal_dir");
    const fs::path dir = temp_dir.path();
    fs::create_directories(dir / "journal/rank-1.jsonl"); // a directory where a file belongs
    try
    {
      kimp::app::SweepJournal::read_all(dir);
      ADD_FAILURE() << "a directory in place of a journal file was accepted";
    }
    catch (const kimp::io::OutputError &error)
    {
      EXPECT_NE(std::string(error.what()).find("rank-1.jsonl"), std::string::npos) << error.what();
    }
  }

  TEST(SweepJournalLine, RoundTripKeepsMetricsAndNan)
  {
    std::mt19937                           random(42);
    std::uniform_real_distribution<double> value(-1e6, 1e6);
    kimp::app::JournalEntry                entry;
    entry.index       = 17;
    entry.id          = "17-00000000deadbeef";
    entry.wall_time   = 0.25;
    entry.rank        = 3;
    entry.row.metrics = {{"a [m]", value(random)},
                         {"b", std::nan("")},
                         {"c \"quoted\"", value(random)}};
    kimp::app::JournalEntry back;
    ASSERT_TRUE(kimp::app::SweepJournal::from_line(kimp::app::SweepJournal::to_line(entry), back));
    EXPECT_EQ(back.index, entry.index);
    EXPECT_EQ(back.id, entry.id);
    EXPECT_EQ(back.rank, entry.rank);
    ASSERT_EQ(back.row.metrics.size(), 3U);
    EXPECT_EQ(back.row.metrics[0], entry.row.metrics[0]) << "doubles must round-trip exactly";
    EXPECT_TRUE(std::isnan(back.row.metrics[1].second));
    EXPECT_EQ(back.row.metrics[2], entry.row.metrics[2]);
    EXPECT_FALSE(kimp::app::SweepJournal::from_line("{\"index\": 3, \"id\": ", back));
  }
} // namespace
