// The HTTP server of `kimp gui` (server/server.h): routes, the Host/Origin checks against DNS
// rebinding and cross-site requests, path confinement of file endpoints, JSON errors.
#include "server/server.h"

#include <atomic>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <signal.h>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <thread>

#include "app/collide_run.h"
#include "app/lumped_scene.h"
#include "base/logging.h"
#include "base/version.h"
#include "io/at2_reader.h"
#include "io/records.h"
#include "io/scene_io.h"

#include "report/assets.h"
#include "report/report.h"
#include "server/run_manager.h"
#ifdef KIMP_WITH_FEM
#  include "app/fem/fem_scene.h"
#  include "app/study/study_scene.h"
#endif

// After the app headers: <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen.
#include <httplib.h>

extern char **environ;

namespace kimp::server
{
  namespace
  {
    /// A request the server refuses, with its HTTP status and message.
    struct HttpError : std::runtime_error
    {
      HttpError(int status_, const std::string &message)
        : std::runtime_error(message)
        , status(status_)
      {
      }
      int status;
    };

    void send_json(httplib::Response &res, const nlohmann::json &value, int status = 200)
    {
      res.status = status;
      res.set_content(value.dump(), "application/json");
    }

    void send_error(httplib::Response &res, int status, const std::string &message)
    {
      send_json(res, {{"error", message}}, status);
    }

    nlohmann::json parse_body(const httplib::Request &req)
    {
      nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
      if (body.is_discarded() || !body.is_object())
        throw HttpError(400, "malformed JSON: the request body must be a JSON object");
      return body;
    }

    std::string text_member(const nlohmann::json &body, const char *key, bool required = true)
    {
      if (!body.contains(key))
      {
        if (required)
          throw HttpError(400, std::string("missing \"") + key + "\" in the request");
        return {};
      }
      if (!body[key].is_string())
        throw HttpError(400, std::string("\"") + key + "\" must be a string");
      return body[key].get<std::string>();
    }

    std::string mime_type(const std::string &name)
    {
      const auto ends = [&](const char *ext)
      {
        const std::string e(ext);
        return name.size() >= e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0;
      };
      if (ends(".js"))
        return "text/javascript; charset=utf-8";
      if (ends(".css"))
        return "text/css; charset=utf-8";
      if (ends(".html"))
        return "text/html; charset=utf-8";
      if (ends(".json"))
        return "application/json";
      if (ends(".svg"))
        return "image/svg+xml";
      if (ends(".png"))
        return "image/png";
      if (ends(".csv"))
        return "text/csv; charset=utf-8";
      return "text/plain; charset=utf-8";
    }

    bool is_ip_literal(const std::string &host)
    {
      static const std::regex ipv4(R"(\d{1,3}(\.\d{1,3}){3})");
      return std::regex_match(host, ipv4) || (host.size() > 2 && host.front() == '[');
    }

    /// The scene `text` of `command` read and validated as the command would: "" when valid,
    /// else the command's own message ("scene.yaml:12: isolator.K2 = ...: must be < K1 ...").
    std::string validation_error(const std::string &command, const std::string &text)
    {
      try
      {
        if (command == "lumped")
          io::read_scene_text<app::LumpedScene>(text, "scene.yaml");
        else if (command == "collide")
          io::read_scene_text<app::CollideScene>(text, "scene.yaml");
#ifdef KIMP_WITH_FEM
        else if (command == "fem")
          io::read_scene_text<app::FemScene>(text, "scene.yaml");
        else if (command == "study")
          io::read_scene_text<app::StudyScene>(text, "scene.yaml");
#endif
        return {};
      }
      catch (const std::exception &error)
      {
        return error.what();
      }
    }

    nlohmann::json record_json(const io::AccelerationRecord &record)
    {
      return {{"name", record.name},
              {"dt", record.dt},
              {"pga", record.pga()},
              {"duration", record.duration()},
              {"acceleration", record.acceleration}};
    }

    /// Contained path: `base`/`relative` when it stays below `base` (no "..", no symlink out).
    std::filesystem::path confined(const std::filesystem::path &base, const std::string &relative)
    {
      const std::filesystem::path rel(relative);
      for (const auto &part : rel)
        if (part == ".." || part == "." || rel.is_absolute())
          throw HttpError(400, "path \"" + relative + "\" leaves its directory");
      const auto root     = std::filesystem::weakly_canonical(base);
      const auto path     = std::filesystem::weakly_canonical(base / rel);
      const auto mismatch = std::mismatch(root.begin(), root.end(), path.begin(), path.end()).first;
      if (mismatch != root.end())
        throw HttpError(400, "path \"" + relative + "\" leaves its directory");
      return path;
    }
  } // namespace

