// The server of `kimp gui` through real HTTP requests: DNS-rebinding and cross-site requests
// refused, paths confined, oversized uploads and malformed JSON answered with 4xx, concurrent
// runs complete while the server keeps answering.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <thread>

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
    void SetUp() override
    {
      server::GuiOptions options;
      options.port            = 0;
      options.runs_dir        = dir_.path() / "runs";
      options.kimp_executable = std::filesystem::path(KIMP_BINARY_DIR) / "kimp";
      server_                 = std::make_unique<server::GuiServer>(options);
      port_                   = server_->bind();
      thread_                 = std::thread([this] { server_->listen(); });
      client_                 = std::make_unique<httplib::Client>("127.0.0.1", port_);
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
} // namespace
