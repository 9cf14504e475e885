// `kimp sweep` plans of millions of cases in little memory, measured on the process: the plan
// keeps its parameters (a range as its bounds), never its cases, so `--check` of a 5 M-case sweep
// and a sweep that has started its first case stay small, and a zip of ranges of unequal length
// is refused from their lengths before anything is expanded.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <thread>

#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/messages.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  /// A sweep of data/studies/scenes/quick_scene.yaml (6 s of synthetic motion) as sweep.yaml in
  /// `dir`.
  fs::path write_sweep(const TempDir &dir, const std::string &body)
  {
    return dir.write("sweep.yaml",
                     "scene: " + (source_dir() / "data/studies/scenes/quick_scene.yaml").string() +
                       "\n" + body);
  }

  /// 2000 gaps x 2500 COR values: 5 M cases.
  const std::string five_million_cases =
    "parameters:\n"
    "  walls.left.gap, walls.right.gap: {from: 40 mm, to: 239.9 mm, step: 0.1 mm}\n"
    "  impact.cor: {from: 0.5, to: 0.7499, step: 0.0001}\n";

  /// The peak resident memory of a process in kB (VmHWM of /proc/<pid>/status), 0 if unknown.
  long peak_rss_kb(pid_t pid)
  {
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string   line;
    while (std::getline(in, line))
      if (line.rfind("VmHWM:", 0) == 0)
        return std::stol(line.substr(6));
    return 0;
  }

  constexpr long plan_budget_kb = 200 * 1024; ///< 200 MB
} // namespace

// The plan of 5 M cases, checked (every value of both parameters on the base scene, the cost
// estimate): before, preparing it took ~1.2 kB per case (393 k cases: 470 MB) and 5 M cases
// several GB.
TEST(SweepPlanMemory, FiveMillionCasesAreCheckedInLittleMemory)
{
  TempDir           dir("e2e_sweep_plan_check");
  const fs::path    sweep = write_sweep(dir, five_million_cases);
  const auto        start = std::chrono::steady_clock::now();
  const KimpProcess run   = run_kimp_process("sweep " + sweep.string() + " --check", dir.path());
  const double      seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, sweep.string() + ": valid, 5000000 cases\n");
  EXPECT_NE(run.err.find("5000000 cases"), std::string::npos) << run.err;
  EXPECT_LT(run.max_rss_kb, plan_budget_kb) << "peak " << run.max_rss_kb << " kB";
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
  std::cout << "5 M-case sweep --check: peak " << run.max_rss_kb / 1024 << " MB, " << seconds
            << " s\n";
}

// The same sweep run: when its first case is journaled, the process has planned 5 M cases and
// set up the run (journal, threads) without holding them.
TEST(SweepPlanMemory, FiveMillionCasesStartRunningInLittleMemory)
{
  TempDir        dir("e2e_sweep_plan_run");
  const fs::path sweep   = write_sweep(dir, five_million_cases);
  const fs::path out     = dir.path() / "out";
  const fs::path journal = out / "journal" / "rank-0.jsonl";
  const pid_t    pid =
    start_kimp("sweep " + sweep.string() + " -o " + out.string() + " -t 1 --no-charts",
               dir.path() / "log.txt");
  bool journaled = false;
  for (int i = 0; i < 1200 && !journaled; ++i)
  {
    journaled = exists_now(journal) && fs::file_size(journal) > 0;
    if (!journaled)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const long peak = peak_rss_kb(pid);
  kill_hard(pid);
  ASSERT_TRUE(journaled) << read_text(dir.path() / "log.txt");
  ASSERT_GT(peak, 0) << "no /proc/" << pid << "/status";
  EXPECT_LT(peak, plan_budget_kb) << "peak " << peak << " kB";
  std::cout << "5 M-case sweep at its first journal line: peak " << peak / 1024 << " MB\n";
}

// Two zipped ranges of 8 M and 10 M values: refused from their lengths alone, in one line. Before,
// both were expanded first (2.4 GB) and the error came after many seconds.
TEST(SweepPlanMemory, ZipOfUnequalLengthsIsFoundBeforeExpanding)
{
  TempDir           dir("e2e_sweep_plan_zip");
  const fs::path    sweep = write_sweep(dir,
                                     "combine: zip\n"
                                        "parameters:\n"
                                        "  walls.left.gap: {from: 1 mm, to: 8000000 mm, step: 1 mm}\n"
                                        "  impact.cor: {from: 1, to: 10000000, step: 1}\n");
  const KimpProcess run   = run_kimp_process("sweep " + sweep.string() + " -o out", dir.path());
  std::string       line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_EQ(line,
            "error: " + sweep.string() +
              ":5: parameters.impact.cor: 10000000 values, but walls.left.gap has 8000000 "
              "(combine: zip needs equal lengths)");
  EXPECT_LT(run.max_rss_kb, 100 * 1024) << "peak " << run.max_rss_kb << " kB";
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}
