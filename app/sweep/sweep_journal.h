// Crash-safe record of finished sweep cases: one JSON line per case appended to
// DIR/journal/rank-<r>.jsonl with write + fsync; a torn last line (kill, power loss) is ignored.
#pragma once

#include <filesystem>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace kimp::app
{
  /// What a runner returns for one case: named metrics (a unit may follow the name in brackets,
  /// "max_impact_velocity [m/s]") and "ok" or "failed: <reason>".
  struct CaseRow
  {
    std::vector<std::pair<std::string, double>> metrics;
    std::string                                 status = "ok";
  };

  /// One finished case as stored in a journal line.
  struct JournalEntry
  {
    std::size_t index = 0;
    std::string id;
    CaseRow     row;
    double      wall_time = 0.0; ///< s
    int         rank      = 0;
  };

  /// Result of reading all journals of a sweep directory.
  struct JournalContents
  {
    std::vector<JournalEntry> entries;          ///< in file order, journals by name
    std::size_t               n_torn_lines = 0; ///< incomplete or unreadable lines skipped
  };

  /**
   * Appends entries to one journal file. Thread-safe: append() takes a mutex; each line is
   * written with one write loop and made durable with fsync before append() returns.
   */
  class SweepJournal
  {
  public:
    /// Open (create) `file` for appending. If the file ends in a torn line, a newline is added
    /// first so that the next entry starts on a line of its own.
    /// @throws OutputError naming the file.
    explicit SweepJournal(std::filesystem::path file);
    SweepJournal(const SweepJournal &)            = delete;
    SweepJournal &operator=(const SweepJournal &) = delete;
    ~SweepJournal();

    /// Append `entry` as one JSON line and fsync. @throws OutputError on a write failure.
    void append(const JournalEntry &entry);

    const std::filesystem::path &file() const { return file_; }

    /// "DIR/journal/rank-<rank>.jsonl".
    static std::filesystem::path file_of(const std::filesystem::path &dir, int rank);

    /// Every complete entry of every DIR/journal/*.jsonl (missing directory: none).
    static JournalContents read_all(const std::filesystem::path &dir);

    /// The JSON line (without newline) of `entry`; NaN metrics are written as null.
    static std::string to_line(const JournalEntry &entry);
    /// Parse one line; false if it is not a complete entry.
    static bool from_line(const std::string &line, JournalEntry &entry);

  private:
    std::filesystem::path file_;
    int                   fd_ = -1;
    std::mutex            mutex_;
  };
} // namespace kimp::app
