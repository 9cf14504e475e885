// PEER AT2 / two-column readers: every record of ../shared/data/records against its README row
// (NPTS, DT, PGA in g), every format quirk of that README, and one clear error per malformed file.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <initializer_list>
#include <map>
#include <optional>
#include <random>
#include <string>

#include "io/at2_reader.h"
#include "io/records.h"
#include "io/units.h"
#include "tests/support/messages.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using kimp::io::GroundMotionFileError;
  using kimp::io::standard_gravity;

  /// README PGA values are rounded to 4 decimals of g.
  constexpr double pga_tolerance_g = 0.5e-4 + 1e-12;
  /// Values parsed from decimal text are exact to a few ulps.
  constexpr double value_rel_tolerance = 1e-14;

  struct RecordRow
  {
    std::size_t npts;
    double      dt;    // s
    double      pga_g; // max |a| in g
    bool        pga_negative;
  };

  // The records' published header values (NPTS, DT, PGA in g; the PGA is negative in all but
  // RSN77), as listed in docs/physics.md "Ground-motion records".
  const std::map<std::string, RecordRow> readme_rows = {
    {"RSN1106_KOBE_KJM000.AT2", {7500, 0.02, 0.8342, true}},
    {"SCS142.AT2", {8000, 0.005, 0.8972, true}},
    {"RSN1084_NORTHR_SCS142.AT2", {8773, 0.005, 0.9234, true}},
    {"RSN77_SFERN_PUL164.AT2", {4172, 0.01, 1.2190, false}},
    {"IELC180.AT2", {4000, 0.01, 0.3129, true}},
    {"I-ELC180.AT2", {4000, 0.01, 0.3129, true}},
    {"RSN6_IMPVALL.I_I-ELC180.AT2", {5372, 0.01, 0.2808, true}},
  };

  /// KIMP_RECORDS_DIR, else ./../shared/data/records (ctest runs in the source directory), else
  /// $KIMP_SOURCE_DIR/../shared/data/records: the resolution order of io/records.h.
  std::optional<fs::path> records_folder()
  {
    const char *source = std::getenv("KIMP_SOURCE_DIR");
    return kimp::io::records_directory(std::nullopt,
                                       source ? std::optional<fs::path>(source) : std::nullopt);
  }

  using kimp::testing::TempDir;

  template <class Function>
  std::string file_error(Function &&function)
  {
    try
    {
      function();
    }
    catch (const GroundMotionFileError &error)
    {
      return error.what();
    }
    catch (const std::exception &error)
    {
      ADD_FAILURE() << "wrong exception type: " << error.what();
      return error.what();
    }
    ADD_FAILURE() << "no exception thrown";
    return {};
  }

  /// The error of read_at2() on `content` written to the file `name` in `dir`.
  std::string at2_error(const TempDir &dir, const std::string &name, const std::string &content)
  {
    return file_error([&] { kimp::io::read_at2(dir.write(name, content)); });
  }

  using kimp::testing::expect_contains;

  const std::string header3 = "PEER NGA STRONG MOTION DATABASE RECORD\n"
                              "Northridge-01, 1/17/1994, Sylmar #74 / 142, 5 POLE @ 30 HZ\n"
                              "ACCELERATION TIME SERIES IN UNITS OF G\n";

  void ExpectValuesInG(const kimp::io::AccelerationRecord &motion,
                       const std::vector<double>          &expected_g)
  {
    ASSERT_EQ(motion.acceleration.size(), expected_g.size()) << motion.name;
    for (std::size_t i = 0; i < expected_g.size(); ++i)
      EXPECT_NEAR(motion.acceleration[i],
                  expected_g[i] * standard_gravity,
                  value_rel_tolerance * std::abs(expected_g[i] * standard_gravity))
        << "value " << i << " of " << motion.name;
  }

  /// Expects read_at2() of `content` written to the file `name` to give the time step `dt` (s)
  /// and the values `expected_g` (in g).
  void expect_at2(const std::string         &name,
                  const std::string         &content,
                  double                     dt,
                  const std::vector<double> &expected_g)
  {
    const TempDir dir;
    const auto    motion = kimp::io::read_at2(dir.write(name, content));
    EXPECT_DOUBLE_EQ(motion.dt, dt);
    ExpectValuesInG(motion, expected_g);
  }

} // namespace

