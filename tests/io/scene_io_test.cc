// Scene files: reading every Io verb, defaults, errors naming file:line:key, validation,
// printed defaults that read back to the defaults, resolved JSON.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "io/scene_io.h"
#include "io/units.h"
#include "tests/support/scene_errors.h"
#include "tests/support/temp_dir.h"

namespace test_scene
{
  using kimp::io::format_quantity;
  using kimp::io::ValidationContext;

  enum class Law
  {
    linear,
    hertz
  };

  struct Isolator
  {
    std::string kind    = "bilinear";
    double      K1      = 200e6;
    double      K2      = 25e6;
    double      Q_ratio = 0.1;
  };

  template <class Io>
  void visit(Io &io, Isolator &s)
  {
    io.choice("kind", s.kind, {"linear", "bilinear"}, "isolator law");
    io.quantity("K1", s.K1, "MN/m", "initial stiffness");
    io.quantity("K2", s.K2, "MN/m", "post-yield stiffness");
    io.quantity("Q_ratio", s.Q_ratio, "%", "characteristic strength / total weight");
  }

  struct Case
  {
    std::string           name = "case";
    double                gap  = 0.15;
    Law                   law  = Law::linear;
    std::optional<double> cor;
  };

  template <class Io>
  void visit(Io &io, Case &s)
  {
    io.text("name", s.name, "case name");
    io.quantity("gap", s.gap, "cm", "clear gap to the moat wall");
    io.choice("law", s.law, {{"linear", Law::linear}, {"hertz", Law::hertz}}, "impact law");
    io.quantity("cor", s.cor, "", "coefficient of restitution");
  }

  struct Damper
  {
    double c = 1.5e6;
  };

  template <class Io>
  void visit(Io &io, Damper &s)
  {
    io.quantity("c", s.c, "MN*s/m", "damping coefficient");
  }

  struct Scene
  {
    int                   n_storeys  = 4;
    bool                  with_walls = true;
    std::string           record     = "synthetic";
    double                mass       = 320e3;
    double                pga        = 0.5 * 9.80665;
    double                k_hertz    = 750e3 / std::pow(1e-3, 1.5);
    double                damping    = 0.05;
    std::optional<double> duration;
    Isolator              isolator;
    std::optional<Damper> damper;
    std::vector<Case>     cases{Case{"near", 0.10, Law::hertz, 0.7}, Case{}};
    std::vector<double>   heights{1.0, 1.25};
  };

  template <class Io>
  void visit(Io &io, Scene &s)
  {
    io.integer("n_storeys", s.n_storeys, "storeys above the isolation level", 1, 50);
    io.flag("with_walls", s.with_walls, "moat walls present");
    io.text("record", s.record, "ground motion: 'synthetic' or an AT2 file name");
    io.quantity("mass", s.mass, "t", "floor mass");
    io.quantity("pga", s.pga, "g", "peak ground acceleration");
    io.quantity("k_hertz", s.k_hertz, "kN/mm^1.5", "Hertz impact stiffness");
    io.quantity("damping", s.damping, "%", "structural damping ratio");
    io.quantity("duration", s.duration, "s", "record duration (all of it when null)");
    io.section("isolator", s.isolator, "isolation system");
    io.optional_section("damper", s.damper, "supplemental damper");
    io.list("cases", s.cases, "cases run in one call");
    io.quantity_list("heights", s.heights, "m", "wall heights");
  }

  /// A validator of a nested struct, with keys relative to it.
  void validate(const Isolator &s, ValidationContext &ctx)
  {
    ctx.check(s.K2 < s.K1,
              "K2",
              format_quantity(s.K2, "MN/m"),
              "must be < K1 = " + format_quantity(s.K1, "MN/m"));
  }

  void validate(const Scene &s, ValidationContext &ctx)
  {
    {
      const auto scope = ctx.section("isolator");
      validate(s.isolator, ctx);
    }
    ctx.check(s.mass > 0, "mass", format_quantity(s.mass, "t"), "must be > 0");
    for (std::size_t i = 0; i < s.cases.size(); ++i)
    {
      const auto scope = ctx.section("cases[" + std::to_string(i) + "]");
      ctx.check(s.cases[i].gap >= 0, "gap", format_quantity(s.cases[i].gap, "cm"), "must be >= 0");
    }
  }

