// io::Table: one set of cells written as CSV (name_unit headers, full precision), Markdown (a few
// significant figures, display units, joined cells) and HDF5 (datasets with units).
#include <cstdint>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/results_file.h"
#include "io/table.h"
#include "tests/support/csv.h"
#include "tests/support/hdf5_reader.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::io::Cell;
  using kimp::io::Table;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();

  Table example()
  {
    Table t;
    t.number("wall_height", "m")
      .number("k", "kN/mm^1.5/m")
      .number("k_lower", "kN/mm^1.5/m")
      .number("h_contact", "m", {3, "cm"})
      .integer("n_steps")
      .text("status");
    t.add_row({1.25, 166.82712345678901, 164.443, 0.025, std::int64_t{5695}, std::string("ok")});
    t.add_row({2.0, nan, nan, 0.05, std::int64_t{12}, std::string("failed: no contact")});
    return t;
  }

  TEST(Table, CsvHasNameUnitHeadersAndEveryDigit)
  {
    const kimp::testing::TempDir dir;
    example().write_csv(dir.path() / "t.csv");
    const auto csv = kimp::testing::read_csv(dir.path() / "t.csv");
    EXPECT_EQ(csv.header,
              (std::vector<std::string>{"wall_height_m",
                                        "k_kN_per_mm1.5_per_m",
                                        "k_lower_kN_per_mm1.5_per_m",
                                        "h_contact_m",
                                        "n_steps",
                                        "status"}));
    ASSERT_EQ(csv.rows.size(), 2u);
    // Shortest text that reads back to the same double; integers without a decimal point.
    EXPECT_EQ(std::stod(csv.rows[0][1]), 166.82712345678901);
    EXPECT_EQ(csv.rows[0][4], "5695");
    EXPECT_EQ(csv.rows[1][1], ""); // NaN is an empty cell, not "nan"
    EXPECT_EQ(csv.rows[1][5], "failed: no contact");
  }

  TEST(Table, MarkdownShowsSignificantFiguresInTheDisplayUnit)
  {
    const std::string md = example().markdown();
    EXPECT_NE(md.find("| wall_height (m) | k (kN/mm^1.5/m) |"), std::string::npos) << md;
    EXPECT_NE(md.find("| h_contact (cm) |"), std::string::npos) << md;
    EXPECT_NE(md.find("| 1.250 | 166.8 | 164.4 | 2.50 | 5695 | ok |"), std::string::npos) << md;
    EXPECT_EQ(md.find("166.827"), std::string::npos) << md;

    const std::string joined =
      example().markdown({{"H (m)", {"wall_height"}, {}},
                          {"k [lower]", {"k", "k_lower"}, [](const std::vector<std::string> &t) {
                             return t[0].empty() ? std::string("-") : t[0] + " [" + t[1] + "]";
                           }}});
    EXPECT_NE(joined.find("| 1.250 | 166.8 [164.4] |"), std::string::npos) << joined;
    EXPECT_NE(joined.find("| 2.000 | - |"), std::string::npos) << joined;
    EXPECT_THROW(example().markdown({{"x", {"no_such_column"}, {}}}), std::out_of_range);
  }

  TEST(Table, Hdf5HasOneDatasetPerColumnWithUnits)
  {
    const kimp::testing::TempDir dir;
    {
      kimp::io::ResultsFile  file(dir.path() / "t.h5", "", "{}");
      kimp::io::ResultsGroup root = file.root();
      example().write_hdf5(root, "k_table");
      file.commit();
    }
    const kimp::testing::Hdf5Reader h5(dir.path() / "t.h5");
    ASSERT_TRUE(h5.ok());
    EXPECT_EQ(h5.attribute("/k_table", "columns"),
              "wall_height,k,k_lower,h_contact,n_steps,status");
    EXPECT_EQ(h5.units("/k_table/k"), "kN/mm^1.5/m");
    EXPECT_EQ(h5.units("/k_table/n_steps"), "1");
    EXPECT_EQ(h5.doubles("/k_table/k").at(0), 166.82712345678901);
    EXPECT_EQ(h5.read<std::int64_t>("/k_table/n_steps", H5T_NATIVE_INT64),
              (std::vector<std::int64_t>{5695, 12}));
  }

  TEST(Table, RefusesCellsOfTheWrongKind)
  {
    Table t;
    t.number("x", "m").text("status");
    EXPECT_THROW(t.add_row({std::string("4 cm"), std::string("ok")}), std::invalid_argument);
    EXPECT_THROW(t.add_row({1.0}), std::invalid_argument);
    EXPECT_THROW(t.number("x", "s"), std::invalid_argument);
    t.add_row({std::int64_t{2}, std::string("ok")}); // an integer in a number column is a double
    EXPECT_EQ(t.csv_text(0, 0), "2");
  }
} // namespace
