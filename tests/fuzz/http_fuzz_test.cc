// HTTP fuzz smoke test of `kimp gui`: a few thousand seeded random requests to the real
// executable, built from its routes and from random bytes: paths (percent-encoded and raw bytes,
// traversal, long segments), queries, methods, headers (Host, Origin, the page's header, body
// codings and lengths that lie) and bodies (mutated JSON requests and scenes, random bytes, chunked
// bodies with bad chunk sizes). Every request must get an HTTP answer or a closed connection, the
// server must stay alive and keep answering /api/info between them and at the end, and its
// resident memory must stay bounded. Deterministic (fixed seed and count), about half a minute.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "tests/server/gui_process_support.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  constexpr unsigned seed     = 20260526;
  constexpr int      requests = 6000;
  /// Requests between two checks that /api/info still answers.
  constexpr int check_every = 100;
  /// The fuzzing stops after this long (a loaded machine): the requests sent by then count.
  constexpr double budget_s = 40.0;

  /// A request and whether all of it is there: a body shorter than its Content-Length, or
  /// chunks without their end, would keep the server waiting for the rest.
  struct Request
  {
    std::string bytes;
    bool        complete = true;
  };

  /// Random requests to `kimp gui` on `port`.
  class RequestMaker
  {
  public:
    /// `run`: the id of a run of the server (done), for the routes of a run.
    RequestMaker(int port, std::string run)
      : host_("127.0.0.1:" + std::to_string(port))
      , run_(std::move(run))
    {
    }

    Request next()
    {
      complete_              = true;
      const double      roll = std::uniform_real_distribution<>(0, 1)(rng_);
      const std::string method =
        roll < 0.4 ?
          "GET" :
        roll < 0.8 ?
          "POST" :
        roll < 0.85 ?
          "DELETE" :
          pick({"PUT", "HEAD", "OPTIONS", "PATCH", "TRACE", "CONNECT", "PRI", "FOO", ""});
      // Mostly a body where one belongs.
      std::string body = method == "POST" || chance(0.1) ? this->body() : std::string();
      std::string head =
        method + " " + target(method) + " " +
        (chance(0.95) ? std::string("HTTP/1.1") : pick({"HTTP/1.0", "HTTP/9", "", "HTTP/1.1 x"})) +
        "\r\n";
      // Headers in random order and spelling; some lie about the body.
      std::vector<std::string> headers;
      if (chance(0.97))
        headers.push_back("Host: " + (chance(0.95) ? host_ : random_text(1, 40)));
      if (chance(0.9))
        headers.push_back("X-Kimp-Request: " +
                          (chance(0.9) ? std::string("1") : random_text(0, 5)));
      if (chance(0.2))
        headers.push_back("Origin: " + (chance(0.5) ? "http://" + host_ : random_text(0, 60)));
      if (chance(0.5))
        headers.push_back("Content-Type: " + pick({"application/json",
                                                   "text/plain",
                                                   "application/x-www-form-urlencoded",
                                                   "multipart/form-data; boundary=xyz",
                                                   "multipart/form-data",
                                                   random_text(0, 30)}));
      bool chunked = false;
      if (chance(0.15))
      {
        const std::string coding =
          pick({"chunked", "chunked", "Chunked", "gzip", "gzip, chunked", "identity", ""});
        chunked = coding == "chunked" || coding == "Chunked";
        headers.push_back("Transfer-Encoding: " + coding);
      }
      if (chance(0.05))
        headers.push_back("Content-Encoding: " + pick({"gzip", "br", "deflate", "x"}));
      if (!chunked && chance(0.9))
      {
        const std::size_t n      = body.size();
        const std::string length = chance(0.9) ? std::to_string(n) :
                                                 pick({"0",
                                                       "-1",
                                                       "abc",
                                                       "18446744073709551615",
                                                       "99999999999",
                                                       std::to_string(n + 10),
                                                       std::to_string(n / 2)});
        // A length beyond the body sent keeps the server reading.
        if (std::strtoull(length.c_str(), nullptr, 10) > n)
          complete_ = false;
        headers.push_back("Content-Length: " + length);
      }
      if (chance(0.1))
        headers.push_back(
          "Range: " + pick({"bytes=0-10", "bytes=-5", "bytes=5-1", "bytes=x", random_text(0, 20)}));
      if (chance(0.05))
        headers.push_back("Expect: 100-continue");
      if (chance(0.3))
        headers.push_back(random_text(1, 20) + ": " + random_bytes(0, 200));
      if (chance(0.05))
        headers.push_back("X-Long: " + std::string(rng_() % 10000, 'h'));
      std::shuffle(headers.begin(), headers.end(), rng_);
      for (const auto &h : headers)
        head += h + (chance(0.98) ? "\r\n" : "\n");
      head += "\r\n";
      if (chunked)
        body = chunks(body);
      return {head + body, complete_};
    }

  private:
    bool        chance(double p) { return std::uniform_real_distribution<>(0, 1)(rng_) < p; }
    std::size_t below(std::size_t n) { return n == 0 ? 0 : rng_() % n; }
    std::string pick(std::initializer_list<std::string> options)
    {
      return *(options.begin() + below(options.size()));
    }
    std::string random_bytes(std::size_t min, std::size_t max)
    {
      std::string text(min + below(max - min + 1), '\0');
      for (char &c : text)
        c = static_cast<char>(rng_() & 0xff);
      return text;
    }
    /// Printable ASCII, no space.
    std::string random_text(std::size_t min, std::size_t max)
    {
      std::string text(min + below(max - min + 1), '\0');
      for (char &c : text)
        c = static_cast<char>('!' + below(94));
      return text;
    }
    std::string percent_bytes(std::size_t n)
    {
      static const char *hex = "0123456789ABCDEF";
      std::string        text;
      for (std::size_t i = 0; i < n; ++i)
      {
        const unsigned b = rng_() & 0xff;
        text += {'%', hex[b >> 4], hex[b & 15]};
      }
      return text;
    }

    std::string target(const std::string &method)
    {
      static const std::vector<std::string> post_routes = {"/api/validate",
                                                           "/api/runs",
                                                           "/api/motion",
                                                           "/api/upload",
                                                           "/api/runs/RUN/cancel"};
      static const std::vector<std::string> routes      = {"/",
                                                           "/api/info",
                                                           "/api/runs",
                                                           "/api/runs/",
                                                           "/api/runs/RUN",
                                                           "/api/runs/RUN/events",
                                                           "/api/runs/RUN/cancel",
                                                           "/api/runs/RUN/data",
                                                           "/api/runs/RUN/report",
                                                           "/api/files/RUN/",
                                                           "/api/files/RUN/scene.yaml",
                                                           "/api/files/RUN/../../../etc/passwd",
                                                           "/api/records",
                                                           "/api/records/RSN1",
                                                           "/api/schema/lumped",
                                                           "/api/defaults/collide",
                                                           "/api/schema/x",
                                                           "/api/validate",
                                                           "/api/motion",
                                                           "/api/upload",
                                                           "/assets/gui.js",
                                                           "/assets/..%2F..%2Fx",
                                                           "/%ff",
                                                           "/%00",
                                                           "/%2e%2e/%2e%2e/"};
      std::string path = method == "POST" && chance(0.8) ? post_routes[below(post_routes.size())] :
                                                           routes[below(routes.size())];
      if (const auto at = path.find("RUN"); at != std::string::npos)
        path.replace(at,
                     3,
                     chance(0.5) ? (chance(0.7) ? run_ : pick({"a", "x_y-z", run_ + "x"})) :
                     chance(0.5) ? percent_bytes(1 + below(8)) :
                                   random_text(1, 30));
      const double roll = std::uniform_real_distribution<>(0, 1)(rng_);
      if (roll < 0.15)
        path += percent_bytes(1 + below(12));
      else if (roll < 0.25)
        path += random_text(1, 40);
      else if (roll < 0.3)
        path += std::string(below(9000), 'a'); // near and past the request line limit
      else if (roll < 0.35)
        path += random_bytes(1, 10); // raw bytes: spaces and line breaks included
      if (chance(0.4))
      {
        path += "?";
        for (std::size_t i = 0, n = 1 + below(3); i < n; ++i)
          path +=
            (i ? "&" : "") + pick({"name", "unit", "x", percent_bytes(2)}) + "=" +
            (chance(0.5) ? pick({"m.txt", "a.AT2", "9.80665", "1e400", "-1", "nan", ".x", "../x"}) :
             chance(0.5) ? percent_bytes(below(10)) :
                           random_text(0, 30));
      }
      return path;
    }

    std::string body()
    {
      const double roll = std::uniform_real_distribution<>(0, 1)(rng_);
      if (roll < 0.3)
        return "";
      if (roll < 0.45)
        return random_bytes(0, 2000);
      if (roll < 0.55)
        return two_column();
      std::string json = request_json().dump();
      // Mutations: bytes flipped, inserted, removed; a prefix only.
      for (std::size_t i = 0, n = below(4); i < n && !json.empty(); ++i)
      {
        const std::size_t at = below(json.size());
        switch (below(4))
        {
          case 0:
            json[at] = static_cast<char>(rng_() & 0xff);
            break;
          case 1:
            json.insert(at, random_bytes(1, 8));
            break;
          case 2:
            json.erase(at, 1 + below(8));
            break;
          default:
            json.resize(at);
        }
      }
      return json;
    }

    nlohmann::json request_json()
    {
      // Mostly lumped and collide (validated in the server); fem, study and sweep rarely (a fem
      // check starts a child process).
      const std::string command =
        chance(0.95) ? pick({"lumped", "lumped", "collide", "x", "", random_text(0, 20)}) :
                       pick({"fem", "study", "sweep"});
      static const std::vector<std::string> scenes = {
        "building:\n  n_storeys: 3\n",
        "building:\n  n_storeys: 300000\n",
        "ground_motion:\n  record: synthetic\n  duration: \"2 s\"\n",
        "ground_motion:\n  record: ../uploads/m.txt\n",
        "ground_motion:\n  record: /etc/passwd\n",
        "walls:\n  left:\n    gap: \"-1 cm\"\n",
        "a: &a [*a]\n",
        "x: [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[\n",
        "integration:\n  dt: \"1e-320 s\"\n",
        "cases:\n  - {name: a}\n  - {name: a}\n",
        "{",
        ""};
      nlohmann::json request = nlohmann::json::object();
      if (chance(0.9))
        request["command"] = command;
      if (chance(0.9))
        request["scene"] = chance(0.8) ? scenes[below(scenes.size())] : random_text(0, 200);
      if (chance(0.2))
        request["sweep"] =
          chance(0.5) ? std::string("scene: scene.yaml\nparameters: {}\n") : random_text(0, 100);
      if (chance(0.1))
        request["command"] = below(5); // not a string
      return request;
    }

    std::string two_column()
    {
      std::string text;
      for (std::size_t i = 0, n = below(50); i < n; ++i)
        text += std::to_string(i * 0.01) + " " +
                (chance(0.9) ? std::to_string(std::uniform_real_distribution<>(-1, 1)(rng_)) :
                               random_text(0, 10)) +
                "\n";
      return text;
    }

    /// `body` in chunks of random sizes, sometimes with a size that lies or is no number.
    std::string chunks(const std::string &body)
    {
      std::string out;
      for (std::size_t at = 0; at < body.size();)
      {
        const std::size_t n = std::min(body.size() - at, 1 + below(600));
        char              size[32];
        std::snprintf(size, sizeof(size), "%zx", n);
        const bool lie = chance(0.05);
        complete_      = complete_ && !lie;
        out += (lie ? pick({"zz", "-1", "ffffffffffffffff", "7fffffff", ""}) : std::string(size)) +
               "\r\n" + body.substr(at, n) + "\r\n";
        at += n;
      }
      if (chance(0.1))
      {
        complete_ = false;
        return out;
      }
      return out + "0\r\n\r\n";
    }

    std::string  host_;
    std::string  run_;
    std::mt19937 rng_{seed};
    bool         complete_ = true;
  };

  TEST(HttpFuzz, KimpGuiAnswersRandomRequestsAndStaysUp)
  {
    const kimp::testing::TempDir dir{"http_fuzz"};
    GuiProcess                   gui(
      binary("kimp"),
      dir.path(),
      {"--port", "0", "--runs-dir", (dir.path() / "runs").string(), "--max-runs", "1"});
    ASSERT_GT(gui.port(), 0) << gui.err();
    const auto info_answers = [&](int seconds = 5)
    {
      httplib::Client client("127.0.0.1", gui.port());
      client.set_connection_timeout(seconds, 0);
      client.set_read_timeout(seconds, 0);
      const auto r = client.Get("/api/info");
      return r && r->status == 200;
    };
    // The first /api/info asks kimp-fem for the fem and study schemas (seconds on a loaded
    // machine); the answer is kept.
    ASSERT_TRUE(info_answers(60));
    const std::size_t memory_before = resident_bytes(gui.pid());
    std::size_t       memory_peak   = memory_before;
    // A finished run, for the routes of a run (its data, report, files, events, deletion).
    const std::string small_scene =
      "building:\n  n_storeys: 3\nground_motion:\n  record: synthetic\n  duration: \"2 s\"\n";
    const auto started = gui.post("/api/runs", {{"command", "lumped"}, {"scene", small_scene}});
    ASSERT_TRUE(started);
    ASSERT_EQ(started->status, 201) << started->body;
    const std::string run = nlohmann::json::parse(started->body)["id"];
    ASSERT_EQ(gui.wait_for_run(run,
                               60,
                               [](const nlohmann::json &r) {
                                 return r["state"] != "running" && r["state"] != "queued";
                               })["state"],
              "done");
    RequestMaker maker(gui.port(), run);
    // status -> count (0: closed without an answer; -1: an incomplete request, dropped)
    std::map<int, int> statuses;
    const auto         start = Clock::now();
    int                sent  = 0;
    for (; sent < requests; ++sent)
    {
      if (std::chrono::duration<double>(Clock::now() - start).count() > budget_s)
        break;
      const Request request = maker.next();
      std::string   answer;
      {
        RawConnection c(gui.port());
        ASSERT_TRUE(c.connected()) << "request " << sent << ": kimp gui refuses connections";
        // A request with all its bytes is answered (the server closes the connection after it;
        // an event stream is cut after 3 s); the others are sent and dropped, which the server
        // must take as well.
        if (c.send_all(request.bytes) && request.complete)
          answer = c.receive_all(3.0);
      }
      ++statuses[request.complete ? status_of(answer) : -1];
      // No server error: every refusal is a 4xx (or 501 for a transfer coding it does not read).
      EXPECT_NE(status_of(answer), 500) << "request " << sent << ":\n"
                                        << request.bytes.substr(0, 600) << "\nanswer:\n"
                                        << answer.substr(0, 600);
      ASSERT_TRUE(process_alive(gui.pid())) << "kimp gui died of request " << sent << ":\n"
                                            << request.bytes.substr(0, 400) << "\n"
                                            << gui.err();
      if (sent % check_every == check_every - 1)
      {
        ASSERT_TRUE(info_answers()) << "GET /api/info not answered after request " << sent;
        memory_peak = std::max(memory_peak, resident_bytes(gui.pid()));
      }
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    RecordProperty("requests", sent);
    RecordProperty("seconds", std::to_string(seconds));
    RecordProperty("peak_rss_growth_mb", std::to_string((memory_peak - memory_before) / 1e6));
    std::string seen;
    for (const auto &[status, count] : statuses)
      seen += " " + std::to_string(status) + ":" + std::to_string(count);
    RecordProperty("statuses", seen);
    std::cout << sent << " requests in " << seconds << " s; statuses" << seen
              << "; resident memory " << memory_before / 1e6 << " -> peak " << memory_peak / 1e6
              << " MB\n";
    // Enough requests to mean something, even on a loaded machine.
    EXPECT_GE(sent, 1000);
    EXPECT_TRUE(process_alive(gui.pid()));
    EXPECT_TRUE(info_answers());
    // A request of the page still does its job.
    const auto valid =
      gui.post("/api/validate", {{"command", "lumped"}, {"scene", "building:\n  n_storeys: 3\n"}});
    ASSERT_TRUE(valid);
    EXPECT_EQ(valid->body, R"({"error":"","ok":true})");
    // Bodies are limited to 16 MB and answers are small: memory stays near where it started.
    EXPECT_LT(memory_peak, memory_before + (200u << 20));
    kill(gui.pid(), SIGTERM);
    EXPECT_TRUE(gui.wait(15).exited);
  }
} // namespace
