// Child processes of `kimp gui` runs (server/run_manager.h): posix_spawn with default signal
// dispositions, an empty signal mask and a process group of their own, stderr on a pipe; one
// watcher thread per run that reads the log, parses progress, escalates a cancel to SIGKILL and
// records the final state.
#include "server/run_manager.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <fstream>
#include <poll.h>
#include <regex>
#include <signal.h>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "io/summary.h"

extern char **environ;

namespace kimp::server
{
  namespace
  {
    /// The environment of a child: this one's, with KIMP_PROGRESS=lines (machine-readable
    /// progress) and KIMP_RECORDS_DIR set to `records_dir` when given.
    std::vector<std::string> child_environment(const std::optional<std::filesystem::path> &records)
    {
      std::vector<std::string> env;
      for (char **e = environ; e && *e; ++e)
      {
        const std::string entry(*e);
        if (entry.rfind("KIMP_PROGRESS=", 0) == 0 ||
            (records && entry.rfind("KIMP_RECORDS_DIR=", 0) == 0))
          continue;
        env.push_back(entry);
      }
      env.push_back("KIMP_PROGRESS=lines");
      if (records)
        env.push_back("KIMP_RECORDS_DIR=" + std::filesystem::absolute(*records).string());
      return env;
    }

    /**
     * posix_spawn of `kimp` with stdout to `out_fd` and stderr to `err_fd` (-1: /dev/null), in
     * `cwd` (empty: this one), as the leader of a new process group. The child starts with an
     * empty signal mask and default SIGINT/SIGTERM/SIGHUP/SIGQUIT/SIGPIPE: `kimp gui` blocks
     * SIGINT and SIGTERM for its signal thread, and a child that inherited that mask could not
     * be cancelled.
     * @return the child's pid, or -1
     */
    int spawn(const std::filesystem::path    &kimp,
              const std::vector<std::string> &arguments,
              int                             out_fd,
              int                             err_fd,
              const std::vector<std::string> &environment,
              const std::filesystem::path    &cwd = {})
    {
      posix_spawn_file_actions_t actions;
      posix_spawn_file_actions_init(&actions);
      if (!cwd.empty())
        posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
      posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
      if (out_fd >= 0)
        posix_spawn_file_actions_adddup2(&actions, out_fd, 1);
      else
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
      if (err_fd >= 0)
        posix_spawn_file_actions_adddup2(&actions, err_fd, 2);
      else
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);

