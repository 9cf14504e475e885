// Scene inputs that used to be read silently wrong: a directory or a device as the scene file, a
// second YAML document, subnormal quantities passing "> 0". Each is refused, naming the file
// (and the line and key).
#include <filesystem>
#include <gtest/gtest.h>
#include <initializer_list>
#include <string>
#include <vector>

#include "io/scene_io.h"
#include "tests/support/messages.h"
#include "tests/support/scene_errors.h"
#include "tests/support/temp_dir.h"

namespace
{
  struct Wall
  {
    double              gap    = 0.1;
    double              offset = 0.0;
    std::vector<double> heights{1.0};
  };

  template <class Io>
  void visit(Io &io, Wall &s)
  {
    io.quantity("gap", s.gap, "cm", "gap", kimp::io::Range::positive());
    io.quantity("offset", s.offset, "m", "offset, any sign");
    io.quantity_list("heights", s.heights, "m", "heights", kimp::io::Range::positive());
  }

  using kimp::testing::expect_contains;

  std::string file_error(const std::filesystem::path &file)
  {
    try
    {
      kimp::io::read_scene<Wall>(file);
    }
    catch (const kimp::io::SceneError &error)
    {
      return error.what();
    }
    return "";
  }

  TEST(SceneInput, ADirectoryOrADeviceIsNotASceneFile)
  {
    const kimp::testing::TempDir dir;
    expect_contains(file_error(dir.path()),
                    {dir.path().string(), "is a directory", "expected a scene file"});
    expect_contains(file_error("/dev/null"), {"/dev/null", "is a device"});
    expect_contains(file_error(dir.file("missing.yaml")), {"missing.yaml", "cannot open"});
    // A regular file and a link to one still read.
    const auto file = dir.write("wall.yaml", "gap: 5 cm\n");
    EXPECT_DOUBLE_EQ(kimp::io::load_scene<Wall>(file).gap, 0.05);
    std::filesystem::create_symlink(file, dir.file("link.yaml"));
    EXPECT_DOUBLE_EQ(kimp::io::load_scene<Wall>(dir.file("link.yaml")).gap, 0.05);
  }

  TEST(SceneInput, ASecondYamlDocumentIsRefusedAtItsLine)
  {
    using kimp::testing::scene_error;
    expect_contains(scene_error<Wall>("gap: 5 cm\n---\ngap: 7 cm\n", "two.yaml"),
                    {"two.yaml:2:", "a second YAML document", "one scene per file"});
    // Opening marker: the second marker starts the second document.
    expect_contains(scene_error<Wall>("# c\n---\ngap: 5 cm\n\n---\noffset: 1 m\n", "three.yaml"),
                    {"three.yaml:5:", "a second YAML document"});
    // An empty second document is a second document too.
    expect_contains(scene_error<Wall>("gap: 5 cm\n---\n", "empty.yaml"),
                    {"empty.yaml:2:", "a second YAML document"});
    // One document, with or without its opening marker or end marker, reads.
    EXPECT_EQ(scene_error<Wall>("---\ngap: 5 cm\n", "one.yaml"), "");
    EXPECT_EQ(scene_error<Wall>("gap: 5 cm\n...\n", "one.yaml"), "");
    EXPECT_EQ(scene_error<Wall>("", "empty.yaml"), "");
  }

  TEST(SceneInput, SubnormalQuantitiesAreRefusedWithTheRangeChecks)
  {
    using kimp::testing::scene_error;
    // 1e-320 m passes "> 0" but is subnormal.
    expect_contains(scene_error<Wall>("gap: 1e-318 cm\n", "wall.yaml"),
                    {"wall.yaml:1: gap = 1e-318 cm", "must be 0 or a normal number"});
    expect_contains(scene_error<Wall>("offset: -1e-320 m\n", "wall.yaml"),
                    {"wall.yaml:1: offset", "must be 0 or a normal number"});
    expect_contains(scene_error<Wall>("heights: [1 m, 1e-320 m]\n", "wall.yaml"),
                    {"wall.yaml:1: heights[1]", "must be 0 or a normal number"});
    // The smallest normal number and zero (where allowed) are accepted.
    EXPECT_EQ(scene_error<Wall>("offset: 0 m\ngap: 2.3e-306 cm\n", "wall.yaml"), "");
  }
} // namespace
