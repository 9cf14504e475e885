// Scene files: reading every Io verb, defaults, range texts, printed defaults and random scenes
// that read back exactly, resolved JSON. Their errors: scene_io_errors_test.cc.
#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include "tests/io/scene_io_test_support.h"

namespace
{
  using namespace kimp::io;
  using namespace scene_io_test;
  using test_scene::Law;
  using test_scene::Scene;

  constexpr double relative_tolerance = 1e-14;

  void expect_near_relative(double actual, double expected, const char *what)
  {
    EXPECT_NEAR(actual, expected, relative_tolerance * std::abs(expected)) << what;
  }

  void expect_same_scene(const Scene &a, const Scene &b)
  {
    EXPECT_EQ(a.n_storeys, b.n_storeys);
    EXPECT_EQ(a.with_walls, b.with_walls);
    EXPECT_EQ(a.record, b.record);
    expect_near_relative(a.mass, b.mass, "mass");
    expect_near_relative(a.pga, b.pga, "pga");
    expect_near_relative(a.k_hertz, b.k_hertz, "k_hertz");
    expect_near_relative(a.damping, b.damping, "damping");
    ASSERT_EQ(a.duration.has_value(), b.duration.has_value());
    if (a.duration)
      expect_near_relative(*a.duration, *b.duration, "duration");
    EXPECT_EQ(a.isolator.kind, b.isolator.kind);
    expect_near_relative(a.isolator.K1, b.isolator.K1, "isolator.K1");
    expect_near_relative(a.isolator.K2, b.isolator.K2, "isolator.K2");
    expect_near_relative(a.isolator.Q_ratio, b.isolator.Q_ratio, "isolator.Q_ratio");
    ASSERT_EQ(a.damper.has_value(), b.damper.has_value());
    if (a.damper)
      expect_near_relative(a.damper->c, b.damper->c, "damper.c");
    ASSERT_EQ(a.cases.size(), b.cases.size());
    for (std::size_t i = 0; i < a.cases.size(); ++i)
    {
      EXPECT_EQ(a.cases[i].name, b.cases[i].name) << "case " << i;
      expect_near_relative(a.cases[i].gap, b.cases[i].gap, "gap");
      EXPECT_EQ(a.cases[i].law, b.cases[i].law) << "case " << i;
      ASSERT_EQ(a.cases[i].cor.has_value(), b.cases[i].cor.has_value()) << "case " << i;
      if (a.cases[i].cor)
        expect_near_relative(*a.cases[i].cor, *b.cases[i].cor, "cor");
    }
    ASSERT_EQ(a.heights.size(), b.heights.size());
    for (std::size_t i = 0; i < a.heights.size(); ++i)
      expect_near_relative(a.heights[i], b.heights[i], "heights");
  }