      posix_spawnattr_t attributes;
      posix_spawnattr_init(&attributes);
      sigset_t none;
      sigemptyset(&none);
      posix_spawnattr_setsigmask(&attributes, &none);
      sigset_t defaults;
      sigemptyset(&defaults);
      for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE})
        sigaddset(&defaults, s);
      posix_spawnattr_setsigdefault(&attributes, &defaults);
      posix_spawnattr_setpgroup(&attributes, 0);
      posix_spawnattr_setflags(&attributes,
                               POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF |
                                 POSIX_SPAWN_SETPGROUP);

      std::vector<std::string> argv_text = {kimp.string()};
      argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
      std::vector<char *> argv;
      for (auto &a : argv_text)
        argv.push_back(a.data());
      argv.push_back(nullptr);
      std::vector<std::string> env_text = environment;
      std::vector<char *>      envp;
      for (auto &e : env_text)
        envp.push_back(e.data());
      envp.push_back(nullptr);
      pid_t     pid = -1;
      const int status =
        posix_spawn(&pid, kimp.c_str(), &actions, &attributes, argv.data(), envp.data());
      posix_spawnattr_destroy(&attributes);
      posix_spawn_file_actions_destroy(&actions);
      return status == 0 ? pid : -1;
    }

    double seconds_since(SteadyClock::time_point t)
    {
      return std::chrono::duration<double>(SteadyClock::now() - t).count();
    }

    std::string now_id()
    {
      const std::time_t t = std::time(nullptr);
      std::tm           tm{};
      gmtime_r(&t, &tm);
      char text[32];
      std::strftime(text, sizeof(text), "%Y%m%d-%H%M%S", &tm);
      return text;
    }

    bool valid_id(const std::string &id)
    {
      if (id.empty() || id.size() > 100)
        return false;
      for (char c : id)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
          return false;
      return true;
    }

    nlohmann::json read_json(const std::filesystem::path &path)
    {
      std::ifstream in(path);
      if (!in)
        return nullptr;
      return nlohmann::json::parse(in, nullptr, false);
    }

    /// The top-level entries of a run's output directory ("out/NAME", "out/DIR/"), at most 50.
    nlohmann::json output_files(const std::filesystem::path &run_dir)
    {
      std::vector<std::string> names;
      std::error_code          ec;
      for (std::filesystem::directory_iterator it(run_dir / "out", ec), end; !ec && it != end;
           it.increment(ec))
        // Hidden files (the output directory's lock `.kimp.lock`) are not results.
        if (it->path().filename().string().front() != '.')
          names.push_back("out/" + it->path().filename().string() +
                          (it->is_directory() ? "/" : ""));
      std::sort(names.begin(), names.end());
      if (names.size() > 50)
        names.resize(50);
      return names;
    }

    /// Progress of `line` for `command`: the fraction done, or nullopt.
    std::optional<double> parse_progress(const std::string &command, const std::string &line)
    {
      // A sweep's own line: "sweep: 87/781 cases of this rank done (87/781 in all incl. ...)".
      static const std::regex sweep(R"(\((\d+)/(\d+) in all)");
      // base::Progress with KIMP_PROGRESS=lines: "progress: 0.4213 ...".
      static const std::regex lines(R"(^progress: ([0-9.]+))");
      // A lumped or collide scene's "info: case 2/5: NAME", logged before case 2 starts.
      static const std::regex cases(R"(^info: case (\d+)/(\d+): )");
      std::smatch             m;
      if (command == "sweep")
      {
        if (std::regex_search(line, m, sweep))
          return std::stod(m[1]) / std::max(1.0, std::stod(m[2]));
        return std::nullopt;
      }
      if (std::regex_search(line, m, lines))
        return std::clamp(std::strtod(m[1].str().c_str(), nullptr), 0.0, 1.0);
      if (std::regex_search(line, m, cases))
        return (std::stod(m[1]) - 1.0) / std::max(1.0, std::stod(m[2]));
      return std::nullopt;
    }

    /// The case of a lumped run from its log: "info: case NAME: estimated ..., ~T s" (its cost
    /// estimate, logged for every case before the first runs) and "info: case i/n: NAME" (case
    /// i starts).
    void note_lumped_case(Run &run, const std::string &line)
    {
      static const std::regex estimate(R"(^info: case (.+): estimated .*, ~([0-9.eE+-]+) s$)");
      static const std::regex starts(R"(^info: case (\d+)/(\d+): (.+)$)");
      std::smatch             m;
      if (std::regex_match(line, m, estimate))
        run.case_estimates[m[1]] = std::strtod(m[2].str().c_str(), nullptr);
      else if (std::regex_match(line, m, starts))
      {
        run.case_index    = std::stoi(m[1]);
        run.case_count    = std::stoi(m[2]);
        run.case_started  = SteadyClock::now();
        const auto it     = run.case_estimates.find(m[3]);
        run.case_estimate = it == run.case_estimates.end() ? 0.0 : it->second;
      }
    }

    /// Seconds to wait between polls of a child's pipe (and for a cancel's SIGKILL).
    constexpr int poll_ms = 100;
  } // namespace

  Captured capture_kimp(const std::filesystem::path    &kimp,
                        const std::vector<std::string> &arguments,
                        const std::filesystem::path    &cwd,
                        double                          timeout_s)
  {
    Captured result;
    int      out[2], err[2];
    if (pipe2(out, O_CLOEXEC) != 0)
      return result;
    if (pipe2(err, O_CLOEXEC) != 0)
    {
      close(out[0]);
      close(out[1]);
      return result;
    }
    const int pid = spawn(kimp, arguments, out[1], err[1], child_environment(std::nullopt), cwd);
    close(out[1]);
    close(err[1]);
    const auto   start    = SteadyClock::now();
    bool         killed   = false;
    pollfd       fds[2]   = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
    std::string *texts[2] = {&result.out, &result.err};
    for (int open = 2; open > 0 && pid > 0;)
    {
      if (poll(fds, 2, poll_ms) < 0 && errno != EINTR)
        break;
      for (int i = 0; i < 2; ++i)
        if (fds[i].fd >= 0 && (fds[i].revents & (POLLIN | POLLHUP | POLLERR)))
        {
          char          buffer[4096];
          const ssize_t n = read(fds[i].fd, buffer, sizeof(buffer));
          if (n > 0)
            texts[i]->append(buffer, static_cast<std::size_t>(n));
          else
          {
            fds[i].fd = -1;
            --open;
          }
        }
      if (!killed && seconds_since(start) > timeout_s)
      {
        kill(-pid, SIGKILL);
        killed = true;
      }
    }
    close(out[0]);
    close(err[0]);
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) < 0)
      return result;
    result.exit_code = !killed && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
  }

  RunManager::RunManager(RunSettings settings)
    : settings_(std::move(settings))
  {
    settings_.max_runs = std::max(1u, settings_.max_runs);
    std::filesystem::create_directories(settings_.runs_dir);
  }

  RunManager::~RunManager()
  {
    shutdown();
  }

  void RunManager::shutdown()
  {
    std::vector<std::shared_ptr<Run>> runs;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
      for (auto &[id, run] : runs_)
        runs.push_back(run);
    }
    for (auto &run : runs)
      cancel(run->id);
    for (auto &run : runs)
      if (run->watcher.joinable())
        run->watcher.join();
  }

  std::string
  RunManager::start(const std::string &command, const std::string &scene, const std::string &sweep)
  {
    static const std::vector<std::string> commands = {"lumped", "collide", "fem", "study", "sweep"};
    if (std::find(commands.begin(), commands.end(), command) == commands.end())
      throw std::invalid_argument("unknown command \"" + command +
                                  "\" (expected lumped, collide, fem, study or sweep)");
    auto run     = std::make_shared<Run>();
    run->command = command;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stopping_)
        throw std::runtime_error("kimp gui is stopping: no new runs");
      if (running_ >= settings_.max_runs && queue_.size() >= settings_.max_queued)
        throw RunQueueFull("too many runs: " + std::to_string(running_) + " running (at most " +
                           std::to_string(settings_.max_runs) + ", kimp gui --max-runs) and " +
                           std::to_string(queue_.size()) + " queued (at most " +
                           std::to_string(settings_.max_queued) +
                           "); wait for one to finish or cancel one");
      run->id  = now_id() + "-" + std::to_string(++counter_) + "-" + command;
      run->dir = settings_.runs_dir / run->id;
    }
    std::filesystem::create_directories(run->dir);
    io::write_text_atomic(run->dir / "scene.yaml", scene);
    std::vector<std::string> arguments = {command};
    if (command == "sweep")
    {
      io::write_text_atomic(run->dir / "sweep.yaml", sweep);
      arguments.push_back((run->dir / "sweep.yaml").string());
      arguments.push_back("--no-charts");
    }
    else
      arguments.push_back((run->dir / "scene.yaml").string());
    arguments.push_back("-o");
    arguments.push_back((run->dir / "out").string());
    run->arguments = std::move(arguments);
    std::lock_guard<std::mutex> lock(mutex_);
    runs_[run->id] = run;
    queue_.push_back(run);
    launch_queued_locked();
    changed_.notify_all();
    return run->id;
  }

  void RunManager::launch_queued_locked()
  {
    while (!stopping_ && running_ < settings_.max_runs && !queue_.empty())
    {
      std::shared_ptr<Run> run = queue_.front();
      queue_.pop_front();
      ++running_;
      run->state   = "running";
      run->started = SteadyClock::now();
      run->watcher = std::thread(&RunManager::watch, this, run);
    }
  }

  void RunManager::watch(std::shared_ptr<Run> run)
  {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0)
    {
      std::lock_guard<std::mutex> lock(mutex_);
      run->error = "cannot create a pipe for the run";
      finish(*run, 0, false);
      return;
    }
    int pid = -1;
    {
      // Under the lock: cancel() sees either no child yet (and the flag stops the spawn) or
      // the child's pid.
      std::lock_guard<std::mutex> lock(mutex_);
      if (!run->cancel)
        pid = spawn(settings_.kimp_executable,
                    run->arguments,
                    fds[1],
                    fds[1],
                    child_environment(settings_.records_dir));
      run->pid = pid;
      if (pid <= 0 && !run->cancel)
        run->error =
          "cannot start " + settings_.kimp_executable.string() + ": " + std::strerror(errno);
      changed_.notify_all();
    }
    close(fds[1]);
    std::ofstream log(run->dir / "run.log");
    std::string   pending;
    char          buffer[4096];
    int           status = 0;
    bool          reaped = pid <= 0;
    for (bool open = pid > 0; open;)
    {
      pollfd    p{fds[0], POLLIN, 0};
      const int ready = poll(&p, 1, poll_ms);
      if (ready > 0)
      {
        const ssize_t n = read(fds[0], buffer, sizeof(buffer));
        if (n <= 0)
          open = false;
        else
          pending.append(buffer, static_cast<std::size_t>(n));
      }
      else if (ready < 0 && errno != EINTR)
        open = false;
      std::lock_guard<std::mutex> lock(mutex_);
      for (std::size_t end; (end = pending.find_first_of("\r\n")) != std::string::npos;)
      {
        std::string line = pending.substr(0, end);
        pending.erase(0, end + 1);
        if (line.empty())
          continue;
        if (const auto fraction = parse_progress(run->command, line))
        {
          // fem and study report each wall height's simulated time from 0 again; the other
          // commands' lines count cases, which never go back (a line rounds to 4 digits).
          const bool per_height = run->command == "fem" || run->command == "study";
          run->progress         = per_height ? *fraction : std::max(run->progress, *fraction);
          if (line.rfind("progress: ", 0) == 0)
          {
            // Not logged: one a second would bury the messages.
            run->progress_text = line.substr(10);
            changed_.notify_all();
            continue;
          }
          run->progress_text = line;
        }
        log << line << '\n' << std::flush;
        if (line.rfind("error: ", 0) == 0)
          run->error += (run->error.empty() ? "" : "\n") + line.substr(7);
        if (run->command == "lumped")
          note_lumped_case(*run, line);
        run->log.push_back(std::move(line));
        changed_.notify_all();
      }
      // A cancelled child that is still there after the grace period is killed (with anything
      // it started: the whole process group).
      if (run->cancel && !run->killed && seconds_since(run->cancelled_at) > settings_.kill_grace)
      {
        kill(-pid, SIGKILL);
        run->killed = true;
      }
      // The child gone and nothing left to read, though a grandchild may hold the pipe open.
      if (!reaped && waitpid(pid, &status, WNOHANG) == pid)
        reaped = true;
      if (reaped && ready == 0)
        open = false;
    }
    close(fds[0]);
    if (!reaped)
      waitpid(pid, &status, 0);
    std::lock_guard<std::mutex> lock(mutex_);
    finish(*run, status, pid > 0);
  }

  void RunManager::finish(Run &run, int status, bool spawned)
  {
    run.exit_code = spawned && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (run.cancel)
    {
      run.state = "cancelled";
      run.error = spawned ?
                    "cancelled after " +
                      std::to_string(static_cast<int>(std::round(seconds_since(run.started)))) +
                      " s" + (run.killed ? " (killed: it did not stop on SIGTERM)" : "") :
                    "cancelled before it started";
    }
    else if (spawned && WIFEXITED(status) && run.exit_code == 0)
    {
      run.state    = "done";
      run.progress = 1.0;
    }
    else
    {
      run.state = "failed";
      if (run.error.empty())
        run.error = !spawned            ? "the run could not be started" :
                    WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status)) :
                                          "exit code " + std::to_string(run.exit_code);
    }
    run.pid = -1;
    std::ofstream(run.dir / "run.json") << nlohmann::json{
      {"id", run.id},
      {"command", run.command},
      {"state", run.state},
      {"progress", run.progress},
      {"exit_code", run.exit_code},
      {"error", run.error}}.dump(1);
    // Called once per launched run (by its watcher): its slot is free for the next in the queue.
    --running_;
    launch_queued_locked();
    changed_.notify_all();
  }

  bool RunManager::cancel(const std::string &id)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto                  it = runs_.find(id);
    if (it == runs_.end())
      return false;
    Run &run = *it->second;
    if (run.state == "queued")
    {
      queue_.erase(std::remove(queue_.begin(), queue_.end(), it->second), queue_.end());
      run.cancel = true;
      run.state  = "cancelled";
      run.error  = "cancelled before it started";
      std::ofstream(run.dir / "run.json") << nlohmann::json{
        {"id", run.id},
        {"command", run.command},
        {"state", run.state},
        {"progress", 0.0},
        {"exit_code", -1},
        {"error", run.error}}.dump(1);
      changed_.notify_all();
      return true;
    }
    if (run.state != "running" || run.cancel)
      return false;
    run.cancel       = true;
    run.cancelled_at = SteadyClock::now();
    if (run.pid > 0)
      kill(-run.pid, SIGTERM);
    changed_.notify_all();
    return true;
  }

  void
  RunManager::set_meta(const std::string &id, const std::string &name, const std::string &notes)
  {
    if (name.size() > 200)
      throw std::invalid_argument("run name of " + std::to_string(name.size()) +
                                  " bytes: at most 200");
    if (notes.size() > 65536)
      throw std::invalid_argument("run notes of " + std::to_string(notes.size()) +
                                  " bytes: at most 64 kB");
    std::lock_guard<std::mutex> lock(mutex_);
    io::write_text_atomic(settings_.runs_dir / id / "meta.json",
                          nlohmann::json{{"name", name}, {"notes", notes}}.dump(1));
    changed_.notify_all();
  }

  bool RunManager::remove(const std::string &id)
  {
    std::shared_ptr<Run> run;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const auto                  it = runs_.find(id);
      if (it != runs_.end())
      {
        if (it->second->state == "queued" || it->second->state == "running")
          return false;
        run = it->second;
        runs_.erase(it);
      }
    }
    // Its watcher has finished (the state is final); joined here, outside the lock.
    if (run && run->watcher.joinable())
      run->watcher.join();
    std::filesystem::remove_all(settings_.runs_dir / id);
    return true;
  }

  bool RunManager::exists(const std::string &id) const
  {
    return valid_id(id) && std::filesystem::is_directory(settings_.runs_dir / id);
  }

  nlohmann::json RunManager::describe(const std::string &id, std::size_t from) const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return describe_locked(id, from);
  }

  nlohmann::json RunManager::describe_locked(const std::string         &id,
                                             std::optional<std::size_t> from) const
  {
    const auto     it = runs_.find(id);
    nlohmann::json j;
    if (it == runs_.end())
    {
      j = read_json(settings_.runs_dir / id / "run.json");
      if (!j.is_object())
        j = {{"id", id}, {"state", "unknown"}};
      if (j.value("state", "") == "done")
        j["progress"] = 1.0;
      else if (!j.contains("progress"))
        j["progress"] = 0.0;
      if (from)
        j["log"] = nlohmann::json::array();
    }
    else
    {
      const Run &run      = *it->second;
      double     progress = run.progress;
      bool       estimate = false;
      if (run.state == "running" && run.case_estimate > 0.0 && run.case_count > 0)
      {
        const double within = std::min(0.9, seconds_since(run.case_started) / run.case_estimate);
        const double p      = (run.case_index - 1 + within) / run.case_count;
        if (p > progress)
        {
          progress = p;
          estimate = true;
        }
      }
      j = {{"id", run.id},
           {"command", run.command},
           {"state", run.state},
           {"progress", progress},
           {"progress_estimated", estimate},
           {"progress_text", run.progress_text},
           {"exit_code", run.exit_code},
           {"error", run.error},
           {"log_lines", run.log.size()}};
      if (run.pid > 0)
        j["pid"] = run.pid;
      if (run.state == "queued")
        j["queue_position"] =
          std::find(queue_.begin(), queue_.end(), it->second) - queue_.begin() + 1;
      if (from)
      {
        nlohmann::json log = nlohmann::json::array();
        for (std::size_t i = *from; i < run.log.size(); ++i)
          log.push_back(run.log[i]);
        j["log_from"] = std::min(*from, run.log.size());
        j["log"]      = std::move(log);
      }
    }
    j["files"]                = output_files(settings_.runs_dir / id);
    const nlohmann::json meta = read_json(settings_.runs_dir / id / "meta.json");
    j["name"]                 = meta.is_object() ? meta.value("name", "") : "";
    j["notes"]                = meta.is_object() ? meta.value("notes", "") : "";
    return j;
  }

  nlohmann::json RunManager::list() const
  {
    std::vector<std::string> ids;
    for (const auto &entry : std::filesystem::directory_iterator(settings_.runs_dir))
      if (entry.is_directory() && valid_id(entry.path().filename().string()) &&
          std::filesystem::exists(entry.path() / "scene.yaml"))
        ids.push_back(entry.path().filename().string());
    std::sort(ids.rbegin(), ids.rend());
    nlohmann::json              list = nlohmann::json::array();
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto &id : ids)
      list.push_back(describe_locked(id, std::nullopt));
    return list;
  }

  void RunManager::wait_for_change(const std::string &id, std::size_t seen_lines, int ms) const
  {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto                   it = runs_.find(id);
    if (it == runs_.end())
      return;
    const std::string state    = it->second->state;
    const double      progress = it->second->progress;
    changed_.wait_for(lock,
                      std::chrono::milliseconds(ms),
                      [&]
                      {
                        return it->second->log.size() != seen_lines || it->second->state != state ||
                               it->second->progress != progress;
                      });
  }
} // namespace kimp::server
