// `kimp` command line through CLI11 in-process: --version, scene commands with --print-defaults
// and --print-schema,
// usage errors, verbosity flags; and the progress line of long runs.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app/sweep/sweep_plan.h"
#include "base/logging.h"
#include "base/version.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "io/units.h"
#include "tests/support/temp_dir.h"

namespace cli_scene
{
  struct Scene
  {
    int    n_storeys = 4;
    double gap       = 0.15;
    double K1        = 200e6;
  };

  template <class Io>
  void visit(Io &io, Scene &s)
  {
    io.integer("n_storeys", s.n_storeys, "storeys", 1, 50);
    io.quantity("gap", s.gap, "cm", "clear gap");
    io.quantity("K1", s.K1, "MN/m", "isolator initial stiffness");
  }

  void validate(const Scene &s, kimp::io::ValidationContext &ctx)
  {
    ctx.check(s.gap >= 0, "gap", kimp::io::format_quantity(s.gap, "cm"), "must be >= 0");
  }
} // namespace cli_scene

namespace
{
  using namespace kimp::cli;
  using namespace kimp::io;
  using kimp::base::Verbosity;
  using kimp::testing::TempDir;

  /// A `kimp` app with one scene command "demo" that records what it was given.
  struct DemoApp
  {
    std::unique_ptr<CLI::App> app  = make_app();
    int                       runs = 0;
    cli_scene::Scene          scene;
    std::filesystem::path     output;
    std::ostringstream        out;
    std::ostringstream        err;

    DemoApp()
    {
      add_scene_command<cli_scene::Scene>(*app,
                                          {"demo", "demo command"},
                                          [this](const LoadedScene<cli_scene::Scene> &loaded,
                                                 const OutputDir                     &dir)
                                          {
                                            ++runs;
                                            scene  = loaded.scene;
                                            output = dir.path();
                                          });
    }

    int run(const std::vector<std::string> &arguments)
    {
      out.str("");
      err.str("");
      return run_app(*app, arguments, out, err);
    }
  };

  TEST(Cli, VersionPrintsNameVersionAndGitRevision)
  {
    DemoApp demo;
    EXPECT_EQ(demo.run({"--version"}), 0);
    EXPECT_EQ(demo.out.str(),
              std::string("kimp ") + kimp::base::version + " (git " + kimp::base::git_revision +
                ")\n");
    EXPECT_EQ(demo.runs, 0);
  }

  TEST(Cli, PrintDefaultsListsTheDefaultSceneThatReadsBack)
  {
    DemoApp demo;
    ASSERT_EQ(demo.run({"demo", "--print-defaults"}), 0) << demo.err.str();
    const std::string listing = demo.out.str();
    EXPECT_NE(listing.find("n_storeys: 4  # storeys (integer in [1, 50])"), std::string::npos)
      << listing;
    EXPECT_NE(listing.find("gap: \"15 cm\"  # clear gap [cm]"), std::string::npos) << listing;
    EXPECT_NE(listing.find("K1: \"200 MN/m\"  # isolator initial stiffness [MN/m]"),
              std::string::npos)
      << listing;
    EXPECT_EQ(demo.runs, 0) << "--print-defaults must not run the command";

    const auto read_back = kimp::io::load_scene_text<cli_scene::Scene>(listing, "defaults");
    EXPECT_EQ(read_back.n_storeys, 4);
    EXPECT_DOUBLE_EQ(read_back.gap, 0.15);
    EXPECT_DOUBLE_EQ(read_back.K1, 200e6);
  }

  TEST(Cli, PrintSchemaListsEveryKeyAsJson)
  {
    DemoApp demo;
    ASSERT_EQ(demo.run({"demo", "--print-schema"}), 0) << demo.err.str();
    EXPECT_EQ(demo.runs, 0) << "--print-schema must not run the command";
    const nlohmann::json  schema = nlohmann::json::parse(demo.out.str());
    const nlohmann::json &keys   = schema.at("keys");
    ASSERT_EQ(keys.size(), 3U) << schema.dump(2);
    EXPECT_EQ(keys.at(0).at("key"), "n_storeys");
    EXPECT_EQ(keys.at(0).at("range").at("max"), 50);
    EXPECT_EQ(keys.at(1).at("key"), "gap");
    EXPECT_EQ(keys.at(1).at("unit"), "cm");
    EXPECT_EQ(keys.at(1).at("default"), "15 cm");
    EXPECT_EQ(keys.at(2).at("doc"), "isolator initial stiffness");
  }

