// Background runs of `kimp gui`: each run is a child `kimp <command> SCENE -o DIR` process (its own
// process group, killed when the server dies) watched by a thread, so a run can be cancelled
// (SIGTERM, then SIGKILL) and a crash never takes the server down. At most max_runs children at a
// time; later runs wait in a queue of at most max_queued. Runs a killed server left behind are
// found at start-up as "interrupted" and can be removed.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "server/run_settings.h"
#include "server/shown_text.h"

namespace kimp::server
{
  using SteadyClock = std::chrono::steady_clock;

  /// Thrown by RunManager::start when max_queued runs are waiting already.
  struct RunQueueFull : std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  /// Thrown by RunManager::remove for a run that is still going.
  struct RunBusy : std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  /// State of one run; every member is guarded by RunManager's mutex.
  struct Run
  {
    std::string              id;
    std::string              command;
    std::filesystem::path    dir;       ///< runs_dir/id: scene, log, results
    std::vector<std::string> arguments; ///< of kimp, after the executable
    /// queued, running, done, failed, cancelled (interrupted: left by a server that died)
    std::string              state     = "queued";
    int                      exit_code = -1;
    std::string              error;            ///< the command's "error: ..." line(s)
    std::vector<std::string> log;              ///< stderr lines (without "progress:" lines)
    bool                     log_full = false; ///< max_log_lines kept; the rest in run.log only
    double                   progress = 0.0;   ///< 0..1, 1 when done
    std::string              progress_text;    ///< the last progress line, for the page
    /// A lumped case's progress between its log lines: the cost estimate of each case ("case
    /// NAME: estimated ..., ~T s", seconds by name), the case going (i of n) and its start.
    std::map<std::string, double> case_estimates;
    int                           case_index    = 0;
    int                           case_count    = 0;
    double                        case_estimate = 0.0;
    SteadyClock::time_point       case_started;
    int                           pid    = -1; ///< of the child, also its process group
    bool                          cancel = false;
    SteadyClock::time_point       started;        ///< when the child was started
    SteadyClock::time_point       cancelled_at;   ///< when SIGTERM was sent
    bool                          killed = false; ///< SIGKILL sent after the grace period
    std::thread                   watcher;
  };

  /**
   * Starts, queues, watches, cancels, lists and removes runs. A run's directory holds
   * `scene.yaml` (and `sweep.yaml` for a sweep), `run.log` (stderr of the child) and `run.json`
   * (its command and state: queued when accepted, then the final state), so the list of past runs
   * survives a restart of the server. The child runs in the run's directory (`kimp COMMAND
   * scene.yaml -o out`), so its messages name its files relative to it; paths of the runs and
   * records folders in its log are shown relative to them (FolderPaths).
   *
   * One server per runs folder: the folder is locked (`.kimp-gui.lock`, flock) for the
   * manager's lifetime. A run whose run.json is not final when the manager starts was left by a
   * server that died (its children died with it: they get SIGKILL when their server's thread
   * ends, PR_SET_PDEATHSIG): it is marked "interrupted" and can be removed.
   *
   * Progress (0..1) comes from the child's stderr: "progress: F" lines (base::Progress with
   * KIMP_PROGRESS=lines, set for every run: after each lumped case, FEM time steps) and, for a
   * sweep, its "sweep: ... (N/M in all ...)" lines. Within a lumped case (whose engine reports
   * nothing until it ends) the progress is estimated from the time spent against the case's
   * logged cost estimate, at most 90 % of the case, and marked "progress_estimated".
   */
  class RunManager
  {
  public:
    /// @throws std::runtime_error when another kimp gui uses the runs folder (its pid named) or
    /// the folder cannot be created or locked.
    explicit RunManager(RunSettings settings);
    /// Cancels every run (queued ones at once, running ones with SIGTERM, SIGKILL after
    /// kill_grace) and waits for the children.
    ~RunManager();
    RunManager(const RunManager &)            = delete;
    RunManager &operator=(const RunManager &) = delete;

