// The one kimp logger (spdlog, on stderr) with three verbosity levels, and the progress line of
// long runs ("step N/M  t = x s  ETA y s"), shown only on a terminal.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <spdlog/logger.h>

namespace kimp::base
{
  /// -q: warnings and errors only; default: info; -v: debug; -vv: trace.
  enum class Verbosity
  {
    quiet,
    normal,
    verbose,
    trace
  };

  /// The process-wide logger "kimp", writing "level: message" lines to stderr.
  spdlog::logger &logger();

  /// Set the logger level (and whether Progress lines are shown by default).
  void      set_verbosity(Verbosity verbosity);
  Verbosity verbosity();

  /// MPI rank of this process: only rank 0 logs (except errors) and shows progress.
  void set_rank(int rank);
  /// The rank given to set_rank() (0 without MPI).
  int rank();

  /// True if stderr is a terminal (progress lines are then worth printing).
  bool stderr_is_terminal();

  /**
   * Progress line "step N/M  t = x s  ETA y s", rewritten in place ('\r') at most every
   * `min_interval` (default 0.25 s, ~4 lines per second), and ended with a newline by finish().
   * Silent when disabled: by default enabled only if stderr is a terminal and verbosity is not
   * quiet, so logs and CI output stay clean.
   */
  class Progress
  {
  public:
    using Clock = std::function<std::chrono::steady_clock::time_point()>;

    /// Progress on stderr, enabled on a terminal unless quiet or not on rank 0.
    /// @param[in] total_steps number of steps M, or 0 if unknown (the line then shows the
    /// simulated time only, and the ETA comes from t / end_time); @param[in] end_time simulated
    /// end time, s
    Progress(std::uint64_t total_steps, double end_time);
    /// Progress on `out`, explicitly enabled or not, with an injectable clock (tests).
    Progress(std::uint64_t total_steps,
             double        end_time,
             std::ostream &out,
             bool          enabled,
             Clock         clock        = std::chrono::steady_clock::now,
             double        min_interval = 0.25);
    Progress(const Progress &) = delete;
    ~Progress();

    /// Report that step `step` (1-based count of completed steps) reached simulated time `time`
    /// (s).
    void update(std::uint64_t step, double time);
    /// Print the last state and end the line, if a line was shown (once; also done by the
    /// destructor).
    void finish();

    bool enabled() const { return enabled_; }

  private:
    void print(std::uint64_t step, double time);

    std::uint64_t                         total_steps_;
    double                                end_time_;
    std::ostream                         *out_;
    bool                                  enabled_;
    Clock                                 clock_;
    double                                min_interval_;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_print_;
    bool                                  printed_   = false;
    bool                                  finished_  = false;
    std::uint64_t                         last_step_ = 0;
    double                                last_time_ = 0.0;
  };
} // namespace kimp::base
