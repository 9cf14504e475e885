// The `kimp` command line (CLI11): global options, the command registry and scene commands with
// the `--print-defaults` convention (docs/architecture.md "CLI").
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "base/logging.h"
#include "base/version.h"
#include "io/scene_io.h"
#include "io/summary.h"

namespace kimp::cli
{
  // The commands themselves are registered by cli/commands.h (one cli/<name>_command.cc each).

  /// The `kimp` app with --version, -v/--verbose (repeatable), -q/--quiet and no commands:
  /// main() adds each engine's command with its register_<name>_command().
  std::unique_ptr<CLI::App> make_app();

  /**
   * Parse the command line and run the selected command.
   * @return 0 on success, after --help, --version or --print-defaults (printed to `out`);
   *         2 on a usage error or when no command is given (message and hint on `err`).
   * Errors of the command itself (scene, numerics, I/O) propagate to main(), which prints
   * "error: <what>" and returns 1.
   */
  int run_app(CLI::App          &app,
              int                argc,
              const char *const *argv,
              std::ostream      &out,
              std::ostream      &err);
  /// run_app() with the arguments after the program name (for tests).
  int run_app(CLI::App                       &app,
              const std::vector<std::string> &arguments,
              std::ostream                   &out,
              std::ostream                   &err);

  /// Thrown by a scene command's --print-defaults or --print-schema; run_app() prints text() to
  /// `out` and returns 0.
  class PrintDefaults : public CLI::Success
  {
  public:
    explicit PrintDefaults(std::string text)
      : CLI::Success("print-defaults", CLI::ExitCodes::Success)
      , text_(std::move(text))
    {
    }
    const std::string &text() const { return text_; }

  private:
    std::string text_;
  };

  /// Adds `--print-schema` (print the JSON schema of the scene's keys and exit) bound to `flag`.
  inline CLI::Option *add_print_schema_flag(CLI::App &command, bool &flag)
  {
    return command.add_flag("--print-schema",
                            flag,
                            "print the scene's keys as JSON (type, unit, default, range, meaning) "
                            "and exit");
  }

  /// What a scene command's run function receives: the validated scene and its output directory.
  template <class Scene>
  using SceneRunner =
    std::function<void(const io::LoadedScene<Scene> &scene, const io::OutputDir &output)>;

  /**
   * Add command `name`: `kimp <name> SCENE.yaml -o DIR` loads and validates the scene
   * (SceneError on bad input), creates DIR and calls `run`; `kimp <name> --print-defaults` prints
   * the annotated default scene of Scene and exits 0; `kimp <name> --print-schema` prints the
   * JSON schema of its keys (io::SchemaWriter) and exits 0.
   * @return the subcommand, for command-specific options.
   */
  template <class Scene>
  CLI::App *add_scene_command(CLI::App          &app,
                              const std::string &name,
                              const std::string &description,
                              SceneRunner<Scene> run)
  {
    struct Options
    {
      std::string scene;
      std::string output;
      bool        print_defaults = false;
      bool        print_schema   = false;
    };
    auto      options = std::make_shared<Options>();
    CLI::App *command = app.add_subcommand(name, description);
    command->add_option("scene", options->scene, "scene file (YAML); see --print-defaults")
      ->type_name("SCENE.yaml");
    command->add_option("-o,--output", options->output, "output directory (created if missing)")
      ->type_name("DIR");
    command->add_flag("--print-defaults",
                      options->print_defaults,
                      "print the annotated default scene (every key with default, unit and "
                      "meaning) and exit");
    add_print_schema_flag(*command, options->print_schema);
    // CLI11 keeps bound values between parses of one app: start each use of the command afresh.
    command->preparse_callback([options](std::size_t) { *options = Options{}; });
    command->callback(
      [options, run, name]()
      {
        if (options->print_defaults)
          throw PrintDefaults(io::default_scene_text<Scene>(
            "kimp " + name + " scene (defaults of kimp " + name + ")"));
        if (options->print_schema)
          throw PrintDefaults(io::schema_text<Scene>());
        if (options->scene.empty())
          throw CLI::RequiredError("the scene file SCENE.yaml (or --print-defaults)");
        if (options->output.empty())
          throw CLI::RequiredError("the output directory -o/--output DIR");
        base::logger().info("{}: {} {}", base::version_line(), name, options->scene);
        const io::LoadedScene<Scene> scene = io::read_scene<Scene>(options->scene);
        base::logger().debug("resolved scene (SI):\n{}", scene.resolved_json);
        const io::OutputDir output(options->output);
        run(scene, output);
      });
    return command;
  }
} // namespace kimp::cli
