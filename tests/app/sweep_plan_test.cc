// Sweep files: inclusive ranges, product/zip enumeration, key-path setting in nested maps
// and lists, stable case ids, and malformed files reported with file:line:key.
#include <gtest/gtest.h>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "app/sweep/sweep_plan.h"
#include "io/scene_io.h"
#include "io/units.h"
#include "tests/support/messages.h"

namespace
{
  using kimp::app::SweepError;
  using kimp::app::SweepPlan;

  struct ToyWall
  {
    double gap     = 0.15;
    bool   present = true;
  };
  struct ToyWalls
  {
    ToyWall left;
    ToyWall right;
  };
  struct ToyCase
  {
    std::string name = "case";
    double      cor  = 0.7;
  };
  struct ToyScene
  {
    ToyWalls             walls;
    std::string          record = "synthetic";
    std::vector<ToyCase> cases;
  };
  template <class Io>
  void visit(Io &io, ToyWall &w)
  {
    io.quantity("gap", w.gap, "cm", "gap");
    io.flag("present", w.present, "is there a wall");
  }

  template <class Io>
  void visit(Io &io, ToyWalls &w)
  {
    io.section("left", w.left, "left wall");
    io.section("right", w.right, "right wall");
  }

  template <class Io>
  void visit(Io &io, ToyCase &c)
  {
    io.text("name", c.name, "name");
    io.quantity("cor", c.cor, "", "coefficient of restitution");
  }

  template <class Io>
  void visit(Io &io, ToyScene &s)
  {
    io.section("walls", s.walls, "walls");
    io.text("record", s.record, "record");
    io.list("cases", s.cases, "cases");
  }

  const std::string base_scene = "walls:\n"
                                 "  left: {gap: 15 cm}\n"
                                 "record: kobe\n"
                                 "cases:\n"
                                 "  - {name: a, cor: 0.5}\n";

  /// The first two lines of a sweep on base.yaml, up to its parameters.
  const std::string on_base = "scene: base.yaml\nparameters:\n";

  SweepPlan parse(const std::string &sweep)
  {
    return SweepPlan::parse(sweep, "sweep.yaml", base_scene, "base.yaml");
  }

  /// A sweep of walls.left.gap over 10, 20 and 30 cm and of record over `records` (a YAML list),
  /// combined by `combine` (the default, product, when empty); record stands on line 4 or 5.
  std::string gap_and_record_sweep(const std::string &combine, const std::string &records)
  {
    return "scene: base.yaml\n" + (combine.empty() ? "" : "combine: " + combine + "\n") +
           "parameters:\n  walls.left.gap: [10 cm, 20 cm, 30 cm]\n  record: " + records + "\n";
  }

  /// `text` parsed must throw SweepError whose message contains every piece of `expected`.
  void expect_sweep_error(const std::string &sweep, const std::vector<std::string> &expected)
  {
    try
    {
      parse(sweep);
      ADD_FAILURE() << "no SweepError for:\n" << sweep;
    }
    catch (const SweepError &error)
    {
      for (const std::string &piece : expected)
        EXPECT_NE(std::string(error.what()).find(piece), std::string::npos)
          << "message: " << error.what() << "\nexpected to contain: " << piece << "\nsweep:\n"
          << sweep;
    }
  }

  void check_toy(const std::string &text, const std::string &name)
  {
    kimp::io::read_scene_text<ToyScene>(text, name);
  }

  /// The SweepError message of checking the key paths of `plan` on the toy scene (a failure of
  /// the test if they pass).
  std::string key_path_error(const SweepPlan &plan)
  {
    return kimp::testing::thrown_message<SweepError>([&] { plan.check_key_paths(check_toy); });
  }

  TEST(SweepRange, InclusiveGapRangeHas71Values)
  {
    const auto values = kimp::app::expand_range("10 cm", "45 cm", "0.5 cm", "test");
    ASSERT_EQ(values.size(), 71U);
    EXPECT_EQ(values.front(), "10 cm");
    EXPECT_EQ(values[1], "10.5 cm");
    EXPECT_EQ(values.back(), "45 cm");
  }

  TEST(SweepRange, RoundOffDoesNotDropTheEndPoint)
  {
    // (1.0 - 0.1) / 0.1 = 8.999999999999998 in binary floating point.
    const auto values = kimp::app::expand_range("0.1", "1.0", "0.1", "test");
    ASSERT_EQ(values.size(), 10U);
    EXPECT_EQ(values[2], "0.3");
    EXPECT_EQ(values.back(), "1");
    constexpr double tolerance = 1e-12;
    EXPECT_NEAR(kimp::io::parse_quantity_as(values[6], ""), 0.7, tolerance);
  }

