// Readable outputs, end to end: the CSV files of `kimp sweep` and `kimp study` follow the one
// header convention name_unit with numbers only in numeric columns; every command writes a
// summary.json with the same common keys and JSON types (counts as integers, `cases` a list of
// {name, status}); and `kimp fit` on the FEM result of a `kimp study` run gives the study's k
// table to 1e-9.
#ifdef KIMP_WITH_FEM

#  include <cmath>
#  include <cstdlib>
#  include <filesystem>
#  include <gtest/gtest.h>
#  include <nlohmann/json.hpp>
#  include <regex>
#  include <set>
#  include <string>
#  include <vector>

#  include "tests/support/csv.h"
#  include "tests/support/files.h"
#  include "tests/support/hdf5_reader.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;
  namespace fs = std::filesystem;

  /// One wall height, fixed fidelity, coarse mesh, rigid slab, a short synthetic record: the
  /// cheapest study with every file.
  constexpr const char *quick_study = R"(fem:
  wall_heights: ["1.0 m"]
  mesh:
    h_contact: "5 cm"
    h_max: "25 cm"
    grading: 1.5
  slab:
    rigid: true
  dynamics:
    end_time: "40 ms"
    output_interval: "0.02 ms"
  fidelity: fixed
  velocities: []
records:
  - record: synthetic
    duration: "4 s"
fit:
  separation_fraction: 10
peer_records: false
charts: false
stability_map: false
accuracy_study: false
)";

  /// The FEM scene of the study above, for `kimp mesh` and `kimp fem`.
  constexpr const char *quick_fem = R"(wall_heights: ["1.0 m"]