  TEST(Cli, SweepPrintsAnExampleSweepFileThatReadsBackAndItsSchema)
  {
    const std::unique_ptr<CLI::App> app = make_app();
    kimp::cli::register_sweep_command(*app);
    std::ostringstream out, err;
    ASSERT_EQ(run_app(*app, {"sweep", "--print-defaults"}, out, err), 0) << err.str();
    const std::string listing = out.str();
    const auto        plan = kimp::app::SweepPlan::parse(listing, "defaults.yaml", "", "base.yaml");
    EXPECT_FALSE(plan.parameters().empty()) << listing;
    EXPECT_FALSE(plan.cases().empty()) << listing;

    out.str("");
    ASSERT_EQ(run_app(*app, {"sweep", "--print-schema"}, out, err), 0) << err.str();
    const nlohmann::json     schema = nlohmann::json::parse(out.str());
    std::vector<std::string> keys;
    for (const nlohmann::json &entry : schema.at("keys"))
      keys.push_back(entry.at("key"));
    for (const char *key : {"parameters", "combine", "companions", "report"})
      EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key << "\n"
                                                                      << schema.dump(2);
  }

  TEST(Cli, SceneCommandLoadsTheSceneAndCreatesTheOutputDirectory)
  {
    const TempDir dir;
    const auto    scene = dir.path() / "scene.yaml";
    std::ofstream(scene) << "n_storeys: 6\ngap: 8 cm\n";
    DemoApp demo;
    ASSERT_EQ(demo.run({"demo", scene.string(), "-o", (dir.path() / "out").string(), "-q"}), 0)
      << demo.err.str();
    EXPECT_EQ(demo.runs, 1);
    EXPECT_EQ(demo.scene.n_storeys, 6);
    EXPECT_DOUBLE_EQ(demo.scene.gap, 0.08);
    EXPECT_DOUBLE_EQ(demo.scene.K1, 200e6);
    EXPECT_EQ(demo.output, dir.path() / "out");
    EXPECT_TRUE(std::filesystem::is_directory(dir.path() / "out"));
    EXPECT_EQ(kimp::base::verbosity(), Verbosity::quiet);
  }

  TEST(Cli, OptionalSceneRunsTheDefaultsAndTheOutputIsPassedAsGiven)
  {
    const TempDir             dir;
    std::unique_ptr<CLI::App> app  = make_app();
    int                       runs = 0;
    cli_scene::Scene          seen;
    std::filesystem::path     output;
    kimp::cli::add_scene_command_at<cli_scene::Scene>(*app,
                                                      {"demo", "demo command", "demo defaults"},
                                                      [&](LoadedScene<cli_scene::Scene> &loaded,
                                                          const std::filesystem::path   &out)
                                                      {
                                                        ++runs;
                                                        seen   = loaded.scene;
                                                        output = out;
                                                      });
    std::ostringstream out;
    std::ostringstream err;
    const std::string  target = (dir.path() / "out").string();
    ASSERT_EQ(run_app(*app, {"demo", "-o", target, "-q"}, out, err), 0) << err.str();
    EXPECT_EQ(runs, 1);
    EXPECT_EQ(seen.n_storeys, 4) << "no scene file: the defaults";
    EXPECT_DOUBLE_EQ(seen.gap, 0.15);
    EXPECT_EQ(output, target);
    EXPECT_FALSE(std::filesystem::exists(target)) << "the run function creates it, not the command";
    EXPECT_EQ(run_app(*app, {"demo"}, out, err), 2) << "the output directory stays required";
    EXPECT_EQ(runs, 1);
  }

  TEST(Cli, APositionalThatNamesACommandIsTheArgumentNotASecondCommand)
  {
    // `kimp export-opensees study -o x`: `study` is the default output directory of kimp study.
    std::unique_ptr<CLI::App> app = make_app();
    std::string               source;
    int                       exports = 0;
    int                       studies = 0;
    CLI::App *export_command = app->add_subcommand("export", "reads a directory (optional)");
    export_command->add_option("source", source);
    export_command->callback([&]() { ++exports; });
    app->add_subcommand("study", "a long computation")->callback([&]() { ++studies; });
    std::ostringstream out;
    std::ostringstream err;
    ASSERT_EQ(run_app(*app, {"export", "study"}, out, err), 0) << err.str();
    EXPECT_EQ(source, "study");
    EXPECT_EQ(exports, 1);
    EXPECT_EQ(studies, 0) << "a directory named like a command must not run that command";
  }

