// Child processes of `kimp gui` runs (server/run_manager.h): posix_spawn with stderr on a pipe,
// one watcher thread per run that reads the log, parses progress and records the final state.
#include "server/run_manager.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fcntl.h>
#include <fstream>
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
    /// posix_spawn of `kimp` with stdout to `out_fd` and stderr to `err_fd` (-1: /dev/null).
    int spawn(const std::filesystem::path    &kimp,
              const std::vector<std::string> &arguments,
              int                             out_fd,
              int                             err_fd)
    {
      posix_spawn_file_actions_t actions;
      posix_spawn_file_actions_init(&actions);
      posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
      if (out_fd >= 0)
        posix_spawn_file_actions_adddup2(&actions, out_fd, 1);
      else
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
      if (err_fd >= 0)
        posix_spawn_file_actions_adddup2(&actions, err_fd, 2);
      else
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
      std::vector<std::string> argv_text = {kimp.string()};
      argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
      std::vector<char *> argv;
      for (auto &a : argv_text)
        argv.push_back(a.data());
      argv.push_back(nullptr);
      pid_t     pid    = -1;
      const int status = posix_spawn(&pid, kimp.c_str(), &actions, nullptr, argv.data(), environ);
      posix_spawn_file_actions_destroy(&actions);
      return status == 0 ? pid : -1;
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
  } // namespace

  std::pair<int, std::string> capture_kimp(const std::filesystem::path    &kimp,
                                           const std::vector<std::string> &arguments)
  {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0)
      return {-1, {}};
    const int pid = spawn(kimp, arguments, fds[1], -1);
    close(fds[1]);
    std::string out;
    char        buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof(buffer))) > 0;)
      out.append(buffer, static_cast<std::size_t>(n));
    close(fds[0]);
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) < 0)
      return {-1, out};
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
  }

  RunManager::RunManager(std::filesystem::path runs_dir, std::filesystem::path kimp)
    : runs_dir_(std::move(runs_dir))
    , kimp_(std::move(kimp))
  {
    std::filesystem::create_directories(runs_dir_);
  }

  RunManager::~RunManager()
  {
    std::vector<std::shared_ptr<Run>> runs;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto &[id, run] : runs_)
      {
        if (run->pid > 0 && run->state == "running")
          kill(run->pid, SIGTERM);
        runs.push_back(run);
      }
    }
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
      run->id        = now_id() + "-" + std::to_string(++counter_) + "-" + command;
      run->dir       = runs_dir_ / run->id;
      runs_[run->id] = run;
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
    run->watcher = std::thread(&RunManager::watch, this, run, arguments);
    return run->id;
  }

  void RunManager::watch(std::shared_ptr<Run> run, std::vector<std::string> arguments)
  {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0)
    {
      std::lock_guard<std::mutex> lock(mutex_);
      run->state = "failed";
      run->error = "cannot create a pipe for the run";
      changed_.notify_all();
      return;
    }
    const int pid = spawn(kimp_, arguments, -1, fds[1]);
    close(fds[1]);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      run->pid   = pid;
      run->state = pid > 0 ? "running" : "failed";
      if (pid <= 0)
        run->error = "cannot start " + kimp_.string();
      changed_.notify_all();
    }
    std::ofstream           log(run->dir / "run.log");
    static const std::regex progress(R"(case (\d+)/(\d+))");
    std::string             pending;
    char                    buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof(buffer))) > 0;)
    {
      pending.append(buffer, static_cast<std::size_t>(n));
      for (std::size_t end; (end = pending.find_first_of("\r\n")) != std::string::npos;)
      {
        std::string line = pending.substr(0, end);
        pending.erase(0, end + 1);
        if (line.empty())
          continue;
        log << line << '\n' << std::flush;
        std::lock_guard<std::mutex> lock(mutex_);
        std::smatch                 m;
        if (std::regex_search(line, m, progress))
          run->progress = (std::stod(m[1]) - 1.0) / std::max(1.0, std::stod(m[2]));
        if (line.rfind("error: ", 0) == 0)
          run->error += (run->error.empty() ? "" : "\n") + line.substr(7);
        run->log.push_back(std::move(line));
        changed_.notify_all();
      }
    }
    close(fds[0]);
    int status = 0;
    if (pid > 0)
      waitpid(pid, &status, 0);
    std::lock_guard<std::mutex> lock(mutex_);
    run->exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (run->cancel)
      run->state = "cancelled";
    else if (pid > 0 && WIFEXITED(status) && run->exit_code == 0)
    {
      run->state    = "done";
      run->progress = 1.0;
    }
    else
    {
      run->state = "failed";
      if (run->error.empty())
        run->error = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status)) :
                                           "exit code " + std::to_string(run->exit_code);
    }
    run->pid = -1;
    std::ofstream(run->dir / "run.json") << nlohmann::json{
      {"id", run->id},
      {"command", run->command},
      {"state", run->state},
      {"exit_code", run->exit_code},
      {"error", run->error}}.dump(1);
    changed_.notify_all();
  }

  bool RunManager::cancel(const std::string &id)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto                  it = runs_.find(id);
    if (it == runs_.end() || it->second->pid <= 0)
      return false;
    it->second->cancel = true;
    kill(it->second->pid, SIGTERM);
    return true;
  }

  bool RunManager::exists(const std::string &id) const
  {
    return valid_id(id) && std::filesystem::is_directory(runs_dir_ / id);
  }

  nlohmann::json RunManager::describe(const std::string &id, std::size_t from) const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto                  it = runs_.find(id);
    if (it == runs_.end())
    {
      nlohmann::json j = read_json(runs_dir_ / id / "run.json");
      if (j.is_null())
        j = {{"id", id}, {"state", "unknown"}};
      j["progress"] = j.value("state", "") == "done" ? 1.0 : 0.0;
      j["log"]      = nlohmann::json::array();
      return j;
    }
    const Run     &run = *it->second;
    nlohmann::json log = nlohmann::json::array();
    for (std::size_t i = from; i < run.log.size(); ++i)
      log.push_back(run.log[i]);
    return {{"id", run.id},
            {"command", run.command},
            {"state", run.state},
            {"progress", run.progress},
            {"exit_code", run.exit_code},
            {"error", run.error},
            {"log_from", from},
            {"log_lines", run.log.size()},
            {"log", log}};
  }

  nlohmann::json RunManager::list() const
  {
    std::vector<std::string> ids;
    for (const auto &entry : std::filesystem::directory_iterator(runs_dir_))
      if (entry.is_directory() && valid_id(entry.path().filename().string()) &&
          std::filesystem::exists(entry.path() / "scene.yaml"))
        ids.push_back(entry.path().filename().string());
    std::sort(ids.rbegin(), ids.rend());
    nlohmann::json list = nlohmann::json::array();
    for (const auto &id : ids)
    {
      nlohmann::json j = describe(id, std::numeric_limits<std::size_t>::max());
      j.erase("log");
      list.push_back(j);
    }
    return list;
  }

  void RunManager::wait_for_change(const std::string &id, std::size_t seen_lines, int ms) const
  {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto                   it = runs_.find(id);
    if (it == runs_.end())
      return;
    const std::string state = it->second->state;
    changed_.wait_for(lock,
                      std::chrono::milliseconds(ms),
                      [&] {
                        return it->second->log.size() != seen_lines || it->second->state != state;
                      });
  }
} // namespace kimp::server
