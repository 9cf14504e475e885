// The server of `kimp gui` through real HTTP requests: DNS-rebinding and cross-site requests
// refused, paths confined, oversized uploads and malformed JSON answered with 4xx, concurrent
// runs complete while the server keeps answering, runs beyond the limit queue, progress reaches
// the page as server-sent events, ports in use and out of range are refused.
#include <algorithm>
#include <arpa/inet.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <sys/socket.h>
#include <sys/time.h>
#include <thread>
#include <unistd.h>

#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/temp_dir.h"

#include "server/server.h"

// Last: <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen headers.
#include <httplib.h>

namespace
{
  using namespace kimp;
  using Clock = std::chrono::steady_clock;

  /// A GuiServer on a free loopback port, serving from a thread for the test's lifetime.
  class ServerFixture : public ::testing::Test
  {
  protected:
    /// Options of the server under test (a fixture may change them).
    virtual void configure(server::GuiOptions &) {}

    void SetUp() override
    {
      server::GuiOptions options;
      options.port            = 0;
      options.runs_dir        = dir_.path() / "runs";
      options.kimp_executable = std::filesystem::path(KIMP_BINARY_DIR) / "kimp";
      configure(options);
      server_ = std::make_unique<server::GuiServer>(options);
      port_   = server_->bind();
      thread_ = std::thread([this] { server_->listen(); });
      client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
      client_->set_read_timeout(30, 0);
    }
    void TearDown() override
    {
      server_->stop();
      thread_.join();
    }
    std::string      host() const { return "127.0.0.1:" + std::to_string(port_); }
    httplib::Headers post_headers() const
    {
      return {{"X-Kimp-Request", "1"}, {"Origin", "http://" + host()}};
    }
    nlohmann::json json_of(const httplib::Result &r) const
    {
      return nlohmann::json::parse(r->body, nullptr, false);
    }
    httplib::Result post(const std::string &path, const nlohmann::json &body)
    {
      return client_->Post(path, post_headers(), body.dump(), "application/json");
    }
    /// Starts a run and returns its id (a failed start fails the test).
    std::string start(const nlohmann::json &request)
    {
      const auto r = post("/api/runs", request);
      EXPECT_TRUE(r);
      if (!r)
        return "";
      EXPECT_EQ(r->status, 201) << r->body;
      return json_of(r).value("id", "");
    }
    /// Polls the run until `done` holds, at most `limit_s` seconds.
    template <class Predicate>
    nlohmann::json wait_for_run(const std::string &id, double limit_s, Predicate done)
    {
      const auto     deadline = Clock::now() + std::chrono::duration<double>(limit_s);
      nlohmann::json run;
      while (Clock::now() < deadline)
      {
        const auto r = client_->Get("/api/runs/" + id);
        run          = r ? json_of(r) : nlohmann::json();
        if (done(run))
          break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      return run;
    }
    static bool finished(const nlohmann::json &run)
    {
      const std::string state = run.value("state", "");
      return state != "running" && state != "queued";
    }
    /// The raw answer of the server to the bytes `request` (for requests httplib cannot send).
    std::string raw_request(const std::string &request) const
    {
      const int   sock = socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in address{};
      address.sin_family = AF_INET;
      address.sin_port   = htons(static_cast<std::uint16_t>(port_));
      inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
      std::string answer;
      timeval     timeout{10, 0};
      setsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
      if (connect(sock, reinterpret_cast<sockaddr *>(&address), sizeof(address)) == 0 &&
          send(sock, request.data(), request.size(), 0) == static_cast<ssize_t>(request.size()))
      {
        char buffer[4096];
        for (ssize_t n; (n = recv(sock, buffer, sizeof(buffer), 0)) > 0;)
          answer.append(buffer, static_cast<std::size_t>(n));
      }
      close(sock);
      return answer;
    }

    kimp::testing::TempDir             dir_{"server"};
    std::unique_ptr<server::GuiServer> server_;
    int                                port_ = 0;
    std::thread                        thread_;
    std::unique_ptr<httplib::Client>   client_;
  };

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
    std::string       scene = small_scene;
    const std::string six   = "duration: \"6 s\"";
    scene.replace(scene.find(six),
                  six.size(),
                  "duration: \"60 s\"\n  synthetic:\n    duration: \"60 s\"");
    return scene + "integration:\n  dt: \"" + dt + "\"\n";
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
      server::GuiOptions bad = same;
      bad.port               = port;
      server::GuiServer s(bad);
      EXPECT_THROW(s.bind(), std::invalid_argument) << port;
    }
  }

  constexpr double standard_gravity = 9.80665;

  /// The largest |a| of a motion's acceleration samples, m/s².
  double peak_of(const nlohmann::json &motion)
  {
    double peak = 0.0;
    for (const auto &a : motion["acceleration"])
      peak = std::max(peak, std::abs(a.get<double>()));
    return peak;
  }

  /// A server whose records directory holds one PEER record: RSN1_TEST_X000.AT2, a 4 s sine of
  /// 0.3 g amplitude and 1 Hz (400 samples at 0.01 s, written to 5 decimals, in g), the
  /// AT2 fixture of the gui process test with a waveform whose samples all differ.
  class RecordsServer : public ServerFixture
  {
  protected:
    void configure(server::GuiOptions &options) override
    {
      std::string at2 = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS OF G\n"
                        "NPTS= 400, DT= .0100 SEC\n";
      for (int i = 0; i < 400; ++i)
      {
        char line[32];
        std::snprintf(line, sizeof(line), " %.5f\n", 0.3 * std::sin(2.0 * M_PI * 0.01 * i));
        at2 += line;
      }
      std::filesystem::create_directories(dir_.path() / "records");
      kimp::testing::write_text(dir_.path() / "records" / "RSN1_TEST_X000.AT2", at2);
      options.records_dir = dir_.path() / "records";
    }
    /// POST /api/motion of `scene` for `command`.
    httplib::Result motion(const std::string &scene, const std::string &command = "lumped")
    {
      return post("/api/motion", {{"command", command}, {"scene", scene}});
    }
  };

  TEST_F(RecordsServer, InfoOffersTheMotionPreview)
  {
    const auto info = client_->Get("/api/info");
    ASSERT_TRUE(info);
    EXPECT_EQ(json_of(info)["motion_preview"], true) << info->body;
  }

  TEST_F(RecordsServer, SyntheticMotionHasTheScenesPgaSamplesAndScaling)
  {
    // The default scene: the generator's 20 s at 5 ms, its PGA (0.8 g) met exactly.
    const auto plain = motion("");
    ASSERT_TRUE(plain);
    ASSERT_EQ(plain->status, 200) << plain->body;
    const nlohmann::json m = json_of(plain);
    EXPECT_EQ(m["name"], "synthetic_near_fault");
    EXPECT_EQ(m["dt"].get<double>(), 0.005);
    EXPECT_EQ(m["acceleration"].size(), 4000u);
    EXPECT_NEAR(peak_of(m), 0.8 * standard_gravity, 1e-12 * 0.8 * standard_gravity);
    EXPECT_EQ(m["pga"].get<double>(), peak_of(m));
    EXPECT_NEAR(m["duration"].get<double>(), 20.0, 1e-12);

    // scale_to_pga "0.3 g": the peak is 0.3 g to 1e-12 (relative); the samples are the
    // unscaled ones times 0.3 g / 0.8 g (scaled_to_pga pins the peak, the rest to rounding).
    const auto to_pga = motion("ground_motion:\n  scale_to_pga: \"0.3 g\"\n");
    ASSERT_TRUE(to_pga);
    ASSERT_EQ(to_pga->status, 200) << to_pga->body;
    const nlohmann::json s = json_of(to_pga);
    ASSERT_EQ(s["acceleration"].size(), 4000u);
    EXPECT_NEAR(peak_of(s), 0.3 * standard_gravity, 1e-12 * 0.3 * standard_gravity);
    for (std::size_t i = 0; i < 4000; i += 97)
      EXPECT_NEAR(s["acceleration"][i].get<double>(),
                  m["acceleration"][i].get<double>() * 0.375,
                  1e-12 * standard_gravity)
        << i;

    // The scene's own synthetic section, then scale (after scale_to_pga) and duration: 0.25 g
    // x -2 = 0.5 g; 6 s at 4 ms = 1500 samples (round(duration / dt), within one).
    const auto own = motion("ground_motion:\n  scale: -2\n  duration: \"6 s\"\n  synthetic:\n"
                            "    pga: \"0.25 g\"\n    dt: \"4 ms\"\n    pulse_time: \"3 s\"\n");
    ASSERT_TRUE(own);
    ASSERT_EQ(own->status, 200) << own->body;
    const nlohmann::json o = json_of(own);
    EXPECT_EQ(o["dt"].get<double>(), 0.004);
    EXPECT_NEAR(static_cast<double>(o["acceleration"].size()), 6.0 / 0.004, 1.0);
    EXPECT_NEAR(peak_of(o), 0.5 * standard_gravity, 1e-12 * 0.5 * standard_gravity);
  }

  TEST_F(RecordsServer, ScaledRecordIsTheRecordTimesTheScale)
  {
    const auto raw = client_->Get("/api/records/RSN1_TEST_X000");
    ASSERT_TRUE(raw);
    ASSERT_EQ(raw->status, 200) << raw->body;
    const nlohmann::json r = json_of(raw);
    ASSERT_EQ(r["acceleration"].size(), 400u);
    // Its peak, sample 25 (sin = 1, written 0.30000), in m/s².
    EXPECT_NEAR(r["pga"].get<double>(), 0.3 * standard_gravity, 1e-12 * 0.3 * standard_gravity);

    // A bare record name found in kimp gui's records directory, scaled by 2.5 and trimmed to
    // 3 s: the first 300 samples of GET /api/records, each times 2.5 (one rounding).
    const auto scaled =
      motion("ground_motion:\n  record: RSN1_TEST_X000\n  scale: 2.5\n  duration: \"3 s\"\n");
    ASSERT_TRUE(scaled);
    ASSERT_EQ(scaled->status, 200) << scaled->body;
    const nlohmann::json s = json_of(scaled);
    EXPECT_EQ(s["name"], r["name"]);
    EXPECT_EQ(s["dt"].get<double>(), r["dt"].get<double>());
    ASSERT_EQ(s["acceleration"].size(), 300u);
    for (std::size_t i = 0; i < 300; ++i)
    {
      const double expected = 2.5 * r["acceleration"][i].get<double>();
      EXPECT_NEAR(s["acceleration"][i].get<double>(), expected, 1e-15 * std::abs(expected)) << i;
    }

    // scale_to_pga "0.45 g" of the record: its peak 0.45 g to 1e-12 (relative).
    const auto to_pga = motion("ground_motion:\n  record: RSN1_TEST_X000\n"
                               "  scale_to_pga: \"0.45 g\"\n");
    ASSERT_TRUE(to_pga);
    ASSERT_EQ(to_pga->status, 200) << to_pga->body;
    EXPECT_EQ(json_of(to_pga)["acceleration"].size(), 400u);
    EXPECT_NEAR(peak_of(json_of(to_pga)), 0.45 * standard_gravity, 1e-12 * 0.45 * standard_gravity);

    // A scene naming its own records_dir: found there, as the run finds it (kimp gui's
    // directory is the run's KIMP_RECORDS_DIR, which the scene's key overrides). There the
    // record is 0.1 g throughout.
    std::string constant = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS "
                           "OF G\nNPTS= 50, DT= .0200 SEC\n";
    for (int i = 0; i < 50; ++i)
      constant += " 0.10000\n";
    std::filesystem::create_directories(dir_.path() / "own_records");
    kimp::testing::write_text(dir_.path() / "own_records" / "RSN1_TEST_X000.AT2", constant);
    const auto own = motion("ground_motion:\n  record: RSN1_TEST_X000\n  records_dir: '" +
                            (dir_.path() / "own_records").string() + "'\n");
    ASSERT_TRUE(own);
    ASSERT_EQ(own->status, 200) << own->body;
    EXPECT_EQ(json_of(own)["dt"].get<double>(), 0.02);
    EXPECT_EQ(json_of(own)["acceleration"].size(), 50u);
    EXPECT_NEAR(peak_of(json_of(own)), 0.1 * standard_gravity, 1e-12 * standard_gravity);

    // A misspelt name: refused at its key as the run refuses it, with the directory's name.
    const auto missing = motion("building:\n  n_storeys: 3\nground_motion:\n"
                                "  record: RSN1_TEST_X00\n");
    ASSERT_TRUE(missing);
    EXPECT_EQ(missing->status, 400) << missing->body;
    const std::string error = json_of(missing).value("error", "");
    EXPECT_EQ(error.rfind("scene.yaml:4: ground_motion.record = 'RSN1_TEST_X00': ", 0), 0u)
      << error;
    EXPECT_NE(error.find("did you mean 'RSN1_TEST_X000'?"), std::string::npos) << error;
  }

  TEST_F(RecordsServer, BadScenesGetTheMessageOfKimpLumpedCheck)
  {
    const kimp::testing::TempDir check_dir{"motion_check"};
    for (const std::string scene :
         {"building:\n  n_storeys: 3\nground_motion:\n  scale_to_pgaa: \"0.3 g\"\n",
          "ground_motion:\n  synthetic:\n    dt: \"-5 ms\"\n",
          "ground_motion:\n  duration: \"30 s\"\n"})
    {
      const auto r = motion(scene);
      ASSERT_TRUE(r);
      EXPECT_EQ(r->status, 400) << r->body;
      const std::string error = json_of(r).value("error", "");
      // `kimp lumped scene.yaml --check` on the same text: "error: <message>" on stderr.
      kimp::testing::write_text(check_dir.path() / "scene.yaml", scene);
      const kimp::testing::KimpRun check =
        kimp::testing::run_kimp("-q lumped scene.yaml --check", check_dir.path());
      EXPECT_NE(check.exit_code, 0) << check.out;
      std::string printed = check.err;
      if (printed.rfind("error: ", 0) == 0)
        printed.erase(0, 7);
      while (!printed.empty() && printed.back() == '\n')
        printed.pop_back();
      EXPECT_EQ(error, printed) << scene;
      EXPECT_EQ(error.rfind("scene.yaml:", 0), 0u) << error;
    }
  }

  TEST_F(RecordsServer, CommandsWithoutAGroundMotionAreRefusedByName)
  {
    for (const std::string command : {"fem", "collide", "study", "sweep", "rm"})
    {
      const auto r = motion("", command);
      ASSERT_TRUE(r) << command;
      EXPECT_EQ(r->status, 400) << command << ": " << r->body;
      EXPECT_NE(json_of(r).value("error", "").find(command), std::string::npos) << r->body;
    }
    // Without the X-Kimp-Request header, as any other POST: refused.
    const auto plain =
      client_->Post("/api/motion", R"({"command": "lumped", "scene": ""})", "application/json");
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->status, 403);
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
} // namespace
