// Child processes of `kimp gui` runs (server/run_manager.h): fork and exec with default signal
// dispositions, an empty signal mask, a process group of their own and death with the server,
// stderr on a pipe; one watcher thread per run that reads the log, parses progress, escalates a
// cancel to SIGKILL and records the final state; the runs folder's lock and the runs a dead server
// left.
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
#include <sstream>
#include <stdexcept>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/logging.h"
#include "base/stopwatch.h"
#include "io/output_dir.h"

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
     * fork and exec of `kimp` with stdout to `out_fd` and stderr to `err_fd` (-1: /dev/null), in
     * `cwd` (empty: this one), as the leader of a new process group, killed (SIGKILL) when the
     * calling thread ends: a server that dies, even of SIGKILL, takes its runs with it. The child
     * starts with an empty signal mask and default SIGINT/SIGTERM/SIGHUP/SIGQUIT/SIGPIPE (`kimp
     * gui` blocks SIGINT and SIGTERM for its signal thread, and a child that inherited that mask
     * could not be cancelled) and with no other descriptor of the server (sockets, locks).
     * posix_spawn cannot set the parent-death signal; between fork and exec the child makes only
     * async-signal-safe calls on data prepared before the fork.
     * @return the child's pid, or -1
     */
    int spawn(const std::filesystem::path    &kimp,
              const std::vector<std::string> &arguments,
              int                             out_fd,
              int                             err_fd,
              const std::vector<std::string> &environment,
              const std::filesystem::path    &cwd = {})
    {
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
      const std::string executable = kimp.string();
      const std::string directory  = cwd.string();
      sigset_t          none;
      sigemptyset(&none);
      struct sigaction fallback
      {
      };
      fallback.sa_handler = SIG_DFL;
      sigemptyset(&fallback.sa_mask);
      const pid_t parent = getpid();
      // The child reports a failure before or in execve on this pipe (closed by a good exec).
      int report[2];
      if (pipe2(report, O_CLOEXEC) != 0)
        return -1;

      const pid_t pid = fork();
      if (pid == 0)
      {
        // The child: async-signal-safe calls only.
        const auto fail = [&]
        {
          const int                      error = errno;
          [[maybe_unused]] const ssize_t n     = write(report[1], &error, sizeof(error));
          _exit(127);
        };
        if (setpgid(0, 0) != 0 || prctl(PR_SET_PDEATHSIG, SIGKILL) != 0)
          fail();
        // The server died before the signal was set: nobody would kill this child.
        if (getppid() != parent)
          _exit(127);
        for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE})
          sigaction(s, &fallback, nullptr);
        sigprocmask(SIG_SETMASK, &none, nullptr);
        // Out of the way of 0-3 first (a server started with a standard stream closed).
        const int out = out_fd >= 0 ? fcntl(out_fd, F_DUPFD, 4) : open("/dev/null", O_WRONLY);
        const int err = err_fd >= 0 ? fcntl(err_fd, F_DUPFD, 4) : open("/dev/null", O_WRONLY);
        const int in  = open("/dev/null", O_RDONLY);
        if (out < 0 || err < 0 || in < 0 || dup2(in, 0) < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0)
          fail();
        if (report[1] != 3 && dup3(report[1], 3, O_CLOEXEC) < 0)
          fail();
        report[1] = 3;
        if (!directory.empty() && chdir(directory.c_str()) != 0)
          fail();
        // Every other descriptor closed (close_range, Linux 5.9; else one by one).
        if (syscall(SYS_close_range, 4u, ~0u, 0u) != 0)
          for (int fd = 4; fd < 65536; ++fd)
            close(fd);
        execve(executable.c_str(), argv.data(), envp.data());
        fail();
      }
      close(report[1]);
      int     error = 0;
      ssize_t n     = -1;
      do
        n = read(report[0], &error, sizeof(error));
      while (n < 0 && errno == EINTR);
      close(report[0]);
      if (pid < 0)
        return -1;
      if (n == static_cast<ssize_t>(sizeof(error)))
      {
        waitpid(pid, nullptr, 0);
        errno = error;
        return -1;
      }
      return pid;
    }

    using base::seconds_since;

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

    /// `state` as `dir`/run.json (written atomically; any bytes of a child's message replaced
    /// where they are not UTF-8); a failure is logged, never thrown into a watcher thread.
    void save_state(const std::filesystem::path &dir, const nlohmann::json &state) noexcept
    {
      try
      {
        io::write_text_atomic(dir / "run.json",
                              state.dump(1, ' ', false, nlohmann::json::error_handler_t::replace));
      }
      catch (const std::exception &error)
      {
        base::logger().warn("cannot save the state of run {}: {}",
                            dir.filename().string(),
                            error.what());
      }
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

    /// The digits of `text` as a number (inf when too long: no exception from a log line).
    double number(const std::string &text)
    {
      return std::strtod(text.c_str(), nullptr);
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
          return std::clamp(number(m[1]) / std::max(1.0, number(m[2])), 0.0, 1.0);
        return std::nullopt;
      }
      if (std::regex_search(line, m, lines))
        return std::clamp(std::strtod(m[1].str().c_str(), nullptr), 0.0, 1.0);
      if (std::regex_search(line, m, cases))
        return std::clamp((number(m[1]) - 1.0) / std::max(1.0, number(m[2])), 0.0, 1.0);
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
        run.case_index    = static_cast<int>(std::min(number(m[1]), 1e9));
        run.case_count    = static_cast<int>(std::min(number(m[2]), 1e9));
        run.case_started  = SteadyClock::now();
        const auto it     = run.case_estimates.find(m[3]);
        run.case_estimate = it == run.case_estimates.end() ? 0.0 : it->second;
      }
    }

    /// Seconds to wait between polls of a child's pipe (and for a cancel's SIGKILL).
    constexpr int poll_ms = 100;
    /// A child's log line is cut after this many bytes (run.log), 240 for the page.
    constexpr std::size_t max_line_bytes = 64u << 10;
    /// run.log grows no further than this.
    constexpr std::size_t max_log_file_bytes = 64u << 20;
    /// The error of a run (its "error: " lines) grows no further than this.
    constexpr std::size_t max_error_bytes = 64u << 10;
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
    , shown_(settings_.runs_dir, settings_.records_dir)
  {
    settings_.max_runs = std::max(1u, settings_.max_runs);
    std::filesystem::create_directories(settings_.runs_dir);
    lock_runs_folder();
    mark_interrupted_runs();
  }

  RunManager::~RunManager()
  {
    shutdown();
    if (lock_fd_ >= 0)
      close(lock_fd_);
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

  void RunManager::lock_runs_folder()
  {
    const auto path = settings_.runs_dir / ".kimp-gui.lock";
    lock_fd_        = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd_ < 0)
      throw std::runtime_error("kimp gui: cannot lock the runs folder " +
                               settings_.runs_dir.string() + ": " + std::strerror(errno));
    if (flock(lock_fd_, LOCK_EX | LOCK_NB) != 0)
    {
      char          pid[32] = {};
      const ssize_t n       = pread(lock_fd_, pid, sizeof(pid) - 1, 0);
      close(lock_fd_);
      lock_fd_ = -1;
      throw std::runtime_error(
        "kimp gui: the runs folder " + settings_.runs_dir.string() +
        " is in use by another kimp gui" +
        (n > 0 ? " (pid " + std::string(pid, static_cast<std::size_t>(n)) + ")" : std::string()) +
        "; stop it, or give this one another --runs-dir");
    }
    const std::string pid = std::to_string(getpid());
    if (ftruncate(lock_fd_, 0) != 0 ||
        pwrite(lock_fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
      base::logger().warn("cannot write the pid into {}", path.string());
  }

  void RunManager::mark_interrupted_runs()
  {
    std::error_code ec;
    for (std::filesystem::directory_iterator it(settings_.runs_dir, ec), end; !ec && it != end;
         it.increment(ec))
    {
      const std::string id = it->path().filename().string();
      if (!valid_id(id) || !std::filesystem::exists(it->path() / "scene.yaml"))
        continue;
      nlohmann::json state = read_json(it->path() / "run.json");
      if (!state.is_object())
        state = nlohmann::json::object();
      const std::string was = state.value("state", "");
      if (was == "done" || was == "failed" || was == "cancelled" || was == "interrupted")
        continue;
      // The command is the last part of the id ("20260101-120000-3-lumped").
      if (!state.contains("command") || !state["command"].is_string())
        state["command"] = id.substr(id.rfind('-') + 1);
      state["id"]        = id;
      state["state"]     = "interrupted";
      state["exit_code"] = -1;
      state["error"]     = was == "queued" ?
                             "interrupted: kimp gui stopped before the run started" :
                             "interrupted: kimp gui stopped while the run was going (its "
                             "results are incomplete)";
      if (!state.contains("progress") || !state["progress"].is_number())
        state["progress"] = 0.0;
      save_state(it->path(), state);
    }
  }

  std::string
  RunManager::start(const std::string &command, const std::string &scene, const std::string &sweep)
  {
    static const std::vector<std::string> commands = {"lumped", "collide", "fem", "study", "sweep"};
    if (std::find(commands.begin(), commands.end(), command) == commands.end())
      throw std::invalid_argument("unknown command " + in_quotes(command) +
                                  " (expected lumped, collide, fem, study or sweep)");
    auto run     = std::make_shared<Run>();
    run->command = command;
    {
      // The place is taken here, under the lock (reserved_), and the files written after it:
      // concurrent starts cannot all pass the check before one of them is queued.
      std::lock_guard<std::mutex> lock(mutex_);
      if (stopping_)
        throw std::runtime_error("kimp gui is stopping: no new runs");
      const unsigned taken = running_ + static_cast<unsigned>(queue_.size()) + reserved_;
      if (taken >= settings_.max_runs + settings_.max_queued)
      {
        const unsigned going = std::min(taken, settings_.max_runs);
        throw RunQueueFull("too many runs: " + std::to_string(going) + " running (at most " +
                           std::to_string(settings_.max_runs) + ", kimp gui --max-runs) and " +
                           std::to_string(taken - going) + " queued (at most " +
                           std::to_string(settings_.max_queued) +
                           "); wait for one to finish or cancel one");
      }
      // A fresh directory: a restarted server's counter starts again within the same second.
      do
        run->id = now_id() + "-" + std::to_string(++counter_) + "-" + command;
      while (runs_.count(run->id) || std::filesystem::exists(settings_.runs_dir / run->id));
      run->dir = settings_.runs_dir / run->id;
      std::filesystem::create_directories(run->dir);
      ++reserved_;
    }
    try
    {
      io::write_text_atomic(run->dir / "scene.yaml", scene);
      // The child runs in the run's directory: its messages name "scene.yaml", not a machine
      // path.
      std::vector<std::string> arguments = {command};
      if (command == "sweep")
      {
        io::write_text_atomic(run->dir / "sweep.yaml", sweep);
        arguments.insert(arguments.end(), {"sweep.yaml", "--no-charts"});
      }
      else
        arguments.push_back("scene.yaml");
      arguments.insert(arguments.end(), {"-o", "out"});
      run->arguments = std::move(arguments);
      save_state(run->dir, {{"id", run->id}, {"command", command}, {"state", "queued"}});
    }
    catch (...)
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --reserved_;
      std::error_code ec;
      std::filesystem::remove_all(run->dir, ec);
      throw;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    --reserved_;
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

  int RunManager::start_child(Run &run, int out)
  {
    // Under the lock: cancel() sees either no child yet (and the flag stops the spawn) or
    // the child's pid.
    std::lock_guard<std::mutex> lock(mutex_);
    int                         pid = -1;
    if (!run.cancel)
      pid = spawn(settings_.kimp_executable,
                  run.arguments,
                  out,
                  out,
                  child_environment(settings_.records_dir),
                  run.dir);
    run.pid = pid;
    if (pid <= 0 && !run.cancel)
      run.error = "cannot start " + settings_.kimp_executable.filename().string() + ": " +
                  std::strerror(errno);
    changed_.notify_all();
    return pid;
  }

  void
  RunManager::take_lines(Run &run, std::string &pending, std::ostream &log, std::size_t &logged)
  {
    for (;;)
    {
      // A line ends at a line break, or after max_line_bytes (a child that writes without
      // one cannot grow the server).
      std::size_t end  = pending.find_first_of("\r\n");
      std::size_t skip = 1;
      if (end == std::string::npos)
      {
        if (pending.size() < max_line_bytes)
          break;
        end  = max_line_bytes;
        skip = 0;
      }
      std::string line = shown_.relative(pending.substr(0, end));
      pending.erase(0, end + skip);
      if (line.empty())
        continue;
      if (const auto fraction = parse_progress(run.command, line))
      {
        // fem and study report each wall height's simulated time from 0 again; the other
        // commands' lines count cases, which never go back (a line rounds to 4 digits).
        const bool per_height = run.command == "fem" || run.command == "study";
        run.progress          = per_height ? *fraction : std::max(run.progress, *fraction);
        if (line.rfind("progress: ", 0) == 0)
        {
          // Not logged: one a second would bury the messages.
          run.progress_text = line.substr(10);
          changed_.notify_all();
          continue;
        }
        run.progress_text = line;
      }
      // run.log stops at max_log_file_bytes (a child that writes without end fills no disk).
      if (logged < max_log_file_bytes)
      {
        logged += line.size() + 1;
        log << line << '\n';
        if (logged >= max_log_file_bytes)
          log << "... (run.log stops here, at " << (max_log_file_bytes >> 20) << " MB)\n";
        log << std::flush;
      }
      // The page gets long lines clipped, and the first max_log_lines lines.
      line = clip_long_lines(std::move(line));
      if (line.rfind("error: ", 0) == 0 && run.error.size() < max_error_bytes)
        run.error += (run.error.empty() ? "" : "\n") + line.substr(7);
      if (run.command == "lumped")
        note_lumped_case(run, line);
      if (run.log.size() < max_log_lines)
        run.log.push_back(std::move(line));
      else if (!run.log_full)
      {
        run.log.push_back("... (more than " + std::to_string(max_log_lines) +
                          " lines: the others are in run.log)");
        run.log_full = true;
      }
      changed_.notify_all();
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
    const int pid = start_child(*run, fds[1]);
    close(fds[1]);
    // A server that dies now leaves the run "running" on disk: interrupted at its next start.
    if (pid > 0)
      save_state(run->dir, {{"id", run->id}, {"command", run->command}, {"state", "running"}});
    std::ofstream log(run->dir / "run.log");
    std::size_t   logged = 0; // bytes written to run.log
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
      take_lines(*run, pending, log, logged);
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
    save_state(run.dir,
               {{"id", run.id},
                {"command", run.command},
                {"state", run.state},
                {"progress", run.progress},
                {"exit_code", run.exit_code},
                {"error", run.error}});
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
      save_state(run.dir,
                 {{"id", run.id},
                  {"command", run.command},
                  {"state", run.state},
                  {"progress", 0.0},
                  {"exit_code", -1},
                  {"error", run.error}});
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
    if (!exists(id))
      return false;
    std::shared_ptr<Run> run;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stopping_)
        throw RunBusy("kimp gui is stopping: runs are not removed now");
      if (const auto it = runs_.find(id); it != runs_.end())
      {
        if (it->second->state == "queued" || it->second->state == "running")
          throw RunBusy("run " + id + " is " + it->second->state + ": cancel it first");
        run = it->second;
      }
      // A child of a server that died before this one could still write there (a process
      // that outlived it: it holds the output lock).
      const auto lock_path = settings_.runs_dir / id / "out" / io::output_lock_name;
      if (const int fd = open(lock_path.c_str(), O_RDONLY | O_CLOEXEC); fd >= 0)
      {
        const bool held = flock(fd, LOCK_SH | LOCK_NB) != 0;
        close(fd);
        if (held)
          throw RunBusy("run " + id + " is still written by a process (out/" +
                        io::output_lock_name + " is held); stop it first");
      }
      runs_.erase(id);
    }
    // Its watcher has finished the run: it ends at once.
    if (run && run->watcher.joinable())
      run->watcher.join();
    std::filesystem::remove_all(settings_.runs_dir / id);
    changed_.notify_all();
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
      if (j.contains("error") && j["error"].is_string())
        j["error"] = shown_(j["error"].get<std::string>());
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