mesh: {h_contact: "5 cm", h_max: "25 cm", grading: 1.5}
slab: {rigid: true}
dynamics: {end_time: "40 ms", output_interval: "0.02 ms"}
)";

  /// A sweep whose parameters carry units (cm, MN/m, %) and a gap for the d_SRSS table.
  std::string quick_sweep()
  {
    return "scene: " + (source_dir() / "data/studies/scenes/quick_scene.yaml").string() +
           "\n"
           "report: {kind: gap_study, gap: walls.left.gap}\n"
           "parameters:\n"
           "  walls.left.gap, walls.right.gap: {from: 4 cm, to: 10 cm, step: 6 cm}\n"
           "  isolator.K2: [\"20 MN/m\", \"25 MN/m\"]\n"
           "  building.damping_ratio: [\"2 %\"]\n";
  }

  /// The output directories, made once for all tests (the study is the slow part).
  class OutputsCli : public ::testing::Test
  {
  protected:
    static void SetUpTestSuite()
    {
      dir_ = new TempDir("outputs_cli");
      write_text(dir().path() / "study.yaml", quick_study);
      study_ = run_kimp("study study.yaml -o study", dir().path());
      write_text(dir().path() / "sweep.yaml", quick_sweep());
      sweep_ = run_kimp("sweep sweep.yaml -o sweep --no-charts", dir().path());
    }
    static void TearDownTestSuite()
    {
      delete dir_;
      dir_ = nullptr;
    }
    static const TempDir &dir() { return *dir_; }

    static TempDir *dir_;
    static KimpRun  study_;
    static KimpRun  sweep_;
  };
  TempDir *OutputsCli::dir_ = nullptr;
  KimpRun  OutputsCli::study_;
  KimpRun  OutputsCli::sweep_;

  /// The whole cell is one finite number.
  bool is_number(const std::string &cell)
  {
    if (cell.empty())
      return false;
    char        *end   = nullptr;
    const double value = std::strtod(cell.c_str(), &end);
    return end == cell.c_str() + cell.size() && std::isfinite(value);
  }

  /// Every header is name_unit (no spaces, commas, slashes, carets or "%") and unique; a column
  /// is numeric (its first non-empty cell is a number) or text; a numeric column holds numbers
  /// only, and no cell anywhere is a number with a unit ("4 cm").
  void expect_name_unit_csv(const fs::path &file)
  {
    SCOPED_TRACE(file.string());
    const CsvTable csv = read_csv(file);
    ASSERT_FALSE(csv.header.empty()) << "no header in " << file;
    const std::set<std::string> unique(csv.header.begin(), csv.header.end());
    EXPECT_EQ(unique.size(), csv.header.size()) << "a column name is repeated";
    const std::regex name_unit("[A-Za-z][A-Za-z0-9_.+\\[\\]]*");
    const std::regex quantity_text("\\s*[-+]?[0-9.]+([eE][-+]?[0-9]+)?\\s+\\S.*");
    for (std::size_t c = 0; c < csv.header.size(); ++c)
    {
      const std::string &h = csv.header[c];
      EXPECT_TRUE(std::regex_match(h, name_unit)) << "header '" << h << "' is not name_unit";
      bool numeric = false, decided = false;
      for (const auto &row : csv.rows)
      {
        ASSERT_EQ(row.size(), csv.header.size());
        const std::string &cell = row[c];
        EXPECT_FALSE(std::regex_match(cell, quantity_text))
          << "column " << h << ": '" << cell << "' is a number with a unit";
        if (cell.empty())
          continue;
        if (!decided)
        {
          numeric = is_number(cell);
          decided = true;
        }
        if (numeric)
        {
          EXPECT_TRUE(is_number(cell)) << "numeric column " << h << " holds '" << cell << "'";
        }
      }
    }
  }

  TEST_F(OutputsCli, CsvHeadersAreNameUnitWithNumbersOnlyInNumericColumns)
  {
    ASSERT_EQ(study_.exit_code, 0) << study_.err;
    ASSERT_EQ(sweep_.exit_code, 0) << sweep_.err;
    for (const char *file : {"sweep/sweep.csv",
                             "sweep/dsrss_table.csv",
                             "study/k_table.csv",
                             "study/building_response.csv"})
      EXPECT_TRUE(fs::exists(dir().path() / file)) << file;
    // Every CSV file the two commands wrote.
    std::size_t n_files = 0;
    for (const char *out : {"sweep", "study"})
      for (const auto &entry : fs::directory_iterator(dir().path() / out))
        if (entry.path().extension() == ".csv")
        {
          expect_name_unit_csv(entry.path());
          ++n_files;
        }
    EXPECT_GE(n_files, 5u);
    EXPECT_EQ(read_csv(dir().path() / "study/k_table.csv").rows.size(), 1u);
    // The parameters in the unit of their values: gap in cm, K2 in MN/m, "2 %" as the fraction.
    const CsvTable sweep = read_csv(dir().path() / "sweep/sweep.csv");
    const auto     gap   = sweep.column("walls.left.gap+walls.right.gap_cm");
    const auto     k2    = sweep.column("isolator.K2_MN_per_m");
    const auto     zeta  = sweep.column("building.damping_ratio");
    ASSERT_EQ(sweep.rows.size(), 4u) << "2 gaps x 2 K2";
    EXPECT_EQ(sweep.rows[0][gap], "4");
    EXPECT_EQ(sweep.rows[3][gap], "10");
    EXPECT_EQ(sweep.rows[0][k2], "20");
    EXPECT_EQ(sweep.rows[1][k2], "25");
    EXPECT_EQ(std::stod(sweep.rows[0][zeta]), 0.02);
    const CsvTable dsrss = read_csv(dir().path() / "sweep/dsrss_table.csv");
    EXPECT_NO_THROW(dsrss.column("isolator.K2_MN_per_m"));
    EXPECT_NO_THROW(dsrss.column("d_req_m"));
  }

  /// The keys every summary.json has, with their JSON types; `cases`, where a command has it, is
  /// a list of objects with a string name and status.
  void expect_common_summary(const fs::path &dir, const std::string &command)
  {
    SCOPED_TRACE(command);
    ASSERT_TRUE(fs::exists(dir / "summary.json")) << dir;
    const nlohmann::json j = read_json(dir / "summary.json");
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j.value("command", ""), command);
    EXPECT_TRUE(j.contains("kimp") && j.at("kimp").is_string());
    EXPECT_TRUE(j.contains("wall_time") && j.at("wall_time").is_number()) << "one key: wall_time";
    EXPECT_FALSE(j.contains("wall_seconds"));
    EXPECT_TRUE(j.contains("units") && j.at("units").is_object());
    if (!j.contains("cases"))
      return;
    ASSERT_TRUE(j.at("cases").is_array());
    EXPECT_FALSE(j.at("cases").empty());
    for (const auto &c : j.at("cases"))
    {
      ASSERT_TRUE(c.is_object());
      EXPECT_TRUE(c.contains("name") && c.at("name").is_string()) << c.dump();
      EXPECT_TRUE(c.contains("status") && c.at("status").is_string()) << c.dump();
    }
  }

  TEST_F(OutputsCli, EveryCommandWritesASummaryWithTheCommonKeysAndTypes)
  {
    ASSERT_EQ(study_.exit_code, 0) << study_.err;
    ASSERT_EQ(sweep_.exit_code, 0) << sweep_.err;
    const fs::path d = dir().path();
    write_text(d / "fem.yaml", quick_fem);
    const std::string lumped_scene =
      (source_dir() / "data/studies/scenes/quick_scene.yaml").string();
    for (const auto &[command, arguments] : std::vector<std::pair<std::string, std::string>>{
           {"lumped", "lumped " + lumped_scene + " -o lumped"},
           {"collide", "collide -o collide"},
           {"mesh", "mesh fem.yaml -o mesh"},
           {"fem", "fem fem.yaml -o fem"},
           {"fit", "fit fem/fem.h5 -o fit"},
           {"export-opensees", "export-opensees study --wall-height \"1 m\" -o opensees"}})
    {
      const KimpRun run = run_kimp("-q " + arguments, d);
      ASSERT_EQ(run.exit_code, 0) << arguments << "\n" << run.err;
    }
    for (const auto &[command, out] :
         std::vector<std::pair<std::string, std::string>>{{"lumped", "lumped"},
                                                          {"collide", "collide"},
                                                          {"mesh", "mesh"},
                                                          {"fem", "fem"},
                                                          {"fit", "fit"},
                                                          {"study", "study"},
                                                          {"sweep", "sweep"},
                                                          {"export-opensees", "opensees"}})
      expect_common_summary(d / out, command);

    // Counts are integers, inputs of the FEM run numbers (not text).
    const nlohmann::json fem = read_json(d / "fem/summary.json").at("cases").at(0);
    for (const char *count : {"n_dofs", "n_steps", "n_cells", "mesh_level"})
      EXPECT_TRUE(fem.at(count).is_number_integer()) << count << " = " << fem.at(count).dump();
    EXPECT_TRUE(fem.at("penalty_factor").is_number()) << fem.at("penalty_factor").dump();
    const nlohmann::json study = read_json(d / "study/summary.json");
    // The export's contact is the study's own: its isolation level against its wall.
    const nlohmann::json &contact = study.at("contact");
    const double          m1 = contact.at("isolation_mass"), m2 = contact.at("wall_mass");
    EXPECT_NEAR(contact.at("effective_mass").get<double>(), m1 * m2 / (m1 + m2), 1e-9 * m1);
    const nlohmann::json exported = read_json(d / "opensees/summary.json");
    EXPECT_EQ(exported.at("input").at("effective_mass"), contact.at("effective_mass"));
    EXPECT_EQ(exported.at("input").at("cor"), contact.at("cor"));
    for (const char *count : {"fem_n_dofs", "fem_n_steps"})
      EXPECT_TRUE(study.at("k_table").at(0).at(count).is_number_integer()) << count;
    // The study's stages add up to its wall time ("other": files and the rest).
    double stages = 0.0;
    for (const auto &[stage, seconds] : study.at("wall_time_by_stage").items())
      stages += seconds.get<double>();
    EXPECT_NEAR(stages, study.at("wall_time").get<double>(), 1e-6 * stages + 1e-9);
    EXPECT_FALSE(study.at("wall_time_by_stage").contains("extras")) << "no extra study ran";
    const nlohmann::json sweep = read_json(d / "sweep/summary.json");
    EXPECT_EQ(sweep.at("n_cases").get<int>(), 4);
    EXPECT_EQ(sweep.at("cases").size(), 4u);
  }

  TEST_F(OutputsCli, FitOnTheStudysFemResultGivesTheStudysKTable)
  {
    ASSERT_EQ(study_.exit_code, 0) << study_.err;
    // The study's fit keys (separation_fraction: 10) as flags: one configuration, one k.
    const KimpRun fit =
      run_kimp("-q fit study/fem/H1.00.h5 -o fit_study --separation-fraction 10", dir().path());
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const Hdf5Reader study(dir().path() / "study/study.h5");
    const Hdf5Reader fitted(dir().path() / "fit_study/fit.h5");
    ASSERT_TRUE(study.ok());
    ASSERT_TRUE(fitted.ok());
    // Only the HDF5 round trip and the unit conversion (kN/mm^n/m from N/m^n/m) separate them.
    constexpr double same_k = 1e-9;
    for (const auto &[law, variant, exponent] :
         {std::tuple{"kelvin_voigt", "kelvin_voigt_cor_fixed", 1.0},
          std::tuple{"jankowski", "jankowski_cor_fixed", 1.5}})
    {
      EXPECT_EQ(fitted.attribute(std::string("/fit/H1.00/") + variant, "status"),
                study.attribute(std::string("/fit/H1.00/") + law, "status"))
        << law;
      const double k_study = study.doubles(std::string("/k_table/") + law).at(0);
      const double k_fit =
        fitted.doubles(std::string("/fit/H1.00/") + variant + "/stiffness").at(0) * 1e-3 *
        std::pow(1e-3, exponent);
      EXPECT_NEAR(k_fit, k_study, same_k * k_study) << law;
    }
  }
} // namespace

#endif
