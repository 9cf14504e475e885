// How `kimp gui` starts its background runs (server::RunManager) and how many at a time; the
// options of `kimp gui` (server::GuiOptions) include them.
#pragma once

#include <filesystem>
#include <optional>

namespace kimp::server
{
  /// How runs are started and how many at a time.
  struct RunSettings
  {
    /// Directory of the runs (one sub-directory per run; created).
    std::filesystem::path runs_dir = "kimp-runs";
    /// The kimp executable that runs are started with.
    std::filesystem::path kimp_executable;
    /// The PEER records directory, if any (records list and plots of `kimp gui`), passed to every
    /// run (as KIMP_RECORDS_DIR): a bare record name in a scene is looked up there unless the
    /// scene names its own records_dir.
    std::optional<std::filesystem::path> records_dir;
    /// Runs at a time (at least 1); more wait in the queue, state "queued".
    unsigned max_runs = 2;
    /// Runs waiting at most; a further start is refused (RunQueueFull).
    unsigned max_queued = 16;
    /// Seconds between SIGTERM and SIGKILL when a run is cancelled or the server stops.
    double kill_grace = 1.0;
  };
} // namespace kimp::server
