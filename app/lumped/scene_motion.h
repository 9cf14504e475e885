// The ground motion a run of a scene would use, without running it: what `kimp gui` draws in its
// Ground-motion tab before a run (the synthetic near-fault motion, or a record as scaled and
// trimmed by the scene).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "lumped/excitation/ground_motion.h"

namespace kimp::app
{
  /**
   * The ground motion of the scene text `scene_text` of `command` (named `file_name` in
   * messages), as a run of it loads it: the scene read and validated as `kimp COMMAND` reads it
   * (io::read_scene_text(), relative paths against `scene_directory`), then its
   * ground_motion section loaded or generated, scaled to PGA, scaled and trimmed by
   * load_ground_motion_at(), the function run_lumped_cases() loads it with. The cases' own
   * records and ground_motion_scale are not applied: this is the scene's ground_motion.
   *
   * Only lumped scenes have a ground motion read here: collide and fem scenes have none, a study
   * scene is read by the FEM executable, and a sweep's motion is that of its base scene
   * (command lumped with the base scene's text).
   *
   * @param[in] records_dir the records directory of a bare record name when the scene names no
   *            records_dir of its own, as a run given KIMP_RECORDS_DIR = records_dir looks it up
   *            (nullopt: $KIMP_RECORDS_DIR, else ../shared/data/records)
   * @param[in] scene_directory the directory relative paths of the scene are read against, as those
   *            of a scene file in it (empty: the working directory)
   * @throws io::SceneError for an invalid scene ("FILE:LINE: KEY = VALUE: rule", the message of
   *         `kimp COMMAND --check`) or a record that cannot be found or read ("FILE:LINE:
   *         ground_motion.record = 'NAME': <problem>")
   * @throws std::invalid_argument naming the command when its scenes have no ground motion here
   */
  lumped::GroundMotion scene_ground_motion(const std::string                          &command,
                                           const std::string                          &scene_text,
                                           const std::string                          &file_name,
                                           const std::optional<std::filesystem::path> &records_dir,
                                           const std::filesystem::path &scene_directory = {});
} // namespace kimp::app
