// ServerFixture: a GuiServer of `kimp gui` on a free loopback port serving from a thread for the
// test's lifetime, with an HTTP client and the requests of the server tests.
#pragma once

#include <arpa/inet.h>
#include <chrono>
#include <filesystem>
#include <gtest/gtest.h>
#include <memory>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/socket.h>
#include <sys/time.h>
#include <thread>
#include <unistd.h>

#include "tests/support/temp_dir.h"

#include "server/server.h"

// Last: <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen headers.
#include <httplib.h>

namespace kimp::testing
{
  using Clock = std::chrono::steady_clock;

  /// A GuiServer on a free loopback port, serving from a thread for the test's lifetime.
  class ServerFixture : public ::testing::Test
  {
  protected:
    /// Options of the server under test (a fixture may change them).
    virtual void configure(kimp::server::GuiOptions &) {}

    void SetUp() override
    {
      kimp::server::GuiOptions options;
      options.port            = 0;
      options.runs_dir        = dir_.path() / "runs";
      options.kimp_executable = std::filesystem::path(KIMP_BINARY_DIR) / "kimp";
      configure(options);
      server_ = std::make_unique<kimp::server::GuiServer>(options);
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

    kimp::testing::TempDir                   dir_{"server"};
    std::unique_ptr<kimp::server::GuiServer> server_;
    int                                      port_ = 0;
    std::thread                              thread_;
    std::unique_ptr<httplib::Client>         client_;
  };
} // namespace kimp::testing
