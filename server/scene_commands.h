// The scene commands that `kimp gui` edits and runs (lumped, collide, fem, study, sweep): their
// schemas and defaults as the kimp executable prints them (asked once), which of them this
// installation runs, and the validation of a scene as its command reads it.
#pragma once

#include <atomic>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

namespace kimp::server
{
  /// The scene commands of the kimp executable that the server starts its runs with.
  class SceneCommands
  {
  public:
    /// `runs_dir`: the runs folder, in which fem and study scenes are checked (so that their
    /// relative paths mean what they mean to a run there).
    SceneCommands(std::filesystem::path kimp_executable, std::filesystem::path runs_dir);

    /// Output of `kimp COMMAND FLAG` (--print-schema or --print-defaults), asked once.
    /// @throws HttpError 404 when that kimp cannot print it (no such command, or no kimp-fem
    /// beside a lean kimp for fem and study).
    std::string schema(const std::string &command, const std::string &flag);

    /// The commands this installation runs: lumped, collide and sweep always; fem and study
    /// when the kimp executable prints their schema (a build with the FEM engine, whose kimp
    /// finds kimp-fem beside it).
    nlohmann::json available();

    /// "" when `text` is a valid scene of `command`, else the command's own message
    /// ("scene.yaml:12: isolator.K2 = ...: must be < K1"). lumped and collide scenes are read
    /// here (kimp::app_core), fem and study scenes by the FEM executable
    /// (`kimp <command> scene.yaml --check`).
    /// @throws HttpError 400 for anything but a command whose scenes kimp gui edits and runs
    std::string validation_error(const std::string &command, const std::string &text);

  private:
    std::filesystem::path              kimp_;
    std::filesystem::path              runs_dir_;
    std::mutex                         mutex_;  ///< guards cache_ and errors_
    std::map<std::string, std::string> cache_;  ///< command + flag -> text
    std::map<std::string, std::string> errors_; ///< command + flag -> why not
    std::atomic<unsigned>              check_counter_{0};
  };
} // namespace kimp::server
