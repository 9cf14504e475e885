// Records directory priority (flag > KIMP_RECORDS_DIR > ./../shared/data/records >
// <source>/../shared/data/records) and record lookup by bare name or path.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <optional>
#include <ostream>
#include <string>

#include "io/at2_reader.h"
#include "io/records.h"
#include "io/units.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using kimp::io::standard_gravity;

  /// Two trees, each with ../shared/data/records next to a "repo" directory, plus a loose dir.
  class RecordsTree : public ::testing::Test
  {
  protected:
    void SetUp() override
    {
      root_ = temp_dir_.path();
      for (const char *tree : {"cwd_tree", "source_tree"})
      {
        fs::create_directories(root_ / tree / "repo");
        fs::create_directories(root_ / tree / "shared/data/records");
      }
      fs::create_directories(root_ / "explicit");
      fs::create_directories(root_ / "from_env");
      fs::create_directories(root_ / "empty_tree/repo");
    }

    fs::path write_at2(const fs::path &directory, const std::string &name, double value_g) const
    {
      const fs::path file = directory / name;
      std::ofstream  out(file, std::ios::binary);
      out << "PEER TEST RECORD\nTest station, 1/2/2003, 45\nUNITS OF G\nNPTS=  2, DT= .0100 SEC\n"
          << "  .0000000E+00  " << value_g << "\n";
      return file;
    }

    const kimp::testing::TempDir temp_dir_{"records_test"};
    fs::path                     root_;
  };

  /// One choice of resolve_records_directory() from both trees' repo directories: the flag and
  /// KIMP_RECORDS_DIR given (directories below the tree root; no flag if null, KIMP_RECORDS_DIR
  /// set but empty, which counts as unset, if ""), and the directory it must pick.
  struct Priority
  {
    const char *name;
    const char *flag;
    const char *env;
    const char *expected;
  };

  /// The case's name in the parameter listing of a failed test.
  void PrintTo(const Priority &p, std::ostream *out)
  {
    *out << p.name;
  }

  class RecordsPriority : public RecordsTree, public ::testing::WithParamInterface<Priority>
  {
  };
} // namespace

TEST_P(RecordsPriority, TheFirstSourceGivenWins)
{
  const Priority &p    = GetParam();
  const auto      flag = p.flag ? std::optional<fs::path>(root_ / p.flag) : std::nullopt;
  const auto      env  = *p.env ? (root_ / p.env).string() : std::string();
  const auto      dir  = kimp::io::resolve_records_directory(flag,
                                                       env,
                                                       root_ / "cwd_tree/repo",
                                                       root_ / "source_tree/repo");
  ASSERT_TRUE(dir.has_value());
  EXPECT_EQ(*dir, (root_ / p.expected).lexically_normal());
}

INSTANTIATE_TEST_SUITE_P(
  RecordsTree,
  RecordsPriority,
  ::testing::Values(Priority{"ExplicitFlagWinsOverEverything", "explicit", "from_env", "explicit"},
                    Priority{"EnvironmentWinsOverDefaults", nullptr, "from_env", "from_env"},
                    Priority{"CurrentDirectoryWinsOverSourceDirectory",
                             nullptr,
                             "",
                             "cwd_tree/shared/data/records"}),
  [](const ::testing::TestParamInfo<Priority> &instance)
  { return std::string(instance.param.name); });

TEST_F(RecordsTree, SourceDirectoryIsTheLastResortAndNoneGivesNothing)
{
  const auto dir = kimp::io::resolve_records_directory(std::nullopt,
                                                       std::nullopt,
                                                       root_ / "empty_tree/repo",
                                                       root_ / "source_tree/repo");
  ASSERT_TRUE(dir.has_value());
  EXPECT_EQ(*dir, (root_ / "source_tree/shared/data/records").lexically_normal());
  EXPECT_FALSE(kimp::io::resolve_records_directory(std::nullopt,
                                                   std::nullopt,
                                                   root_ / "empty_tree/repo",
                                                   std::nullopt)
                 .has_value());
  EXPECT_FALSE(kimp::io::resolve_records_directory(std::nullopt,
                                                   std::nullopt,
                                                   root_ / "empty_tree/repo",
                                                   root_ / "empty_tree/repo")
                 .has_value());
}

