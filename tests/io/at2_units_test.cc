// AT2 header units: the "UNITS OF ..." line sets the conversion to m/s²; velocity and
// displacement series, a missing unit statement and an unknown unit are refused with the file,
// the line and the header line quoted. Also two-column files, which need a caller's unit.
#include <filesystem>
#include <gtest/gtest.h>
#include <initializer_list>
#include <string>

#include "io/at2_reader.h"
#include "io/units.h"
#include "tests/support/messages.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::io::GroundMotionFileError;
  using kimp::io::parse_at2;
  using kimp::io::standard_gravity;

  std::string at2_text(const std::string &third_line)
  {
    return "PEER NGA STRONG MOTION DATABASE RECORD\n"
           "Somewhere, 1/2/2003, Station 7, 90\n" +
           third_line + "\nNPTS=    3, DT= .0100 SEC\n  .1000000E+01 -.2000000E+01  .5000000E+00\n";
  }

  std::string error_of(const std::string &content, const std::string &source = "rec.AT2")
  {
    try
    {
      parse_at2(content, source);
    }
    catch (const GroundMotionFileError &error)
    {
      return error.what();
    }
    return "";
  }

  using kimp::testing::expect_contains;

  TEST(At2Units, HeaderUnitSetsTheConversion)
  {
    struct Case
    {
      const char *line;
      double      si; // m/s² per unit
    };
    for (const Case &c : {Case{"ACCELERATION TIME SERIES IN UNITS OF G", standard_gravity},
                          Case{"ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz",
                               standard_gravity},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF CM/S/S", 0.01},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC", 0.01},
                          Case{"Acceleration time series in units of cm/s^2", 0.01},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF GAL", 0.01},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF M/S/S", 1.0},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF M/SEC**2", 1.0},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF MM/S/S", 0.001},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF IN/S/S", 0.0254},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF IN/SEC/SEC", 0.0254},
                          Case{"ACCELERATION TIME SERIES IN UNITS OF FT/S/S", 0.3048}})
    {
      SCOPED_TRACE(c.line);
      const kimp::io::AccelerationRecord r = parse_at2(at2_text(c.line), "rec.AT2");
      ASSERT_EQ(r.acceleration.size(), 3u);
      // The value in the file times the unit, exactly as one multiplication.
      EXPECT_EQ(r.acceleration[0], 1.0 * c.si);
      EXPECT_EQ(r.acceleration[1], -2.0 * c.si);
      EXPECT_EQ(r.acceleration[2], 0.5 * c.si);
    }
  }

  TEST(At2Units, VelocityAndDisplacementSeriesAreRefused)
  {
    const std::string velocity = error_of(at2_text("VELOCITY TIME SERIES IN UNITS OF CM/S"));
    expect_contains(velocity,
                    {"rec.AT2:3:",
                     "velocity series",
                     "'VELOCITY TIME SERIES IN UNITS OF CM/S'",
                     "expected an ACCELERATION time series"});
    const std::string displacement =
      error_of(at2_text("DISPLACEMENT TIME SERIES IN UNITS OF CM"), "dir/rec.DT2");
    expect_contains(
      displacement,
      {"dir/rec.DT2:3:", "displacement series", "'DISPLACEMENT TIME SERIES IN UNITS OF CM'"});
  }

  TEST(At2Units, UnknownOrMissingUnitIsRefusedNeverAssumedG)
  {
    expect_contains(error_of(at2_text("ACCELERATION TIME SERIES IN UNITS OF FURLONGS")),
                    {"rec.AT2:3:",
                     "unknown unit \"FURLONGS\"",
                     "'ACCELERATION TIME SERIES IN UNITS OF FURLONGS'",
                     "never assumes a unit"});
    // "UNITS OF" with a length unit: not an acceleration.
    expect_contains(error_of(at2_text("ACCELERATION TIME SERIES IN UNITS OF CM")),
                    {"rec.AT2:3:", "unknown unit \"CM\""});
    expect_contains(error_of(at2_text("ACCELERATION TIME SERIES")),
                    {"rec.AT2:4:", "no 'UNITS OF ...' statement", "header lines 1-3"});
    expect_contains(error_of("NPTS= 1, DT= .01 SEC\n .1\n"),
                    {"rec.AT2:1:", "no 'UNITS OF ...' statement", "no line before"});
  }

  TEST(At2Units, TwoColumnFileNeedsTheCallersUnit)
  {
    const kimp::testing::TempDir dir;
    const auto                   file = dir.write("motion.txt", "0 0.1\n0.01 -0.2\n0.02 0.3\n");
    try
    {
      kimp::io::read_ground_motion(file);
      FAIL() << "a two-column file without a unit was read";
    }
    catch (const GroundMotionFileError &error)
    {
      expect_contains(error.what(), {"motion.txt:1:", "does not state its unit", "record_unit"});
    }
    const kimp::io::AccelerationRecord r = kimp::io::read_ground_motion(file, 0.01);
    ASSERT_EQ(r.acceleration.size(), 3u);
    EXPECT_DOUBLE_EQ(r.acceleration[1], -0.002);
    EXPECT_DOUBLE_EQ(r.dt, 0.01);
  }

  TEST(At2Units, RecordUnitThatContradictsTheHeaderIsRefused)
  {
    const kimp::testing::TempDir dir;
    const auto file = dir.write("rec.AT2", at2_text("ACCELERATION TIME SERIES IN UNITS OF G"));
    try
    {
      kimp::io::read_ground_motion(file, 0.01); // record_unit cm/s^2 for a file in g
      FAIL() << "record_unit cm/s^2 was ignored for an AT2 file in g";
    }
    catch (const GroundMotionFileError &error)
    {
      expect_contains(error.what(), {"rec.AT2:4:", "9.80665", "0.01", "record_unit"});
    }
    // The header's own unit given again is no contradiction: the values are read in g.
    const kimp::io::AccelerationRecord r = kimp::io::read_ground_motion(file, standard_gravity);
    ASSERT_EQ(r.acceleration.size(), 3u);
    EXPECT_DOUBLE_EQ(r.acceleration[1], -2.0 * standard_gravity);
  }
} // namespace
