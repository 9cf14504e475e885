// The `kimp` command line (CLI11): global options, the command registry and scene commands with
// the `--print-defaults` convention (docs/architecture.md "CLI").
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <functional>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
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

  /// Adds `-o,--output DIR` (the output directory, created if missing) bound to `output`.
  inline CLI::Option *add_output_option(CLI::App &command, std::string &output)
  {
    return command.add_option("-o,--output", output, "output directory (created if missing)")
      ->type_name("DIR");
  }

  /// Adds `--print-schema` (print the JSON schema of the scene's keys and exit) bound to `flag`.
  inline CLI::Option *add_print_schema_flag(CLI::App &command, bool &flag)
  {
    return command.add_flag("--print-schema",
                            flag,
                            "print the scene's keys as JSON (type, unit, default, range, meaning) "
                            "and exit");
  }

  /// Adds `--check` (read and validate the scene, print "SCENE: valid" and exit without running;
  /// an invalid scene is an error as for a run) bound to `flag`.
  inline CLI::Option *add_check_flag(CLI::App &command, bool &flag)
  {
    return command.add_flag("--check",
                            flag,
                            "read and validate the scene, then exit without running (an error "
                            "names the line and key, as for a run)");
  }

  /// How a scene command reads its scene file.
  struct SceneCommandSpec
  {
    std::string name;        ///< the command, `kimp <name>`
    std::string description; ///< its line in `kimp --help`
    /// Empty: SCENE.yaml is required. Otherwise the scene file is optional and this names the
    /// defaults used without it in the log and the resolved scene ("default study scene").
    std::string default_scene = "";
  };

  /**
   * A scene command's cost guard: estimates what the scene would cost (DoFs, steps, memory, time)
   * and throws above its limits with the estimate and the key to change, unless `accept` (the
   * command's --accept-cost), then it only warns. Run before the output directory is made, and
   * by --check, so that --check refuses what a run would refuse.
   */
  template <class Scene>
  using CostCheck = std::function<void(const Scene &scene, bool accept)>;

  /// Calls a scene command's run function as run(scene, output) or, when it takes a third
  /// argument, as run(scene, output, command): the command, whose own options it reads (count(),
  /// as()).
  template <class Run, class LoadedScene, class Output>
  void call_scene_runner(const Run      &run,
                         LoadedScene    &scene,
                         const Output   &output,
                         const CLI::App &command)
  {
    if constexpr (std::is_invocable_v<const Run &, LoadedScene &, const Output &, const CLI::App &>)
      run(scene, output, command);
    else
      run(scene, output);
  }

  /**
   * Add command `spec.name`: `kimp <name> [SCENE.yaml] -o DIR` loads and validates the scene
   * (SceneError on bad input) and calls `run` with the output directory as given (a command run
   * on several MPI ranks creates it on one rank only); `kimp <name> --print-defaults` prints the
   * annotated default scene of Scene and exits 0; `kimp <name> --print-schema` prints the JSON
   * schema of its keys (io::SchemaWriter) and exits 0; `kimp <name> [SCENE.yaml] --check`
   * validates the scene and exits 0 without running (`kimp gui` validates fem and study scenes
   * so). `run` receives the validated scene (which it may still adjust, e.g. from a command-line
   * flag), the output directory as given and, if it takes it, the command
   * (call_scene_runner()). Command-specific options are added to the returned subcommand unbound
   * (read with count()/as() of the command in `run`), so every parse starts afresh. With a
   * `cost_check` the command has `--accept-cost`, and the check runs before `run` and in --check.
   */
  template <class Scene, class Run>
  CLI::App *add_scene_command_at(CLI::App        &app,
                                 SceneCommandSpec spec,
                                 Run              run,
                                 CostCheck<Scene> cost_check = {})
  {
    struct Options
    {
      std::string scene;
      std::string output;
      bool        print_defaults = false;
      bool        print_schema   = false;
      bool        check          = false;
      bool        accept_cost    = false;
    };
    auto        options  = std::make_shared<Options>();
    CLI::App   *command  = app.add_subcommand(spec.name, spec.description);
    const bool  optional = !spec.default_scene.empty();
    std::string what     = optional ? "scene file (YAML; none: the " + spec.default_scene + ")" :
                                      "scene file (YAML); see --print-defaults";
    command->add_option("scene", options->scene, what)->type_name("SCENE.yaml");
    add_output_option(*command, options->output);
    command->add_flag("--print-defaults",
                      options->print_defaults,
                      "print the annotated default scene (every key with default, unit and "
                      "meaning) and exit");
    add_print_schema_flag(*command, options->print_schema);
    add_check_flag(*command, options->check);
    if (cost_check)
      command->add_flag("--accept-cost",
                        options->accept_cost,
                        "run although the estimated cost (DoFs, memory or time) is above the "
                        "limits, which otherwise refuse the run with the estimate");
    // CLI11 keeps bound values between parses of one app: start each use of the command afresh.
    command->preparse_callback([options](std::size_t) { *options = Options{}; });
    command->callback(
      [options, run, spec, optional, command, cost_check]()
      {
        if (options->print_defaults)
          throw PrintDefaults(io::default_scene_text<Scene>(
            "kimp " + spec.name + " scene (defaults of kimp " + spec.name + ")"));
        if (options->print_schema)
          throw PrintDefaults(io::schema_text<Scene>());
        if (options->scene.empty() && !optional)
          throw CLI::RequiredError("the scene file SCENE.yaml (or --print-defaults)");
        if (options->check)
        {
          if (!options->scene.empty() || cost_check)
          {
            const io::LoadedScene<Scene> checked =
              options->scene.empty() ?
                io::read_scene_text<Scene>("", "(" + spec.default_scene + ")") :
                io::read_scene<Scene>(options->scene);
            if (cost_check)
              cost_check(checked.scene, options->accept_cost);
          }
          throw PrintDefaults(
            (options->scene.empty() ? "(" + spec.default_scene + ")" : options->scene) +
            ": valid\n");
        }
        if (options->output.empty())
          throw CLI::RequiredError("the output directory -o/--output DIR");
        const bool defaults = options->scene.empty();
        base::logger().info("{}: {} {}",
                            base::version_line(),
                            spec.name,
                            defaults ? "(" + spec.default_scene + ")" : options->scene);
        io::LoadedScene<Scene> scene =
          defaults ? io::read_scene_text<Scene>("", "(" + spec.default_scene + ")") :
                     io::read_scene<Scene>(options->scene);
        base::logger().debug("resolved scene (SI):\n{}", scene.resolved_json);
        if (cost_check)
          cost_check(scene.scene, options->accept_cost);
        call_scene_runner(run, scene, options->output, *command);
      });
    return command;
  }

  /// add_scene_command_at() whose run function gets the scene as const and the output directory
  /// created and locked (io::OutputDir).
  template <class Scene, class Run>
  CLI::App *
  add_scene_command(CLI::App &app, SceneCommandSpec spec, Run run, CostCheck<Scene> cost_check = {})
  {
    return add_scene_command_at<Scene>(
      app,
      std::move(spec),
      [run](const io::LoadedScene<Scene> &scene,
            const std::filesystem::path  &output,
            const CLI::App               &command)
      { call_scene_runner(run, scene, io::OutputDir(output), command); },
      std::move(cost_check));
  }

  /// Adds `--records-dir DIR` (a directory of PEER records that overrides those of the scene),
  /// described by `help`.
  inline CLI::Option *add_records_dir_option(CLI::App &command, const std::string &help)
  {
    return command.add_option("--records-dir", help)->type_name("DIR");
  }

  /// The --records-dir of a command (add_records_dir_option()) if it was given.
  inline std::optional<std::string> given_records_dir(const CLI::App &command)
  {
    const CLI::Option *option = command.get_option("--records-dir");
    if (option->count() == 0)
      return std::nullopt;
    return option->as<std::string>();
  }

  /**
   * A default of --help with a few significant figures: "195.121951219512 t" -> "≈195.1 t"
   * (the exact value is in --print-defaults); other texts unchanged.
   */
  inline std::string readable_default(const std::string &text)
  {
    const char  *begin = text.c_str();
    char        *end   = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin || (*end != '\0' && *end != ' '))
      return text;
    const std::string short_number = fmt::format("{:.4g}", value);
    if (std::strtod(short_number.c_str(), nullptr) == value)
      return text;
    return "≈" + short_number + std::string(end);
  }

  /**
   * Adds one option `--<key>` (underscores written as dashes) per top-level key of Settings'
   * visit(): a quantity or text takes a value (`--width "27.78 m"`), a flag is a flag
   * (`--raw-force`, `--raw-force=false`). The returned function reads the options given as a
   * scene document through that same visit() (units, ranges and messages of the scene keys;
   * the others keep Settings' defaults), so a setting is declared once for file and command line.
   * @throws (the returned function) io::SceneError naming the key, the value and the rule.
   */
  template <class Settings>
  std::function<Settings()> add_key_options(CLI::App &command)
  {
    struct Entry
    {
      std::string  key;
      bool         is_flag = false;
      std::string  text;
      bool         flag   = false;
      CLI::Option *option = nullptr;
    };
    auto                 entries = std::make_shared<std::vector<Entry>>();
    const nlohmann::json schema  = nlohmann::json::parse(io::schema_text<Settings>());
    for (const nlohmann::json &key : schema.at("keys"))
    {
      Entry entry;
      entry.key     = key.at("key").get<std::string>();
      entry.is_flag = key.at("type") == "flag";
      entries->push_back(entry);
    }
    for (std::size_t i = 0; i < entries->size(); ++i)
    {
      const nlohmann::json &key  = schema.at("keys").at(i);
      Entry                &e    = (*entries)[i];
      std::string           name = "--" + e.key;
      std::replace(name.begin(), name.end(), '_', '-');
      std::string help = key.value("doc", "");
      if (key.contains("unit") && key.at("unit").is_string() &&
          !key.at("unit").get<std::string>().empty())
        help += " [unit: " + key.at("unit").get<std::string>() + "]";
      if (key.contains("range") && key.at("range").is_object())
        help += " (" + key.at("range").at("text").get<std::string>() + ")";
      if (key.contains("default"))
        help +=
          " (default " +
          (key.at("default").is_string() ? readable_default(key.at("default").get<std::string>()) :
                                           key.at("default").dump()) +
          ")";
      e.option = e.is_flag ? command.add_flag(name, e.flag, help) :
                             command.add_option(name, e.text, help)->type_name("VALUE");
    }
    return [entries]()
    {
      std::string yaml;
      for (const Entry &e : *entries)
      {
        if (e.option->count() == 0)
          continue;
        std::string value = e.is_flag ? (e.flag ? "true" : "false") : e.text;
        std::string quoted;
        for (const char c : value)
          quoted += c == '\'' ? std::string("''") : std::string(1, c);
        yaml += e.key + ": " + (e.is_flag ? value : "'" + quoted + "'") + "\n";
      }
      return io::load_scene_text<Settings>(yaml, "command line");
    };
  }
} // namespace kimp::cli