TEST_F(RecordsTree, WrongExplicitChoicesAreErrorsNotFallbacks)
{
  try
  {
    kimp::io::resolve_records_directory(root_ / "missing",
                                        std::nullopt,
                                        root_ / "cwd_tree/repo",
                                        std::nullopt);
    ADD_FAILURE() << "no exception for a missing flag directory";
  }
  catch (const std::invalid_argument &error)
  {
    const std::string msg = error.what();
    EXPECT_NE(msg.find("records directory = '" + (root_ / "missing").string() + "'"),
              std::string::npos)
      << msg;
    EXPECT_NE(msg.find("must be an existing directory"), std::string::npos) << msg;
  }
  try
  {
    kimp::io::resolve_records_directory(std::nullopt,
                                        (root_ / "nope").string(),
                                        root_ / "cwd_tree/repo",
                                        std::nullopt);
    ADD_FAILURE() << "no exception for a missing KIMP_RECORDS_DIR";
  }
  catch (const std::invalid_argument &error)
  {
    const std::string msg = error.what();
    EXPECT_NE(msg.find("KIMP_RECORDS_DIR = '"), std::string::npos) << msg;
  }
}

TEST_F(RecordsTree, RecordsDirectoryReadsTheEnvironment)
{
  const char *const                previous = std::getenv(kimp::io::records_dir_env_var);
  const std::optional<std::string> saved =
    previous ? std::optional<std::string>(previous) : std::nullopt;
  ASSERT_EQ(::setenv(kimp::io::records_dir_env_var, (root_ / "from_env").c_str(), 1), 0);
  const auto dir = kimp::io::records_directory(std::nullopt, root_ / "source_tree/repo");
  if (saved)
    ::setenv(kimp::io::records_dir_env_var, saved->c_str(), 1);
  else
    ::unsetenv(kimp::io::records_dir_env_var);
  ASSERT_TRUE(dir.has_value());
  EXPECT_EQ(*dir, (root_ / "from_env").lexically_normal());
}

TEST_F(RecordsTree, BareNameWithOrWithoutExtensionAndPath)
{
  const fs::path records = root_ / "explicit";
  const fs::path file    = write_at2(records, "RSN1_TEST_ABC000.AT2", 0.25);
  write_at2(records, "OTHER.AT2", 0.5);

  for (const char *name : {"RSN1_TEST_ABC000.AT2", "RSN1_TEST_ABC000"})
  {
    const auto motion = kimp::io::load_record(name, records);
    ASSERT_EQ(motion.acceleration.size(), 2u) << name;
    EXPECT_DOUBLE_EQ(motion.acceleration[1], 0.25 * standard_gravity) << name;
    EXPECT_EQ(motion.name, "RSN1_TEST_ABC000");
  }
  // A path is read as given, whatever the records directory says.
  const auto by_path = kimp::io::load_record(file.string(), std::nullopt);
  EXPECT_DOUBLE_EQ(by_path.acceleration[1], 0.25 * standard_gravity);

  const auto listed = kimp::io::list_records(records);
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].filename(), "OTHER.AT2");
  EXPECT_EQ(listed[1].filename(), "RSN1_TEST_ABC000.AT2");
}

TEST_F(RecordsTree, UnknownNameListsWhatExists)
{
  const fs::path records = root_ / "explicit";
  write_at2(records, "KOBE.AT2", 0.8);
  try
  {
    kimp::io::load_record("SAKARYA", records);
    ADD_FAILURE() << "no exception";
  }
  catch (const std::invalid_argument &error)
  {
    const std::string msg = error.what();
    for (const char *part :
         {"record = 'SAKARYA' not found in", "SAKARYA.AT2", "expected one of: KOBE.AT2"})
      EXPECT_NE(msg.find(part), std::string::npos) << msg << "\nmissing: " << part;
  }
  try
  {
    kimp::io::load_record("KOBE", std::nullopt);
    ADD_FAILURE() << "no exception";
  }
  catch (const std::invalid_argument &error)
  {
    const std::string msg = error.what();
    EXPECT_NE(msg.find("no records directory is configured"), std::string::npos) << msg;
    EXPECT_NE(msg.find("KIMP_RECORDS_DIR"), std::string::npos) << msg;
  }
}

TEST(Records, SharedKobeRecordLoadsByBareName)
{
  const char *source = std::getenv("KIMP_SOURCE_DIR");
  const auto  dir =
    kimp::io::records_directory(std::nullopt,
                                source ? std::optional<fs::path>(source) : std::nullopt);
  if (!dir || !fs::exists(*dir / "RSN1106_KOBE_KJM000.AT2"))
    GTEST_SKIP() << "records folder with RSN1106_KOBE_KJM000.AT2 absent (set KIMP_RECORDS_DIR)";
  const auto kobe = kimp::io::load_record("RSN1106_KOBE_KJM000", dir);
  EXPECT_EQ(kobe.acceleration.size(), 7500u);
  double pga = 0.0;
  for (const double a : kobe.acceleration)
    pga = std::max(pga, std::abs(a));
  EXPECT_NEAR(pga / standard_gravity, 0.8342, 0.5e-4);
}