TEST(At2Records, EveryRecordMatchesItsReadmeRow)
{
  const auto folder = records_folder();
  if (!folder)
    GTEST_SKIP() << "records folder absent: set KIMP_RECORDS_DIR or provide "
                    "$KIMP_SOURCE_DIR/../shared/data/records";
  std::size_t n_checked = 0;
  for (const auto &entry : fs::directory_iterator(*folder))
  {
    if (entry.path().extension() != ".AT2")
      continue;
    const std::string name = entry.path().filename().string();
    const auto        row  = readme_rows.find(name);
    if (row == readme_rows.end())
    {
      ADD_FAILURE() << name << " has no row in this test's copy of the README table";
      continue;
    }
    const auto motion = kimp::io::read_at2(entry.path());
    EXPECT_EQ(motion.acceleration.size(), row->second.npts) << name;
    EXPECT_DOUBLE_EQ(motion.dt, row->second.dt) << name;
    EXPECT_EQ(motion.name, entry.path().stem().string());
    const auto peak =
      std::max_element(motion.acceleration.begin(),
                       motion.acceleration.end(),
                       [](double a, double b) { return std::abs(a) < std::abs(b); });
    EXPECT_NEAR(std::abs(*peak) / standard_gravity, row->second.pga_g, pga_tolerance_g) << name;
    EXPECT_EQ(*peak < 0.0, row->second.pga_negative) << name << " peak " << *peak;
    ++n_checked;
  }
  EXPECT_EQ(n_checked, readme_rows.size()) << "records in " << *folder;
}

TEST(At2Records, FirstAndLastValuesAreReadInOrder)
{
  const auto folder = records_folder();
  if (!folder)
    GTEST_SKIP() << "records folder absent";
  // Values copied from the files' first and last data lines.
  const auto elc = kimp::io::read_at2(*folder / "IELC180.AT2");
  EXPECT_DOUBLE_EQ(elc.acceleration.front(), -.6403182E-02 * standard_gravity);
  EXPECT_DOUBLE_EQ(elc.acceleration.back(), .9459335E-04 * standard_gravity);
  const auto pacoima = kimp::io::read_at2(*folder / "RSN77_SFERN_PUL164.AT2");
  EXPECT_DOUBLE_EQ(pacoima.acceleration.back(), -.3428101E-03 * standard_gravity);
  const auto kobe = kimp::io::read_at2(*folder / "RSN1106_KOBE_KJM000.AT2");
  EXPECT_DOUBLE_EQ(kobe.acceleration.front(), -.1416764E-03 * standard_gravity);
  EXPECT_DOUBLE_EQ(kobe.acceleration.back(), .1754978E-04 * standard_gravity);
  const auto scs = kimp::io::read_at2(*folder / "RSN1084_NORTHR_SCS142.AT2");
  EXPECT_DOUBLE_EQ(scs.acceleration.back(), -.6728563E-03 * standard_gravity);
}

TEST(At2Records, SixAndSevenDigitElCentroCopiesAgree)
{
  const auto folder = records_folder();
  if (!folder)
    GTEST_SKIP() << "records folder absent";
  // I-ELC180 writes 6 significant digits, IELC180 7: same data to half a unit in the 6th digit.
  const auto six   = kimp::io::read_at2(*folder / "I-ELC180.AT2");
  const auto seven = kimp::io::read_at2(*folder / "IELC180.AT2");
  ASSERT_EQ(six.acceleration.size(), seven.acceleration.size());
  for (std::size_t i = 0; i < six.acceleration.size(); ++i)
    ASSERT_LE(std::abs(six.acceleration[i] - seven.acceleration[i]),
              0.51e-5 * std::abs(seven.acceleration[i]) + 1e-15)
      << "sample " << i << ": " << six.acceleration[i] << " vs " << seven.acceleration[i];
}

TEST(At2Format, TouchingFortranFieldsAndExponentLetters)
{
  expect_at2("touching.AT2",
             header3 + "NPTS=    8, DT= .0100 SEC\n"
                       "-.1E-02-.2E-02 .3E-02.4E-02\n"
                       "  .5E-02\t-6.0D-03 +7E+00 .8123-105\n",
             0.01,
             {-0.001, -0.002, 0.003, 0.004, 0.005, -0.006, 7.0, 0.8123e-105});
}

