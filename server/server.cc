// The HTTP server of `kimp gui` (server/server.h): routes, the Host/Origin checks against DNS
// rebinding and cross-site requests, path confinement of file endpoints, request bodies read and
// counted against the limit, a cap on event streams, JSON errors that echo at most 80 bytes of a
// bad value and no machine path, and nothing a request holds that can escape as an exception.
#include "server/server.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <signal.h>
#include <spawn.h>
#include <stdexcept>
#include <strings.h>
#include <sys/wait.h>
#include <thread>

#include "app/lumped/collide_run.h"
#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_scene.h"
#include "app/lumped/scene_motion.h"
#include "app/lumped/scene_preview.h"
#include "base/logging.h"
#include "base/version.h"
#include "io/at2_reader.h"
#include "io/records.h"
#include "io/scene_io.h"

#include "report/assets.h"
#include "report/report.h"
#include "server/http_error.h"
#include "server/run_manager.h"
#include "server/scene_commands.h"
#include "server/shown_text.h"

// After the app headers: <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen.
#include <httplib.h>

extern char **environ;

namespace kimp::server
{
  namespace
  {
    /**
     * `body` as the response, never compressed: cpp-httplib compresses a set_content() body
     * (Brotli when the browser offers it, about 1 MB/s: 25 s for a 16 MB result) but not a
     * content provider of known length. On the loopback the bytes cost nothing.
     */
    void set_body(httplib::Response &res, std::string body, const std::string &type)
    {
      auto text = std::make_shared<const std::string>(std::move(body));
      res.set_content_provider(
        text->size(),
        type,
        [text](std::size_t offset, std::size_t length, httplib::DataSink &sink)
        { return sink.write(text->data() + offset, std::min(length, text->size() - offset)); });
    }

    /// Threads serving requests, and the event streams among them at most: the others always
    /// have threads for ordinary requests.
    constexpr unsigned request_threads   = 32;
    constexpr unsigned max_event_streams = 16;
    /// Connections the kernel holds until a thread accepts them. Debian's compiled cpp-httplib
    /// listens with a backlog of 5: a burst past that (a page's parallel requests, many clients
    /// at once) overflows it, the kernel falls back to SYN cookies, and each connection whose
    /// cookie fails is reset without an answer. listen() again on the bound socket raises it.
    constexpr int listen_backlog = 1024;

    /// `value` as JSON text: any bytes that are not UTF-8 (a request's path, a child's log)
    /// replaced by U+FFFD, never an exception.
    std::string json_text(const nlohmann::json &value)
    {
      return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }

    void send_json(httplib::Response &res, const nlohmann::json &value, int status = 200)
    {
      res.status = status;
      // Errors stay in res.body, where the error handler finds them (and they are small);
      // results go uncompressed (set_body()).
      if (status >= 400)
        res.set_content(json_text(value), "application/json");
      else
        set_body(res, json_text(value), "application/json");
    }

    /// One of the event streams open, for as long as its response lives.
    class EventStreamSlot
    {
    public:
      explicit EventStreamSlot(std::atomic<unsigned> &open)
        : open_(open)
      {
      }
      ~EventStreamSlot() { --open_; }
      EventStreamSlot(const EventStreamSlot &)            = delete;
      EventStreamSlot &operator=(const EventStreamSlot &) = delete;

    private:
      std::atomic<unsigned> &open_;
    };

    /// Whether the body comes in chunks (Transfer-Encoding: chunked, as cpp-httplib reads it).
    bool chunked(const httplib::Request &req)
    {
      return strcasecmp(req.get_header_value("Transfer-Encoding").c_str(), "chunked") == 0;
    }

    /// The Content-Length of a request; 0 when absent.
    std::uint64_t content_length(const httplib::Request &req)
    {
      const std::string text = req.get_header_value("Content-Length");
      return text.empty() ? 0 : std::strtoull(text.c_str(), nullptr, 10);
    }

