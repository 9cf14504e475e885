// The output directory of a command and the files a run writes into it: atomic writes (temporary
// file, then rename), a lock against a second kimp, the run's output set (all or nothing: a
// failed run removes what it wrote), and the SIGTERM/SIGINT cleanup of temporary files.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace kimp::io
{
  /// Failure to create an output directory or to write a file; names the path and the reason.
  class OutputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// The temporary name of `path` for this process: `<path>.tmp-<pid>`, or with
  /// `keep_extension` `<path>.tmp-<pid><extension of path>` for writers that choose the format
  /// by the extension (gmsh, matplotlib): "mesh/H1.25.msh.tmp-812.msh".
  std::filesystem::path temporary_path(const std::filesystem::path &path,
                                       bool                         keep_extension = false);

  /// Write all `size` bytes of `data` to the file descriptor `fd` (again after EINTR); returns 0
  /// or the errno of the failed write.
  int write_all(int fd, const void *data, std::size_t size);

  /// write_all() and then fsync(fd); returns 0, or the errno of the failed write or sync.
  int write_all_and_sync(int fd, const void *data, std::size_t size);

  /**
   * The temporary file temporary_path(final, keep_extension) of a file being written. It is
   * registered at once for removal by the SIGTERM/SIGINT handler (install_signal_handlers()),
   * removed at destruction unless committed, and commit() renames it to the final name. Nothing
   * is created: the writer creates path() itself.
   */
  class TemporaryFile
  {
  public:
    explicit TemporaryFile(std::filesystem::path final_path, bool keep_extension = false);
    TemporaryFile(TemporaryFile &&other) noexcept;
    TemporaryFile &operator=(TemporaryFile &&) = delete;
    TemporaryFile(const TemporaryFile &)       = delete;
    ~TemporaryFile();

    const std::filesystem::path &path() const { return path_; }
    const std::filesystem::path &final_path() const { return final_path_; }

    /**
     * Rename path() to final_path() and note it as written by this run (note_written()).
     * @throws OutputError naming both files (path() is removed).
     */
    void commit();

    /// Remove path() now (a failed write); never throws.
    void discard() noexcept;

  private:
    std::filesystem::path final_path_;
    std::filesystem::path path_;
    int                   slot_      = -1; ///< of the signal handler's list, or -1
    bool                  committed_ = false;
  };

  /**
   * Write `text` to `<path>.tmp-<pid>` (write, fsync) and rename it to `path`, so readers see
   * either the old file or the complete new one, never a partial file.
   * @throws OutputError (the temporary file is removed).
   */
  void write_text_atomic(const std::filesystem::path &path, std::string_view text);

  /**
   * Note `file`, just renamed into place by this process, as part of the output set of the run
   * of the outermost OutputDir containing it: if that run fails, the file is removed again (see
   * OutputDir). Files outside every OutputDir of this process are not tracked.
   * write_text_atomic(), TemporaryFile::commit() and ResultsFile::commit() call it.
   */
  void note_written(const std::filesystem::path &file);

  /**
   * Keep `file` even if the run fails: a cache meant to survive a failed run (the study's FEM
   * results per height). Undoes note_written().
   */
  void keep_on_failure(const std::filesystem::path &file);

  /**
   * Ignore SIGPIPE (a closed pipe, `kimp ... | head -1`, must not stop a run before it writes
   * its files: writes to the pipe fail quietly instead) and SIGXFSZ (a write beyond the file size
   * limit, `ulimit -f`, fails with EFBIG and is reported like a full disk, with the temporary
   * files and the lock removed) and handle SIGTERM, SIGINT and SIGHUP:
   * the handler removes the temporary files being written, the files of the failed run's output
   * set and the lock files of this process (unlink only: async-signal-safe), then ends the
   * process by the same signal (exit status 128 + signal number in a shell). Call at the start
   * of main() and again after anything that may install its own handlers (MPI initialisation).
   */
  void install_signal_handlers();

  namespace detail
  {
    struct OutputState;
  }

  /**
   * The output directory of a command, created (with parents) on construction and checked
   * before any computation:
   * - it must be writable (a probe file is created and removed), else OutputError at once;
   * - on MPI rank 0 (base::rank()) it is locked for the lifetime of the last OutputDir of this
   *   process naming it: `flock` on `DIR/.kimp.lock`, which holds the owner's pid and is removed
   *   on release. Another process finding the lock taken gets OutputError naming that pid, so
   *   two runs never write into one directory at the same time;
   * - once the lock is taken, every temporary file (temporary_path()) of another process below
   *   it is removed with a warning (remove_stale_temporaries()): the lock proves that no other
   *   kimp writes there;
   * - all or nothing: the files written into it by this process while an OutputDir of it lives
   *   (note_written()) are removed again if the last OutputDir of the directory is destroyed by
   *   an exception (the command failed), unless kept (keep_on_failure()).
   */
  class OutputDir
  {
  public:
    /// @throws OutputError if `path` exists and is not a directory, cannot be created, is not
    /// writable or is locked by another process.
    explicit OutputDir(std::filesystem::path path);
    ~OutputDir();
    OutputDir(const OutputDir &);
    OutputDir &operator=(const OutputDir &);

    const std::filesystem::path &path() const { return path_; }
    /// `path() / name`, creating parent directories of `name` inside path() if needed.
    std::filesystem::path file(const std::filesystem::path &name) const;
    /// The files written so far are a complete result (failed cases recorded in it, charts still
    /// to come): a failure the command reports after this point keeps them.
    void keep_written() const;

  private:
    std::filesystem::path                path_;
    std::shared_ptr<detail::OutputState> state_;
    int                                  uncaught_ = 0; ///< std::uncaught_exceptions() at creation
  };

  /// Name of the lock file inside a locked output directory.
  inline constexpr const char *output_lock_name = ".kimp.lock";

  /**
   * Remove the temporary files `<name>.tmp-<pid>[.<extension>]` below `dir` of any process but
   * this one,
   * except below a sub-directory locked by another kimp (its `.kimp.lock` is held). Call only
   * with the lock of `dir` held.
   * @return the removed files.
   */
  std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path &dir);
} // namespace kimp::io