    /**
     * Start `kimp <command>` on `scene` (YAML text), now or when a running run ends. For a sweep,
     * `sweep` is the sweep file and `scene` its base scene (written beside it as scene.yaml).
     * @return the run's id
     * The place in the queue is taken atomically: of any number of concurrent calls, at most
     * max_runs + max_queued runs are running or queued at any time.
     * @throws std::invalid_argument for an unknown command; RunQueueFull when max_queued runs
     *         wait already
     */
    std::string
    start(const std::string &command, const std::string &scene, const std::string &sweep);
    /// Cancel a queued run, or stop a running child (SIGTERM to its process group, SIGKILL after
    /// kill_grace); false when there is no such run or it has finished.
    bool cancel(const std::string &id);
    /// Delete a finished run's directory (done, failed, cancelled or interrupted); false when
    /// there is no such run.
    /// @throws RunBusy while it is queued or running, or a process still holds its output lock.
    bool remove(const std::string &id);
    /// Cancel everything and wait for the children (as the destructor; idempotent).
    void shutdown();
    /// The run as JSON (id, command, state, progress, exit_code, error, pid, files written, log
    /// tail from line `from`).
    nlohmann::json describe(const std::string &id, std::size_t from = 0) const;
    /// Every run in runs_dir, newest first (finished ones read from run.json), without logs.
    nlohmann::json list() const;
    /**
     * Set a run's name and notes (the page's label of the run and a free text), kept in
     * `meta.json` of its directory and shown by describe() and list().
     * @throws std::invalid_argument for a name longer than 200 bytes or notes over 64 kB
     */
    void set_meta(const std::string &id, const std::string &name, const std::string &notes);
    /// Whether `id` names a run directory (only [A-Za-z0-9_-] characters).
    bool exists(const std::string &id) const;
    /// Block until the run changed after `seen_lines` log lines or finished, at most `ms` ms.
    void wait_for_change(const std::string &id, std::size_t seen_lines, int ms) const;
    const std::filesystem::path &runs_dir() const { return settings_.runs_dir; }
    const RunSettings           &settings() const { return settings_; }
    /// Text as the page is shown it: paths relative to the runs and records folders.
    const FolderPaths &shown() const { return shown_; }

    /// Log lines of a run kept in memory (and sent to the page); the rest go to run.log only.
    static constexpr std::size_t max_log_lines = 20000;

  private:
    nlohmann::json describe_locked(const std::string &id, std::optional<std::size_t> from) const;
    void           launch_queued_locked();
    void           watch(std::shared_ptr<Run> run);
    /// watch(): the child of `run` with stdout and stderr on `out` (-1: not started, the reason
    /// in run.error, or cancelled before).
    int start_child(Run &run, int out);
    /// watch(), under the lock: the complete lines of `pending` (taken out of it) into `run`:
    /// progress, run.log (`logged` bytes written so far), errors and the page's log.
    void take_lines(Run &run, std::string &pending, std::ostream &log, std::size_t &logged);
    void finish(Run &run, int status, bool spawned);
    void lock_runs_folder();
    void mark_interrupted_runs();

    RunSettings                                 settings_;
    FolderPaths                                 shown_;
    int                                         lock_fd_ = -1; ///< of runs_dir/.kimp-gui.lock
    mutable std::mutex                          mutex_;
    mutable std::condition_variable             changed_;
    std::map<std::string, std::shared_ptr<Run>> runs_;
    std::deque<std::shared_ptr<Run>>            queue_;
    unsigned                                    running_ = 0;
    /// start() calls that took a place and are writing their run's files.
    unsigned reserved_ = 0;
    unsigned counter_  = 0;
    bool     stopping_ = false;
  };

  /// Output of `kimp ARGS...` and its exit code (-1 when it could not be started, timed out
  /// after `timeout_s` and was killed, or died of a signal). `cwd`: its working directory
  /// (empty: this one's). Used for --print-schema and --check. The child dies with the calling
  /// thread (PR_SET_PDEATHSIG).
  struct Captured
  {
    int         exit_code = -1;
    std::string out;
    std::string err;
  };
  Captured capture_kimp(const std::filesystem::path    &kimp,
                        const std::vector<std::string> &arguments,
                        const std::filesystem::path    &cwd       = {},
                        double                          timeout_s = 60.0);
} // namespace kimp::server