    nlohmann::json parse_body(const std::string &text)
    {
      nlohmann::json body = nlohmann::json::parse(text, nullptr, false);
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
      static const std::pair<const char *, const char *> types[] = {
        {".js", "text/javascript; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},
        {".html", "text/html; charset=utf-8"},
        {".json", "application/json"},
        {".svg", "image/svg+xml"},
        {".png", "image/png"},
        {".csv", "text/csv; charset=utf-8"},
      };
      for (const auto &[extension, type] : types)
      {
        const std::string_view e(extension);
        if (name.size() >= e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0)
          return type;
      }
      return "text/plain; charset=utf-8";
    }

    bool is_ip_literal(const std::string &host)
    {
      static const std::regex ipv4(R"(\d{1,3}(\.\d{1,3}){3})");
      return std::regex_match(host, ipv4) || (host.size() > 2 && host.front() == '[');
    }

    /// The number in query parameter `key` of an upload, or HttpError 400 naming it.
    double positive_number_parameter(const httplib::Request &req, const char *key, double fallback)
    {
      if (!req.has_param(key))
        return fallback;
      const std::string text = req.get_param_value(key);
      errno                  = 0;
      char        *end       = nullptr;
      const double value     = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
          !std::isfinite(value) || !(value > 0))
        throw HttpError(400,
                        std::string(key) + " = " + in_quotes(text) +
                          ": must be a positive finite number (m/s² per unit of the file's "
                          "acceleration values, e.g. 9.80665 for g)");
      return value;
    }

    /// A motion as the page plots it: name, dt (s), pga (m/s²), duration (s) and the
    /// acceleration samples (m/s²).
    nlohmann::json motion_json(const lumped::GroundMotion &motion)
    {
      return {{"name", motion.name},
              {"dt", motion.dt},
              {"pga", motion.pga()},
              {"duration", motion.duration()},
              {"acceleration", motion.acceleration}};
    }

    /// Contained path: `base`/`relative` when it stays below `base` (no "..", no symlink out).
    std::filesystem::path confined(const std::filesystem::path &base, const std::string &relative)
    {
      if (relative.find('\0') != std::string::npos)
        throw HttpError(400, "path " + in_quotes(relative) + " holds a NUL byte");
      const std::filesystem::path rel(relative);
      for (const auto &part : rel)
        if (part == ".." || part == "." || rel.is_absolute())
          throw HttpError(400, "path " + in_quotes(relative) + " leaves its directory");
      // A name the file system refuses (too long, ...) names no file of the run.
      std::error_code ec;
      const auto      root = std::filesystem::weakly_canonical(base, ec);
      const auto      path = ec ? root : std::filesystem::weakly_canonical(base / rel, ec);
      if (ec)
        throw HttpError(404, "no file " + in_quotes(relative) + " (" + ec.message() + ")");
      const auto mismatch = std::mismatch(root.begin(), root.end(), path.begin(), path.end()).first;
      if (mismatch != root.end())
        throw HttpError(400, "path " + in_quotes(relative) + " leaves its directory");
      return path;
    }
  } // namespace

  struct GuiServer::Impl
  {
    GuiOptions      options;
    httplib::Server http;
    RunManager      runs;
    int             port          = 0;
    int             listen_socket = -1; ///< the bound socket (its backlog raised after bind)
    SceneCommands   commands;
    /// The POST routes (post()): the only requests whose body is read.
    std::vector<std::regex> post_routes;
    /// Event streams open now (at most max_event_streams).
    std::atomic<unsigned> event_streams{0};
    /// listen() and stop() from different threads, in either order (a stop() before the
    /// server loop runs must still end it): guarded by listen_mutex.
    std::mutex        listen_mutex;
    bool              stop_requested = false;
    bool              listening      = false;
    std::atomic<bool> listen_returned{false};

    explicit Impl(GuiOptions o)
      : options(std::move(o))
      , runs(options)
      , commands(options.kimp_executable, options.runs_dir)
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

    /// The answer {"error": message} with `status`: machine paths of the runs and records
    /// folders made relative, long lines clipped; nothing thrown (a plain text answer if even
    /// that fails).
    void send_error(httplib::Response &res, int status, const std::string &message) const noexcept
    {
      try
      {
        send_json(res, {{"error", runs.shown()(message)}}, status);
      }
      catch (...)
      {
        res.status = status;
        res.body   = "kimp gui: error " + std::to_string(status);
        res.set_header("Content-Type", "text/plain");
      }
    }

    /// The body limit as people read it ("16 MB").
    std::string body_limit() const
    {
      return options.max_body >= (1u << 20) ? std::to_string(options.max_body >> 20) + " MB" :
                                              std::to_string(options.max_body) + " bytes";
    }

