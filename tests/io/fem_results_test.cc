// FEM results schema (io/fem_results.h): two cases written and read back equal, units
// attributes as specified, failed cases, schema version and missing/wrong objects rejected.
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <random>
#include <string>
#include <vector>

#include "io/fem_results.h"
#include "io/results_file.h"
#include "tests/support/fem_cases.h"
#include "tests/support/hdf5_reader.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::io::FemCase;
  using kimp::io::ResultsError;
  using kimp::io::ResultsFile;

  using kimp::testing::TempDir;

  /// A case with every field set; values from a seeded generator so that no two series agree.
  FemCase make_case(const std::string &name, double height, unsigned seed, std::size_t n)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    FemCase                                c;
    c.name            = name;
    c.wall_height     = height;
    c.slab_mass       = 3840.0;
    c.impact_velocity = 1.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      c.time.push_back(1.0e-5 * static_cast<double>(i));
      c.contact_force.push_back(1.0e6 * u(rng));
      c.smoothed_contact_force.push_back(1.0e6 * u(rng));
      c.indentation.push_back(1.0e-4 * u(rng));
      c.slab_displacement.push_back(1.0e-3 * u(rng));
      c.slab_velocity.push_back(u(rng));
      c.wall_displacement.push_back(1.0e-3 * u(rng));
    }
    c.summary.peak_force             = 1.2e6;
    c.summary.contact_duration       = 4.5e-3;
    c.summary.impulse                = 6528.0;
    c.summary.apparent_cor           = 0.7;
    c.summary.n_dofs                 = 12345;
    c.summary.wall_time              = 3.25;
    c.summary.extra["custom_length"] = 0.25;
    c.summary_units                  = {{"custom_length", "mm"}};
    c.labels                         = {{"mesh_level", "2"}, {"integrator", "central_difference"}};
    return c;
  }

  void write_cases(const std::filesystem::path &path, const std::vector<FemCase> &cases)
  {
    kimp::testing::write_fem_cases(path, cases, "scene: test");
  }

  void expect_error(const std::filesystem::path &path, const std::string &part)
  {
    try
    {
      kimp::io::read_fem_cases(path);
      ADD_FAILURE() << "no ResultsError containing '" << part << "'";
    }
    catch (const ResultsError &error)
    {
      const std::string what = error.what();
      EXPECT_NE(what.find(part), std::string::npos) << what;
      EXPECT_NE(what.find(path.filename().string()), std::string::npos) << what;
    }
  }

  TEST(FemResults, TwoCasesRoundTripWithAllFieldsAndUnits)
  {
    const TempDir        dir;
    const auto           path  = dir.file("fem.h5");
    std::vector<FemCase> cases = {make_case("H1.00", 1.0, 1u, 57),
                                  make_case("H1.25", 1.25, 2u, 31)};
    write_cases(path, cases);

    const std::vector<FemCase> read = kimp::io::read_fem_cases(path);
    ASSERT_EQ(read.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i)
    {
      const FemCase &a = cases[i], &b = read[i];
      EXPECT_EQ(b.name, a.name);
      EXPECT_EQ(b.status, "ok");
      EXPECT_EQ(b.wall_height, a.wall_height);
      EXPECT_EQ(b.slab_mass, a.slab_mass);
      EXPECT_EQ(b.impact_velocity, a.impact_velocity);
      EXPECT_EQ(b.time, a.time);
      EXPECT_EQ(b.contact_force, a.contact_force);
      EXPECT_EQ(b.smoothed_contact_force, a.smoothed_contact_force);
      EXPECT_EQ(b.indentation, a.indentation);
      EXPECT_EQ(b.slab_displacement, a.slab_displacement);
      EXPECT_EQ(b.slab_velocity, a.slab_velocity);
      EXPECT_EQ(b.wall_displacement, a.wall_displacement);
      EXPECT_EQ(b.summary, a.summary);
      EXPECT_EQ(b.summary_units, a.summary_units);
      EXPECT_EQ(b.labels, a.labels);
    }

    const kimp::testing::Hdf5Reader file(path);
    ASSERT_GE(file.id(), 0);
    const std::vector<std::pair<std::string, std::string>> expected = {
      {"/fem/H1.00/wall_height", "m"},
      {"/fem/H1.00/slab_mass", "kg/m"},
      {"/fem/H1.00/impact_velocity", "m/s"},
      {"/fem/H1.00/contact_force/value", "N/m"},
      {"/fem/H1.00/contact_force/time", "s"},
      {"/fem/H1.00/contact_force/step", "1"},
      {"/fem/H1.00/smoothed_contact_force/value", "N/m"},
      {"/fem/H1.00/indentation/value", "m"},
      {"/fem/H1.00/slab_displacement/value", "m"},
      {"/fem/H1.00/slab_velocity/value", "m/s"},
      {"/fem/H1.00/wall_displacement/value", "m"},
      {"/fem/H1.00/summary/peak_force", "N/m"},
      {"/fem/H1.00/summary/impulse", "N*s/m"},
      {"/fem/H1.00/summary/contact_duration", "s"},
      {"/fem/H1.00/summary/apparent_cor", "1"},
      {"/fem/H1.00/summary/custom_length", "mm"},
      {"/fem/H1.25/labels/mesh_level", "1"}};
    for (const auto &[dataset, units] : expected)
      EXPECT_EQ(file.units(dataset), units) << dataset;
  }

  TEST(FemResults, FailedCaseKeepsStatusAndLabelsAndEmptySeriesStayEmpty)
  {
    const TempDir dir;
    const auto    path = dir.file("failed.h5");
    FemCase       failed;
    failed.name    = "H2.00";
    failed.status  = "failed: time step above the stability limit";
    failed.labels  = {{"penalty_level", "3"}};
    FemCase sparse = make_case("H1.50", 1.5, 3u, 12);
    sparse.smoothed_contact_force.clear();
    sparse.wall_displacement.clear();
    sparse.summary.clear();
    sparse.summary_units.clear();
    write_cases(path, {failed, sparse});

    const auto read = kimp::io::read_fem_cases(path);
    ASSERT_EQ(read.size(), 2u);
    EXPECT_EQ(read[0].name, "H1.50"); // name order
    EXPECT_TRUE(read[0].smoothed_contact_force.empty());
    EXPECT_TRUE(read[0].wall_displacement.empty());
    EXPECT_EQ(read[0].contact_force, sparse.contact_force);
    EXPECT_TRUE(read[0].summary.empty());
    EXPECT_EQ(read[1].name, "H2.00");
    EXPECT_EQ(read[1].status, failed.status);
    EXPECT_EQ(read[1].labels, failed.labels);
    EXPECT_TRUE(read[1].time.empty());
  }

  TEST(FemResults, WriterRejectsInconsistentCase)
  {
    const TempDir dir;
    ResultsFile   file(dir.file("bad.h5"), "", "{}");
    auto          root         = file.root();
    auto          fem          = root.group("fem");
    FemCase       short_series = make_case("H1.00", 1.0, 4u, 10);
    short_series.indentation.pop_back();
    try
    {
      kimp::io::write_fem_case(fem, short_series);
      ADD_FAILURE() << "no error for a short series";
    }
    catch (const std::invalid_argument &error)
    {
      EXPECT_NE(std::string(error.what()).find("indentation has 9 samples, time has 10"),
                std::string::npos)
        << error.what();
    }
    FemCase unknown_key                  = make_case("H1.25", 1.25, 5u, 10);
    unknown_key.summary.extra["mystery"] = 1.0;
    EXPECT_THROW(kimp::io::write_fem_case(fem, unknown_key), ResultsError);
  }

  TEST(FemResults, ReaderRejectsMissingFileSchemaAndObjects)
  {
    const TempDir dir;
    expect_error(dir.file("absent.h5"), "no such file");

    // Schema major version 2 is not ours.
    const auto future = dir.file("future.h5");
    write_cases(future, {make_case("H1.00", 1.0, 6u, 8)});
    {
      const hid_t file = H5Fopen(future.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      const hid_t meta = H5Gopen2(file, "/meta", H5P_DEFAULT);
      const hid_t a    = H5Aopen(meta, "schema_version", H5P_DEFAULT);
      const int   v[2] = {2, 0};
      H5Awrite(a, H5T_NATIVE_INT, v);
      H5Aclose(a);
      H5Gclose(meta);
      H5Fclose(file);
    }
    expect_error(future, "schema_version 2.0");

    // An "ok" case without its contact force, and one with wrong units.
    // An "ok" case H1.00 of scalars only: wall height 1 m, slab mass 3840 in `slab_mass_units`
    // and, if `velocity`, an impact velocity of 1 m/s.
    const auto scalars_only =
      [&](const char *name, const std::string &slab_mass_units, bool velocity)
    {
      const auto  path = dir.file(name);
      ResultsFile file(path, "", "{}");
      auto        root = file.root();
      auto        c    = root.group("fem").case_group("H1.00");
      c.write_scalar("wall_height", 1.0, "m");
      c.write_scalar("slab_mass", 3840.0, slab_mass_units);
      if (velocity)
        c.write_scalar("impact_velocity", 1.0, "m/s");
      c.set_status("ok");
      file.commit();
      return path;
    };
    expect_error(scalars_only("broken.h5", "kg/m", true),
                 "/fem/H1.00/contact_force: time series missing");
    expect_error(scalars_only("units.h5", "kg", false),
                 "/fem/H1.00/slab_mass: units 'kg', expected 'kg/m'");
  }
} // namespace
