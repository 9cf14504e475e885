// summary.json / CSV written atomically, output directory creation.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "io/summary.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::io;
  using namespace kimp::testing;

  std::size_t n_entries(const std::filesystem::path &dir)
  {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto &entry : std::filesystem::directory_iterator(dir))
      ++n;
    return n;
  }

  TEST(Summary, JsonRoundTripsAndReplacesTheOldFile)
  {
    const TempDir  dir;
    const auto     path = dir.path() / "summary.json";
    nlohmann::json summary{{"wall_time_s", 12.5},
                           {"steps", 250000},
                           {"dofs", 18432},
                           {"k_per_m", {{"linear", 1.2e9}, {"hertz", 3.4e10}}}};
    write_json_atomic(path, summary);
    EXPECT_EQ(read_json(path), summary);
    summary["steps"] = 1;
    write_json_atomic(path, summary);
    EXPECT_EQ(read_json(path).at("steps"), 1);
    EXPECT_EQ(n_entries(dir.path()), 1u) << "no temporary file may remain";
  }

  TEST(Summary, CsvQuotesFieldsAsRfc4180)
  {
    const TempDir dir;
    const auto    path = dir.path() / "table.csv";
    write_csv_atomic(path,
                     {"case", "note"},
                     std::vector<std::vector<std::string>>{{"a,b", "say \"hi\""}, {"plain", "x"}});
    EXPECT_EQ(read_text(path), "case,note\n\"a,b\",\"say \"\"hi\"\"\"\nplain,x\n");
  }

  TEST(Summary, NumericCsvReadsBackExactly)
  {
    const TempDir                          dir;
    const auto                             path = dir.path() / "k_table.csv";
    std::mt19937                           random(11);
    std::uniform_real_distribution<double> u(-1e10, 1e10);
    std::vector<std::vector<double>>       rows(50, std::vector<double>(3));
    for (auto &row : rows)
      for (auto &v : row)
        v = u(random) * std::pow(10.0, static_cast<int>(u(random)) % 12);
    write_csv_atomic(path, {"height_m", "k_linear_N_per_m", "k_hertz_N_per_m1.5"}, rows);

    std::istringstream in(read_text(path));
    std::string        line;
    std::getline(in, line);
    EXPECT_EQ(line, "height_m,k_linear_N_per_m,k_hertz_N_per_m1.5");
    for (const auto &row : rows)
    {
      ASSERT_TRUE(std::getline(in, line));
      std::istringstream fields(line);
      for (const double expected : row)
      {
        std::string field;
        std::getline(fields, field, ',');
        EXPECT_EQ(std::strtod(field.c_str(), nullptr), expected) << "field: " << field;
      }
    }
  }

  TEST(Summary, FailedWriteKeepsTheOldFileAndLeavesNoTemporary)
  {
    const TempDir dir;
    const auto    path = dir.path() / "table.csv";
    write_csv_atomic(path, {"a", "b"}, std::vector<std::vector<double>>{{1.0, 2.0}});
    const std::string before = read_text(path);
    try
    {
      write_csv_atomic(path, {"a", "b"}, std::vector<std::vector<double>>{{1.0, 2.0}, {3.0}});
      ADD_FAILURE() << "a short row must throw";
    }
    catch (const OutputError &error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find("CSV row 2 has 1 fields, the header has 2"), std::string::npos)
        << message;
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    }
    EXPECT_EQ(read_text(path), before);
    EXPECT_EQ(n_entries(dir.path()), 1u);
    EXPECT_THROW(write_text_atomic(dir.path() / "missing_dir" / "x.json", "{}"), OutputError);
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "missing_dir"));
  }

  TEST(Summary, OutputDirCreatesDirectoriesAndRejectsFiles)
  {
    const TempDir   dir;
    const OutputDir out(dir.path() / "out" / "study");
    EXPECT_TRUE(std::filesystem::is_directory(out.path()));
    const auto mesh = out.file("mesh/H1.25.msh");
    EXPECT_EQ(mesh, out.path() / "mesh" / "H1.25.msh");
    EXPECT_TRUE(std::filesystem::is_directory(out.path() / "mesh"));
    EXPECT_FALSE(std::filesystem::exists(mesh));
    const OutputDir again(dir.path() / "out" / "study");
    EXPECT_EQ(again.path(), out.path());

    write_text_atomic(dir.path() / "a_file", "x");
    try
    {
      OutputDir bad(dir.path() / "a_file");
      ADD_FAILURE() << "a file is not an output directory";
    }
    catch (const OutputError &error)
    {
      EXPECT_NE(std::string(error.what()).find("exists and is not a directory"), std::string::npos)
        << error.what();
    }
  }

  /// The pid of a process that has ended (a child that exits at once, reaped).
  pid_t dead_pid()
  {
    const pid_t pid = ::fork();
    if (pid == 0)
      ::_exit(0);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return pid;
  }

  // Under the lock no other kimp writes into the directory: the temporary files of every other
  // process are stale, also those of a live process (a reused pid).
  TEST(Summary, StaleTemporariesOfOtherProcessesAreRemoved)
  {
    const TempDir dir;
    const auto    dead  = std::to_string(dead_pid());
    const auto    alive = std::to_string(::getppid());
    std::filesystem::create_directories(dir.path() / "fem");
    const auto orphan        = dir.write("lumped.h5.tmp-" + dead, "partial");
    const auto nested_orphan = dir.write("fem/H1.5.h5.tmp-" + dead, "partial");
    const auto running       = dir.write("summary.json.tmp-" + alive, "being written");
    const auto own           = dir.write("k_table.csv.tmp-" + std::to_string(::getpid()), "x");
    const auto not_temporary = dir.write("notes.tmp-x1", "kept");
    const auto partial_sweep = dir.write("sweep.h5.partial", "kept for resuming");

    const OutputDir out(dir.path());
    EXPECT_FALSE(std::filesystem::exists(orphan));
    EXPECT_FALSE(std::filesystem::exists(nested_orphan));
    EXPECT_FALSE(std::filesystem::exists(running));
    for (const auto &kept : {own, not_temporary, partial_sweep})
      EXPECT_TRUE(std::filesystem::exists(kept)) << kept;
  }

  TEST(Summary, OutputDirIsLockedWhileInUseAndReleasedAfter)
  {
    const TempDir dir;
    const auto    lock = dir.path() / kimp::io::output_lock_name;
    {
      const OutputDir first(dir.path() / "out");
      // The same process may name the directory again (a command and its writers).
      const OutputDir again(dir.path() / "out" / ".");
      EXPECT_TRUE(std::filesystem::exists(dir.path() / "out" / kimp::io::output_lock_name));
      EXPECT_EQ(read_text(dir.path() / "out" / kimp::io::output_lock_name),
                std::to_string(::getpid()) + "\n");
      // Another process is refused.
      const pid_t child = ::fork();
      if (child == 0)
      {
        try
        {
          const OutputDir other(dir.path() / "out");
        }
        catch (const OutputError &error)
        {
          const std::string text = error.what();
          ::_exit(text.find("is in use by another kimp (pid " + std::to_string(::getppid())) !=
                      std::string::npos ?
                    0 :
                    2);
        }
        ::_exit(1);
      }
      int status = 0;
      ::waitpid(child, &status, 0);
      EXPECT_TRUE(WIFEXITED(status));
      EXPECT_EQ(WEXITSTATUS(status), 0) << "1: not refused, 2: wrong message";
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / kimp::io::output_lock_name));
    EXPECT_FALSE(std::filesystem::exists(lock));
  }

  TEST(Summary, CsvColumnsFollowTheNameUnitConvention)
  {
    using kimp::io::csv_column;
    EXPECT_EQ(csv_column("peak_force", "N"), "peak_force_N");
    EXPECT_EQ(csv_column("peak_acceleration", "m/s^2"), "peak_acceleration_m_per_s2");
    EXPECT_EQ(csv_column("k", "kN/mm^1.5/m"), "k_kN_per_mm1.5_per_m");
    EXPECT_EQ(csv_column("damping", "N*s/m"), "damping_N_s_per_m");
    EXPECT_EQ(csv_column("cor", "1"), "cor");
    EXPECT_EQ(csv_column("n_impacts", ""), "n_impacts");
    EXPECT_EQ(csv_column("left_wall.clearance [m]"), "left_wall.clearance_m");
    EXPECT_EQ(csv_column("wall_time [s]"), "wall_time_s");
    EXPECT_EQ(csv_column("amp_drift_storey1"), "amp_drift_storey1");
    EXPECT_EQ(csv_column("ratio [1]"), "ratio");
  }
} // namespace
