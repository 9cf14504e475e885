// `kimp gui` as a user starts it: the real executable as a child process on a free port, driven
// by HTTP requests. A cancel stops the run's child process, SIGTERM stops the server and its runs,
// the commands offered and validated are those of the executable (fem and study through
// kimp-fem), --records-dir reaches the runs, and bad ports are refused.
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "tests/server/gui_process_support.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  const nlohmann::json long_sweep = long_sweep_request();

  /// The arguments of a server on a free port that keeps its runs in `dir`/runs.
  std::vector<std::string> serving_runs_in(const fs::path &dir)
  {
    return {"--port", "0", "--runs-dir", (dir / "runs").string()};
  }

  /// Posts the run `body` to `gui`, asserts that it is accepted (201) and sets `id` to its id.
  void start_run(GuiProcess &gui, const nlohmann::json &body, std::string &id)
  {
    const auto started = gui.post("/api/runs", body);
    ASSERT_TRUE(started);
    ASSERT_EQ(started->status, 201) << started->body;
    id = nlohmann::json::parse(started->body)["id"].get<std::string>();
  }

  /// The run `id` once it is neither running nor queued (at most 60 s).
  nlohmann::json finished_run(GuiProcess &gui, const std::string &id)
  {
    return gui.wait_for_run(id,
                            60,
                            [](const nlohmann::json &r)
                            { return r["state"] != "running" && r["state"] != "queued"; });
  }

  /// A running run's child pid, after waiting for the run to be running.
  int running_pid(GuiProcess &gui, const std::string &id)
  {
    const nlohmann::json run =
      gui.wait_for_run(id, 30, [](const nlohmann::json &r) { return r.contains("pid"); });
    return run.value("pid", -1);
  }

  /// Runs `stop(gui, id, pid)` on `kimp gui` serving its runs in a fresh directory `tag`, once
  /// the long sweep `id` runs in its child process `pid` (asserted first); the sweep must then be
  /// saved as cancelled.
  template <class Stop>
  void stop_long_sweep(const char *tag, Stop &&stop)
  {
    const kimp::testing::TempDir dir{tag};
    GuiProcess                   gui(binary("kimp"), dir.path(), serving_runs_in(dir.path()));
    ASSERT_GT(gui.port(), 0) << gui.err();
    std::string id;
    ASSERT_NO_FATAL_FAILURE(start_run(gui, long_sweep, id));
    const int pid = running_pid(gui, id);
    ASSERT_GT(pid, 0);
    ASSERT_NO_FATAL_FAILURE(stop(gui, id, pid));
    const nlohmann::json saved =
      nlohmann::json::parse(kimp::testing::read_text(dir.path() / "runs" / id / "run.json"));
    EXPECT_EQ(saved["state"], "cancelled");
  }

  TEST(GuiProcess, CancelStopsTheRunsChildProcessAndTheListShowsIt)
  {
    const auto stop = [](GuiProcess &gui, const std::string &id, int pid)
    {
      ASSERT_TRUE(process_alive(pid));
      // The child inherits no blocked signal from the server (which blocks SIGINT and SIGTERM).
      EXPECT_EQ(blocked_signals(pid), "0000000000000000");
      // The sweep reports its progress ("(N/M in all ...)" every 2 s) before it is cancelled.
      const nlohmann::json going =
        gui.wait_for_run(id,
                         30,
                         [](const nlohmann::json &r) { return r.value("progress", 0.0) > 0.0; });
      EXPECT_GT(going.value("progress", 0.0), 0.0) << going.dump();
      EXPECT_LT(going.value("progress", 1.0), 0.5) << going.dump();

      const auto cancel = gui.post("/api/runs/" + id + "/cancel", nlohmann::json::object());
      ASSERT_TRUE(cancel);
      EXPECT_EQ(cancel->status, 200) << cancel->body;
      EXPECT_TRUE(nlohmann::json::parse(cancel->body)["cancelled"].get<bool>());
      // SIGTERM ends a kimp child at once; the check allows for a loaded machine.
      const auto deadline = Clock::now() + std::chrono::seconds(10);
      while (process_alive(pid) && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      EXPECT_FALSE(process_alive(pid)) << "the sweep child is still running after the cancel";
      const nlohmann::json run =
        gui.wait_for_run(id, 10, [](const nlohmann::json &r) { return r["state"] != "running"; });
      EXPECT_EQ(run["state"], "cancelled") << run.dump();
      EXPECT_NE(run.value("error", "").find("cancelled after"), std::string::npos) << run.dump();

      // The list of runs keeps the cancelled run, its state and the files it wrote.
      const nlohmann::json list = gui.get_json("/api/runs");
      ASSERT_EQ(list.size(), 1u) << list.dump();
      EXPECT_EQ(list[0]["id"], id);
      EXPECT_EQ(list[0]["state"], "cancelled");
      EXPECT_FALSE(list[0].contains("log_from")) << list.dump();
      EXPECT_FALSE(list[0]["files"].empty()) << "a sweep writes its journal as it goes";
    };
    stop_long_sweep("gui_cancel", stop);
  }

  TEST(GuiProcess, SigtermStopsTheServerAndItsRunsPromptly)
  {
    const auto stop = [](GuiProcess &gui, const std::string &id, int pid)
    {
      // A page following the run keeps an event stream open.
      std::atomic<bool> streaming{false};
      std::thread       stream(
        [&]
        {
          httplib::Client c("127.0.0.1", gui.port());
          c.set_read_timeout(30, 0);
          c.Get("/api/runs/" + id + "/events",
                [&](const char *, std::size_t)
                {
                  streaming = true;
                  return true;
                });
        });
      const auto deadline = Clock::now() + std::chrono::seconds(10);
      while (!streaming && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      ASSERT_TRUE(streaming);

      kill(gui.pid(), SIGTERM);
      // Measured: about 0.2 s (the child ends on SIGTERM at once); the bound allows
      // for a loaded machine and stays far below the minutes the sweep would take.
      const Exit e = gui.wait(10.0);
      stream.join();
      ASSERT_TRUE(e.exited) << "kimp gui still running 10 s after SIGTERM";
      RecordProperty("seconds_to_stop", std::to_string(e.seconds));
      EXPECT_EQ(e.exit_code, 0) << gui.err();
      EXPECT_LT(e.seconds, 5.0);
      EXPECT_FALSE(process_alive(pid)) << "the run's child outlived kimp gui";
    };
    stop_long_sweep("gui_sigterm", stop);
  }

  /// The fem scene of the quick smoke run, as the page would send it.
  std::string quick_fem_scene()
  {
    return kimp::testing::read_text(kimp::testing::source_dir() / "data/scenes/fem_quick.yaml");
  }

  /// /api/info and /api/validate of `kimp gui` and `kimp-fem gui`: fem and study are offered
  /// exactly when kimp-fem is there, and their scenes are validated by it.
  void check_commands_and_validation(const fs::path &executable)
  {
    const kimp::testing::TempDir dir{"gui_commands"};
    GuiProcess                   gui(executable, dir.path(), serving_runs_in(dir.path()));
    ASSERT_GT(gui.port(), 0) << gui.err();
    const bool               with_fem = fs::exists(binary("kimp-fem"));
    const nlohmann::json     info     = gui.get_json("/api/info");
    std::vector<std::string> commands;
    for (const auto &c : info["commands"])
      commands.push_back(c);
    const auto offered = [&](const std::string &c)
    { return std::find(commands.begin(), commands.end(), c) != commands.end(); };
    EXPECT_TRUE(offered("lumped") && offered("collide") && offered("sweep")) << info.dump();
    EXPECT_EQ(offered("fem"), with_fem) << info.dump();
    EXPECT_EQ(offered("study"), with_fem) << info.dump();

    // An unknown command is refused, for validation and for runs.
    for (const char *path : {"/api/validate", "/api/runs"})
    {
      const auto rm = gui.post(path, {{"command", "rm"}, {"scene", "x: 1\n"}});
      ASSERT_TRUE(rm);
      EXPECT_EQ(rm->status, 400) << path << ": " << rm->body;
      EXPECT_NE(rm->body.find("unknown command \\\"rm\\\""), std::string::npos) << rm->body;
    }
    if (!with_fem)
      return;
    // fem and study scenes are read by the FEM executable as its run would read them.
    for (const char *command : {"fem", "study"})
    {
      const auto bogus = gui.post("/api/validate", {{"command", command}, {"scene", "bogus: 1\n"}});
      ASSERT_TRUE(bogus);
      ASSERT_EQ(bogus->status, 200) << bogus->body;
      const nlohmann::json answer = nlohmann::json::parse(bogus->body);
      EXPECT_FALSE(answer["ok"].get<bool>()) << command << ": " << bogus->body;
      EXPECT_NE(answer["error"].get<std::string>().find("scene.yaml:1: "), std::string::npos)
        << bogus->body;
      EXPECT_NE(answer["error"].get<std::string>().find("bogus"), std::string::npos) << bogus->body;
      const auto refused = gui.post("/api/runs", {{"command", command}, {"scene", "bogus: 1\n"}});
      ASSERT_TRUE(refused);
      EXPECT_EQ(refused->status, 400) << refused->body;
    }
    const auto good = gui.post("/api/validate", {{"command", "fem"}, {"scene", quick_fem_scene()}});
    ASSERT_TRUE(good);
    EXPECT_EQ(good->body, R"({"error":"","ok":true})");
    const auto bad_value =
      gui.post("/api/validate",
               {{"command", "fem"},
                {"scene", "wall_heights: [\"1.25 m\"]\nslab:\n  velocity: \"-1 m/s\"\n"}});
    ASSERT_TRUE(bad_value);
    EXPECT_NE(bad_value->body.find("scene.yaml:3: slab.velocity"), std::string::npos)
      << bad_value->body;
    const auto schema = gui.get_json("/api/schema/fem");
    EXPECT_TRUE(schema.contains("keys")) << schema.dump();
  }

  TEST(GuiProcess, KimpGuiOffersAndValidatesFemAndStudyThroughKimpFem)
  {
    check_commands_and_validation(binary("kimp"));
  }

  TEST(GuiProcess, KimpFemGuiOffersAndValidatesFemAndStudy)
  {
    if (!fs::exists(binary("kimp-fem")))
      GTEST_SKIP() << "a build without the FEM engine has no kimp-fem";
    check_commands_and_validation(binary("kimp-fem"));
  }

  TEST(GuiProcess, RunsFindBareRecordNamesInTheRecordsDirectoryOfKimpGui)
  {
    const kimp::testing::TempDir dir{"gui_records"};
    // A 4 s square wave of +-0.3 g as a PEER AT2 file.
    std::string at2 = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS OF G\n"
                      "NPTS= 400, DT= .0100 SEC\n";
    for (int i = 0; i < 400; ++i)
      at2 += (i / 100) % 2 == 0 ? " 0.30\n" : " -0.30\n";
    fs::create_directories(dir.path() / "records");
    std::ofstream(dir.path() / "records" / "RSN1_TEST_X000.AT2") << at2;
    std::vector<std::string> arguments = serving_runs_in(dir.path());
    arguments.insert(arguments.end(), {"--records-dir", (dir.path() / "records").string()});
    GuiProcess gui(binary("kimp"), dir.path(), arguments);
    ASSERT_GT(gui.port(), 0) << gui.err();
    EXPECT_EQ(gui.get_json("/api/records"), nlohmann::json::array({"RSN1_TEST_X000"}));
    std::string id;
    ASSERT_NO_FATAL_FAILURE(start_run(
      gui,
      {{"command", "lumped"},
       {"scene", "building:\n  n_storeys: 3\nground_motion:\n  record: RSN1_TEST_X000\n"}},
      id));
    const nlohmann::json run = finished_run(gui, id);
    EXPECT_EQ(run["state"], "done") << run.dump();
    const nlohmann::json summary =
      nlohmann::json::parse(kimp::testing::read_text(dir.path() / "runs" / id / "out/summary.json"),
                            nullptr,
                            false);
    ASSERT_TRUE(summary.is_object());
    // The record's PGA, 0.3 g, as the run read it from the records directory.
    EXPECT_NEAR(summary["ground_motion"]["pga"].get<double>(), 0.3 * 9.80665, 1e-9)
      << summary["ground_motion"].dump();
  }

  TEST(GuiProcess, MotionPreviewIsTheMotionOfTheRun)
  {
    const kimp::testing::TempDir dir{"gui_motion"};
    GuiProcess                   gui(binary("kimp"),
                   dir.path(),
                   {"--port", "0", "--runs-dir", (dir.path() / "runs").string()});
    ASSERT_GT(gui.port(), 0) << gui.err();
    // The synthetic motion of the scene's own section, scaled to 0.35 g, by -1.2, trimmed to 5 s.
    const std::string scene   = "building:\n  n_storeys: 3\nground_motion:\n"
                                "  scale_to_pga: \"0.35 g\"\n  scale: -1.2\n  duration: \"5 s\"\n"
                                "  synthetic:\n    seed: 7\n    pulse_time: \"3 s\"\n";
    const auto        preview = gui.post("/api/motion", {{"command", "lumped"}, {"scene", scene}});
    ASSERT_TRUE(preview);
    ASSERT_EQ(preview->status, 200) << preview->body;
    const nlohmann::json motion = nlohmann::json::parse(preview->body);
    std::string          id;
    ASSERT_NO_FATAL_FAILURE(start_run(gui, {{"command", "lumped"}, {"scene", scene}}, id));
    const nlohmann::json run = finished_run(gui, id);
    ASSERT_EQ(run["state"], "done") << run.dump();
    const nlohmann::json summary = nlohmann::json::parse(
      kimp::testing::read_text(dir.path() / "runs" / id / "out/summary.json"))["ground_motion"];
    // The same samples: name, dt, length and PGA equal to the last bit (JSON keeps doubles).
    EXPECT_EQ(motion["name"], summary["name"]);
    EXPECT_EQ(motion["dt"].get<double>(), summary["dt"].get<double>());
    EXPECT_EQ(motion["duration"].get<double>(), summary["duration"].get<double>());
    EXPECT_EQ(motion["pga"].get<double>(), summary["pga"].get<double>());
    EXPECT_NEAR(motion["pga"].get<double>(), 1.2 * 0.35 * 9.80665, 1e-12 * 4.2);
    EXPECT_EQ(motion["acceleration"].size(), 1000u); // 5 s at the default 5 ms
  }

  TEST(GuiProcess, PortsOutsideTheRangeAndPortsInUseAreRefused)
  {
    const kimp::testing::TempDir dir{"gui_ports"};
    GuiProcess                   first(binary("kimp"), dir.path(), serving_runs_in(dir.path()));
    ASSERT_GT(first.port(), 0) << first.err();
    EXPECT_NE(first.out().find("http://127.0.0.1:" + std::to_string(first.port()) + "/"),
              std::string::npos);
    EXPECT_EQ(first.get_json("/api/info")["commands"][0], "lumped");

    const fs::path second_dir = dir.path() / "second";
    fs::create_directories(second_dir);
    GuiProcess second(
      binary("kimp"),
      second_dir,
      {"--port", std::to_string(first.port()), "--runs-dir", (dir.path() / "runs2").string()},
      false);
    const Exit e = second.wait(30);
    ASSERT_TRUE(e.exited) << "a second kimp gui on a port in use must fail, not serve";
    EXPECT_EQ(e.exit_code, 1);
    EXPECT_NE(second.err().find("port is in use"), std::string::npos) << second.err();
    EXPECT_EQ(second.out().find("http://"), std::string::npos) << second.out();

    const fs::path third_dir = dir.path() / "third";
    fs::create_directories(third_dir);
    GuiProcess third(binary("kimp"), third_dir, {"--port", "99999"}, false);
    const Exit e3 = third.wait(30);
    ASSERT_TRUE(e3.exited);
    EXPECT_EQ(e3.exit_code, 2);
    EXPECT_NE(third.err().find("--port"), std::string::npos) << third.err();
    EXPECT_EQ(third.out().find("http://"), std::string::npos) << third.out();
  }
} // namespace
