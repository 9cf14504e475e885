// Every case of every shipped lumped scene (data/scenes), for the tests that run them all; scenes
// on PEER records are skipped when the records are not found.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iostream>
#include <optional>
#include <string>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_scene.h"
#include "io/scene_io.h"
#include "lumped/excitation/ground_motion.h"
#include "tests/support/files.h"

namespace kimp::testing
{
  /// The scene's motion, or nullopt when its record is not available here.
  inline std::optional<lumped::GroundMotion> motion_of(const app::LumpedScene &scene)
  {
    try
    {
      return app::load_ground_motion(scene.ground_motion);
    }
    catch (const std::exception &)
    {
      if (scene.ground_motion.is_record())
        return std::nullopt;
      throw;
    }
  }

  /// Whether a shipped scene has a top-level `plan:` section (a building in plan, 3D).
  inline bool is_plan_scene(const std::filesystem::path &path)
  {
    std::ifstream in(path);
    std::string   line;
    while (std::getline(in, line))
      if (line.rfind("plan:", 0) == 0)
        return true;
    return false;
  }

  /// One case of a shipped lumped scene.
  struct ShippedCase
  {
    std::string          what;   ///< "<file name> <case name>"
    app::LumpedScene     scene;  ///< the case, resolved
    lumped::GroundMotion motion; ///< the scene's motion at the case's scale
  };

  /**
   * Calls `each(const ShippedCase &)` for every case of every lumped scene of data/scenes (the
   * FEM and study scenes left out), inside a SCOPED_TRACE of the file name; stops at a fatal
   * failure. A scene whose record is not found is skipped with a line on stdout. Returns the
   * number of scenes skipped.
   */
  template <class Each>
  std::size_t for_each_shipped_lumped_case(const Each &each)
  {
    std::size_t skipped = 0;
    for (const auto &item : std::filesystem::directory_iterator(source_dir() / "data/scenes"))
    {
      const std::filesystem::path path = item.path();
      const std::string           name = path.filename().string();
      if (path.extension() != ".yaml" || name.rfind("fem_", 0) == 0 ||
          name == "wall_height_study.yaml" || name == "my_site.yaml" || is_plan_scene(path))
        continue; // FEM and study scenes; scenes in plan run the plan engine (e2e_plan_cli)
      SCOPED_TRACE(name);
      const app::LumpedScene scene = io::load_scene<app::LumpedScene>(path);
      const auto             g     = motion_of(scene);
      if (!g)
      {
        std::cout << "  " << name << ": record not found, skipped\n";
        ++skipped;
        continue;
      }
      for (const auto &[case_name, case_scene] : app::resolve_cases(scene))
      {
        const double scale = case_scene.ground_motion.scale;
        each(ShippedCase{name + " " + case_name,
                         case_scene,
                         scale != scene.ground_motion.scale ?
                           lumped::scaled(*g, scale / scene.ground_motion.scale) :
                           *g});
        if (::testing::Test::HasFatalFailure())
          return skipped;
      }
    }
    return skipped;
  }
} // namespace kimp::testing
