// kimp::testing::scene_error(): the message a scene text is refused with, for the tests of the
// scene schemas read through kimp::io (only for targets linking kimp::io).
#pragma once

#include <string>

#include "io/scene_io.h"

namespace kimp::testing
{
  /// The message of the io::SceneError thrown by reading `text` as a `Scene` named `file_name`
  /// in messages, or "" if it reads and validates.
  template <class Scene>
  std::string scene_error(const std::string &text, const std::string &file_name)
  {
    try
    {
      io::read_scene_text<Scene>(text, file_name);
    }
    catch (const io::SceneError &error)
    {
      return error.what();
    }
    return "";
  }
} // namespace kimp::testing