  TEST(SweepRange, ValuesAreInTheUnitOfFromAndReadBackInSi)
  {
    const auto values = kimp::app::expand_range("500 kN/mm", "5000 kN/mm", "1500 kN/mm", "t");
    ASSERT_EQ(values.size(), 4U);
    constexpr double relative_tolerance = 1e-14;
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      const double expected = (500.0 + 1500.0 * static_cast<double>(i)) * 1e6;
      EXPECT_NEAR(kimp::io::parse_quantity_as(values[i], "N/m"),
                  expected,
                  relative_tolerance * expected)
        << values[i];
    }
  }

  TEST(SweepRange, BadRangesAreRejectedWithTheirValues)
  {
    EXPECT_THROW(kimp::app::expand_range("10 cm", "45 cm", "0 cm", "w"), SweepError);
    EXPECT_THROW(kimp::app::expand_range("10 cm", "45 s", "1 cm", "w"), SweepError);
    EXPECT_THROW(kimp::app::expand_range("45 cm", "10 cm", "1 cm", "w"), SweepError);
    EXPECT_THROW(kimp::app::expand_range("ten", "45 cm", "1 cm", "w"), SweepError);
  }

  TEST(SweepRange, TenMillionValuesAreKeptAsTheirBounds)
  {
    const kimp::app::SweepValues values =
      kimp::app::SweepValues::range("1 mm", "10000000 mm", "1 mm", "test");
    EXPECT_TRUE(values.is_range());
    ASSERT_EQ(values.size(), 10'000'000U);
    EXPECT_EQ(values[0], "1 mm");
    EXPECT_EQ(values[4'999'999], "5000000 mm");
    EXPECT_EQ(values[9'999'999], "10000000 mm");
    EXPECT_THROW(values[10'000'000], std::out_of_range);
    // Formatted on demand exactly as the expanded range.
    EXPECT_EQ(kimp::app::SweepValues::range("10 cm", "45 cm", "0.5 cm", "t").to_vector(),
              kimp::app::expand_range("10 cm", "45 cm", "0.5 cm", "t"));
  }

  TEST(SweepPlan, CasesAreMadeOnDemandInEnumerationOrder)
  {
    // 10 M cases: counted from the lengths, any case made alone.
    const SweepPlan plan =
      parse(on_base + "  walls.left.gap: {from: 1 mm, to: 1000 mm, step: 1 mm}\n"
                      "  cases[0].cor: {from: 1, to: 10000, step: 1}\n");
    ASSERT_EQ(plan.n_cases(), 10'000'000U);
    const kimp::app::SweepCase last = plan.case_at(9'999'999);
    EXPECT_EQ(last.values, (std::vector<std::string>{"1000 mm", "10000"}));
    EXPECT_EQ(last.id.rfind("9999999-", 0), 0U) << last.id;
    const kimp::app::SweepCase middle = plan.case_at(12'345);
    EXPECT_EQ(middle.values, (std::vector<std::string>{"2 mm", "2346"}));
    const ToyScene scene = kimp::io::load_scene_text<ToyScene>(middle.scene_text, "middle");
    EXPECT_NEAR(scene.walls.left.gap, 0.002, 1e-15);
    EXPECT_NEAR(scene.cases.at(0).cor, 2346.0, 1e-12);
    const kimp::app::SweepCase info = plan.case_info(12'345);
    EXPECT_EQ(info.id, middle.id);
    EXPECT_EQ(info.values, middle.values);
    EXPECT_TRUE(info.scene_text.empty());
    EXPECT_TRUE(plan.parameters()[0].sets("walls.left.gap"));
    EXPECT_FALSE(plan.parameters()[0].sets("walls.right.gap"));
  }

  TEST(SweepPlan, ZipOfRangesOfUnequalLengthIsRefusedFromTheLengths)
  {
    expect_sweep_error("scene: base.yaml\ncombine: zip\nparameters:\n"
                       "  walls.left.gap: {from: 1 mm, to: 8000000 mm, step: 1 mm}\n"
                       "  cases[0].cor: {from: 1, to: 10000000, step: 1}\n",
                       {"sweep.yaml:5: parameters.cases[0].cor: 10000000 values, but "
                        "walls.left.gap has 8000000 (combine: zip needs equal lengths)"});
  }

  TEST(SweepPlan, ProductCountsAndOrderFirstParameterSlowest)
  {
    const SweepPlan plan = parse(gap_and_record_sweep("", "[kobe, sylmar, pacoima, sakarya]"));
    ASSERT_EQ(plan.cases().size(), 12U);
    EXPECT_EQ(plan.cases()[0].values, (std::vector<std::string>{"10 cm", "kobe"}));
    EXPECT_EQ(plan.cases()[1].values, (std::vector<std::string>{"10 cm", "sylmar"}));
    EXPECT_EQ(plan.cases()[4].values, (std::vector<std::string>{"20 cm", "kobe"}));
    EXPECT_EQ(plan.cases()[11].values, (std::vector<std::string>{"30 cm", "sakarya"}));
    for (std::size_t i = 0; i < plan.cases().size(); ++i)
      EXPECT_EQ(plan.cases()[i].index, i);
  }

  TEST(SweepPlan, ZipPairsValuesAndNeedsEqualLengths)
  {
    const SweepPlan plan = parse(gap_and_record_sweep("zip", "[kobe, sylmar, pacoima]"));
    ASSERT_EQ(plan.cases().size(), 3U);
    EXPECT_EQ(plan.cases()[2].values, (std::vector<std::string>{"30 cm", "pacoima"}));
    expect_sweep_error(gap_and_record_sweep("zip", "[kobe, sylmar]"),
                       {"sweep.yaml:5", "parameters.record", "equal lengths"});
  }

  TEST(SweepPlan, CompanionRunFollowsEachCase)
  {
    const SweepPlan plan =
      parse(on_base + "  walls.left.gap: {from: 10 cm, to: 12 cm, step: 1 cm}\n"
                      "companions:\n"
                      "  no_contact: {walls.left.present: false}\n");
    ASSERT_EQ(plan.cases().size(), 6U);
    EXPECT_EQ(plan.cases()[0].companion, "");
    EXPECT_EQ(plan.cases()[1].companion, "no_contact");
    EXPECT_EQ(plan.cases()[1].values, plan.cases()[0].values);
    EXPECT_NE(plan.cases()[1].id, plan.cases()[0].id);
    const ToyScene main_run =
      kimp::io::load_scene_text<ToyScene>(plan.cases()[2].scene_text, "main");
    const ToyScene companion =
      kimp::io::load_scene_text<ToyScene>(plan.cases()[3].scene_text, "companion");
    constexpr double tolerance = 1e-15;
    EXPECT_TRUE(main_run.walls.left.present);
    EXPECT_FALSE(companion.walls.left.present);
    EXPECT_NEAR(companion.walls.left.gap, 0.11, tolerance);
  }

  TEST(SweepPlan, KeyPathsReachNestedMapsAndListItems)
  {
    const SweepPlan plan = parse(on_base + "  walls.left.gap, walls.right.gap: [25 cm]\n"
                                           "  cases[0].cor: [0.9]\n"
                                           "  cases[1].cor: [0.3]\n");
    ASSERT_EQ(plan.cases().size(), 1U);
    const ToyScene scene = kimp::io::load_scene_text<ToyScene>(plan.cases()[0].scene_text, "case");
    constexpr double tolerance = 1e-15;
    EXPECT_NEAR(scene.walls.left.gap, 0.25, tolerance);
    EXPECT_NEAR(scene.walls.right.gap, 0.25, tolerance);
    ASSERT_EQ(scene.cases.size(), 2U);
    EXPECT_EQ(scene.cases[0].name, "a"); // the rest of the item is kept
    EXPECT_NEAR(scene.cases[0].cor, 0.9, tolerance);
    EXPECT_NEAR(scene.cases[1].cor, 0.3, tolerance);
    EXPECT_EQ(scene.record, "kobe");
  }

  TEST(SweepPlan, MapValuesSetSeveralKeysTogether)
  {
    const SweepPlan plan =
      parse(on_base + "  motion:\n"
                      "    - {label: near, walls.left.gap: 10 cm, record: pacoima}\n"
                      "    - {walls.left.gap: 20 cm, record: kobe}\n"
                      "  cases[0].cor: [0.5, 0.6]\n");
    ASSERT_EQ(plan.cases().size(), 4U);
    EXPECT_EQ(plan.cases()[0].values[0], "near");
    EXPECT_EQ(plan.cases()[2].values[0], "{walls.left.gap: 20 cm, record: kobe}");
    const ToyScene   near = kimp::io::load_scene_text<ToyScene>(plan.cases()[1].scene_text, "n");
    const ToyScene   far  = kimp::io::load_scene_text<ToyScene>(plan.cases()[2].scene_text, "f");
    constexpr double tolerance = 1e-15;
    EXPECT_NEAR(near.walls.left.gap, 0.10, tolerance);
    EXPECT_EQ(near.record, "pacoima");
    EXPECT_NEAR(near.cases[0].cor, 0.6, tolerance);
    EXPECT_NEAR(far.walls.left.gap, 0.20, tolerance);
    EXPECT_EQ(far.record, "kobe");
    plan.check_key_paths(check_toy);
    expect_sweep_error("scene: base.yaml\nparameters:\n  motion:\n    - {label: x}\n",
                       {"sweep.yaml:4", "parameters.motion", "sets no key path"});
  }

  TEST(SweepPlan, SetYamlValueRejectsPathsItCannotFollow)
  {
    EXPECT_THROW(kimp::app::set_yaml_value(base_scene, "cases[3].cor", "0.5"),
                 std::invalid_argument);
    EXPECT_THROW(kimp::app::set_yaml_value(base_scene, "walls.left", "3 cm"),
                 std::invalid_argument);
    EXPECT_THROW(kimp::app::set_yaml_value(base_scene, "record.name", "x"), std::invalid_argument);
    EXPECT_THROW(kimp::app::set_yaml_value(base_scene, "walls..gap", "x"), std::invalid_argument);
    const YAML::Node node =
      YAML::Load(kimp::app::set_yaml_value(base_scene, "walls.right.gap", "30 cm"));
    EXPECT_EQ(node["walls"]["right"]["gap"].as<std::string>(), "30 cm");
    EXPECT_EQ(node["walls"]["left"]["gap"].as<std::string>(), "15 cm");
  }

  TEST(SweepPlan, CaseIdsAreStableAndDependOnValues)
  {
    const std::string sweep = "scene: base.yaml\n"
                              "parameters:\n"
                              "  walls.left.gap: {from: 10 cm, to: 45 cm, step: 0.5 cm}\n"
                              "  record: [kobe, sylmar]\n";
    const SweepPlan   a     = parse(sweep);
    const SweepPlan   b     = parse(sweep);
    ASSERT_EQ(a.cases().size(), 142U);
    std::set<std::string> ids;
    for (std::size_t i = 0; i < a.cases().size(); ++i)
    {
      EXPECT_EQ(a.cases()[i].id, b.cases()[i].id);
      EXPECT_EQ(a.cases()[i].id.rfind(std::to_string(i) + "-", 0), 0U) << a.cases()[i].id;
      ids.insert(a.cases()[i].id.substr(a.cases()[i].id.find('-')));
    }
    EXPECT_EQ(ids.size(), a.cases().size()) << "hash parts must differ between value sets";
    const SweepPlan c = parse(on_base + "  walls.left.gap: {from: 10 cm, to: 45 cm, step: 0.5 cm}\n"
                                        "  record: [kobe, pacoima]\n");
    EXPECT_EQ(c.cases()[0].id, a.cases()[0].id);
    EXPECT_NE(c.cases()[1].id, a.cases()[1].id);
  }

  TEST(SweepPlan, UnknownKeyPathNamesSweepFileLineAndKey)
  {
    const SweepPlan plan = parse(on_base + "  record: [kobe]\n"
                                           "  walls.left.gapp: [10 cm, 20 cm]\n");
    kimp::testing::expect_contains(key_path_error(plan), {"sweep.yaml:4", "walls.left.gapp"});
  }

  TEST(SweepPlan, BadValueNamesSweepFileLineAndValue)
  {
    const SweepPlan plan = parse(on_base + "  walls.left.gap: [10 cm, 20 kg]\n"
                                           "companions:\n"
                                           "  off: {walls.left.present: maybe}\n");
    kimp::testing::expect_contains(key_path_error(plan), {"sweep.yaml:3", "20 kg"});
    const SweepPlan good_values = parse(on_base + "  walls.left.gap: [10 cm]\n"
                                                  "companions:\n"
                                                  "  off: {walls.left.present: maybe}\n");
    kimp::testing::expect_contains(key_path_error(good_values), {"sweep.yaml:5: companions.off"});
  }

  TEST(SweepPlan, MalformedFilesGetFileLineAndKey)
  {
    expect_sweep_error("scene: base.yaml\nparamters:\n  record: [kobe]\n",
                       {"sweep.yaml:2", "paramters", "unknown key"});
    expect_sweep_error("scene: base.yaml\ncombine: cartesian\nparameters:\n  record: [kobe]\n",
                       {"sweep.yaml:2", "combine", "'cartesian'", "one of: product, zip"});
    expect_sweep_error("scene: base.yaml\n", {"sweep.yaml:1", "parameters", "missing"});
    expect_sweep_error("scene: base.yaml\nengine: bogus\nparameters:\n  record: [kobe]\n",
                       {"sweep.yaml:2", "engine", "'bogus'", "one of: lumped"});
    expect_sweep_error("parameters:\n  record: [kobe]\n", {"sweep.yaml:1", "scene", "missing"});
    expect_sweep_error("scene: base.yaml\nparameters:\n  walls.left.gap: {from: 1 cm, to: 2 cm}\n",
                       {"sweep.yaml:3", "parameters.walls.left.gap", "step"});
    expect_sweep_error("scene: base.yaml\nparameters:\n  walls.left.gap: {from: 1 cm, to: 2 cm, "
                       "step: -1 cm}\n",
                       {"sweep.yaml:3", "walls.left.gap", "step = -1 cm", "> 0"});
    expect_sweep_error("scene: base.yaml\nparameters:\n  record: kobe\n",
                       {"sweep.yaml:3", "parameters.record", "list of values or a range"});
    expect_sweep_error("scene: base.yaml\nparameters:\n  record:\n    - [kobe]\n",
                       {"sweep.yaml:4", "parameters.record", "single value"});
    expect_sweep_error("scene: base.yaml\nparameters:\n  record: []\n",
                       {"sweep.yaml:3", "parameters.record", "no values"});
    expect_sweep_error("scene: base.yaml\nparameters:\n  cases[x].cor: [1]\n",
                       {"sweep.yaml:3", "cases[x].cor", "index"});
    expect_sweep_error("scene: base.yaml\nparameters: [\n", {"sweep.yaml:", "YAML syntax error"});
    EXPECT_THROW(SweepPlan::base_scene_path("parameters: {}\n", "dir/sweep.yaml"), SweepError);
    EXPECT_EQ(SweepPlan::base_scene_path("scene: ../scenes/a.yaml\n", "data/studies/s.yaml"),
              std::filesystem::path("data/studies/../scenes/a.yaml"));
  }

  TEST(SweepPlan, ReportSectionIsParsedAndOptional)
  {
    EXPECT_FALSE(parse("scene: base.yaml\nparameters:\n  record: [kobe]\n").report());
    const SweepPlan plan = parse("scene: base.yaml\n"
                                 "report:\n"
                                 "  kind: adjacent_buildings\n"
                                 "  gap: walls.right.gap\n"
                                 "  title: Study 5\n"
                                 "parameters:\n"
                                 "  record: [kobe]\n");
    ASSERT_TRUE(plan.report());
    EXPECT_EQ(plan.report()->kind, "adjacent_buildings");
    EXPECT_EQ(plan.report()->gap_key, "walls.right.gap");
    EXPECT_EQ(plan.report()->title, "Study 5");
    EXPECT_EQ(plan.report()->line, 2);
    EXPECT_NE(plan.to_json_text().find("\"kind\": \"adjacent_buildings\""), std::string::npos)
      << plan.to_json_text();
    const SweepPlan defaults =
      parse("scene: base.yaml\nreport: {kind: bumpers}\nparameters:\n  record: [kobe]\n");
    EXPECT_EQ(defaults.report()->gap_key, "walls.left.gap");
    for (const std::string &kind : kimp::app::sweep_report_kinds())
      EXPECT_EQ(parse("scene: base.yaml\nreport: {kind: " + kind +
                      "}\nparameters:\n  record: [kobe]\n")
                  .report()
                  ->kind,
                kind);
  }

  TEST(SweepPlan, MalformedReportSectionsGetFileLineAndKey)
  {
    const std::string parameters = "parameters:\n  record: [kobe]\n";
    expect_sweep_error("scene: base.yaml\nreport:\n  kind: histogram\n" + parameters,
                       {"sweep.yaml:3", "report.kind", "'histogram'", "gap_study", "bumpers"});
    expect_sweep_error("scene: base.yaml\nreport:\n  title: x\n" + parameters,
                       {"sweep.yaml:2", "report.kind", "missing"});
    expect_sweep_error("scene: base.yaml\nreport:\n  kind: gap_study\n  chart: bar\n" + parameters,
                       {"sweep.yaml:4",
                        "unknown key 'chart' in report",
                        "known: kind, gap, title"});
    expect_sweep_error("scene: base.yaml\nreport:\n  kind: gap_study\n  gap: walls..gap\n" +
                         parameters,
                       {"sweep.yaml:4", "report.gap", "empty key"});
    expect_sweep_error("scene: base.yaml\nreport: gap_study\n" + parameters,
                       {"sweep.yaml:2", "report", "is not a section"});
  }

  /// A scene with keys chosen by the file, as a sweep file has.
  struct ToyMaps
  {
    std::vector<std::pair<std::string, std::string>> values;
    std::vector<std::pair<std::string, ToyCase>>     cases;
  };
  template <class Io>
  void visit(Io &io, ToyMaps &m)
  {
    io.map_of("values", m.values, "key path -> YAML value");
    io.map_of("cases", m.cases, "name -> case");
  }

  TEST(SceneMaps, MapOfKeepsFileOrderRawTextAndReadsBack)
  {
    const std::string text = "values:\n"
                             "  z.gap: [10 cm, \"20 cm\"]\n"
                             "  a.cor: {from: 0.5, to: 0.9, step: 0.2}\n"
                             "cases:\n"
                             "  second: {cor: 0.6}\n"
                             "  first: {name: f}\n";
    const ToyMaps     maps = kimp::io::load_scene_text<ToyMaps>(text, "maps.yaml");
    ASSERT_EQ(maps.values.size(), 2U);
    EXPECT_EQ(maps.values[0].first, "z.gap");
    EXPECT_EQ(YAML::Load(maps.values[0].second)[1].as<std::string>(), "20 cm");
    EXPECT_EQ(maps.values[1].first, "a.cor");
    EXPECT_EQ(YAML::Load(maps.values[1].second)["step"].as<std::string>(), "0.2");
    ASSERT_EQ(maps.cases.size(), 2U);
    EXPECT_EQ(maps.cases[0].first, "second");
    EXPECT_DOUBLE_EQ(maps.cases[0].second.cor, 0.6);
    EXPECT_EQ(maps.cases[1].second.name, "f");
    EXPECT_NE(kimp::io::to_json_text(maps).find("\"z.gap\": ["), std::string::npos)
      << kimp::io::to_json_text(maps);

    std::ostringstream        listing;
    kimp::io::DefaultsPrinter printer(listing);
    ToyMaps                   copy = maps;
    visit(printer, copy);
    const ToyMaps again = kimp::io::load_scene_text<ToyMaps>(listing.str(), "listing.yaml");
    EXPECT_EQ(again.values, maps.values) << listing.str();
    ASSERT_EQ(again.cases.size(), 2U) << listing.str();
    EXPECT_EQ(again.cases[1].first, "first");

    kimp::testing::expect_contains(
      kimp::testing::thrown_message<kimp::io::SceneError>(
        [] { kimp::io::load_scene_text<ToyMaps>("cases:\n  a: {corr: 1}\n", "maps.yaml"); }),
      {"maps.yaml:2: unknown key 'corr' in cases.a"});
  }

  TEST(SweepPlan, PrintedDefaultsAreAValidSweep)
  {
    const SweepPlan plan = parse(kimp::app::sweep_file_defaults_text());
    EXPECT_EQ(plan.parameters().size(), 2U);
    EXPECT_EQ(plan.companions().size(), 1U);
    EXPECT_EQ(plan.cases().size(), 8U * 3U * 2U);
    EXPECT_FALSE(plan.report());
  }

  TEST(SweepPlan, GetYamlValueReadsScalarsAndReportsMissingPaths)
  {
    EXPECT_EQ(kimp::app::get_yaml_value(base_scene, "walls.left.gap"), "15 cm");
    EXPECT_EQ(kimp::app::get_yaml_value(base_scene, "cases[0].cor"), "0.5");
    EXPECT_FALSE(kimp::app::get_yaml_value(base_scene, "walls.right.gap"));
    EXPECT_FALSE(kimp::app::get_yaml_value(base_scene, "cases[3].cor"));
    EXPECT_THROW(kimp::app::get_yaml_value(base_scene, "walls.left"), std::invalid_argument);
    // A value set by a sweep reads back unchanged.
    const std::string set = kimp::app::set_yaml_value(base_scene, "walls.left.gap", "12.5 cm");
    EXPECT_EQ(kimp::app::get_yaml_value(set, "walls.left.gap"), "12.5 cm");
  }
} // namespace