TEST(At2Format, CrlfNoCommaPaddingAndPartialLastLine)
{
  expect_at2("crlf.AT2",
             "PEER NGA STRONG MOTION DATABASE RECORD\r\nKobe Japan, 1/16/1995, KJMA, 0\r\n"
             "ACCELERATION TIME SERIES IN UNITS OF G\r\n"
             "NPTS=   7  DT=   .0200 SEC,                          \r\n"
             "  -.1416764E-03  -.1418977E-03  -.1421037E-03  -.1423125E-03  -.1425214E-03\r\n"
             "   .1735176E-04   .1754978E-04          \r\n",
             0.02,
             {-.1416764E-03,
              -.1418977E-03,
              -.1421037E-03,
              -.1423125E-03,
              -.1425214E-03,
              .1735176E-04,
              .1754978E-04});
}

TEST(At2Format, ClassicMacLineEndings)
{
  const TempDir dir;
  const auto    file =
    dir.write("cr.AT2", header3 + "NPTS=  3, DT= .0100 SEC\r -.1E-02 .2E-02\r .3E-02\r");
  const auto motion = kimp::io::read_at2(file);
  ExpectValuesInG(motion, {-0.001, 0.002, 0.003});
  const auto msg = at2_error(dir, "cr_bad.AT2", header3 + "NPTS= 2, DT= .01\r .1\r x\r");
  expect_contains(msg, {"cr_bad.AT2:6:", "non-numeric token \"x\""});
}

TEST(At2Format, NumbersFirstNptsLine)
{
  expect_at2("numbers_first.AT2",
             "PEER NGA STRONG MOTION DATABASE RECORD\n"
             "IMPERIAL VALLEY 5/19/40 0439, EL CENTRO ARRAY #9, 180\n"
             "ACCELERATION TIME HISTORY IN UNITS OF G\n"
             "3    0.0100    NPTS, DT\n"
             "  -0.640318E-02  -0.602871E-02   0.530416E-03\n",
             0.01,
             {-0.640318E-02, -0.602871E-02, 0.530416E-03});
}

TEST(At2Format, FilterTextAfterDtAndDigitsInHeaderAreIgnored)
{
  // Header lines full of numbers; the NPTS line ends with filter corners that are numbers too.
  expect_at2("filter.AT2",
             "PEER 1994 11 22 33\nNorthridge-01, 1/17/1994, 142, 74 # 5\nUNITS OF G 9.81 1.0E+00\n"
             "NPTS=   2, DT=   .0050 SEC,   4 POLE @    30.00000 HZ,  -5 POLE @      .23000\n"
             "   .2846611E-02   .2830781E-02",
             0.005,
             {.2846611E-02, .2830781E-02});
}

TEST(At2Errors, EmptyFile)
{
  const TempDir dir;
  for (const std::string &content : {std::string(), std::string("  \n\n \r\n")})
  {
    const auto msg = at2_error(dir, "empty.AT2", content);
    expect_contains(msg, {"empty.AT2:1:", "empty file", "expected 3 header lines"});
  }
}

TEST(At2Errors, BinaryJunk)
{
  const TempDir     dir;
  const std::string junk = header3 + "NPTS= 2, DT= .01 SEC\n .1E-02\n" +
                           std::string("\x7f\x45\x4c\x46\x02\x01\x00\x00\xff\xfe", 10);
  const auto msg = at2_error(dir, "junk.AT2", junk);
  expect_contains(msg, {"junk.AT2:6:", "binary data", "0x7f", "column 1", "expected a text file"});
}

TEST(At2Errors, TruncatedFilesAndValueCountsOtherThanNpts)
{
  const TempDir dir;
  struct Case
  {
    std::string              file, content;
    std::vector<std::string> expected;
    std::string              absent; ///< a part the message must not contain, if any
  };
  const Case cases[] = {
    {"cut.AT2",
     "PEER NGA STRONG MOTION DATABASE RECORD\nKobe",
     {"cut.AT2:2:", "truncated", "before any NPTS/DT line", "NPTS="},
     ""},
    // Cut in the middle of the 5th value: no final newline; 4.5 of 6 values.
    {"cut_data.AT2",
     header3 + "NPTS= 6, DT= .01 SEC\n .1E-02 .2E-02 .3E-02\n .4E-02 .51",
     {"cut_data.AT2:6:",
      "fewer values than NPTS",
      "5 of NPTS = 6",
      "expected 1 more",
      "last line has no newline"},
     ""},
    {"fewer.AT2",
     header3 + "NPTS= 7, DT= .01 SEC\n .1E-02 .2E-02 .3E-02 .4E-02 .5E-02\n .6E-02\n\n",
     {"fewer.AT2:7:", "fewer values than NPTS", "6 of NPTS = 7"},
     "no newline"},
    {"more.AT2",
     header3 + "NPTS= 5, DT= .01 SEC\n .1E-02 .2E-02 .3E-02 .4E-02 .5E-02\n .6E-02\n",
     {"more.AT2:6:", "more values than NPTS = 5", "value 6"},
     ""},
  };
  for (const Case &c : cases)
  {
    SCOPED_TRACE(c.file);
    const auto msg = at2_error(dir, c.file, c.content);
    expect_contains(msg, c.expected);
    if (!c.absent.empty())
    {
      EXPECT_EQ(msg.find(c.absent), std::string::npos) << msg;
    }
  }
}

