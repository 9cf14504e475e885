// The server of `kimp gui` through real HTTP requests: DNS-rebinding and cross-site requests
// refused, paths confined, oversized uploads and malformed JSON answered with 4xx, concurrent
// runs complete while the server keeps answering, runs beyond the limit queue, progress reaches
// the page as server-sent events, ports in use and out of range are refused. The ground-motion
// preview: server_motion_test.cc.
#include <algorithm>
#include <arpa/inet.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <sys/socket.h>
#include <sys/time.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "io/results_json.h"
#include "tests/server/server_test_support.h"
#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/scene_texts.h"
#include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp;
  using kimp::testing::Clock;
  using kimp::testing::ServerFixture;

  /// A lumped scene that runs in well under a second (3 storeys, 6 s of synthetic motion).
  constexpr const char *small_scene = R"(building:
  n_storeys: 3
walls:
  left:
    gap: "8 cm"
  right:
    gap: "8 cm"
ground_motion:
  record: synthetic
  duration: "6 s"
)";

  TEST_F(ServerFixture, OwnHostIsServedAndForeignHostIsRefused)
  {
    const auto own = client_->Get("/api/info");
    ASSERT_TRUE(own);
    EXPECT_EQ(own->status, 200);
    EXPECT_TRUE(json_of(own)["commands"].is_array());
    // DNS rebinding: the page of attacker.example resolves to 127.0.0.1 but keeps its name.
    const auto foreign =
      client_->Get("/api/info", {{"Host", "attacker.example:" + std::to_string(port_)}});
    ASSERT_TRUE(foreign);
    EXPECT_EQ(foreign->status, 403);
    EXPECT_NE(foreign->body.find("foreign Host"), std::string::npos) << foreign->body;
    const auto other_port = client_->Get("/", {{"Host", "127.0.0.1:1"}});
    ASSERT_TRUE(other_port);
    EXPECT_EQ(other_port->status, 403);
  }

  TEST_F(ServerFixture, CrossOriginPostIsRefused)
  {
    const std::string body = R"({"command": "lumped", "scene": "building:\n  n_storeys: 3\n"})";
    const auto        cross =
      client_->Post("/api/validate",
                    {{"X-Kimp-Request", "1"}, {"Origin", "http://attacker.example"}},
                    body,
                    "application/json");
    ASSERT_TRUE(cross);
    EXPECT_EQ(cross->status, 403);
    EXPECT_NE(cross->body.find("cross-origin"), std::string::npos) << cross->body;
    // A form post from another site cannot add the custom header.
    const auto plain = client_->Post("/api/validate", body, "text/plain");
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->status, 403);
    const auto own = client_->Post("/api/validate", post_headers(), body, "application/json");
    ASSERT_TRUE(own);
    EXPECT_EQ(own->status, 200);
    EXPECT_TRUE(json_of(own)["ok"].get<bool>()) << own->body;
  }

  TEST_F(ServerFixture, PlanScenesAreValidatedAsKimpLumpedReadsThem)
  {
    const std::string good = R"({"command": "lumped", "scene": "plan:\n  angle: 30\n"})";
    const auto        ok = client_->Post("/api/validate", post_headers(), good, "application/json");
    ASSERT_TRUE(ok);
    EXPECT_EQ(ok->status, 200);
    EXPECT_TRUE(json_of(ok)["ok"].get<bool>()) << ok->body;
    const std::string bad =
      R"({"command": "lumped", "scene": "plan:\n  moat:\n    gaps: [\"4 cm\"]\n"})";
    const auto refused = client_->Post("/api/validate", post_headers(), bad, "application/json");
    ASSERT_TRUE(refused);
    EXPECT_FALSE(json_of(refused)["ok"].get<bool>()) << refused->body;
    EXPECT_NE(refused->body.find("plan.moat.gaps"), std::string::npos) << refused->body;
  }

  TEST_F(ServerFixture, PathsLeavingTheRunDirectoryAreRefused)
  {
    const auto run = dir_.path() / "runs" / "r1";
    std::filesystem::create_directories(run);
    std::ofstream(run / "scene.yaml") << "building:\n  n_storeys: 3\n";
    std::ofstream(dir_.path() / "secret.txt") << "TOP-SECRET-CONTENT";
    const auto inside = client_->Get("/api/files/r1/scene.yaml");
    ASSERT_TRUE(inside);
    EXPECT_EQ(inside->status, 200);
    EXPECT_EQ(inside->body, "building:\n  n_storeys: 3\n");
    for (const char *path : {"/api/files/r1/../../secret.txt",
                             "/api/files/r1/%2E%2E/%2E%2E/secret.txt",
                             "/api/files/r1/..%2F..%2Fsecret.txt"})
    {
      const auto outside = client_->Get(path);
      ASSERT_TRUE(outside) << path;
      EXPECT_GE(outside->status, 400) << path;
      EXPECT_LT(outside->status, 500) << path;
      EXPECT_EQ(outside->body.find("TOP-SECRET-CONTENT"), std::string::npos) << path;
    }
    const auto record = client_->Get("/api/records/..%2F..%2Fsecret.txt");
    ASSERT_TRUE(record);
    EXPECT_GE(record->status, 400);
  }

  TEST_F(ServerFixture, HundredMegabyteUploadIsRefusedAndTheServerStaysUp)
  {
    const std::string big(100u << 20, '1');
    const auto r = client_->Post("/api/upload?name=big.txt", post_headers(), big, "text/plain");
    // The server answers 413 before reading the body; the client may see the closed socket.
    if (r)
    {
      EXPECT_EQ(r->status, 413);
    }
    EXPECT_FALSE(std::filesystem::exists(dir_.path() / "runs" / "uploads" / "big.txt"));
    httplib::Client fresh("127.0.0.1", port_);
    const auto      info = fresh.Get("/api/info");
    ASSERT_TRUE(info);
    EXPECT_EQ(info->status, 200);
  }

  TEST_F(ServerFixture, MalformedJsonGets400WithAMessage)
  {
    for (const char *body :
         {"{not json", "[1, 2]", R"({"command": 3, "scene": ""})", R"({"scene": ""})"})
    {
      const auto r = client_->Post("/api/runs", post_headers(), body, "application/json");
      ASSERT_TRUE(r) << body;
      EXPECT_EQ(r->status, 400) << body;
      EXPECT_FALSE(json_of(r)["error"].get<std::string>().empty()) << body;
    }
    // A bad scene gets the command's own message, naming line and key.
    const auto bad =
      client_->Post("/api/runs",
                    post_headers(),
                    R"({"command": "lumped", "scene": "isolator:\n  K2: \"250 MN/m\"\n"})",
                    "application/json");
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 400);
    EXPECT_NE(bad->body.find("scene.yaml:2: isolator.K2 = 250 MN/m"), std::string::npos)
      << bad->body;
  }

  TEST_F(ServerFixture, TwoConcurrentRunsCompleteWhileTheServerAnswers)
  {
    const nlohmann::json     request = {{"command", "lumped"}, {"scene", small_scene}};
    std::vector<std::string> ids;
    for (int i = 0; i < 2; ++i)
    {
      const auto r = client_->Post("/api/runs", post_headers(), request.dump(), "application/json");
      ASSERT_TRUE(r);
      ASSERT_EQ(r->status, 201) << r->body;
      ids.push_back(json_of(r)["id"]);
    }
    EXPECT_NE(ids[0], ids[1]);
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    for (const auto &id : ids)
    {
      std::string state;
      while (Clock::now() < deadline)
      {
        const auto start = Clock::now();
        const auto r     = client_->Get("/api/runs/" + id);
        ASSERT_TRUE(r);
        // Responsive: a status request is answered at once while runs are going.
        EXPECT_LT(Clock::now() - start, std::chrono::seconds(2));
        state = json_of(r)["state"];
        if (state != "running" && state != "queued")
          break;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      EXPECT_EQ(state, "done") << id;
      EXPECT_TRUE(std::filesystem::exists(dir_.path() / "runs" / id / "out" / "summary.json"));
      const auto data = client_->Get("/api/runs/" + id + "/data");
      ASSERT_TRUE(data);
      EXPECT_EQ(data->status, 200);
      EXPECT_EQ(json_of(data)["kind"], "lumped");
    }
    const auto list = client_->Get("/api/runs");
    ASSERT_TRUE(list);
    EXPECT_EQ(json_of(list).size(), 2u);
  }

  /// The small scene over 60 s of synthetic motion at a fixed step `dt`: a case of about
  /// 3e-6 s / dt seconds of work (measured: 0.63 s at 5e-6 s on the 2-core test machine).
  std::string long_scene(const std::string &dt)
  {
    return kimp::testing::replaced(small_scene,
                                   "duration: \"6 s\"",
                                   "duration: \"60 s\"\n  synthetic:\n    duration: \"60 s\"") +
           "integration:\n  dt: \"" + dt + "\"\n";
  }

  /// A lumped base scene and a sweep over it of 3000 cases, minutes of work: a run to cancel.
  const nlohmann::json long_sweep = {
    {"command", "sweep"},
    {"scene", small_scene},
    {"sweep",
     "scene: scene.yaml\ncombine: product\nparameters:\n"
     "  walls.left.gap: {from: \"1 cm\", to: \"30 cm\", step: \"0.01 cm\"}\n"}};

  TEST_F(ServerFixture, RunListHasNoLogFieldsAndARunItsLogFromTheStart)
  {
    const std::string    id  = start({{"command", "lumped"}, {"scene", small_scene}});
    const nlohmann::json run = wait_for_run(id, 60, finished);
    EXPECT_EQ(run["state"], "done") << run.dump();
    EXPECT_EQ(run["log_from"], 0) << run.dump();
    EXPECT_EQ(run["log"].size(), run["log_lines"].get<std::size_t>()) << run.dump();
    EXPECT_NE(std::find(run["files"].begin(), run["files"].end(), "out/summary.json"),
              run["files"].end())
      << run.dump();
    const auto list = client_->Get("/api/runs");
    ASSERT_TRUE(list);
    const nlohmann::json runs = json_of(list);
    ASSERT_EQ(runs.size(), 1u);
    EXPECT_FALSE(runs[0].contains("log_from")) << runs.dump();
    EXPECT_FALSE(runs[0].contains("log")) << runs.dump();
  }

  TEST_F(ServerFixture, AFailedRunKeepsEveryErrorLineOfItsLog)
  {
    // Both cases fail at run time (a peak displacement above 1 mm is "implausible"): kimp logs
    // an error line per case, then ends with "error: 2 of 2 cases failed ...".
    const std::string scene = std::string(small_scene) +
                              "integration:\n  plausible_displacement: \"1 mm\"\n"
                              "cases:\n  - {name: first}\n  - {name: second}\n";
    const std::string    id  = start({{"command", "lumped"}, {"scene", scene}});
    const nlohmann::json run = wait_for_run(id, 60, finished);
    EXPECT_EQ(run["state"], "failed") << run.dump();
    const std::string error = run["error"];
    EXPECT_EQ(error.rfind("case first: failed: implausible result", 0), 0u) << error;
    EXPECT_NE(error.find("\ncase second: failed: implausible result"), std::string::npos) << error;
    EXPECT_NE(error.find("\n2 of 2 cases failed"), std::string::npos) << error;
  }

  /// The events of GET /api/runs/ID/events, each the JSON after "data: ", until the stream ends.
  std::vector<nlohmann::json> read_events(int port, const std::string &id)
  {
    httplib::Client client("127.0.0.1", port);
    client.set_read_timeout(120, 0);
    std::string                 pending;
    std::vector<nlohmann::json> events;
    const auto                  r =
      client.Get("/api/runs/" + id + "/events",
                 [&](const char *data, std::size_t n)
                 {
                   pending.append(data, n);
                   for (std::size_t end; (end = pending.find("\n\n")) != std::string::npos;)
                   {
                     const std::string event = pending.substr(0, end);
                     pending.erase(0, end + 2);
                     EXPECT_EQ(event.rfind("data: ", 0), 0u) << event;
                     events.push_back(nlohmann::json::parse(event.substr(6), nullptr, false));
                   }
                   return true;
                 });
    EXPECT_TRUE(r);
    if (r)
    {
      EXPECT_EQ(r->status, 200);
      EXPECT_EQ(r->get_header_value("Content-Type"), "text/event-stream");
    }
    return events;
  }

  TEST_F(ServerFixture, ProgressOfALumpedRunReachesThePageAsServerSentEvents)
  {
    // Six cases of 2.4e7 steps each: several seconds in all, a progress line after each case.
    std::string scene = long_scene("2.5e-6 s") + "cases:\n";
    for (int i = 0; i < 6; ++i)
      scene +=
        "  - {name: c" + std::to_string(i) + ", gap: \"" + std::to_string(4 + i) + " cm\"}\n";
    const std::string                 id     = start({{"command", "lumped"}, {"scene", scene}});
    const std::vector<nlohmann::json> events = read_events(port_, id);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back()["state"], "done") << events.back().dump();
    EXPECT_EQ(events.back()["progress"], 1.0);
    double      last     = 0.0;
    std::size_t log      = 0;
    int         measured = 0, estimated = 0;
    for (const nlohmann::json &e : events)
    {
      ASSERT_TRUE(e.is_object());
      const double p = e["progress"];
      EXPECT_GE(p, last) << "progress never goes back in a lumped run";
      last = p;
      // Each event carries the log lines after the previous one, without the progress lines.
      EXPECT_EQ(e["log_from"], log);
      log += e["log"].size();
      for (const auto &line : e["log"])
        EXPECT_NE(line.get<std::string>().rfind("progress: ", 0), 0u) << "progress lines stay out";
      if (!(p > 0.0 && p < 1.0))
        continue;
      if (e["progress_estimated"].get<bool>())
        ++estimated; // within a case, from its cost estimate: less than its end
      else
      {
        // From the run's own lines: whole cases done, in steps of 1/6.
        ++measured;
        EXPECT_NEAR(p * 6.0, std::round(p * 6.0), 1e-3) << p;
      }
    }
    EXPECT_GT(measured, 0) << events.size() << " events";
    EXPECT_GT(estimated, 0) << events.size() << " events";
  }

  TEST_F(ServerFixture, ProgressOfASingleLumpedCaseIsEstimatedFromItsCost)
  {
    // One case of 6e7 steps: seconds of work, and no line from the engine until it ends.
    const std::string                 scene  = long_scene("1e-6 s");
    const std::string                 id     = start({{"command", "lumped"}, {"scene", scene}});
    const std::vector<nlohmann::json> events = read_events(port_, id);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back()["state"], "done") << events.back().dump();
    EXPECT_EQ(events.back()["progress"], 1.0);
    std::vector<double> between;
    for (const nlohmann::json &e : events)
      if (e["progress"] > 0.0 && e["progress"] < 1.0)
      {
        EXPECT_TRUE(e["progress_estimated"].get<bool>()) << e.dump();
        EXPECT_LE(e["progress"].get<double>(), 0.9) << "an estimate stops at 90 % of the case";
        between.push_back(e["progress"]);
      }
    EXPECT_FALSE(between.empty()) << events.size() << " events";
    EXPECT_TRUE(std::is_sorted(between.begin(), between.end()));
  }

  TEST_F(ServerFixture, ProgressOfAFemRunIsItsSimulatedTime)
  {
    if (!std::filesystem::exists(std::filesystem::path(KIMP_BINARY_DIR) / "kimp-fem"))
      GTEST_SKIP() << "a build without the FEM engine has no kimp-fem";
    // The quick smoke scene: about 2 s, ended by separation at about 17 of its 40 ms.
    const std::string scene =
      kimp::testing::read_text(kimp::testing::source_dir() / "data/scenes/fem_quick.yaml");
    const std::string                 id     = start({{"command", "fem"}, {"scene", scene}});
    const std::vector<nlohmann::json> events = read_events(port_, id);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back()["state"], "done") << events.back().dump();
    int between = 0;
    for (const nlohmann::json &e : events)
    {
      const double p = e["progress"];
      if (!(p > 0.0 && p < 1.0))
        continue;
      ++between;
      // "progress: F t = T/0.04 s ..." of base::Progress: F = T / end_time.
      const std::string text = e["progress_text"];
      const std::size_t at   = text.find("t = ");
      ASSERT_NE(at, std::string::npos) << text;
      const double t = std::stod(text.substr(at + 4));
      EXPECT_NEAR(p, t / 0.04, 1e-3) << text;
    }
    EXPECT_GT(between, 0) << events.size() << " events";
  }

  TEST_F(ServerFixture, UploadUnitsAndBodiesAreCheckedWithMessagesNamingTheField)
  {
    const std::string two_column = "0.00 0.0\n0.01 0.5\n0.02 -0.5\n0.03 0.0\n";
    for (const char *unit : {"1e400", "abc", "-1", "0", "nan", "2x"})
    {
      const auto r = client_->Post(std::string("/api/upload?name=m.txt&unit=") + unit,
                                   post_headers(),
                                   two_column,
                                   "text/plain");
      ASSERT_TRUE(r) << unit;
      EXPECT_EQ(r->status, 400) << unit << ": " << r->body;
      EXPECT_NE(r->body.find(std::string("unit = \\\"") + unit + "\\\": must be a positive finite"),
                std::string::npos)
        << r->body;
    }
    const auto ok =
      client_->Post("/api/upload?name=m.txt&unit=1", post_headers(), two_column, "text/plain");
    ASSERT_TRUE(ok);
    ASSERT_EQ(ok->status, 201) << ok->body;
    EXPECT_DOUBLE_EQ(json_of(ok)["pga"].get<double>(), 0.5); // unit 1: m/s² as written
    EXPECT_DOUBLE_EQ(json_of(ok)["dt"].get<double>(), 0.01);

    // A form-encoded upload (curl -d) of 40 KB is read like any other, up to the body limit.
    std::string big = "0 0\n";
    for (int i = 1; big.size() < 40000; ++i)
      big += std::to_string(i * 0.01) + " " + (i % 2 ? "0.25" : "-0.25") + "\n";
    const auto form = client_->Post("/api/upload?name=big.txt&unit=1",
                                    post_headers(),
                                    big,
                                    "application/x-www-form-urlencoded");
    ASSERT_TRUE(form);
    EXPECT_EQ(form->status, 201) << form->body;
    EXPECT_DOUBLE_EQ(json_of(form).value("pga", 0.0), 0.25);

    // An empty body is not JSON; a request without a body says what was expected.
    const auto empty = client_->Post("/api/runs", post_headers(), "", "application/json");
    ASSERT_TRUE(empty);
    EXPECT_EQ(empty->status, 400);
    EXPECT_NE(empty->body.find("must be a JSON object"), std::string::npos) << empty->body;
    const std::string host   = this->host();
    const std::string answer = raw_request("POST /api/runs HTTP/1.1\r\nHost: " + host +
                                           "\r\nX-Kimp-Request: 1\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(answer.rfind("HTTP/1.1 411", 0), 0u) << "[" << answer << "]";
    EXPECT_NE(answer.find("a POST to /api/runs needs its body with a Content-Length header (a "
                          "JSON object"),
              std::string::npos)
      << answer;
  }

  TEST_F(ServerFixture, UnknownPagesAndRunsAreNamedInThe404)
  {
    const auto page = client_->Get("/nothing/here");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 404);
    EXPECT_NE(page->body.find("GET /nothing/here"), std::string::npos) << page->body;
    const auto cancel = post("/api/runs/no-such-run/cancel", nlohmann::json::object());
    ASSERT_TRUE(cancel);
    EXPECT_EQ(cancel->status, 404) << cancel->body;
    const auto schema = client_->Get("/api/schema/rm");
    ASSERT_TRUE(schema);
    EXPECT_EQ(schema->status, 404);
    EXPECT_NE(schema->body.find("no scene command \\\"rm\\\""), std::string::npos) << schema->body;
  }

  TEST_F(ServerFixture, PortsInUseAndOutOfRangeAreRefused)
  {
    EXPECT_NE(server_->url().find(":" + std::to_string(port_) + "/"), std::string::npos)
      << server_->url();
    server::GuiOptions same;
    same.port            = port_;
    same.runs_dir        = dir_.path() / "runs2";
    same.kimp_executable = std::filesystem::path(KIMP_BINARY_DIR) / "kimp";
    server::GuiServer second(same);
    try
    {
      second.bind();
      ADD_FAILURE() << "a second server bound the port of a running one";
    }
    catch (const std::runtime_error &error)
    {
      EXPECT_NE(std::string(error.what())
                  .find("127.0.0.1:" + std::to_string(port_) + ": the port is in use"),
                std::string::npos)
        << error.what();
    }
    for (const int port : {99999, 65536, -1})
    {
      // A runs folder of its own: one server per runs folder.
      server::GuiOptions bad = same;
      bad.port               = port;
      bad.runs_dir           = dir_.path() / ("runs" + std::to_string(port));
      server::GuiServer s(bad);
      EXPECT_THROW(s.bind(), std::invalid_argument) << port;
    }
  }

  /// A server that runs one run at a time and queues one more.
  class OneRunServer : public ServerFixture
  {
  protected:
    void configure(server::GuiOptions &options) override
    {
      options.max_runs   = 1;
      options.max_queued = 1;
    }
  };

  TEST_F(OneRunServer, RunsBeyondTheLimitAreQueuedThenRefused)
  {
    const std::string long_run = start(long_sweep);
    EXPECT_EQ(wait_for_run(long_run, 30, [](const nlohmann::json &r) { return r.contains("pid"); })
                .value("state", ""),
              "running");
    const std::string queued = start({{"command", "lumped"}, {"scene", small_scene}});
    const auto        q      = client_->Get("/api/runs/" + queued);
    ASSERT_TRUE(q);
    EXPECT_EQ(json_of(q)["state"], "queued") << q->body;
    EXPECT_EQ(json_of(q)["queue_position"], 1) << q->body;
    const auto refused = post("/api/runs", {{"command", "lumped"}, {"scene", small_scene}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 429) << refused->body;
    EXPECT_NE(refused->body.find(
                "too many runs: 1 running (at most 1, kimp gui --max-runs) and 1 queued"),
              std::string::npos)
      << refused->body;

    // Cancelling the long run frees its place: the queued run starts and completes.
    ASSERT_EQ(post("/api/runs/" + long_run + "/cancel", nlohmann::json::object())->status, 200);
    EXPECT_EQ(wait_for_run(long_run, 30, finished)["state"], "cancelled");
    EXPECT_EQ(wait_for_run(queued, 60, finished)["state"], "done");

    // A queued run can be cancelled before it starts.
    const std::string second_long = start(long_sweep);
    const std::string never       = start({{"command", "lumped"}, {"scene", small_scene}});
    ASSERT_EQ(post("/api/runs/" + never + "/cancel", nlohmann::json::object())->status, 200);
    const nlohmann::json n = wait_for_run(never, 5, finished);
    EXPECT_EQ(n["state"], "cancelled");
    EXPECT_EQ(n["error"], "cancelled before it started");
    EXPECT_FALSE(std::filesystem::exists(dir_.path() / "runs" / never / "out"));
    ASSERT_EQ(post("/api/runs/" + second_long + "/cancel", nlohmann::json::object())->status, 200);
  }
  // Results are sent uncompressed on the loopback: a browser offers Brotli, which cpp-httplib
  // would apply to every body at about 1 MB/s (25 s for a 16 MB result).
  TEST_F(ServerFixture, ResultsAndPagesAreSentUncompressedThoughTheBrowserOffersBrotli)
  {
    const std::string id = start({{"command", "lumped"}, {"scene", small_scene}});
    ASSERT_EQ(wait_for_run(id, 60, finished)["state"], "done");
    client_->set_decompress(false);
    const httplib::Headers offers = {{"Accept-Encoding", "gzip, deflate, br"}};
    for (const std::string &path :
         std::vector<std::string>{"/api/runs/" + id + "/data",
                                  "/api/runs/" + id + "/report",
                                  "/api/files/" + id + "/out/summary.json",
                                  std::string("/")})
    {
      const auto r = client_->Get(path, offers);
      ASSERT_TRUE(r) << path;
      EXPECT_EQ(r->status, 200) << path;
      EXPECT_EQ(r->get_header_value("Content-Encoding"), "") << path;
      EXPECT_GT(r->body.size(), 100u) << path;
      if (path.find("/data") != std::string::npos)
      {
        EXPECT_EQ(json_of(r)["kind"], "lumped");
      }
    }
  }

  // The data the page draws is the results file's, each number to 7 significant digits (what
  // "%.7g" then strtod give): rounded, not truncated, shortened or left at full precision.
  TEST_F(ServerFixture, ResultsDataHoldsTheResultsFileToSevenSignificantDigits)
  {
    const std::string id = start({{"command", "lumped"}, {"scene", small_scene}});
    ASSERT_EQ(wait_for_run(id, 60, finished)["state"], "done");
    const auto r = client_->Get("/api/runs/" + id + "/data");
    ASSERT_TRUE(r);
    const nlohmann::json shown = json_of(r)["h5"]["lumped.h5"]["datasets"];
    const nlohmann::json file =
      io::results_to_json(dir_.path() / "runs" / id / "out" / "lumped.h5")["datasets"];
    std::size_t numbers = 0;
    std::size_t changed = 0;
    for (const auto &[path, dataset] : file.items())
    {
      const nlohmann::json &values = dataset.value("data", nlohmann::json());
      const nlohmann::json  flat =
        values.is_array() ? values.flatten() : nlohmann::json{{"", values}};
      const nlohmann::json got    = shown.at(path).value("data", nlohmann::json());
      const nlohmann::json gotten = got.is_array() ? got.flatten() : nlohmann::json{{"", got}};
      for (const auto &[at, value] : flat.items())
      {
        if (!value.is_number_float() || !std::isfinite(value.get<double>()))
          continue;
        char text[32];
        std::snprintf(text, sizeof(text), "%.7g", value.get<double>());
        const double expected = std::strtod(text, nullptr);
        ASSERT_EQ(gotten.at(at).get<double>(), expected) << path << at;
        ++numbers;
        changed += expected != value.get<double>() ? 1 : 0;
      }
    }
    EXPECT_GT(numbers, 1000u);
    EXPECT_GT(changed, numbers / 2) << "the results file's numbers have more than 7 digits";
  }
} // namespace