    /// Whether a POST to `path` has a route (and so may have a body).
    bool post_route(const std::string &path) const
    {
      return std::any_of(post_routes.begin(),
                         post_routes.end(),
                         [&](const std::regex &route) { return std::regex_match(path, route); });
    }

    /**
     * A POST route whose body is read here, not by cpp-httplib (which would refuse a
     * form-encoded body over 8 KB, and reads a chunked body without any limit): counted as it
     * arrives, decompressed if it is, and refused with 413 as soon as it passes max_body.
     */
    void
    post(const std::string &pattern,
         std::function<void(const httplib::Request &, const std::string &, httplib::Response &)>
           handler)
    {
      post_routes.emplace_back(pattern);
      http.Post(pattern,
                [this, handler](const httplib::Request       &req,
                                httplib::Response            &res,
                                const httplib::ContentReader &reader)
                {
                  // Without a length the body would be read until the client closes: say
                  // what is missing at once instead.
                  if (!req.has_header("Content-Length") && !chunked(req))
                    throw HttpError(411,
                                    "a POST to " + clipped(req.path) +
                                      " needs its body with a Content-Length header (a JSON "
                                      "object for /api/validate, /api/runs and /api/motion, the "
                                      "file for /api/upload, {} for a cancel)");
                  if (req.is_multipart_form_data())
                    throw HttpError(415,
                                    "multipart bodies are not read: send the JSON object or the "
                                    "file itself as the body");
                  std::string body;
                  bool        too_large = false;
                  const bool  read      = reader(
                    [&](const char *data, std::size_t n)
                    {
                      if (n > options.max_body - body.size())
                      {
                        too_large = true;
                        return false;
                      }
                      body.append(data, n);
                      return true;
                    });
                  if (too_large || res.status == 413)
                    throw HttpError(413,
                                    "request body too large (at most " + body_limit() +
                                      ", kimp gui reads no more of it)");
                  if (!read)
                    throw HttpError(400, "the request body could not be read");
                  handler(req, body, res);
                });
    }

    /**
     * Checks of every request before any of its body is read: the Host and Origin headers, the
     * custom header of a state-changing request, and where a body may be. Only a POST to one of
     * the POST routes has a body (read and counted by post()); a body anywhere else, or one in a
     * transfer coding other than chunked, is refused unread.
     * @return the refusal's status and message, or status 0
     */
    std::pair<int, std::string> refusal(const httplib::Request &req) const
    {
      if (!host_allowed(req.get_header_value("Host")))
        return {403,
                "foreign Host header " + in_quotes(req.get_header_value("Host")) +
                  " refused (kimp gui answers only to its own address)"};
      const std::string origin = req.get_header_value("Origin");
      if (!origin.empty() && origin != "http://" + req.get_header_value("Host"))
        return {403, "cross-origin request from " + in_quotes(origin) + " refused"};
      // A custom header forces a CORS preflight, which this server never grants: no other
      // site can make a browser send a state-changing request here.
      if (req.method != "GET" && req.method != "HEAD" &&
          req.get_header_value("X-Kimp-Request") != "1")
        return {403, "request without the X-Kimp-Request header refused"};
      if (req.method != "GET" && req.method != "HEAD" && req.method != "POST" &&
          req.method != "DELETE")
        return {405, "method " + in_quotes(req.method) + " not allowed (GET, POST or DELETE)"};
      const bool        with_body = req.method == "POST" && post_route(req.path);
      const std::string coding    = req.get_header_value("Transfer-Encoding");
      if (req.method == "POST" && !with_body)
        return {404, "no such page or endpoint: POST " + clipped(req.path)};
      if (!coding.empty() && !chunked(req))
        return {501,
                "Transfer-Encoding " + in_quotes(coding) +
                  " not supported (send the body with a Content-Length, or chunked)"};
      if (!with_body &&
          (!coding.empty() || req.has_header("Content-Encoding") || content_length(req) > 0))
        return {400, "a " + req.method + " request to this server has no body"};
      return {0, {}};
    }

    /// A run's folder as scenes sent to the server are read from (its relative paths, such
    /// as an upload's "../uploads/NAME", mean what they mean to the run's child).
    std::filesystem::path run_folder() const { return options.runs_dir / "run"; }

    /** Registers every handler (the areas below, in turn). */
    void routes();
    void install_guards();
    void page_routes();
    void scene_routes();
    void run_routes();
    void run_output_routes();
    void record_routes();
  };

