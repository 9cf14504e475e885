// The ground motion of a scene without a run (app/lumped/scene_motion.h).
#include "app/lumped/scene_motion.h"

#include <stdexcept>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_scene.h"
#include "io/scene_io.h"

namespace kimp::app
{
  lumped::GroundMotion scene_ground_motion(const std::string                          &command,
                                           const std::string                          &scene_text,
                                           const std::string                          &file_name,
                                           const std::optional<std::filesystem::path> &records_dir,
                                           const std::filesystem::path &scene_directory)
  {
    if (command == "collide")
      throw std::invalid_argument("a kimp collide scene has no ground motion (two bodies meet at "
                                  "their initial velocities): nothing to draw");
    if (command == "fem")
      throw std::invalid_argument("a kimp fem scene has no ground motion (a slab strikes the wall "
                                  "at slab.velocity): nothing to draw");
    if (command == "study")
      throw std::invalid_argument(
        "the ground motion of a kimp study scene is not drawn before its run (its scene is read "
        "by the FEM executable); each of its records[i] is a ground_motion section: draw it as "
        "the ground_motion of a lumped scene");
    if (command == "sweep")
      throw std::invalid_argument("a sweep's ground motion is that of its base scene: ask for it "
                                  "with the base scene's command (lumped) and text");
    if (command != "lumped")
      throw std::invalid_argument("unknown command \"" + command +
                                  "\" (the ground motion is drawn for lumped scenes)");
    const io::LoadedScene<LumpedScene> loaded =
      io::read_scene_text<LumpedScene>(scene_text, file_name, scene_directory);
    const GroundMotionScene &section = loaded.scene.ground_motion;
    // A run gets `records_dir` as KIMP_RECORDS_DIR, below the scene's own records_dir.
    const std::optional<std::filesystem::path> directory =
      section.records_dir.empty() ? records_dir : std::nullopt;
    return load_ground_motion_at(section,
                                 directory,
                                 loaded.file_name,
                                 loaded.text,
                                 "ground_motion");
  }
} // namespace kimp::app
