// The local web server of `kimp gui` (cpp-httplib): the page, the scene schemas, validation,
// background runs with progress, results, records and scenes' ground motions, behind
// loopback-only security checks.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "server/run_settings.h"

namespace kimp::server
{
  /// Options of `kimp gui`: where it listens, and its runs (RunSettings).
  struct GuiOptions : RunSettings
  {
    /// Interface to bind; anything but loopback must be asked for explicitly (--host).
    std::string host = "127.0.0.1";
    /// TCP port, 1-65535; 0 picks a free one.
    int port = 8080;
    /// Largest accepted request body (uploads, scenes, form-encoded or not), bytes.
    std::size_t max_body = 16u << 20;
  };

  /// The server; listen() blocks until stop() (from another thread or a signal handler's thread).
  class GuiServer
  {
  public:
    explicit GuiServer(GuiOptions options);
    ~GuiServer();
    GuiServer(const GuiServer &)            = delete;
    GuiServer &operator=(const GuiServer &) = delete;

    /// Bind host:port; returns the bound port (a free one for port 0).
    /// @throws std::invalid_argument for a port outside 0-65535; std::runtime_error naming host
    /// and port when the socket cannot be bound (also when another server listens there).
    int bind();
    /// Serve requests until stop(); bind() first.
    void listen();
    /// Stop listen() and cancel the runs (SIGTERM, SIGKILL after kill_grace); returns once the
    /// children are gone.
    void stop();
    /// http://host:port/ of the bound server.
    std::string url() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };

  /// `kimp gui`: bind, print the URL on `announce`, optionally open a browser, serve until SIGINT
  /// or SIGTERM, which cancel the runs and return within about kill_grace.
  void run_gui(const GuiOptions                               &options,
               bool                                            open_browser,
               const std::function<void(const std::string &)> &announce);
} // namespace kimp::server