  void GuiServer::Impl::routes()
  {
    install_guards();
    page_routes();
    scene_routes();
    run_routes();
    run_output_routes();
    record_routes();
  }

  /** Thread pool, limits, security headers, and the JSON error answers of every failure. */
  void GuiServer::Impl::install_guards()
  {
    http.new_task_queue = [] { return new httplib::ThreadPool(request_threads); };
    http.set_payload_max_length(options.max_body);
    // One request per connection: an idle connection holds no thread, and the rest of a body
    // that was refused is never read as a next request.
    http.set_keep_alive_max_count(1);
    http.set_pre_routing_handler(
      [this](const httplib::Request &req, httplib::Response &res)
      {
        const auto [status, message] = refusal(req);
        if (status != 0)
        {
          send_error(res, status, message);
          return httplib::Server::HandlerResponse::Handled;
        }
        res.set_header("X-Content-Type-Options", "nosniff");
        res.set_header("X-Frame-Options", "DENY");
        return httplib::Server::HandlerResponse::Unhandled;
      });
    http.set_exception_handler(
      [this](const httplib::Request &, httplib::Response &res, std::exception_ptr ep)
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
    // Called for every answer >= 400, outside cpp-httplib's exception handling: nothing may
    // escape it.
    http.set_error_handler(
      [this](const httplib::Request &req, httplib::Response &res)
      {
        if (!res.body.empty())
          return;
        std::string message;
        try
        {
          switch (res.status)
          {
            case 400:
              message = "bad request: malformed HTTP request";
              break;
            case 404:
              message = "no such page or endpoint: " + req.method + " " + clipped(req.path);
              break;
            case 413:
              message = "request body too large (at most " + body_limit() + ")";
              break;
            case 414:
              message = "request line too long";
              break;
            default:
              message = "HTTP error " + std::to_string(res.status);
          }
        }
        catch (...)
        {
          message = "HTTP error " + std::to_string(res.status);
        }
        send_error(res, res.status, message);
      });
  }

  /** The page, its assets, the server's info, the commands' schemas and the example scenes. */
  void GuiServer::Impl::page_routes()
  {
    http.Get("/",
             [](const httplib::Request &, httplib::Response &res)
             { set_body(res, report::gui_html(), "text/html; charset=utf-8"); });
    http.Get(R"(/assets/([A-Za-z0-9_.-]+))",
             [](const httplib::Request &req, httplib::Response &res)
             {
               const auto text = report::asset(req.matches[1].str());
               if (!text)
                 throw HttpError(404, "no asset " + req.matches[1].str());
               set_body(res, std::string(*text), mime_type(req.matches[1].str()).c_str());
             });
    http.Get("/api/info",
             [this](const httplib::Request &, httplib::Response &res)
             {
               send_json(res,
                         {{"version", base::version_line()},
                          {"commands", commands.available()},
                          {"max_runs", options.max_runs},
                          {"motion_preview", true},
                          // The folders by their names: no machine path leaves the server.
                          {"runs_dir", FolderPaths::folder_name(options.runs_dir)},
                          {"records_dir",
                           options.records_dir ? FolderPaths::folder_name(*options.records_dir) :
                                                 std::string()},
                          {"limits",
                           {{"max_body", options.max_body},
                            {"max_queued", options.max_queued},
                            {"max_event_streams", max_event_streams}}}});
             });
    http.Get(R"(/api/(schema|defaults)/([a-z]+))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               const bool schema_wanted = req.matches[1] == "schema";
               const auto text =
                 commands.schema(req.matches[2].str(),
                                 schema_wanted ? "--print-schema" : "--print-defaults");
               set_body(res, text, schema_wanted ? "application/json" : "text/plain");
             });
    // The scenes shipped with kimp (data/scenes, embedded at build time): name and the first
    // line of their leading comment; the text is GET /assets/NAME.
    http.Get("/api/examples",
             [](const httplib::Request &, httplib::Response &res)
             {
               nlohmann::json list = nlohmann::json::array();
               for (const auto name : report::asset_names())
               {
                 if (name.size() < 6 || name.substr(name.size() - 5) != ".yaml")
                   continue;
                 const std::string_view text = *report::asset(name);
                 std::string            about;
                 if (text.rfind("# ", 0) == 0)
                   about = std::string(text.substr(2, text.find('\n') - 2));
                 list.push_back({{"name", std::string(name)}, {"about", about}});
               }
               send_json(res, list);
             });
  }

