// GuiProcess: `kimp gui` as a user starts it, the real executable as a child process on a free
// port with an HTTP client, and the process checks of the tests that drive it (alive, blocked
// signals, exit, resident memory).
#pragma once

#include <arpa/inet.h>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <memory>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <poll.h>
#include <regex>
#include <spawn.h>
#include <string>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "tests/support/files.h"
#include "tests/support/scoped_handle.h"

// Last: <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen headers.
#include <httplib.h>

extern char **environ;

namespace kimp::testing
{
  namespace fs = std::filesystem;
  using Clock  = std::chrono::steady_clock;

  /// A run request of a lumped base scene and a sweep over it of 29 001 cases (the left gap from
  /// 1 to 30 cm in steps of 0.001 cm), many minutes of work: a run that is still going when a
  /// test looks at it, or one to cancel.
  inline nlohmann::json long_sweep_request()
  {
    return {{"command", "sweep"},
            {"scene",
             "building:\n  n_storeys: 3\nwalls:\n  left:\n    gap: \"8 cm\"\n  right:\n    gap: "
             "\"8 cm\"\nground_motion:\n  record: synthetic\n  duration: \"20 s\"\n"},
            {"sweep",
             "scene: scene.yaml\ncombine: product\nparameters:\n"
             "  walls.left.gap: {from: \"1 cm\", to: \"30 cm\", step: \"0.001 cm\"}\n"}};
  }

  /// Whether process `pid` still exists as a running (not zombie) process.
  inline bool process_alive(int pid)
  {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string   text;
    if (!stat || !std::getline(stat, text))
      return false;
    const std::size_t close = text.rfind(')');
    return close != std::string::npos && close + 2 < text.size() && text[close + 2] != 'Z';
  }

