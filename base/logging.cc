// kimp logger and progress line; see logging.h. With KIMP_PROGRESS=lines in the environment (set by
// `kimp gui` for its runs) an enabled Progress writes whole machine-readable lines instead,
// "progress: 0.2500 step 1/4  t = 1/4 s  ETA 3 s" (the fraction done first), at most one a second,
// and the default Progress is enabled whatever stderr is.
#include "base/logging.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <unistd.h>

namespace kimp::base
{
  namespace
  {
    Verbosity current_verbosity = Verbosity::normal;
    int       current_rank      = 0;

    /// Whether KIMP_PROGRESS is "lines" (machine-readable progress lines for `kimp gui`).
    bool progress_lines()
    {
      const char *value = std::getenv("KIMP_PROGRESS");
      return value != nullptr && std::strcmp(value, "lines") == 0;
    }

    std::shared_ptr<spdlog::logger> make_logger()
    {
      auto sink   = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
      auto logger = std::make_shared<spdlog::logger>("kimp", sink);
      logger->set_pattern("%^%l%$: %v");
      logger->set_level(spdlog::level::info);
      return logger;
    }
  } // namespace

  spdlog::logger &logger()
  {
    static const std::shared_ptr<spdlog::logger> instance = make_logger();
    return *instance;
  }

  void set_verbosity(Verbosity verbosity)
  {
    // The level of each Verbosity, in the order of its enumerators.
    constexpr std::array<spdlog::level::level_enum, 4> levels{spdlog::level::warn,
                                                              spdlog::level::info,
                                                              spdlog::level::debug,
                                                              spdlog::level::trace};
    current_verbosity = verbosity;
    logger().set_level(current_rank != 0 ? spdlog::level::err :
                                           levels.at(static_cast<std::size_t>(verbosity)));
  }

  void set_rank(int rank)
  {
    current_rank = rank;
    set_verbosity(current_verbosity);
  }

  int rank()
  {
    return current_rank;
  }

  Verbosity verbosity()
  {
    return current_verbosity;
  }

  bool stderr_is_terminal()
  {
    return ::isatty(STDERR_FILENO) == 1;
  }

  Progress::Progress(std::uint64_t total_steps, double end_time)
    : Progress(total_steps,
               end_time,
               std::cerr,
               current_rank == 0 &&
                 (progress_lines() || (stderr_is_terminal() && verbosity() != Verbosity::quiet)),
               std::chrono::steady_clock::now,
               progress_lines() ? 1.0 : 0.25)
  {
  }

  Progress::Progress(std::uint64_t total_steps,
                     double        end_time,
                     std::ostream &out,
                     bool          enabled,
                     Clock         clock,
                     double        min_interval)
    : total_steps_(total_steps)
    , end_time_(end_time)
    , out_(&out)
    , enabled_(enabled)
    , clock_(std::move(clock))
    , min_interval_(min_interval)
    , start_(clock_())
    , last_print_(start_)
  {
  }

  Progress::~Progress()
  {
    finish();
  }

  void Progress::update(std::uint64_t step, double time)
  {
    last_step_ = step;
    last_time_ = time;
    if (!enabled_ || finished_)
      return;
    const auto   now   = clock_();
    const double since = std::chrono::duration<double>(now - last_print_).count();
    if (printed_ && since < min_interval_)
      return;
    last_print_ = now;
    print(step, time);
  }

  void Progress::finish()
  {
    if (finished_)
      return;
    finished_ = true;
    if (!enabled_ || !printed_)
      return;
    print(last_step_, last_time_);
    if (!progress_lines())
      *out_ << '\n' << std::flush;
  }

  void Progress::print(std::uint64_t step, double time)
  {
    const double elapsed = std::chrono::duration<double>(clock_() - start_).count();
    // Fraction done: by steps when their number is known, else by simulated time.
    const double done = total_steps_ > 0 ?
                          static_cast<double>(step) / static_cast<double>(total_steps_) :
                          (end_time_ > 0 ? time / end_time_ : 0.0);
    std::string  eta  = "--";
    if (done > 0 && done <= 1)
      eta = fmt::format("{:.0f} s", elapsed * (1 - done) / done);
    // Trailing spaces wipe the remains of a longer previous line.
    const std::string steps =
      total_steps_ > 0 ? fmt::format("step {}/{}  ", step, total_steps_) : std::string();
    if (progress_lines())
      *out_ << fmt::format("progress: {:.4f} {}t = {:.4g}/{:.4g} s  ETA {}\n",
                           std::clamp(done, 0.0, 1.0),
                           steps,
                           time,
                           end_time_,
                           eta)
            << std::flush;
    else
      *out_ << fmt::format("\r{}t = {:.4g}/{:.4g} s  ETA {}    ", steps, time, end_time_, eta)
            << std::flush;
    printed_ = true;
  }
} // namespace kimp::base