TEST(At2Errors, NonNumericTokenIsQuoted)
{
  const TempDir dir;
  for (const char *bad : {"abc", "NaN", ".1E-0x", "1.0E", "1,2"})
  {
    const auto msg =
      at2_error(dir, "text.AT2", header3 + "NPTS= 3, DT= .01 SEC\n .1E-02 " + bad + " .3E-02\n");
    expect_contains(msg,
                    {"text.AT2:5:",
                     std::string("non-numeric token \"") + bad + "\"",
                     "column 9",
                     "expected numbers in Fortran E format"});
  }
}

TEST(At2Errors, NoNptsLine)
{
  const TempDir dir;
  std::string   content = header3;
  for (int i = 0; i < 10; ++i)
    content += " .1E-02 .2E-02 .3E-02 .4E-02 .5E-02\n";
  const auto msg = at2_error(dir, "headerless.AT2", content);
  expect_contains(msg, {"headerless.AT2:10:", "no NPTS/DT line in lines 1-10", "NPTS="});
}

TEST(At2Errors, NptsAndDtMustBePositive)
{
  const TempDir dir;
  struct Case
  {
    std::string line, expected;
  };
  for (const Case &c : {Case{"NPTS=     0, DT= .01 SEC", "NPTS = \"0\""},
                        Case{"NPTS=    -5, DT= .01 SEC", "NPTS = \"-5\""},
                        Case{"NPTS= 40.5, DT= .01 SEC", "NPTS = \"40.5\""},
                        Case{"NPTS=, DT= .01 SEC", "NPTS = \"\""},
                        Case{"NPTS= 3, DT= 0.0 SEC", "DT = \"0.0\""},
                        Case{"NPTS= 3, DT= -.01 SEC", "DT = \"-.01\""},
                        Case{"NPTS= 3, DT= fast", "DT = \"fast\""},
                        Case{"0  0.01  NPTS, DT", "NPTS = \"0\""}})
  {
    const auto msg = at2_error(dir, "bad_header.AT2", header3 + c.line + "\n .1 .2 .3\n");
    expect_contains(msg, {"bad_header.AT2:4:", c.expected, "expected a positive"});
  }
}

TEST(At2Errors, MissingFileAndDirectory)
{
  const TempDir dir;
  const auto    msg = file_error([&] { kimp::io::read_at2("/nonexistent/x.AT2"); });
  expect_contains(msg, {"/nonexistent/x.AT2: cannot open"});
  const auto msg_dir = file_error([&] { kimp::io::read_at2(fs::temp_directory_path()); });
  expect_contains(msg_dir, {"is a directory"});
}

TEST(At2Errors, ErrorCarriesFileAndLine)
{
  const TempDir dir;
  const auto    file = dir.write("line.AT2", header3 + "NPTS= 2, DT= .01 SEC\n .1 x\n");
  try
  {
    kimp::io::read_at2(file);
    ADD_FAILURE() << "no exception";
  }
  catch (const GroundMotionFileError &error)
  {
    EXPECT_EQ(error.file(), file.string());
    EXPECT_EQ(error.line(), 5u);
  }
}

TEST(TwoColumn, ReadsUniformTimeSeriesWithComments)
{
  const TempDir dir;
  const auto    file   = dir.write("two.txt",
                              "# time (s)  acceleration (g)\n"
                                   "0.000  0.10\n"
                                   "0.005, -0.20   # comma separated\n"
                                   "\n"
                                   "0.010\t0.30\r\n"
                                   "0.015  4.0E-01\n");
  const auto    motion = kimp::io::read_two_column(file, standard_gravity);
  EXPECT_NEAR(motion.dt, 0.005, 1e-15);
  ExpectValuesInG(motion, {0.10, -0.20, 0.30, 0.40});
  EXPECT_EQ(motion.name, "two");
}