  /** A scene checked, its ground motion and its lumped model, as its run would read them. */
  void GuiServer::Impl::scene_routes()
  {
    post("/api/validate",
         [this](const httplib::Request &, const std::string &text, httplib::Response &res)
         {
           const auto        body = parse_body(text);
           const std::string error =
             commands.validation_error(text_member(body, "command"), text_member(body, "scene"));
           send_json(res, {{"ok", error.empty()}, {"error", runs.shown()(error)}});
         });
    // The scene's ground motion as its run would load, scale and trim it (the synthetic
    // near-fault motion included), in the shape of GET /api/records/NAME.
    post("/api/motion",
         [this](const httplib::Request &, const std::string &text, httplib::Response &res)
         {
           const auto body = parse_body(text);
           try
           {
             send_json(res,
                       motion_json(app::scene_ground_motion(text_member(body, "command"),
                                                            text_member(body, "scene"),
                                                            "scene.yaml",
                                                            options.records_dir,
                                                            run_folder())));
           }
           catch (const io::SceneError &error)
           {
             throw HttpError(400, error.what());
           }
         });
    // The model of a lumped scene (buildings, periods, walls, gaps) as its run would assemble it.
    post("/api/preview",
         [](const httplib::Request &, const std::string &text, httplib::Response &res)
         {
           const auto        body    = parse_body(text);
           const std::string command = text_member(body, "command");
           if (command != "lumped")
             throw HttpError(400,
                             "the model preview is drawn for lumped scenes (command \"" + command +
                               "\")");
           try
           {
             send_json(res, app::scene_model_preview(text_member(body, "scene"), "scene.yaml"));
           }
           catch (const io::SceneError &error)
           {
             throw HttpError(400, error.what());
           }
         });
  }

