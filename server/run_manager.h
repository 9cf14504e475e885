// Background runs of `kimp gui`: each run is a child `kimp <command> SCENE -o DIR` process watched
// by a thread, so a run can be cancelled (SIGTERM) and a crash never takes the server down.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

namespace kimp::server
{
  /// State of one run; every member is guarded by RunManager's mutex.
  struct Run
  {
    std::string              id;
    std::string              command;
    std::filesystem::path    dir;                  ///< runs_dir/id: scene, log, results
    std::string              state     = "queued"; ///< queued, running, done, failed, cancelled
    int                      exit_code = -1;
    std::string              error;          ///< the command's "error: ..." line(s)
    std::vector<std::string> log;            ///< stderr lines
    double                   progress = 0.0; ///< 0..1 from "case i/n" lines, 1 when done
    int                      pid      = -1;
    bool                     cancel   = false;
    std::thread              watcher;
  };

  /**
   * Starts, watches, cancels and lists runs. A run's directory holds `scene.yaml` (and `sweep.yaml`
   * for a sweep), `run.log` (stderr of the child) and `run.json` (final state), so the list of past
   * runs survives a restart of the server.
   */
  class RunManager
  {
  public:
    /// @param runs_dir directory of the runs (created); @param kimp the kimp executable
    RunManager(std::filesystem::path runs_dir, std::filesystem::path kimp);
    ~RunManager();
    RunManager(const RunManager &)            = delete;
    RunManager &operator=(const RunManager &) = delete;

    /**
     * Start `kimp <command>` on `scene` (YAML text). For a sweep, `sweep` is the sweep file and
     * `scene` its base scene (written beside it as scene.yaml).
     * @return the run's id
     * @throws std::invalid_argument for an unknown command
     */
    std::string
    start(const std::string &command, const std::string &scene, const std::string &sweep);
    /// Send SIGTERM to a running child; false when there is no such run or it has finished.
    bool cancel(const std::string &id);
    /// The run as JSON (id, command, state, progress, exit_code, error, log tail from `from`).
    nlohmann::json describe(const std::string &id, std::size_t from = 0) const;
    /// Every run in runs_dir, newest first (finished ones read from run.json).
    nlohmann::json list() const;
    /// Whether `id` names a run directory (only [A-Za-z0-9_-] characters).
    bool exists(const std::string &id) const;
    /// Block until the run changed after `seen_lines` log lines or finished, at most `ms` ms.
    void wait_for_change(const std::string &id, std::size_t seen_lines, int ms) const;
    const std::filesystem::path &runs_dir() const { return runs_dir_; }

  private:
    void watch(std::shared_ptr<Run> run, std::vector<std::string> arguments);

    std::filesystem::path                       runs_dir_;
    std::filesystem::path                       kimp_;
    mutable std::mutex                          mutex_;
    mutable std::condition_variable             changed_;
    std::map<std::string, std::shared_ptr<Run>> runs_;
    unsigned                                    counter_ = 0;
  };

  /// Output of `kimp ARGS...` (stdout) and its exit code; used for --print-schema and the like.
  std::pair<int, std::string> capture_kimp(const std::filesystem::path    &kimp,
                                           const std::vector<std::string> &arguments);
} // namespace kimp::server