  /// The "SigBlk:" mask of process `pid` (hexadecimal text), or "" when it is gone.
  inline std::string blocked_signals(int pid)
  {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("SigBlk:", 0) == 0)
        return line.substr(line.find_first_not_of(" \t", 7));
    return "";
  }

  /// The result of waiting for a child process.
  struct Exit
  {
    bool   exited    = false; ///< it ended before the deadline
    int    exit_code = -1;    ///< exit code, or -1 after a signal
    double seconds   = 0.0;   ///< how long it took
  };

  /// Waits up to `limit_s` for child `pid` to end.
  inline Exit wait_for_exit(int pid, double limit_s)
  {
    Exit       e;
    const auto start = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - start).count() < limit_s)
    {
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid)
      {
        e.exited    = true;
        e.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    e.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return e;
  }

  /// `EXECUTABLE gui --port 0 ARGS...` with its stdout and stderr in files of `dir`, and the
  /// environment without KIMP_RECORDS_DIR; the URL read from its first line.
  class GuiProcess
  {
  public:
    GuiProcess(const fs::path                 &executable,
               const fs::path                 &dir,
               const std::vector<std::string> &arguments,
               bool                            wait_for_url = true)
      : out_(dir / "gui_stdout.txt")
      , err_(dir / "gui_stderr.txt")
    {
      std::vector<std::string> argv_text = {executable.string(), "gui"};
      argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
      std::vector<char *> argv;
      for (auto &a : argv_text)
        argv.push_back(a.data());
      argv.push_back(nullptr);
      std::vector<std::string> env_text;
      for (char **e = environ; *e; ++e)
        if (std::string(*e).rfind("KIMP_RECORDS_DIR=", 0) != 0)
          env_text.emplace_back(*e);
      std::vector<char *> envp;
      for (auto &e : env_text)
        envp.push_back(e.data());
      envp.push_back(nullptr);
      posix_spawn_file_actions_t actions;
      posix_spawn_file_actions_init(&actions);
      posix_spawn_file_actions_addopen(&actions,
                                       1,
                                       out_.c_str(),
                                       O_WRONLY | O_CREAT | O_TRUNC,
                                       0644);
      posix_spawn_file_actions_addopen(&actions,
                                       2,
                                       err_.c_str(),
                                       O_WRONLY | O_CREAT | O_TRUNC,
                                       0644);
      const int status =
        posix_spawn(&pid_, executable.c_str(), &actions, nullptr, argv.data(), envp.data());
      posix_spawn_file_actions_destroy(&actions);
      if (status != 0)
        pid_ = -1;
      if (!wait_for_url || pid_ <= 0)
        return;
      static const std::regex url(R"(http://127\.0\.0\.1:(\d+)/)");
      const auto              deadline = Clock::now() + std::chrono::seconds(30);
      while (Clock::now() < deadline && port_ == 0)
      {
        std::smatch       m;
        const std::string text = kimp::testing::read_text(out_);
        if (std::regex_search(text, m, url))
          port_ = std::stoi(m[1]);
        else if (wait_for_exit_now())
          break;
        else
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      if (port_ > 0)
      {
        client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
        client_->set_read_timeout(60, 0);
      }
    }

    ~GuiProcess()
    {
      if (pid_ > 0 && !exit_)
      {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
      }
    }

    int              pid() const { return pid_; }
    int              port() const { return port_; }
    httplib::Client &client() { return *client_; }
    std::string      out() const { return kimp::testing::read_text(out_); }
    std::string      err() const { return kimp::testing::read_text(err_); }

    /// POST of a JSON body with the headers the page sends.
    httplib::Result post(const std::string &path, const nlohmann::json &body)
    {
      const std::string host = "127.0.0.1:" + std::to_string(port_);
      return client_->Post(path,
                           {{"X-Kimp-Request", "1"}, {"Origin", "http://" + host}},
                           body.dump(),
                           "application/json");
    }

    nlohmann::json get_json(const std::string &path)
    {
      const auto r = client_->Get(path);
      return r ? nlohmann::json::parse(r->body, nullptr, false) : nlohmann::json();
    }

    /// Polls GET /api/runs/ID until `done` holds for it, at most `limit_s`.
    template <class Predicate>
    nlohmann::json wait_for_run(const std::string &id, double limit_s, Predicate done)
    {
      const auto     deadline = Clock::now() + std::chrono::duration<double>(limit_s);
      nlohmann::json run;
      while (Clock::now() < deadline)
      {
        run = get_json("/api/runs/" + id);
        if (done(run))
          break;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      return run;
    }

    /// Waits up to `limit_s` for the process to end.
    Exit wait(double limit_s)
    {
      exit_ = wait_for_exit(pid_, limit_s);
      if (!exit_->exited)
        exit_.reset();
      return exit_ ? *exit_ : Exit{};
    }

  private:
    bool wait_for_exit_now()
    {
      const Exit e = wait_for_exit(pid_, 0.0);
      if (e.exited)
        exit_ = e;
      return e.exited;
    }

    fs::path                         out_;
    fs::path                         err_;
    pid_t                            pid_  = -1;
    int                              port_ = 0;
    std::optional<Exit>              exit_;
    std::unique_ptr<httplib::Client> client_;
  };


  /// An executable of the build (kimp, kimp-fem).
  inline fs::path binary(const char *name)
  {
    return fs::path(KIMP_BINARY_DIR) / name;
  }

  /// A TCP connection to 127.0.0.1:`port` for requests httplib cannot send (any bytes, a body
  /// in chunks, a stream held open).
  class RawConnection
  {
  public:
    explicit RawConnection(int port)
      : fd_(socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0))
    {
      sockaddr_in address{};
      address.sin_family = AF_INET;
      address.sin_port   = htons(static_cast<std::uint16_t>(port));
      inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
      if (fd_ >= 0 && connect(fd_, reinterpret_cast<sockaddr *>(&address), sizeof(address)) != 0)
        fd_.reset();
    }

    bool connected() const { return fd_ >= 0; }
    /// Sends all of `bytes`; false when the server closed the connection (or 30 s passed).
    bool send_all(const std::string &bytes)
    {
      for (std::size_t sent = 0; sent < bytes.size();)
      {
        pollfd p{fd_, POLLOUT, 0};
        if (poll(&p, 1, 30000) <= 0)
          return false;
        const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (n <= 0)
          return false;
        sent += static_cast<std::size_t>(n);
      }
      return true;
    }
    /// What has arrived, waiting up to `ms` for the first bytes (0: only what is there).
    std::string receive(int ms)
    {
      std::string text;
      for (int wait = ms;; wait = 0)
      {
        pollfd p{fd_, POLLIN, 0};
        if (poll(&p, 1, wait) <= 0)
          return text;
        char          buffer[65536];
        const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
        if (n <= 0)
          return text;
        text.append(buffer, static_cast<std::size_t>(n));
      }
    }
    /// Everything until the server closes the connection, at most `seconds`.
    std::string receive_all(double seconds)
    {
      std::string text;
      const auto  deadline = Clock::now() + std::chrono::duration<double>(seconds);
      while (Clock::now() < deadline)
      {
        pollfd p{fd_, POLLIN, 0};
        if (poll(&p, 1, 50) < 0)
          break;
        if (!(p.revents & (POLLIN | POLLHUP | POLLERR)))
          continue;
        char          buffer[65536];
        const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
        if (n <= 0)
          break;
        text.append(buffer, static_cast<std::size_t>(n));
      }
      return text;
    }

  private:
    ScopedHandle<int, ::close> fd_;
  };

  /// The answer of the server on `port` to the request `bytes`, read until the server closes
  /// the connection (it serves one request per connection), at most `seconds` of waiting. (The
  /// sending side stays open: cpp-httplib writes no answer to a peer that has closed it.)
  inline std::string raw_exchange(int port, const std::string &bytes, double seconds = 10.0)
  {
    RawConnection c(port);
    if (!c.connected() || !c.send_all(bytes))
      return {};
    return c.receive_all(seconds);
  }

  /// The status code of a raw HTTP answer ("HTTP/1.1 404 Not Found" -> 404), or 0.
  inline int status_of(const std::string &answer)
  {
    if (answer.rfind("HTTP/1.", 0) != 0 || answer.size() < 12)
      return 0;
    return std::atoi(answer.substr(9, 3).c_str());
  }

  /// The body of a raw HTTP answer (after the blank line).
  inline std::string body_of(const std::string &answer)
  {
    const std::size_t at = answer.find("\r\n\r\n");
    return at == std::string::npos ? std::string() : answer.substr(at + 4);
  }

  /// The resident memory of process `pid` (VmRSS, bytes), or 0 when it is gone.
  inline std::size_t resident_bytes(int pid)
  {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmRSS:", 0) == 0)
        return std::stoull(line.substr(6)) * 1024;
    return 0;
  }
} // namespace kimp::testing
