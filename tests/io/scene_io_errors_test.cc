// Scene-file errors: unknown keys, wrong dimensions and types, syntax, validation rules and
// ranges, each naming file:line:key, in file order; missing and invalid files.
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "tests/io/scene_io_test_support.h"
#include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::io;
  using namespace scene_io_test;
  using test_scene::Scene;

  /// A text loaded as a Scene and the parts its error message must contain.
  struct SceneErrorCase
  {
    std::string              text;
    std::vector<std::string> parts;
  };

  void expect_scene_errors(const std::vector<SceneErrorCase> &cases)
  {
    for (const SceneErrorCase &c : cases)
    {
      SCOPED_TRACE(c.text);
      expect_contains(scene_error(c.text), c.parts);
    }
  }

  TEST(SceneIo, UnknownKeyNamesFileLineKeyAndKnownKeys)
  {
    expect_scene_errors({
      {"n_storeys: 3\nwith_walls: true\nisolatr:\n  K1: 1 MN/m\n",
       {"scene.yaml:3: unknown key 'isolatr'",
        "known: n_storeys, with_walls, record",
        "did you mean 'isolator'?"}},
      {"isolator:\n  K1: 300 MN/m\n  K3: 1 MN/m\n",
       {"scene.yaml:3: unknown key 'K3' in isolator", "known: kind, K1, K2, Q_ratio"}},
      {"cases:\n  - name: a\n  - name: b\n    gapp: 3 cm\n",
       {"scene.yaml:4: unknown key 'gapp' in cases[1]", "did you mean 'gap'?"}},
      // Unknown keys of every level are reported together, each with its line.
      {"isolator:\n  K3: 1 MN/m\ncases:\n  - gapp: 1 cm\nmas: 1 t\n",
       {"scene.yaml:2: unknown key 'K3' in isolator",
        "scene.yaml:4: unknown key 'gapp' in cases[0]",
        "scene.yaml:5: unknown key 'mas'"}},
      {"damper:\n  k: 1 MN*s/m\n", {"scene.yaml:2: unknown key 'k' in damper"}},
    });
  }

  TEST(SceneIo, WrongDimensionNamesFileLineKeyValueAndExpectation)
  {
    expect_scene_errors({
      {"n_storeys: 3\nisolator:\n  K1: 200 kg\n",
       {"scene.yaml:3: isolator.K1: '200 kg' has the wrong dimension",
        "expected a stiffness in units like 'MN/m'",
        "got a mass"}},
      {"mass: 320 g\n", {"scene.yaml:1: mass:", "grams are not supported"}},
      {"k_hertz: 750 kN/mm\n", {"scene.yaml:1: k_hertz:", "'kN/mm^1.5'"}},
      {"mass: 320\n", {"scene.yaml:1: mass: '320' has no unit"}},
      {"heights: [1 m, 2 kg]\n", {"scene.yaml:1: heights[1]: '2 kg' has the wrong dimension"}},
      {"cases:\n  - gap: 3 s\n", {"scene.yaml:2: cases[0].gap: '3 s'", "expected a length"}},
    });
  }

  TEST(SceneIo, TypeErrorsNameFileLineKeyAndValue)
  {
    expect_scene_errors({
      {"n_storeys: 4.5\n", {"scene.yaml:1: n_storeys: '4.5' is not an integer", "[1, 50]"}},
      {"\nn_storeys: 60\n", {"scene.yaml:2: n_storeys: 60 is out of range", "integer in [1, 50]"}},
      {"n_storeys: 99999999999999999999\n",
       {"scene.yaml:1: n_storeys: '99999999999999999999' is not an integer"}},
      {"with_walls: maybe\n", {"scene.yaml:1: with_walls: 'maybe' is not true or false"}},
      {"isolator:\n  kind: bilnear\n",
       {"scene.yaml:2: isolator.kind: 'bilnear' is not one of: linear, bilinear"}},
      {"cases:\n  - law: kelvin\n",
       {"scene.yaml:2: cases[0].law: 'kelvin' is not one of: linear, hertz"}},
      {"isolator: 5\n", {"scene.yaml:1: isolator: '5' is not a section"}},
      {"cases: 5\n", {"scene.yaml:1: cases: '5' is not a list"}},
      {"cases:\n  - 5\n", {"scene.yaml:2: cases[0]: '5' is not a section"}},
      {"record: [a, b]\n", {"scene.yaml:1: record: a list is not a single value"}},
      {"mass:\n", {"scene.yaml:1: mass: (empty) is not a single value"}},
      {"heights: 1 m\n", {"scene.yaml:1: heights: '1 m' is not a list"}},
    });
    expect_contains(scene_error<test_scene::Study>("n_threads: -1\n"),
                    {"scene.yaml:1: n_threads: -1 is out of range: expected an integer >= 0"});
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
