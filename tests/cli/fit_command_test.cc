// `kimp fit`: a results file with FEM-like cases made by the Kelvin-Voigt law is fitted end to
// end; the table gives back k per metre and k·W, fit.h5 has units and statuses.
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app/laws/fit_run.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "io/fem_results.h"
#include "io/results_file.h"
#include "lumped/collision/two_body.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/csv.h"
#include "tests/support/fem_cases.h"
#include "tests/support/files.h"
#include "tests/support/hdf5_reader.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::io::FemCase;
  using kimp::testing::Hdf5Reader;
  using kimp::testing::read_csv_lines;
  using kimp::testing::TempDir;

  constexpr double slab_mass = 3840.0; // kg/m
  // The CSV prints 6 significant digits; the noise-free fit is exact to 1e-4.
  constexpr double table_tolerance = 1.0e-4;

  /// A rigid-slab FEM case imitated by the Kelvin-Voigt law (k in N/m per metre, COR 0.7).
  FemCase kelvin_voigt_case(const std::string &name, double height, double k)
  {
    kimp::lumped::ForceLawSpec spec;
    spec.law                      = "kelvin_voigt";
    spec.stiffness                = k;
    spec.cor                      = 0.7;
    spec.effective_mass           = slab_mass;
    const double               dt = std::sqrt(slab_mass / k) / 200.0;
    kimp::lumped::TwoBodySetup setup;
    setup.mass_1            = slab_mass;
    setup.mass_2            = std::numeric_limits<double>::infinity();
    setup.velocity_1        = 1.0;
    setup.velocity_2        = 0.0;
    setup.time_step         = dt / 100.0;
    setup.velocity_estimate = kimp::lumped::VelocityEstimate::second_order;
    const auto law          = kimp::lumped::make_force_law(spec);
    const auto r            = kimp::lumped::simulate_two_body(*law, setup);

    FemCase c;
    c.name            = name;
    c.wall_height     = height;
    c.slab_mass       = slab_mass;
    c.impact_velocity = 1.0;
    const auto add    = [&](double t, double force, double delta)
    {
      kimp::testing::add_sample(c, 0.001 + t, force, delta);
      c.indentation.push_back(delta);
    };
    for (int j = -20; j <= 0; ++j)
      add(j * dt, 0.0, j * dt);
    const long n_first = std::lround(r.history.time.front() / setup.time_step);
    int        j       = 1;
    for (; j * 100 - n_first < static_cast<long>(r.history.time.size()); ++j)
    {
      const auto i = static_cast<std::size_t>(j * 100 - n_first);
      add(j * dt, r.history.force[i], r.history.deformation[i]);
    }
    for (const int end = j + 100; j < end; ++j)
      add(j * dt,
          0.0,
          r.history.deformation.back() + r.velocity_1_after * (j * dt - r.history.time.back()));
    return c;
  }

  TEST(FitCommand, TableGivesBackStiffnessPerMetreAndTotal)
  {
    const TempDir dir;
    const auto    fem_file = dir.path() / "fem.h5";
    FemCase       failed;
    failed.name   = "H1.50";
    failed.status = "failed: diverged";
    kimp::testing::write_fem_cases(fem_file,
                                   {kelvin_voigt_case("H1.00", 1.0, 1.5e8),
                                    kelvin_voigt_case("H2.00", 2.0, 2.5e7),
                                    failed});

    auto app = kimp::cli::make_app();
    kimp::cli::register_fit_command(*app);
    std::ostringstream out, err;
    const auto         output = dir.path() / "out";
    ASSERT_EQ(
      kimp::cli::run_app(*app, {"-q", "fit", fem_file.string(), "-o", output.string()}, out, err),
      0)
      << err.str();

    const auto rows = read_csv_lines(output / "fit_table.csv");
    ASSERT_EQ(rows.size(), 1u + 2u * 5u); // header + 2 ok cases × 5 variants (H1.50 skipped)
    const std::vector<std::string> &header = rows[0];
    const auto                      column = [&](const std::string &name)
    {
      return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) -
                                      header.begin());
    };
    int checked = 0;
    for (std::size_t i = 1; i < rows.size(); ++i)
    {
      const auto &row = rows[i];
      // Linear data: the free-exponent Hertz fit collapses to n = 1 with an unbounded interval,
      // which is a failed fit, not "ok" (docs/physics.md §4 "Status of a fit").
      if (row[column("variant")] == "hertz_free_exponent")
        EXPECT_EQ(row[column("status")].rfind("failed: ", 0), 0u) << row[0] << " " << row[2];
      else
        EXPECT_EQ(row[column("status")], "ok") << row[0] << " " << row[2];
      if (row[column("variant")] != "kelvin_voigt_cor_fixed")
        continue;
      const double k_table = row[0] == "H1.00" ? 150.0 : 25.0; // kN/mm/m
      EXPECT_NEAR(std::stod(row[column("k_per_m")]), k_table, table_tolerance * k_table) << row[0];
      EXPECT_NEAR(std::stod(row[column("k_total")]),
                  k_table * kimp::fit::thesis_building_width,
                  table_tolerance * k_table * kimp::fit::thesis_building_width)
        << row[0];
      EXPECT_EQ(row[column("k_per_m_unit")], "kN/mm/m");
      EXPECT_EQ(row[column("k_total_unit")], "kN/mm");
      ++checked;
    }
    EXPECT_EQ(checked, 2);

    const Hdf5Reader h5(output / "fit.h5");
    ASSERT_GE(h5.id(), 0);
    const std::string stiffness = "/fit/H1.00/kelvin_voigt_cor_fixed/stiffness";
    ASSERT_TRUE(h5.exists(stiffness));
    const double k = h5.doubles(stiffness).at(0);
    EXPECT_NEAR(k, 1.5e8, table_tolerance * 1.5e8);
    EXPECT_STREQ(h5.units(stiffness).c_str(), "N/m/m");

    // summary.json: `cases` a list of objects with "name" and "status", k in SI at full
    // precision (as fit.h5), counts as integers.
    const nlohmann::json summary = kimp::testing::read_json(output / "summary.json");
    EXPECT_EQ(summary.at("command"), "fit");
    EXPECT_TRUE(summary.at("n_failed").is_number_integer());
    // The two free-exponent fits of linear data fail (see above); every other fit is ok.
    EXPECT_EQ(summary.at("n_failed"), 2);
    ASSERT_EQ(summary.at("cases").size(), 2u * 5u);
    const nlohmann::json &first = summary.at("cases").at(0);
    EXPECT_EQ(first.at("name"), "H1.00/" + first.at("variant").get<std::string>());
    EXPECT_EQ(first.at("status"), "ok");
    for (const nlohmann::json &c : summary.at("cases"))
      if (c.at("name") == "H1.00/kelvin_voigt_cor_fixed")
      {
        EXPECT_EQ(c.at("stiffness_per_metre").get<double>(), k) << "the value of fit.h5";
        EXPECT_EQ(c.at("stiffness_per_metre_unit"), "N/m/m");
      }
  }

  // --width takes a length with its unit like every quantity of kimp; a bare number is metres.
  TEST(FitCommand, WidthAcceptsUnits)
  {
    const TempDir dir;
    const auto    fem_file = dir.path() / "fem.h5";
    kimp::testing::write_fem_cases(fem_file, {kelvin_voigt_case("H1.00", 1.0, 1.5e8)});
    auto app = kimp::cli::make_app();
    kimp::cli::register_fit_command(*app);
    std::ostringstream out, err;
    const auto         width_of = [&](const std::string &width, const std::string &name)
    {
      const auto output = dir.path() / name;
      EXPECT_EQ(kimp::cli::run_app(
                  *app,
                  {"-q", "fit", fem_file.string(), "-o", output.string(), "--width", width},
                  out,
                  err),
                0)
        << err.str();
      return kimp::testing::read_json(output / "summary.json").at("options").at("width");
    };
    EXPECT_DOUBLE_EQ(width_of("27.78 m", "a").get<double>(), 27.78);
    EXPECT_DOUBLE_EQ(width_of("2778 cm", "b").get<double>(), 27.78);
    // As in scene files, a quantity needs its unit: a bare number and a force are refused,
    // naming the option's key.
    for (const std::string bad : {"27.78", "27 kN"})
    {
      err.str("");
      std::string message;
      int         code = 0;
      try
      {
        code = kimp::cli::run_app(
          *app,
          {"fit", fem_file.string(), "-o", (dir.path() / "d").string(), "--width", bad},
          out,
          err);
        message = err.str();
      }
      catch (const std::exception &error)
      {
        code    = 1;
        message = error.what();
      }
      EXPECT_NE(code, 0) << bad;
      EXPECT_NE(message.find("width"), std::string::npos) << message;
      EXPECT_FALSE(std::filesystem::exists(dir.path() / "d" / "summary.json")) << bad;
    }
  }

  TEST(FitCommand, MissingInputIsAnErrorNamingTheFile)
  {
    const TempDir dir;
    auto          app = kimp::cli::make_app();
    kimp::cli::register_fit_command(*app);
    std::ostringstream out, err;
    const auto         missing = (dir.path() / "absent.h5").string();
    try
    {
      kimp::cli::run_app(*app, {"-q", "fit", missing, "-o", (dir.path() / "o").string()}, out, err);
      ADD_FAILURE() << "no error for a missing FEM file";
    }
    catch (const kimp::io::ResultsError &error)
    {
      EXPECT_NE(std::string(error.what()).find("absent.h5"), std::string::npos) << error.what();
    }
    EXPECT_EQ(kimp::cli::run_app(*app, {"fit", missing}, out, err), 2) << "no -o given";
  }
} // namespace
