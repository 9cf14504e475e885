// The scene commands of `kimp gui` (server/scene_commands.h): schemas asked of the kimp executable
// once, the commands available, and validation in process (lumped, collide) or by the FEM
// executable (fem, study).
#include "server/scene_commands.h"

#include <algorithm>
#include <unistd.h>
#include <utility>
#include <vector>

#include "app/lumped/collide_run.h"
#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_scene.h"
#include "io/output_dir.h"
#include "io/scene_io.h"

#include "server/http_error.h"
#include "server/run_manager.h"

namespace kimp::server
{
  namespace
  {
    /// The commands whose scenes the server validates itself (kimp::app_core); fem and study
    /// are validated by the FEM executable (`kimp fem SCENE --check`).
    bool validated_here(const std::string &command)
    {
      return command == "lumped" || command == "collide";
    }

    /// The scene `text` of lumped or collide read and validated as the command would: "" when
    /// valid, else the command's own message ("scene.yaml:12: isolator.K2 = ...: must be < K1").
    std::string validation_error_here(const std::string &command, const std::string &text)
    {
      try
      {
        if (command == "lumped")
          io::read_scene_text<app::PlanLumpedScene>(text, "scene.yaml"); // planar or plan
        else
          io::read_scene_text<app::CollideScene>(text, "scene.yaml");
        return {};
      }
      catch (const std::exception &error)
      {
        return error.what();
      }
    }

    /// What a kimp that failed wrote on stderr, without its trailing line breaks.
    std::string error_output(const Captured &result)
    {
      std::string text = result.err;
      while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
        text.pop_back();
      return text;
    }
  } // namespace

  SceneCommands::SceneCommands(std::filesystem::path kimp_executable,
                               std::filesystem::path runs_dir)
    : kimp_(std::move(kimp_executable))
    , runs_dir_(std::move(runs_dir))
  {
  }

  std::string SceneCommands::schema(const std::string &command, const std::string &flag)
  {
    static const std::vector<std::string> scene_commands = {"lumped",
                                                            "collide",
                                                            "fem",
                                                            "study",
                                                            "sweep"};
    if (std::find(scene_commands.begin(), scene_commands.end(), command) == scene_commands.end())
      throw HttpError(404,
                      "no scene command " + in_quotes(command) +
                        " (kimp gui edits lumped, collide, fem, study and sweep scenes)");
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string           key = command + flag;
    if (const auto it = cache_.find(key); it != cache_.end())
      return it->second;
    if (const auto it = errors_.find(key); it != errors_.end())
      throw HttpError(404, it->second);
    const Captured result = capture_kimp(kimp_, {command, flag});
    if (result.exit_code != 0)
    {
      std::string why = error_output(result);
      if (why.rfind("error: ", 0) == 0)
        why.erase(0, 7);
      throw HttpError(404,
                      errors_[key] = "kimp " + command + " is not available here" +
                                     (why.empty() ? std::string() : ": " + why));
    }
    return cache_[key] = result.out;
  }

  nlohmann::json SceneCommands::available()
  {
    nlohmann::json commands = nlohmann::json::array({"lumped", "collide"});
    for (const char *command : {"fem", "study"})
    {
      try
      {
        schema(command, "--print-schema");
        commands.push_back(command);
      }
      catch (const HttpError &)
      {
      }
    }
    commands.push_back("sweep");
    return commands;
  }

  std::string SceneCommands::validation_error(const std::string &command, const std::string &text)
  {
    if (validated_here(command))
      return validation_error_here(command, text);
    if (command == "sweep")
      throw HttpError(400,
                      "a sweep file is checked by kimp sweep when its run starts; validate "
                      "its base scene with the base scene's command (lumped)");
    if (command != "fem" && command != "study")
      throw HttpError(400,
                      "unknown command " + in_quotes(command) +
                        " (expected lumped, collide, fem, study or sweep)");
    try
    {
      schema(command, "--print-schema");
    }
    catch (const HttpError &error)
    {
      throw HttpError(400, error.what());
    }
    // The FEM executable reads the scene as its run would: in a folder of its own beside the
    // runs (not listed: a run's id has no '.'), so that its messages name "scene.yaml" as the
    // in-process ones do and its relative paths ("../uploads/NAME") mean what they mean to a run.
    const auto dir =
      runs_dir_ / (".check-" + std::to_string(getpid()) + "-" + std::to_string(++check_counter_));
    std::filesystem::create_directories(dir);
    io::write_text_atomic(dir / "scene.yaml", text);
    const Captured  result = capture_kimp(kimp_, {"-q", command, "scene.yaml", "--check"}, dir);
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    if (result.exit_code == 0)
      return {};
    std::string message = error_output(result);
    if (const std::size_t at = message.find("error: "); at != std::string::npos)
      message.erase(0, at + 7);
    if (message.empty())
      message =
        "kimp " + command + " --check failed (exit code " + std::to_string(result.exit_code) + ")";
    return message;
  }
} // namespace kimp::server
