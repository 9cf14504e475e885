// HDF5 results file: values and `units` attributes read back with the HDF5 C API, /meta and
// /input, extendible time series, and no file left under the final name after a failure.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/version.h"
#include "io/results_file.h"
#include "tests/support/hdf5_reader.h"
#include "tests/support/temp_dir.h"

namespace
{
  using kimp::io::ResultsFile;
  using kimp::io::ResultsGroup;

  using kimp::testing::TempDir;
  using Reader = kimp::testing::Hdf5Reader;

  TEST(ResultsFile, WritesMetaInputAndDatasetsWithUnits)
  {
    const TempDir     dir;
    const auto        final_path = dir.path() / "results.h5";
    const std::string scene      = "isolator:\n  K1: 200 MN/m  # verbatim, ünïcödé\n";
    const std::string json       = R"({"isolator":{"K1":200000000.0}})";

    std::mt19937                           random(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double>                    u_values(40);
    for (auto &v : u_values)
      v = u(random);
    {
      ResultsFile file(final_path, scene, json);
      EXPECT_TRUE(std::filesystem::exists(file.temporary_path()));
      EXPECT_FALSE(std::filesystem::exists(final_path)) << "final name only after commit()";

      ResultsGroup root = file.root();
      ResultsGroup run  = root.case_group("lumped/with_walls");
      run.write("peak_drift", std::vector<double>{0.01, 0.02, 0.015}, "m");
      run.write("n_impacts", std::vector<std::int64_t>{3, 0, 7}, "1");
      run.write_matrix("u", u_values, 10, 4, "m");
      run.write_scalar("k_total", 2.5e9, "N/m");
      run.write_time_series("impact_force",
                            {0, 10, 20},
                            {0.0, 1e-3, 2e-3},
                            {0.0, 5.0e5, 1.2e6},
                            1,
                            "N");
      run.write_table("k_table", {{"height", "m", {1.0, 1.25}}, {"k_linear", "N/m", {2e8, 2.6e8}}});
      run.set_attribute("gap", 0.15);
      run.set_attribute("n_storeys", 4);
      run.set_status("ok");
      root.case_group("lumped/no_walls").set_status("failed: Newton did not converge at t = 3 s");
      file.commit();
      EXPECT_TRUE(file.committed());
      EXPECT_FALSE(std::filesystem::exists(file.temporary_path()));
    }
    ASSERT_TRUE(std::filesystem::exists(final_path));

    const Reader r(final_path);
    EXPECT_EQ(r.numeric_attribute<int>("/meta", "schema_version", H5T_NATIVE_INT),
              (std::vector<int>{1, 0}));
    EXPECT_EQ(r.attribute("/meta", "creator"), "kimp");
    EXPECT_EQ(r.attribute("/meta", "creator_version"), kimp::base::version);
    EXPECT_EQ(r.attribute("/meta", "git_revision"), kimp::base::git_revision);
    const std::string created = r.attribute("/meta", "created_utc");
    EXPECT_EQ(created.size(), 20u) << created;
    EXPECT_EQ(created.back(), 'Z') << created;
    EXPECT_EQ(r.text("/input/scene"), scene);
    EXPECT_EQ(r.text("/input/resolved"), json);

    EXPECT_EQ(r.read<double>("/lumped/with_walls/peak_drift", H5T_NATIVE_DOUBLE),
              (std::vector<double>{0.01, 0.02, 0.015}));
    EXPECT_EQ(r.attribute("/lumped/with_walls/peak_drift", "units"), "m");
    EXPECT_EQ(r.read<std::int64_t>("/lumped/with_walls/n_impacts", H5T_NATIVE_INT64),
              (std::vector<std::int64_t>{3, 0, 7}));
    EXPECT_EQ(r.dims("/lumped/with_walls/u"), (std::vector<hsize_t>{10, 4}));
    EXPECT_EQ(r.read<double>("/lumped/with_walls/u", H5T_NATIVE_DOUBLE), u_values);
    EXPECT_EQ(r.read<double>("/lumped/with_walls/k_total", H5T_NATIVE_DOUBLE),
              (std::vector<double>{2.5e9}));
    EXPECT_EQ(r.attribute("/lumped/with_walls/k_total", "units"), "N/m");
    EXPECT_EQ(r.read<std::int64_t>("/lumped/with_walls/impact_force/step", H5T_NATIVE_INT64),
              (std::vector<std::int64_t>{0, 10, 20}));
    EXPECT_EQ(r.attribute("/lumped/with_walls/impact_force/time", "units"), "s");
    EXPECT_EQ(r.attribute("/lumped/with_walls/impact_force/value", "units"), "N");
    EXPECT_EQ(r.dims("/lumped/with_walls/impact_force/value"), (std::vector<hsize_t>{3}));
    EXPECT_EQ(r.read<double>("/lumped/with_walls/k_table/k_linear", H5T_NATIVE_DOUBLE),
              (std::vector<double>{2e8, 2.6e8}));
    EXPECT_EQ(r.attribute("/lumped/with_walls/k_table", "columns"), "height,k_linear");
    EXPECT_EQ(r.numeric_attribute<double>("/lumped/with_walls", "gap", H5T_NATIVE_DOUBLE),
              (std::vector<double>{0.15}));
    EXPECT_EQ(r.numeric_attribute<std::int64_t>("/lumped/with_walls",
                                                "n_storeys",
                                                H5T_NATIVE_INT64),
              (std::vector<std::int64_t>{4}));
    EXPECT_EQ(r.attribute("/lumped/with_walls", "status"), "ok");
    EXPECT_EQ(r.attribute("/lumped/no_walls", "status"),
              "failed: Newton did not converge at t = 3 s");

    const auto datasets = r.datasets();
    EXPECT_EQ(datasets.size(), 11u) << "2 input + 4 plain + 3 time series + 2 table columns";
    for (const auto &name : datasets)
      EXPECT_NE(r.attribute(name, "units"), "<missing>") << "dataset without units: " << name;
  }

  // A whole series written at once (the lumped history, 48 s at 0.01 s: 4801 rows) is stored in
  // chunks of its own length: the file holds the values, not 8192 rows of which 3391 are padding.
  TEST(ResultsFile, WholeTimeSeriesIsStoredWithoutChunkPadding)
  {
    const TempDir             dir;
    const auto                final_path = dir.path() / "whole.h5";
    constexpr std::size_t     n_rows     = 4801;
    constexpr std::size_t     width      = 20;
    std::vector<std::int64_t> steps(n_rows);
    std::vector<double>       times(n_rows), values(n_rows * width);
    for (std::size_t i = 0; i < n_rows; ++i)
    {
      steps[i] = static_cast<std::int64_t>(500 * i);
      times[i] = 0.01 * static_cast<double>(i);
      for (std::size_t j = 0; j < width; ++j)
        values[i * width + j] = std::sin(times[i] + static_cast<double>(j));
    }
    {
      ResultsFile  file(final_path, "", "{}");
      ResultsGroup g = file.root().group("history");
      g.write_time_series("response", steps, times, values, width, "m");
      file.commit();
    }
    const Reader r(final_path);
    EXPECT_EQ(r.read<double>("/history/response/value", H5T_NATIVE_DOUBLE), values);
    const double data_bytes = static_cast<double>(n_rows * (width + 2) * sizeof(double));
    const double file_bytes = static_cast<double>(std::filesystem::file_size(final_path));
    EXPECT_LT(file_bytes, data_bytes + 64 * 1024) << "chunks padded beyond the series' length";
  }

  TEST(ResultsFile, IncrementalTimeSeriesMatchesWhatWasAppended)
  {
    const TempDir         dir;
    const auto            final_path = dir.path() / "series.h5";
    constexpr std::size_t n_steps    = 1000;
    constexpr double      dt         = 2e-5;
    {
      ResultsFile  file(final_path, "", "{}");
      ResultsGroup g = file.root().case_group("fem/H1.25");
      // A small buffer forces several extensions of the chunked datasets.
      auto displacement = g.time_series("slab_displacement", 3, "m", 64);
      auto force        = g.time_series("contact_force", 1, "N", 64);
      for (std::size_t n = 0; n < n_steps; ++n)
      {
        const double t = static_cast<double>(n) * dt;
        displacement.append(static_cast<std::int64_t>(n),
                            t,
                            std::vector<double>{std::sin(t), std::cos(t), t});
        force.append(static_cast<std::int64_t>(n), t, 1e6 * t);
      }
      EXPECT_EQ(displacement.size(), n_steps);
      EXPECT_THROW(displacement.append(0, 0.0, 1.0), kimp::io::ResultsError)
        << "a 3-wide series takes rows of 3";
      file.commit();
    }
    const Reader r(final_path);
    EXPECT_EQ(r.dims("/fem/H1.25/slab_displacement/value"), (std::vector<hsize_t>{n_steps, 3}));
    EXPECT_EQ(r.dims("/fem/H1.25/contact_force/value"), (std::vector<hsize_t>{n_steps}));
    const auto value = r.read<double>("/fem/H1.25/slab_displacement/value", H5T_NATIVE_DOUBLE);
    const auto time  = r.read<double>("/fem/H1.25/slab_displacement/time", H5T_NATIVE_DOUBLE);
    const auto step  = r.read<std::int64_t>("/fem/H1.25/contact_force/step", H5T_NATIVE_INT64);
    const auto force = r.read<double>("/fem/H1.25/contact_force/value", H5T_NATIVE_DOUBLE);
    for (std::size_t n = 0; n < n_steps; n += 97)
    {
      const double t = static_cast<double>(n) * dt;
      EXPECT_EQ(time[n], t) << "n = " << n;
      EXPECT_EQ(step[n], static_cast<std::int64_t>(n));
      EXPECT_EQ(value[3 * n + 0], std::sin(t)) << "n = " << n;
      EXPECT_EQ(value[3 * n + 2], t) << "n = " << n;
      EXPECT_EQ(force[n], 1e6 * t) << "n = " << n;
    }
  }

  TEST(ResultsFile, QuantitiesSampledTogetherShareOneHardLinkedClock)
  {
    const TempDir dir;
    const auto    final_path = dir.path() / "set.h5";
    constexpr int n_steps    = 100;
    {
      ResultsFile file(final_path, "", "{}");
      auto        set = file.root()
                   .group("fem/H1.00")
                   .time_series_set({{"contact_force", 1, "N"},
                                     {"indentation", 1, "m"},
                                     {"wall_displacement", 2, "m"}},
                                    16);
      EXPECT_EQ(set.row_width(), 4u);
      for (int n = 0; n < n_steps; ++n)
        set.append(n, n * 1e-5, {1e3 * n, 1e-6 * n, 0.5 * n, -0.5 * n});
      EXPECT_EQ(set.size(), static_cast<std::size_t>(n_steps));
      EXPECT_THROW(set.append(0, 0.0, {1.0}), kimp::io::ResultsError);
      file.commit();
    }
    const Reader r(final_path);
    for (const char *quantity : {"contact_force", "indentation", "wall_displacement"})
    {
      const std::string group = std::string("/fem/H1.00/") + quantity;
      H5O_info_t        info{};
      ASSERT_GE(
        H5Oget_info_by_name2(r.id(), (group + "/step").c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT),
        0)
        << group;
      EXPECT_EQ(info.rc, 3u) << group << "/step is one dataset linked from three groups";
      const auto step = r.read<std::int64_t>(group + "/step", H5T_NATIVE_INT64);
      const auto time = r.read<double>(group + "/time", H5T_NATIVE_DOUBLE);
      ASSERT_EQ(step.size(), static_cast<std::size_t>(n_steps)) << group;
      EXPECT_EQ(step[57], 57);
      EXPECT_EQ(time[57], 57 * 1e-5);
    }
    EXPECT_EQ(r.read<double>("/fem/H1.00/indentation/value", H5T_NATIVE_DOUBLE)[99], 99e-6);
    EXPECT_EQ(r.attribute("/fem/H1.00/indentation/value", "units"), "m");
    EXPECT_EQ(r.dims("/fem/H1.00/wall_displacement/value"),
              (std::vector<hsize_t>{static_cast<hsize_t>(n_steps), 2}));
    const auto wall = r.read<double>("/fem/H1.00/wall_displacement/value", H5T_NATIVE_DOUBLE);
    EXPECT_EQ(wall[2 * 99 + 1], -0.5 * 99);
  }

  TEST(ResultsFile, ExceptionBeforeCommitLeavesNoFile)
  {
    const TempDir         dir;
    const auto            final_path = dir.path() / "failed.h5";
    std::filesystem::path temporary;
    try
    {
      ResultsFile file(final_path, "scene", "{}");
      temporary           = file.temporary_path();
      ResultsGroup g      = file.root().case_group("lumped/case_1");
      auto         series = g.time_series("u", 2, "m", 8);
      for (int n = 0; n < 20; ++n)
        series.append(n, n * 1e-3, std::vector<double>{1.0, 2.0});
      ASSERT_TRUE(std::filesystem::exists(temporary));
      throw std::runtime_error("simulated solver failure");
    }
    catch (const std::runtime_error &error)
    {
      EXPECT_STREQ(error.what(), "simulated solver failure");
    }
    EXPECT_FALSE(temporary.empty());
    EXPECT_FALSE(std::filesystem::exists(final_path));
    EXPECT_FALSE(std::filesystem::exists(temporary));
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  }

  TEST(ResultsFile, CommitReplacesAnOlderFileAtomically)
  {
    const TempDir dir;
    const auto    final_path = dir.path() / "results.h5";
    for (const double value : {1.0, 2.0})
    {
      ResultsFile file(final_path, "", "{}");
      file.root().write_scalar("x", value, "m");
      file.commit();
    }
    const Reader r(final_path);
    EXPECT_EQ(r.read<double>("/x", H5T_NATIVE_DOUBLE), (std::vector<double>{2.0}));
  }

  TEST(ResultsFile, ErrorsNameTheFileAndObject)
  {
    const TempDir dir;
    const auto    final_path = dir.path() / "errors.h5";
    ResultsFile   file(final_path, "", "{}");
    ResultsGroup  root = file.root();
    root.write_scalar("x", 1.0, "m");
    try
    {
      root.write_scalar("x", 2.0, "m");
      ADD_FAILURE() << "writing a dataset twice must throw";
    }
    catch (const kimp::io::ResultsError &error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find(final_path.string()), std::string::npos) << message;
      EXPECT_NE(message.find("creating dataset '/x'"), std::string::npos) << message;
    }
    EXPECT_THROW(root.write_matrix("m", {1.0, 2.0, 3.0}, 2, 2, "m"), kimp::io::ResultsError);
    EXPECT_THROW(ResultsFile(dir.path() / "no_such_dir" / "x.h5", "", "{}"),
                 kimp::io::ResultsError);
  }
} // namespace