  struct GuiServer::Impl
  {
    GuiOptions                         options;
    httplib::Server                    http;
    RunManager                         runs;
    int                                port = 0;
    std::mutex                         cache_mutex;
    std::map<std::string, std::string> schema_cache;

    explicit Impl(GuiOptions o)
      : options(std::move(o))
      , runs(options.runs_dir, options.kimp_executable)
    {
    }

    bool loopback() const
    {
      return options.host == "127.0.0.1" || options.host == "localhost" || options.host == "::1";
    }

    /// Host header check: the server's own name and port only (DNS rebinding sends a foreign
    /// name); with an explicit --host also any IP literal, which DNS cannot rebind.
    bool host_allowed(const std::string &value) const
    {
      const std::size_t colon = value.rfind(':');
      if (colon == std::string::npos || value.substr(colon + 1) != std::to_string(port))
        return false;
      const std::string name = value.substr(0, colon);
      if (name == "127.0.0.1" || name == "localhost" || name == "[::1]")
        return true;
      return !loopback() && (name == options.host || is_ip_literal(name));
    }

    std::string schema(const std::string &command, const std::string &flag)
    {
      std::lock_guard<std::mutex> lock(cache_mutex);
      const std::string           key = command + flag;
      const auto                  it  = schema_cache.find(key);
      if (it != schema_cache.end())
        return it->second;
      const auto [status, out] = capture_kimp(options.kimp_executable, {command, flag});
      if (status != 0)
        throw HttpError(404, "kimp " + command + " has no " + flag + " in this build");
      return schema_cache[key] = out;
    }

    void routes();
  };