  /** Runs started, listed, described, cancelled, named and deleted. */
  void GuiServer::Impl::run_routes()
  {
    post("/api/runs",
         [this](const httplib::Request &, const std::string &text, httplib::Response &res)
         {
           const auto        body    = parse_body(text);
           const std::string command = text_member(body, "command");
           const std::string scene   = text_member(body, "scene");
           const std::string sweep   = text_member(body, "sweep", command == "sweep");
           if (command != "sweep")
           {
             const std::string error = commands.validation_error(command, scene);
             if (!error.empty())
               throw HttpError(400, error);
           }
           try
           {
             const std::string id = runs.start(command, scene, sweep);
             if (body.contains("name") || body.contains("notes"))
               runs.set_meta(id,
                             text_member(body, "name", false),
                             text_member(body, "notes", false));
             send_json(res, {{"id", id}}, 201);
           }
           catch (const RunQueueFull &error)
           {
             throw HttpError(429, error.what());
           }
         });
    http.Get("/api/runs",
             [this](const httplib::Request &, httplib::Response &res)
             { send_json(res, runs.list()); });
    http.Get(R"(/api/runs/([A-Za-z0-9_-]+))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               if (!runs.exists(req.matches[1]))
                 throw HttpError(404, "no run " + clipped(req.matches[1].str()));
               send_json(res, runs.describe(req.matches[1]));
             });
    // A finished run (or one a dead server left, "interrupted") is deleted with its files.
    http.Delete(R"(/api/runs/([A-Za-z0-9_-]+))",
                [this](const httplib::Request &req, httplib::Response &res)
                {
                  try
                  {
                    if (!runs.remove(req.matches[1]))
                      throw HttpError(404, "no run " + clipped(req.matches[1].str()));
                  }
                  catch (const RunBusy &error)
                  {
                    throw HttpError(409, error.what());
                  }
                  send_json(res, {{"deleted", req.matches[1].str()}});
                });
    post(R"(/api/runs/([A-Za-z0-9_-]+)/cancel)",
         [this](const httplib::Request &req, const std::string &, httplib::Response &res)
         {
           if (!runs.exists(req.matches[1]))
             throw HttpError(404, "no run " + clipped(req.matches[1].str()));
           send_json(res, {{"cancelled", runs.cancel(req.matches[1])}});
         });
    // A run's name and notes (meta.json of its directory), and deleting a finished run.
    post(R"(/api/runs/([A-Za-z0-9_-]+)/meta)",
         [this](const httplib::Request &req, const std::string &text, httplib::Response &res)
         {
           const std::string id = req.matches[1];
           if (!runs.exists(id) || !std::filesystem::exists(options.runs_dir / id / "scene.yaml"))
             throw HttpError(404, "no run " + clipped(id));
           const auto body = parse_body(text);
           runs.set_meta(id, text_member(body, "name"), text_member(body, "notes", false));
           send_json(res, runs.describe(id));
         });
    post(R"(/api/runs/([A-Za-z0-9_-]+)/delete)",
         [this](const httplib::Request &req, const std::string &, httplib::Response &res)
         {
           const std::string id = req.matches[1];
           try
           {
             if (!runs.remove(id))
               throw HttpError(404, "no run " + clipped(id));
           }
           catch (const RunBusy &error)
           {
             throw HttpError(409, error.what());
           }
           send_json(res, {{"deleted", id}});
         });
  }

  /** A run's progress as server-sent events, its report and data, and its files. */
  void GuiServer::Impl::run_output_routes()
  {
    http.Get(R"(/api/runs/([A-Za-z0-9_-]+)/events)",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               const std::string id = req.matches[1];
               if (!runs.exists(id))
                 throw HttpError(404, "no run " + clipped(id));
               // Each stream holds a thread while it is open: past the cap the others are
               // refused, so that ordinary requests always find a thread.
               if (++event_streams > max_event_streams)
               {
                 --event_streams;
                 res.set_header("Retry-After", "5");
                 throw HttpError(503,
                                 "too many event streams open (at most " +
                                   std::to_string(max_event_streams) +
                                   "); close a page that follows a run, or poll GET /api/runs/" +
                                   clipped(id));
               }
               auto slot = std::make_shared<EventStreamSlot>(event_streams);
               auto seen = std::make_shared<std::size_t>(0);
               res.set_header("Cache-Control", "no-cache");
               // Written outside cpp-httplib's exception handling: nothing may escape.
               res.set_chunked_content_provider(
                 "text/event-stream",
                 [this, id, seen, slot](std::size_t, httplib::DataSink &sink)
                 {
                   try
                   {
                     runs.wait_for_change(id, *seen, 1000);
                     const nlohmann::json state = runs.describe(id, *seen);
                     *seen                      = state.value("log_lines", *seen);
                     const std::string event    = "data: " + json_text(state) + "\n\n";
                     if (!sink.write(event.data(), event.size()))
                       return false;
                     const std::string s = state.value("state", "");
                     if (s != "running" && s != "queued")
                       sink.done();
                     return true;
                   }
                   catch (...)
                   {
                     return false;
                   }
                 });
             });
    http.Get(R"(/api/runs/([A-Za-z0-9_-]+)/(data|report))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               if (!runs.exists(req.matches[1]))
                 throw HttpError(404, "no run " + clipped(req.matches[1].str()));
               const auto data =
                 report::report_data(options.runs_dir / req.matches[1].str() / "out");
               if (req.matches[2] == "data")
                 send_json(res, data);
               else
                 set_body(res, report::report_html(data), "text/html; charset=utf-8");
             });
    http.Get(R"(/api/files/([A-Za-z0-9_-]+)/(.+))",
             [this](const httplib::Request &req, httplib::Response &res)
             {
               if (!runs.exists(req.matches[1]))
                 throw HttpError(404, "no run " + clipped(req.matches[1].str()));
               const auto path = confined(options.runs_dir / req.matches[1].str(), req.matches[2]);
               std::error_code ec;
               if (!std::filesystem::is_regular_file(path, ec))
                 throw HttpError(404, "no file " + in_quotes(req.matches[2].str()));
               const std::uintmax_t size = std::filesystem::file_size(path, ec);
               const std::string    type = mime_type(path.filename().string());
               if (ec || size == 0)
                 return res.set_content("", type.c_str());
               // Streamed from the file (a run's results can be large): 64 kB in memory at a
               // time, whatever the file's size. Called outside cpp-httplib's exception
               // handling: nothing may escape.
               auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
               res.set_content_provider(
                 static_cast<std::size_t>(size),
                 type.c_str(),
                 [in](std::size_t offset, std::size_t length, httplib::DataSink &sink)
                 {
                   try
                   {
                     std::vector<char> buffer(std::min<std::size_t>(length, 64u << 10));
                     in->seekg(static_cast<std::streamoff>(offset));
                     in->read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
                     const auto n = static_cast<std::size_t>(in->gcount());
                     return n > 0 && sink.write(buffer.data(), n);
                   }
                   catch (...)
                   {
                     return false;
                   }
                 });
             });
  }

  /** The ground-motion records of the records directory, and uploads. */
  void GuiServer::Impl::record_routes()
  {
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
                 throw HttpError(404,
                                 "no records directory (kimp gui --records-dir DIR, or set "
                                 "KIMP_RECORDS_DIR)");
               for (const auto &path : io::list_records(*options.records_dir))
                 if (path.stem().string() == req.matches[1].str())
                   return send_json(res, motion_json(app::ground_motion_of(io::read_at2(path))));
               throw HttpError(404, "no record " + in_quotes(req.matches[1].str()));
             });
    post("/api/upload",
         [this](const httplib::Request &req, const std::string &body, httplib::Response &res)
         {
           static const std::regex safe(R"([A-Za-z0-9_.-]{1,100})");
           const std::string       name = req.get_param_value("name");
           if (!std::regex_match(name, safe) || name.front() == '.')
             throw HttpError(400,
                             "upload name " + in_quotes(name) +
                               " must be 1-100 letters, digits, '_', '-' or '.'");
           const double unit = positive_number_parameter(req, "unit", 9.80665);
           const auto   dir  = options.runs_dir / "uploads";
           std::filesystem::create_directories(dir);
           const auto path = dir / name;
           try
           {
             const auto record = name.size() > 4 && (name.substr(name.size() - 4) == ".AT2" ||
                                                     name.substr(name.size() - 4) == ".at2") ?
                                   io::parse_at2(body, name) :
                                   io::parse_two_column(body, name, unit);
             io::write_text_atomic(path, body);
             nlohmann::json j = motion_json(app::ground_motion_of(record));
             // The record as a run's scene names it: relative to the run's folder (the child
             // runs there, and the motion preview reads scenes as if from there).
             j["path"] = "../uploads/" + name;
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
    const int requested = impl_->options.port;
    if (requested < 0 || requested > 65535)
      throw std::invalid_argument("kimp gui: port " + std::to_string(requested) +
                                  " is not a TCP port (1-65535, or 0 for any free port)");
    // SO_REUSEADDR only: cpp-httplib's default SO_REUSEPORT would let a second kimp gui bind the
    // port of a running one (and the kernel share the connections between them).
    impl_->http.set_socket_options(
      [this](socket_t sock)
      {
        int yes = 1;
        setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
        fcntl(sock, F_SETFD, FD_CLOEXEC);
        impl_->listen_socket = sock;
      });
    const std::string host = impl_->options.host == "localhost" ? "127.0.0.1" : impl_->options.host;
    errno                  = 0;
    if (requested == 0)
      impl_->port = impl_->http.bind_to_any_port(host.c_str());
    else if (impl_->http.bind_to_port(host.c_str(), requested))
      impl_->port = requested;
    else
      impl_->port = -1;
    if (impl_->port > 0 && ::listen(impl_->listen_socket, listen_backlog) != 0)
      throw std::runtime_error(std::string("kimp gui: cannot raise the listen backlog: ") +
                               std::strerror(errno));
    if (impl_->port <= 0)
    {
      const int error = errno;
      throw std::runtime_error(
        "kimp gui: cannot listen on " + impl_->options.host + ":" + std::to_string(requested) +
        (error == EADDRINUSE ? ": the port is in use (another kimp gui?); choose another with "
                               "--port, or --port 0 for any free port" :
                               std::string(": ") + (error ? std::strerror(error) : "bind failed") +
                                 " (choose another --host or --port)"));
    }
    return impl_->port;
  }

  void GuiServer::listen()
  {
    {
      std::lock_guard<std::mutex> lock(impl_->listen_mutex);
      if (impl_->stop_requested)
        return;
      impl_->listening = true;
    }
    impl_->http.listen_after_bind();
    impl_->listen_returned = true;
  }

  void GuiServer::stop()
  {
    if (!impl_)
      return;
    bool listening = false;
    {
      std::lock_guard<std::mutex> lock(impl_->listen_mutex);
      impl_->stop_requested = true;
      listening             = impl_->listening;
    }
    // cpp-httplib's stop() does nothing until its loop runs: wait for the loop (or its end).
    if (listening)
    {
      while (!impl_->http.is_running() && !impl_->listen_returned)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      impl_->http.stop();
    }
    impl_->runs.shutdown();
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