  TEST(SceneIo, ReadsEveryVerbInSI)
  {
    const std::string text = R"(n_storeys: 6
with_walls: false
record: RSN1106_KOBE_KJM000.AT2
mass: "250 t"
pga: 0.821 g
k_hertz: 2 N/m^1.5
damping: 3 %
duration: 20 s
isolator:
  kind: linear
  K1: 2500 kN/mm
  K2: 600 MN/m
  Q_ratio: 7.5 %
damper:
  c: 4 kN*s/m
cases:
  - name: far
    gap: 25 cm
    law: hertz
  - name: touching
    gap: 0 m
    cor: 0.5
heights: ["1 m", "150 cm", "1750 mm"]
)";
    const Scene       s    = load_scene_text<Scene>(text, file_name);
    EXPECT_EQ(s.n_storeys, 6);
    EXPECT_FALSE(s.with_walls);
    EXPECT_EQ(s.record, "RSN1106_KOBE_KJM000.AT2");
    expect_near_relative(s.mass, 250e3, "mass");
    expect_near_relative(s.pga, 0.821 * 9.80665, "pga");
    expect_near_relative(s.k_hertz, 2.0, "k_hertz");
    expect_near_relative(s.damping, 0.03, "damping");
    ASSERT_TRUE(s.duration.has_value());
    expect_near_relative(*s.duration, 20.0, "duration");
    EXPECT_EQ(s.isolator.kind, "linear");
    expect_near_relative(s.isolator.K1, 2.5e9, "K1");
    expect_near_relative(s.isolator.K2, 6e8, "K2");
    expect_near_relative(s.isolator.Q_ratio, 0.075, "Q_ratio");
    ASSERT_TRUE(s.damper.has_value());
    expect_near_relative(s.damper->c, 4e3, "damper.c");
    ASSERT_EQ(s.cases.size(), 2u);
    EXPECT_EQ(s.cases[0].name, "far");
    expect_near_relative(s.cases[0].gap, 0.25, "cases[0].gap");
    EXPECT_EQ(s.cases[0].law, Law::hertz);
    EXPECT_FALSE(s.cases[0].cor.has_value()) << "a list item starts from the item defaults";
    EXPECT_EQ(s.cases[1].name, "touching");
    EXPECT_EQ(s.cases[1].gap, 0.0);
    EXPECT_EQ(s.cases[1].law, Law::linear);
    ASSERT_TRUE(s.cases[1].cor.has_value());
    EXPECT_EQ(*s.cases[1].cor, 0.5);
    ASSERT_EQ(s.heights.size(), 3u);
    expect_near_relative(s.heights[1], 1.5, "heights[1]");
    expect_near_relative(s.heights[2], 1.75, "heights[2]");
  }

  TEST(SceneIo, MissingKeysKeepTheDefaults)
  {
    Scene       expected;
    const Scene defaults;
    expected.n_storeys   = 2;
    expected.isolator.K2 = 30e6;
    expect_same_scene(load_scene_text<Scene>("n_storeys: 2\nisolator:\n  K2: 30 MN/m\n", file_name),
                      expected);
    expect_same_scene(load_scene_text<Scene>("", file_name), defaults);
    expect_same_scene(load_scene_text<Scene>("# only a comment\n", file_name), defaults);
  }

  TEST(SceneIo, NullAndEmptyValuesClearOptionalsAndLists)
  {
    const Scene s = load_scene_text<Scene>("damper: ~\ncases: []\nheights: []\nduration: null\n"
                                           "isolator:\n",
                                           file_name);
    EXPECT_FALSE(s.damper.has_value());
    EXPECT_TRUE(s.cases.empty());
    EXPECT_TRUE(s.heights.empty());
    EXPECT_FALSE(s.duration.has_value());
    expect_near_relative(s.isolator.K1,
                         test_scene::Isolator{}.K1,
                         "an empty section keeps its defaults");
  }

  TEST(SceneIo, RangeTextsAndBounds)
  {
    using kimp::io::Range;
    EXPECT_EQ(Range::positive().text("m"), "> 0");
    EXPECT_EQ(Range::non_negative().expectation("ms"), "must be >= 0");
    EXPECT_EQ(Range::at_least(1.0).text(""), ">= 1");
    EXPECT_EQ(Range::less(0.5).text("m"), "< 0.5 m");
    EXPECT_EQ(Range::at_most(2.0).text(""), "<= 2");
    EXPECT_EQ(Range::greater(0.0).and_at_most(1.0).text(""), "in (0, 1]");
    EXPECT_EQ(Range::at_least(0.0).and_less(1.0).text("%"), "in [0 %, 100 %)");
    EXPECT_EQ(Range::positive().because("toward the wall").expectation("m/s"),
              "must be > 0 (toward the wall)");
    EXPECT_TRUE(Range::greater(0.0).and_at_most(1.0).contains(1.0));
    EXPECT_FALSE(Range::greater(0.0).and_at_most(1.0).contains(0.0));
    EXPECT_FALSE(Range::positive().contains(std::nan("")));
    EXPECT_TRUE(Range().contains(-1.0));
    EXPECT_EQ(Range::nonzero().text(""), "!= 0");
    EXPECT_FALSE(Range::nonzero().contains(0.0));
    EXPECT_TRUE(Range::nonzero().contains(-0.5));
    EXPECT_FALSE(Range::nonzero().contains(std::nan("")));
  }

  TEST(SceneIo, RangesAppearInTheDefaultsAndTheSchema)
  {
    using test_scene::Ranged;
    const std::string text = default_scene_text<Ranged>("ranged");
    expect_contains(text,
                    {"x: \"1 m\"  # length [m, > 0]",
                     "y: null  # time [s, > 0] (optional: null = not set)",
                     "z: [\"0.5\"]  # fractions [dimensionless, list, each in (0, 1]]",
                     "r: \"50 %\"  # ratio [%, in [0 %, 100 %)]"});
    const nlohmann::json  schema = nlohmann::json::parse(kimp::io::schema_text<Ranged>());
    const nlohmann::json &x      = schema.at("keys").at(0);
    EXPECT_EQ(x.at("path"), "x");
    EXPECT_EQ(x.at("unit"), "m");
    EXPECT_EQ(x.at("default"), "1 m");
    EXPECT_EQ(x.at("range").at("min"), 0.0);
    EXPECT_EQ(x.at("range").at("min_open"), true);
    EXPECT_FALSE(x.at("range").contains("max"));
    EXPECT_TRUE(schema.at("keys").at(1).at("default").is_null());
    EXPECT_EQ(schema.at("keys").at(2).at("range").at("text"), "in (0, 1]");
    // JsonWriter ignores ranges: the resolved JSON holds values only.
    EXPECT_EQ(nlohmann::json::parse(kimp::io::to_json_text(Ranged{})).at("x"), 1.0);
  }

  TEST(SceneIo, PrintedDefaultsReadBackToTheDefaults)
  {
    const std::string text = default_scene_text<Scene>("test scene");
    SCOPED_TRACE(text);
    for (const char *part :
         {"n_storeys: 4  # storeys above the isolation level (integer in [1, 50])",
          "K1: \"200 MN/m\"  # initial stiffness [MN/m]",
          "damping: \"5 %\"",
          "pga: \"0.5 g\"",
          "k_hertz: \"750 kN/mm^1.5\"",
          "kind: \"bilinear\"  # isolator law (one of: linear, bilinear)",
          "duration: null",
          "# damper:",
          "#   c: \"1.5 MN*s/m\"",
          "  - name: \"near\"",
          "heights: [\"1 m\", \"1.25 m\"]"})
      EXPECT_NE(text.find(part), std::string::npos) << "missing: " << part;
    const Scene defaults;
    expect_same_scene(load_scene_text<Scene>(text, "defaults.yaml"), defaults);

    const std::string study = default_scene_text<test_scene::Study>("study");
    SCOPED_TRACE(study);
    EXPECT_NE(study.find("cases: []"), std::string::npos);
    EXPECT_NE(study.find("n_threads: 1  # worker threads (integer >= 0)"), std::string::npos);
    EXPECT_NE(study.find("#   - name: \"case\""), std::string::npos);
    EXPECT_TRUE(load_scene_text<test_scene::Study>(study, "study.yaml").cases.empty());
  }

  TEST(SceneIo, PrintedRandomScenesReadBackExactly)
  {
    std::mt19937                           random(42);
    std::uniform_real_distribution<double> u(0.01, 10.0);
    for (int trial = 0; trial < 20; ++trial)
    {
      Scene s;
      s.n_storeys   = 1 + static_cast<int>(u(random));
      s.with_walls  = trial % 2 == 0;
      s.record      = "rec \"" + std::to_string(trial) + "\": a\\b";
      s.mass        = u(random) * 1e5;
      s.pga         = u(random);
      s.k_hertz     = u(random) * 1e10;
      s.damping     = u(random) / 100;
      s.duration    = trial % 3 == 0 ? std::optional<double>() : u(random);
      s.isolator.K1 = u(random) * 1e9;
      s.isolator.K2 = s.isolator.K1 / 8;
      s.damper =
        trial % 2 == 0 ? std::optional<test_scene::Damper>() : test_scene::Damper{u(random) * 1e6};
      s.cases.resize(static_cast<std::size_t>(trial % 4));
      for (auto &c : s.cases)
      {
        c.gap = u(random) / 10;
        c.cor = u(random) / 10;
      }
      s.heights = {u(random), u(random), u(random)};

      std::ostringstream        out;
      kimp::io::DefaultsPrinter printer(out);
      Scene                     copy = s;
      visit(printer, copy);
      SCOPED_TRACE(out.str());
      expect_same_scene(load_scene_text<Scene>(out.str(), "printed.yaml"), s);
    }
  }

  TEST(SceneIo, ResolvedJsonHoldsSIValuesAndTheTextVerbatim)
  {
    const std::string text   = "isolator:\n  K1: 2500 kN/mm   # a comment kept verbatim\n";
    const auto        loaded = read_scene_text<Scene>(text, file_name);
    EXPECT_EQ(loaded.text, text);
    EXPECT_EQ(loaded.file_name, file_name);
    const auto json = nlohmann::json::parse(loaded.resolved_json);
    EXPECT_EQ(json.at("isolator").at("K1").get<double>(), 2.5e9);
    EXPECT_EQ(json.at("isolator").at("kind").get<std::string>(), "bilinear");
    EXPECT_EQ(json.at("n_storeys").get<int>(), 4);
    EXPECT_TRUE(json.at("duration").is_null());
    EXPECT_TRUE(json.at("damper").is_null());
    ASSERT_EQ(json.at("cases").size(), 2u);
    EXPECT_EQ(json.at("cases").at(0).at("law").get<std::string>(), "hertz");
    EXPECT_EQ(json.at("cases").at(0).at("gap").get<double>(), 0.10);
    EXPECT_EQ(json.at("heights").at(1).get<double>(), 1.25);
  }
} // namespace