  /// A struct with a member validate() and an empty default list.
  struct Study
  {
    std::vector<Case> cases;
    double            dt        = 1e-4;
    std::size_t       n_threads = 1;

    void validate(ValidationContext &ctx) const
    {
      ctx.check(dt > 0, "dt", format_quantity(dt, "s"), "must be > 0");
    }
  };

  template <class Io>
  void visit(Io &io, Study &s)
  {
    io.list("cases", s.cases, "cases");
    io.quantity("dt", s.dt, "s", "time step");
    io.integer("n_threads", s.n_threads, "worker threads");
  }

  /// Quantities with ranges, and one rule linking two keys.
  struct Ranged
  {
    double                x = 1.0;
    std::optional<double> y;
    std::vector<double>   z = {0.5};
    double                r = 0.5;
    double                f = 1.0;
  };

  template <class Io>
  void visit(Io &io, Ranged &s)
  {
    using kimp::io::Range;
    io.quantity("x", s.x, "m", "length", Range::positive());
    io.quantity("y", s.y, "s", "time", Range::positive().because("or null"));
    io.quantity_list("z", s.z, "", "fractions", Range::greater(0.0).and_at_most(1.0));
    io.quantity("r", s.r, "%", "ratio", Range::at_least(0.0).and_less(1.0));
    io.quantity("f", s.f, "", "factor (negative flips it)", Range::nonzero());
  }

  void validate(const Ranged &s, ValidationContext &ctx)
  {
    ctx.check(s.z.size() <= 3, "z", std::to_string(s.z.size()) + " values", "must be at most 3");
    // A rule that follows from x's range too: reported once, by the range.
    ctx.check(s.x > 0.0 && s.x < 10.0, "x", format_quantity(s.x, "m"), "must be in (0, 10 m)");
  }
} // namespace test_scene

namespace
{
  using namespace kimp::io;
  using test_scene::Law;
  using test_scene::Scene;

  constexpr double  relative_tolerance = 1e-14;
  const std::string file_name          = "scene.yaml";

  /// The SceneError message of loading `text` as Scene, or "" if it loads.
  template <class T = Scene>
  std::string scene_error(const std::string &text)
  {
    return kimp::testing::scene_error<T>(text, file_name);
  }