  void GuiServer::Impl::routes()
  {
    http.new_task_queue = [] { return new httplib::ThreadPool(32); };
    http.set_payload_max_length(options.max_body);
    http.set_pre_routing_handler(
      [this](const httplib::Request &req, httplib::Response &res)
      {
        if (!host_allowed(req.get_header_value("Host")))
        {
          send_error(res,
                     403,
                     "foreign Host header \"" + req.get_header_value("Host") +
                       "\" refused (kimp gui answers only to its own address)");
          return httplib::Server::HandlerResponse::Handled;
        }
        const std::string origin = req.get_header_value("Origin");
        if (!origin.empty() && origin != "http://" + req.get_header_value("Host"))
        {
          send_error(res, 403, "cross-origin request from \"" + origin + "\" refused");
          return httplib::Server::HandlerResponse::Handled;
        }
        // A custom header forces a CORS preflight, which this server never grants: no other
        // site can make a browser send a state-changing request here.
        if (req.method != "GET" && req.get_header_value("X-Kimp-Request") != "1")
        {
          send_error(res, 403, "request without the X-Kimp-Request header refused");
          return httplib::Server::HandlerResponse::Handled;
        }
        res.set_header("X-Content-Type-Options", "nosniff");
        res.set_header("X-Frame-Options", "DENY");
        return httplib::Server::HandlerResponse::Unhandled;
      });
    http.set_exception_handler(
      [](const httplib::Request &, httplib::Response &res, std::exception_ptr ep)
      {
        try
        {
          std::rethrow_exception(ep);
        }
        catch (const HttpError &error)
        {
          send_error(res, error.status, error.what());
        }
        catch (const std::invalid_argument &error)
        {
          send_error(res, 400, error.what());
        }
        catch (const std::exception &error)
        {
          send_error(res, 500, error.what());
        }
        catch (...)
        {
          send_error(res, 500, "unknown error");
        }
      });
    http.set_error_handler(
      [](const httplib::Request &, httplib::Response &res)
      {
        if (res.body.empty())
          send_error(res,
                     res.status,
                     res.status == 413 ? "request body too large" : "no such page or endpoint");
      });

    http.Get("/",
             [](const httplib::Request &, httplib::Response &res)
             { res.set_content(report::gui_html(), "text/html; charset=utf-8"); });
    http.Get(R"(/assets/([A-Za-z0-9_.-]+))",
             [](const httplib::Request &req, httplib::Response &res)
             {
               const auto text = report::asset(req.matches[1].str());
               if (!text)
                 throw HttpError(404, "no asset " + req.matches[1].str());
               res.set_content(std::string(*text), mime_type(req.matches[1].str()).c_str());
             });
    http.Get("/api/info",
             [this](const httplib::Request &, httplib::Response &res)
             {
               nlohmann::json commands = nlohmann::json::array({"lumped", "collide", "sweep"});
#ifdef KIMP_WITH_FEM
               commands.push_back("fem");
               commands.push_back("study");
#endif
               send_json(res,
                         {{"version", base::version_line()},
                          {"commands", commands},
                          {"runs_dir", std::filesystem::absolute(options.runs_dir).string()},
                          {"records_dir",
                           options.records_dir ? options.records_dir->string() : std::string()}});
             });
    http.Get(R"(/api/(schema|defaults)/([a-z]+))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               const bool schema_wanted = req.matches[1] == "schema";
               const auto text          = schema(req.matches[2].str(),
                                        schema_wanted ? "--print-schema" : "--print-defaults");
               res.set_content(text, schema_wanted ? "application/json" : "text/plain");
             });
    http.Post("/api/validate",
              [](const httplib::Request &req, httplib::Response &res)
              {
                const auto        body = parse_body(req);
                const std::string error =
                  validation_error(text_member(body, "command"), text_member(body, "scene"));
                send_json(res, {{"ok", error.empty()}, {"error", error}});
              });
    http.Post("/api/runs",
              [this](const httplib::Request &req, httplib::Response &res)
              {
                const auto        body    = parse_body(req);
                const std::string command = text_member(body, "command");
                const std::string scene   = text_member(body, "scene");
                const std::string sweep   = text_member(body, "sweep", command == "sweep");
                if (command != "sweep")
                {
                  const std::string error = validation_error(command, scene);
                  if (!error.empty())
                    throw HttpError(400, error);
                }
                send_json(res, {{"id", runs.start(command, scene, sweep)}}, 201);
              });
    http.Get("/api/runs",
             [this](const httplib::Request &, httplib::Response &res)
             { send_json(res, runs.list()); });
    http.Get(R"(/api/runs/([A-Za-z0-9_-]+))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               if (!runs.exists(req.matches[1]))
                 throw HttpError(404, "no run " + req.matches[1].str());
               send_json(res, runs.describe(req.matches[1]));
             });
    http.Post(R"(/api/runs/([A-Za-z0-9_-]+)/cancel)",
              [this](const httplib::Request &req, httplib::Response &res) {
                send_json(res, {{"cancelled", runs.cancel(req.matches[1])}});
              });
    http.Get(R"(/api/runs/([A-Za-z0-9_-]+)/events)",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               const std::string id = req.matches[1];
               if (!runs.exists(id))
                 throw HttpError(404, "no run " + id);
               auto seen = std::make_shared<std::size_t>(0);
               res.set_header("Cache-Control", "no-cache");
               res.set_chunked_content_provider(
                 "text/event-stream",
                 [this, id, seen](std::size_t, httplib::DataSink &sink)
                 {
                   runs.wait_for_change(id, *seen, 1000);
                   const nlohmann::json state = runs.describe(id, *seen);
                   *seen                      = state.value("log_lines", *seen);
                   const std::string event    = "data: " + state.dump() + "\n\n";
                   if (!sink.write(event.data(), event.size()))
                     return false;
                   const std::string s = state.value("state", "");
                   if (s != "running" && s != "queued")
                     sink.done();
                   return true;
                 });
             });
    http.Get(R"(/api/runs/([A-Za-z0-9_-]+)/(data|report))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               if (!runs.exists(req.matches[1]))
                 throw HttpError(404, "no run " + req.matches[1].str());
               const auto data =
                 report::report_data(options.runs_dir / req.matches[1].str() / "out");
               if (req.matches[2] == "data")
                 send_json(res, data);
               else
                 res.set_content(report::report_html(data), "text/html; charset=utf-8");
             });
    http.Get(R"(/api/files/([A-Za-z0-9_-]+)/(.+))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               if (!runs.exists(req.matches[1]))
                 throw HttpError(404, "no run " + req.matches[1].str());
               const auto path = confined(options.runs_dir / req.matches[1].str(), req.matches[2]);
               if (!std::filesystem::is_regular_file(path))
                 throw HttpError(404, "no file " + req.matches[2].str());
               std::ifstream      in(path, std::ios::binary);
               std::ostringstream text;
               text << in.rdbuf();
               res.set_content(text.str(), mime_type(path.filename().string()).c_str());
             });
    http.Get("/api/records",
             [this](const httplib::Request &, httplib::Response &res)
             {
               nlohmann::json names = nlohmann::json::array();
               if (options.records_dir)
                 for (const auto &path : io::list_records(*options.records_dir))
                   names.push_back(path.stem().string());
               send_json(res, names);
             });
    http.Get(R"(/api/records/([A-Za-z0-9_.-]+))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               if (!options.records_dir)
                 throw HttpError(404, "no records directory (set KIMP_RECORDS_DIR)");
               for (const auto &path : io::list_records(*options.records_dir))
                 if (path.stem().string() == req.matches[1].str())
                   return send_json(res, record_json(io::read_at2(path)));
               throw HttpError(404, "no record " + req.matches[1].str());
             });
    http.Post("/api/upload",
              [this](const httplib::Request &req, httplib::Response &res)
              {
                static const std::regex safe(R"([A-Za-z0-9_.-]{1,100})");
                const std::string       name = req.get_param_value("name");
                if (!std::regex_match(name, safe) || name.front() == '.')
                  throw HttpError(400,
                                  "upload name \"" + name +
                                    "\" must be 1-100 letters, digits, '_', '-' or '.'");
                double unit = 9.80665;
                if (req.has_param("unit"))
                  unit = std::stod(req.get_param_value("unit"));
                const auto dir = options.runs_dir / "uploads";
                std::filesystem::create_directories(dir);
                const auto path = dir / name;
                try
                {
                  const auto record = name.size() > 4 && (name.substr(name.size() - 4) == ".AT2" ||
                                                          name.substr(name.size() - 4) == ".at2") ?
                                        io::parse_at2(req.body, name) :
                                        io::parse_two_column(req.body, name, unit);
                  io::write_text_atomic(path, req.body);
                  nlohmann::json j = record_json(record);
                  j["path"]        = std::filesystem::absolute(path).string();
                  send_json(res, j, 201);
                }
                catch (const io::GroundMotionFileError &error)
                {
                  throw HttpError(400, error.what());
                }
              });
  }

  GuiServer::GuiServer(GuiOptions options)
    : impl_(std::make_unique<Impl>(std::move(options)))
  {
    impl_->routes();
  }

  GuiServer::~GuiServer()
  {
    stop();
  }

  int GuiServer::bind()
  {
    const std::string host = impl_->options.host == "localhost" ? "127.0.0.1" : impl_->options.host;
    if (impl_->options.port == 0)
      impl_->port = impl_->http.bind_to_any_port(host.c_str());
    else if (impl_->http.bind_to_port(host.c_str(), impl_->options.port))
      impl_->port = impl_->options.port;
    else
      impl_->port = -1;
    if (impl_->port <= 0)
      throw std::runtime_error("kimp gui: cannot listen on " + impl_->options.host + ":" +
                               std::to_string(impl_->options.port) +
                               " (port in use? choose another with --port)");
    return impl_->port;
  }

  void GuiServer::listen()
  {
    impl_->http.listen_after_bind();
  }

  void GuiServer::stop()
  {
    if (impl_ && impl_->http.is_running())
      impl_->http.stop();
  }

  std::string GuiServer::url() const
  {
    const std::string host = impl_->options.host.find(':') != std::string::npos ?
                               "[" + impl_->options.host + "]" :
                               impl_->options.host;
    return "http://" + host + ":" + std::to_string(impl_->port) + "/";
  }

  void run_gui(const GuiOptions                               &options,
               bool                                            open_browser,
               const std::function<void(const std::string &)> &announce)
  {
    if (options.host != "127.0.0.1" && options.host != "localhost" && options.host != "::1")
      base::logger().warn("kimp gui listens on {}: other machines can reach it and start runs; "
                          "use it only on a trusted network",
                          options.host);
    // SIGINT and SIGTERM are taken by a waiting thread, which stops the server cleanly.
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);
    GuiServer server(options);
    server.bind();
    announce(server.url());
    std::atomic<bool> signalled{false};
    std::thread       waiter(
      [&]
      {
        int signal = 0;
        sigwait(&signals, &signal);
        signalled = true;
        server.stop();
      });
    if (open_browser)
    {
      std::string              url  = server.url();
      std::vector<std::string> args = {"xdg-open", url};
      std::vector<char *>      argv = {args[0].data(), args[1].data(), nullptr};
      pid_t                    pid  = -1;
      if (posix_spawnp(&pid, "xdg-open", nullptr, nullptr, argv.data(), environ) != 0)
        base::logger().warn("cannot start xdg-open: open {} in a browser", url);
    }
    server.listen();
    if (!signalled)
      pthread_kill(waiter.native_handle(), SIGTERM);
    waiter.join();
  }
} // namespace kimp::server