TEST(TwoColumn, RejectsNonUniformNonZeroStartAndBadRows)
{
  const TempDir dir;
  struct Case
  {
    std::string content, expected;
  };
  for (const Case &c :
       {Case{"0 1\n0.01 2\n0.025 3\n0.03 4\n", "bad.txt:3: time 0.025 s is"},
        Case{"0.5 1\n0.51 2\n0.52 3\n", "bad.txt:1: first time 0.5 s (expected 0"},
        Case{"0 1\n0.01 2 3\n", "bad.txt:2: 3 numbers on the line (expected 2"},
        Case{"0 1\n0.01 2\n0.01 3\n", "bad.txt:3: time 0.01 s after 0.01 s (expected strictly"},
        Case{"time accel\n0 1\n0.01 2\n", "bad.txt:1: non-numeric token \"time\""},
        Case{"# only a comment\n0 1\n", "bad.txt:2: 1 data row(s) (expected at least 2"}})
  {
    const auto msg =
      file_error([&] { kimp::io::read_two_column(dir.write("bad.txt", c.content), 1.0); });
    expect_contains(msg, {c.expected});
  }
  EXPECT_THROW(kimp::io::read_two_column(dir.write("ok.txt", "0 1\n1 2\n"), 0.0),
               std::invalid_argument);
}

TEST(GroundMotionDispatch, ChoosesTheFormatByContent)
{
  const TempDir dir;
  const auto    at2 = dir.write("a.txt", header3 + "NPTS= 2, DT= .01 SEC\n .1E+00 -.2E+00\n");
  ExpectValuesInG(kimp::io::read_ground_motion(at2), {0.1, -0.2});

  const auto two    = dir.write("b.AT2", "# t a\n0 1.5\n0.02 -2.5\n");
  const auto motion = kimp::io::read_ground_motion(two, 1.0);
  EXPECT_NEAR(motion.dt, 0.02, 1e-15);
  EXPECT_DOUBLE_EQ(motion.acceleration.at(1), -2.5);

  expect_contains(file_error([&] { kimp::io::read_ground_motion(two); }),
                  {"b.AT2:2:", "does not state its unit"});
  expect_contains(
    file_error([&] { kimp::io::read_ground_motion(dir.write("c.txt", "hello world\n1 2 3\n")); }),
    {"c.txt:1:", "neither a PEER AT2 file", "nor two-column text"});
}

TEST(At2Errors, RandomCorruptionGivesAFileErrorOrAValidRecord)
{
  // Seeded byte mutations of a valid file: every outcome is either a record with NPTS finite
  // values or a GroundMotionFileError, never another exception or a crash.
  const std::string valid    = header3 + "NPTS=    7, DT= .0100 SEC\n"
                                         "-.1E-02-.2E-02 .3E-02.4E-02  .5E-02\n"
                                         "  .6E-02  -.7E-02\n";
  const std::string alphabet = "0123456789.+-EeD ,\n\r\t\x01xNPTS=";
  std::mt19937      engine(20260101);
  std::size_t       n_parsed = 0, n_rejected = 0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    std::string corrupted = valid;
    const int   n_edits   = 1 + static_cast<int>(engine() % 3);
    for (int e = 0; e < n_edits; ++e)
    {
      const std::size_t pos = engine() % corrupted.size();
      switch (engine() % 3)
      {
        case 0:
          corrupted[pos] = alphabet[engine() % alphabet.size()];
          break;
        case 1:
          corrupted.erase(pos, 1 + engine() % 4);
          break;
        default:
          corrupted.insert(pos, 1, alphabet[engine() % alphabet.size()]);
      }
    }
    try
    {
      const auto motion = kimp::io::parse_at2(corrupted, "fuzz.AT2");
      ASSERT_GT(motion.dt, 0.0) << corrupted;
      ASSERT_FALSE(motion.acceleration.empty()) << corrupted;
      for (const double a : motion.acceleration)
        ASSERT_TRUE(std::isfinite(a)) << corrupted;
      ++n_parsed;
    }
    catch (const GroundMotionFileError &error)
    {
      ASSERT_EQ(std::string(error.what()).rfind("fuzz.AT2:", 0), 0u) << error.what();
      ++n_rejected;
    }
  }
  EXPECT_GT(n_parsed, 0u);
  EXPECT_GT(n_rejected, 0u);
}