  TEST(Cli, SceneErrorsPropagateToMain)
  {
    const TempDir dir;
    const auto    scene = dir.path() / "scene.yaml";
    std::ofstream(scene) << "n_storeys: 6\ngap: -8 cm\n";
    DemoApp demo;
    try
    {
      demo.run({"demo", scene.string(), "-o", (dir.path() / "out").string()});
      ADD_FAILURE() << "a scene that fails validation must throw";
    }
    catch (const kimp::io::SceneError &error)
    {
      EXPECT_NE(std::string(error.what()).find(scene.string() + ":2: gap = -8 cm: must be >= 0"),
                std::string::npos)
        << error.what();
    }
    EXPECT_EQ(demo.runs, 0);
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out")) << "no output for a bad scene";
  }

  TEST(Cli, CheckValidatesTheSceneWithoutRunning)
  {
    const TempDir dir;
    const auto    good = dir.path() / "good.yaml";
    const auto    bad  = dir.path() / "bad.yaml";
    std::ofstream(good) << "n_storeys: 6\n";
    std::ofstream(bad) << "n_storeys: 6\nbogus: 1\n";
    DemoApp demo;
    ASSERT_EQ(demo.run({"demo", good.string(), "--check"}), 0) << demo.err.str();
    EXPECT_EQ(demo.out.str(), good.string() + ": valid\n");
    EXPECT_THROW(demo.run({"demo", bad.string(), "--check"}), kimp::io::SceneError);
    EXPECT_EQ(demo.runs, 0) << "--check must not run the command";
  }

  TEST(Cli, UsageErrorsReturnTwoWithAMessage)
  {
    DemoApp demo;
    EXPECT_EQ(demo.run({"demo", "scene.yaml"}), 2);
    EXPECT_NE(demo.err.str().find("error: the output directory -o/--output DIR is required"),
              std::string::npos)
      << demo.err.str();
    EXPECT_EQ(demo.run({"demo", "-o", "out"}), 2);
    EXPECT_NE(demo.err.str().find("SCENE.yaml"), std::string::npos) << demo.err.str();
    EXPECT_EQ(demo.run({"--no-such-option"}), 2);
    EXPECT_NE(demo.err.str().find("--no-such-option"), std::string::npos) << demo.err.str();
    EXPECT_EQ(demo.run({"no-such-command"}), 2);
    EXPECT_NE(demo.err.str().find("unknown command 'no-such-command' (commands: demo)"),
              std::string::npos)
      << demo.err.str();
    EXPECT_EQ(demo.run({"-q", "dmeo", "scene.yaml", "-o", "out"}), 2);
    EXPECT_NE(demo.err.str().find("unknown command 'dmeo'; did you mean 'demo'?"),
              std::string::npos)
      << demo.err.str();
    EXPECT_EQ(demo.run({}), 2);
    EXPECT_NE(demo.err.str().find("no command given"), std::string::npos) << demo.err.str();
    EXPECT_EQ(demo.run({"-v", "-q", "demo", "--print-defaults"}), 2) << "-v and -q conflict";
    EXPECT_EQ(demo.runs, 0);
  }

  TEST(Cli, HelpListsTheCommandAndItsOptions)
  {
    DemoApp demo;
    EXPECT_EQ(demo.run({"--help"}), 0);
    EXPECT_NE(demo.out.str().find("demo"), std::string::npos) << demo.out.str();
    EXPECT_EQ(demo.run({"demo", "--help"}), 0);
    for (const char *part : {"SCENE.yaml", "-o,--output", "--print-defaults"})
      EXPECT_NE(demo.out.str().find(part), std::string::npos) << demo.out.str();
  }