  /// Expects `message` to contain every one of `parts`.
  void expect_contains(const std::string &message, const std::vector<std::string> &parts)
  {
    EXPECT_FALSE(message.empty()) << "expected an error containing '" << parts.front() << "'";
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos)
        << "message: " << message << "\nmissing: " << part;
  }

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

  TEST(SceneIo, UnknownKeyNamesFileLineKeyAndKnownKeys)
  {
    expect_contains(scene_error("n_storeys: 3\nwith_walls: true\nisolatr:\n  K1: 1 MN/m\n"),
                    {"scene.yaml:3: unknown key 'isolatr'",
                     "known: n_storeys, with_walls, record",
                     "did you mean 'isolator'?"});
    expect_contains(scene_error("isolator:\n  K1: 300 MN/m\n  K3: 1 MN/m\n"),
                    {"scene.yaml:3: unknown key 'K3' in isolator", "known: kind, K1, K2, Q_ratio"});
    expect_contains(scene_error("cases:\n  - name: a\n  - name: b\n    gapp: 3 cm\n"),
                    {"scene.yaml:4: unknown key 'gapp' in cases[1]", "did you mean 'gap'?"});
    // Unknown keys of every level are reported together, each with its line.
    expect_contains(scene_error("isolator:\n  K3: 1 MN/m\ncases:\n  - gapp: 1 cm\nmas: 1 t\n"),
                    {"scene.yaml:2: unknown key 'K3' in isolator",
                     "scene.yaml:4: unknown key 'gapp' in cases[0]",
                     "scene.yaml:5: unknown key 'mas'"});
    expect_contains(scene_error("damper:\n  k: 1 MN*s/m\n"),
                    {"scene.yaml:2: unknown key 'k' in damper"});
  }

  TEST(SceneIo, WrongDimensionNamesFileLineKeyValueAndExpectation)
  {
    expect_contains(scene_error("n_storeys: 3\nisolator:\n  K1: 200 kg\n"),
                    {"scene.yaml:3: isolator.K1: '200 kg' has the wrong dimension",
                     "expected a stiffness in units like 'MN/m'",
                     "got a mass"});
    expect_contains(scene_error("mass: 320 g\n"),
                    {"scene.yaml:1: mass:", "grams are not supported"});
    expect_contains(scene_error("k_hertz: 750 kN/mm\n"), {"scene.yaml:1: k_hertz:", "'kN/mm^1.5'"});
    expect_contains(scene_error("mass: 320\n"), {"scene.yaml:1: mass: '320' has no unit"});
    expect_contains(scene_error("heights: [1 m, 2 kg]\n"),
                    {"scene.yaml:1: heights[1]: '2 kg' has the wrong dimension"});
    expect_contains(scene_error("cases:\n  - gap: 3 s\n"),
                    {"scene.yaml:2: cases[0].gap: '3 s'", "expected a length"});
  }

  TEST(SceneIo, TypeErrorsNameFileLineKeyAndValue)
  {
    expect_contains(scene_error("n_storeys: 4.5\n"),
                    {"scene.yaml:1: n_storeys: '4.5' is not an integer", "[1, 50]"});
    expect_contains(scene_error("\nn_storeys: 60\n"),
                    {"scene.yaml:2: n_storeys: 60 is out of range", "integer in [1, 50]"});
    expect_contains(scene_error<test_scene::Study>("n_threads: -1\n"),
                    {"scene.yaml:1: n_threads: -1 is out of range: expected an integer >= 0"});
    expect_contains(scene_error("n_storeys: 99999999999999999999\n"),
                    {"scene.yaml:1: n_storeys: '99999999999999999999' is not an integer"});
    expect_contains(scene_error("with_walls: maybe\n"),
                    {"scene.yaml:1: with_walls: 'maybe' is not true or false"});
    expect_contains(scene_error("isolator:\n  kind: bilnear\n"),
                    {"scene.yaml:2: isolator.kind: 'bilnear' is not one of: linear, bilinear"});
    expect_contains(scene_error("cases:\n  - law: kelvin\n"),
                    {"scene.yaml:2: cases[0].law: 'kelvin' is not one of: linear, hertz"});
    expect_contains(scene_error("isolator: 5\n"), {"scene.yaml:1: isolator: '5' is not a section"});
    expect_contains(scene_error("cases: 5\n"), {"scene.yaml:1: cases: '5' is not a list"});
    expect_contains(scene_error("cases:\n  - 5\n"),
                    {"scene.yaml:2: cases[0]: '5' is not a section"});
    expect_contains(scene_error("record: [a, b]\n"),
                    {"scene.yaml:1: record: a list is not a single value"});
    expect_contains(scene_error("mass:\n"), {"scene.yaml:1: mass: (empty) is not a single value"});
    expect_contains(scene_error("heights: 1 m\n"), {"scene.yaml:1: heights: '1 m' is not a list"});
  }

  TEST(SceneIo, SyntaxErrorsAndDuplicatesNameFileAndLine)
  {
    expect_contains(scene_error("n_storeys: 3\nisolator:\n  K1: [1 MN/m\n"),
                    {"scene.yaml:", "YAML syntax error"});
    expect_contains(scene_error("n_storeys: 3\nmass: 1 t\nn_storeys: 4\n"),
                    {"scene.yaml:3: duplicate key 'n_storeys' (first at line 1)"});
    expect_contains(scene_error("- a\n- b\n"),
                    {"scene.yaml:1: expected a map of 'key: value' lines at the top level"});
  }

  TEST(SceneIo, ValidationErrorsNameFileLineKeyValueAndRule)
  {
    expect_contains(scene_error("n_storeys: 2\nisolator:\n  K1: 200 MN/m\n  K2: 250 MN/m\n"),
                    {"scene.yaml:4: isolator.K2 = 250 MN/m: must be < K1 = 200 MN/m"});
    // K2 left at its default: the message says so and points at the enclosing section.
    expect_contains(scene_error("isolator:\n  K1: 20 MN/m\n"),
                    {"scene.yaml:1: isolator.K2 = 25 MN/m (default): must be < K1 = 20 MN/m"});
    // Every violated rule is reported, each with its own line.
    const std::string both = scene_error("mass: -3 t\ncases:\n  - gap: 1 cm\n  - gap: -2 cm\n");
    expect_contains(both,
                    {"scene.yaml:1: mass = -3 t: must be > 0",
                     "scene.yaml:4: cases[1].gap = -2 cm: must be >= 0"});
    expect_contains(scene_error<test_scene::Study>("dt: -1 ms\n"),
                    {"scene.yaml:1: dt = -0.001 s: must be > 0"});
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

  TEST(SceneIo, RangesAreCheckedWhereWrittenWithValidationMessages)
  {
    using test_scene::Ranged;
    EXPECT_EQ(scene_error<Ranged>(""), "");
    EXPECT_EQ(scene_error<Ranged>("y: null\n"), "") << "a cleared optional has no range to meet";
    expect_contains(scene_error<Ranged>("x: -1 m\n"), {"scene.yaml:1: x = -1 m: must be > 0"});
    expect_contains(scene_error<Ranged>("x: 1 m\ny: -2 s\n"),
                    {"scene.yaml:2: y = -2 s: must be > 0 (or null)"});
    expect_contains(scene_error<Ranged>("z: [0.5, 0]\n"),
                    {"scene.yaml:1: z[1] = 0: must be in (0, 1]"});
    expect_contains(scene_error<Ranged>("r: 100 %\n"),
                    {"scene.yaml:1: r = 100 %: must be in [0 %, 100 %)"});
    // Range failures are reported together with validate()'s.
    expect_contains(scene_error<Ranged>("x: 0 m\nz: [0.1, 0.2, 0.3, 0.4]\n"),
                    {"scene.yaml:1: x = 0 m: must be > 0",
                     "scene.yaml:2: z = 4 values: must be at most 3"});
  }

  TEST(SceneIo, ErrorsStandOnePerLineInFileOrderAndEachKeyOnce)
  {
    using test_scene::Ranged;
    // Written out of order: the reader's range failures and validate()'s are merged by line.
    const std::string message = scene_error<Ranged>("z: [0.1, 0.2, 0.3, 0.4]\n"
                                                    "f: 0\n"
                                                    "r: -1 %\n"
                                                    "x: -2 m\n");
    EXPECT_EQ(message,
              "scene.yaml:1: z = 4 values: must be at most 3\n"
              "scene.yaml:2: f = 0: must be != 0\n"
              "scene.yaml:3: r = -1 %: must be in [0 %, 100 %)\n"
              "scene.yaml:4: x = -2 m: must be > 0");
    // x within its range but beyond validate()'s rule: that rule is reported.
    EXPECT_EQ(scene_error<Ranged>("x: 20 m\n"), "scene.yaml:1: x = 20 m: must be in (0, 10 m)");
    // Unknown keys too, in file order whatever the nesting.
    expect_contains(scene_error("isolator:\n  K3: 1 MN/m\nmasss: 1 t\n"),
                    {"scene.yaml:2: unknown key 'K3' in isolator",
                     "\nscene.yaml:3: unknown key 'masss'"});
    EXPECT_LT(scene_error("masss: 1 t\nisolator:\n  K3: 1 MN/m\n").find("masss"),
              scene_error("masss: 1 t\nisolator:\n  K3: 1 MN/m\n").find("K3"));
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

  TEST(SceneIo, LoadsFilesAndNamesMissingOnes)
  {
    const kimp::testing::TempDir dir("scene_io_test");
    const auto                   path = dir.file("scene.yaml");
    {
      std::ofstream out(path);
      out << "n_storeys: 7\n";
    }
    EXPECT_EQ(load_scene<Scene>(path).n_storeys, 7);
    {
      std::ofstream out(path);
      out << "n_storeys: 7\nisolator:\n  K2: 300 MN/m\n";
    }
    try
    {
      load_scene<Scene>(path);
      ADD_FAILURE() << "K2 > K1 must fail validation";
    }
    catch (const SceneError &error)
    {
      expect_contains(error.what(), {path.string() + ":3: isolator.K2 = 300 MN/m"});
    }
    std::filesystem::remove(path);
    try
    {
      load_scene<Scene>(path);
      ADD_FAILURE() << "a missing file must throw";
    }
    catch (const SceneError &error)
    {
      expect_contains(error.what(), {path.string(), "cannot open scene file"});
    }
  }
} // namespace