  TEST(Cli, VerbosityFlagsSetTheLoggerLevel)
  {
    DemoApp demo;
    demo.run({"-v", "demo", "--print-defaults"});
    EXPECT_EQ(kimp::base::verbosity(), Verbosity::verbose);
    EXPECT_EQ(kimp::base::logger().level(), spdlog::level::debug);
    demo.run({"-vv", "demo", "--print-defaults"});
    EXPECT_EQ(kimp::base::logger().level(), spdlog::level::trace);
    demo.run({"demo", "--print-defaults", "--quiet"});
    EXPECT_EQ(kimp::base::logger().level(), spdlog::level::warn);
    demo.run({"demo", "--print-defaults"});
    EXPECT_EQ(kimp::base::verbosity(), Verbosity::normal);
    EXPECT_EQ(kimp::base::logger().level(), spdlog::level::info);
  }

  /// A clock the test advances by hand.
  struct FakeClock
  {
    static inline std::chrono::steady_clock::time_point now{};
    static std::chrono::steady_clock::time_point        read() { return now; }
    static void                                         advance(double seconds)
    {
      now += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(seconds));
    }
  };

  TEST(Progress, DisabledOrUnusedProgressPrintsNothing)
  {
    std::ostringstream out;
    {
      kimp::base::Progress progress(100, 1.0, out, false, FakeClock::read);
      for (int n = 1; n <= 100; ++n)
        progress.update(static_cast<std::uint64_t>(n), n * 0.01);
    }
    EXPECT_TRUE(out.str().empty()) << out.str();
    {
      kimp::base::Progress unused(100, 1.0, out, true, FakeClock::read);
    }
    EXPECT_TRUE(out.str().empty()) << "no update, no line: " << out.str();
  }

  TEST(Progress, EnabledProgressIsThrottledAndShowsStepTimeAndEta)
  {
    constexpr double     step_wall_time = 0.1;  // s of wall time per step
    constexpr double     min_interval   = 0.25; // s between lines
    std::ostringstream   out;
    kimp::base::Progress progress(10, 1.0, out, true, FakeClock::read, min_interval);
    for (int n = 1; n <= 10; ++n)
    {
      FakeClock::advance(step_wall_time);
      progress.update(static_cast<std::uint64_t>(n), n * 0.1);
    }
    progress.finish();
    const std::string text = out.str();
    // Lines at steps 1, 4, 7, 10 (every >= 0.25 s) and the final line from finish().
    EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 5) << text;
    EXPECT_NE(text.find("\rstep 1/10  t = 0.1/1 s  ETA 1 s"), std::string::npos) << text;
    EXPECT_NE(text.find("\rstep 4/10  t = 0.4/1 s  ETA 1 s"), std::string::npos) << text;
    EXPECT_NE(text.find("\rstep 10/10  t = 1/1 s  ETA 0 s"), std::string::npos) << text;
    EXPECT_EQ(text.back(), '\n');
    EXPECT_EQ(text.find("step 2/10"), std::string::npos) << text;
  }

  TEST(Progress, UnknownStepCountShowsSimulatedTimeAndEtaFromIt)
  {
    std::ostringstream   out;
    kimp::base::Progress progress(0, 2.0, out, true, FakeClock::read, 0.0);
    FakeClock::advance(1.0);
    progress.update(0, 0.5); // a quarter of the simulated time in 1 s of wall time
    progress.finish();
    const std::string text = out.str();
    EXPECT_NE(text.find("\rt = 0.5/2 s  ETA 3 s"), std::string::npos) << text;
    EXPECT_EQ(text.find("step"), std::string::npos) << text;
  }

  TEST(Progress, LinesModeWritesWholeProgressLinesWithTheFractionDone)
  {
    std::ostringstream out;
    ::setenv("KIMP_PROGRESS", "lines", 1); // as `kimp gui` starts its runs
    {
      kimp::base::Progress progress(4, 4.0, out, true, FakeClock::read, 1.0);
      for (int n = 1; n <= 4; ++n)
      {
        FakeClock::advance(1.0); // 1 s per step: every step is printed
        progress.update(static_cast<std::uint64_t>(n), n * 1.0);
      }
      progress.finish();
    }
    ::unsetenv("KIMP_PROGRESS");
    const std::string text = out.str();
    EXPECT_EQ(text.find('\r'), std::string::npos) << text;
    EXPECT_NE(text.find("progress: 0.2500 step 1/4  t = 1/4 s  ETA 3 s\n"), std::string::npos)
      << text;
    EXPECT_NE(text.find("progress: 1.0000 step 4/4  t = 4/4 s  ETA 0 s\n"), std::string::npos)
      << text;
    EXPECT_EQ(text.rfind("progress: ", 0), 0u) << text;
  }
} // namespace
