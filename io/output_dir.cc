// The output directory, atomic writes, the run's output set and the signal cleanup; see
// output_dir.h.
#include "io/output_dir.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <string>
#include <sys/file.h>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>
#include <utility>

#include "base/logging.h"

namespace kimp::io
{
  namespace
  {
    // ---- Paths the SIGTERM/SIGINT handler unlinks ---------------------------------------------
    // A fixed table of C strings read by the handler with lock-free atomic loads (async-signal-
    // safe). A string is never freed: a handler running on another thread may still read it, so
    // a cleared slot's string stays allocated (a run registers a few hundred paths at most).

    constexpr std::size_t                                    max_cleanup_paths = 2048;
    std::array<std::atomic<const char *>, max_cleanup_paths> cleanup_paths{};

    /// Register `path` for the handler; returns its slot, or -1 when the table is full.
    int register_cleanup(const std::filesystem::path &path)
    {
      const std::string &text = path.native();
      char              *copy = new char[text.size() + 1]; // never freed, see above
      std::memcpy(copy, text.c_str(), text.size() + 1);
      for (std::size_t i = 0; i < cleanup_paths.size(); ++i)
      {
        const char *expected = nullptr;
        if (cleanup_paths[i].compare_exchange_strong(expected, copy))
          return static_cast<int>(i);
      }
      return -1;
    }

    void unregister_cleanup(int &slot)
    {
      if (slot >= 0)
        cleanup_paths[static_cast<std::size_t>(slot)].store(nullptr);
      slot = -1;
    }

    extern "C" void on_termination_signal(int signal_number)
    {
      for (const std::atomic<const char *> &slot : cleanup_paths)
        if (const char *path = slot.load())
          ::unlink(path);
      // The signal is blocked while its handler runs: re-raised with the default action, it ends
      // the process as soon as the handler returns, with the usual status of that signal.
      ::signal(signal_number, SIG_DFL);
      ::raise(signal_number);
    }

    std::filesystem::path canonical_or_absolute(const std::filesystem::path &path)
    {
      std::error_code       error;
      std::filesystem::path canonical = std::filesystem::weakly_canonical(path, error);
      return error ? std::filesystem::absolute(path) : canonical;
    }

    /// Whether `path` lies inside `dir` (both canonical), or is it.
    bool is_inside(const std::filesystem::path &path, const std::filesystem::path &dir)
    {
      auto p = path.begin();
      for (auto d = dir.begin(); d != dir.end(); ++d, ++p)
      {
        if (d->empty() && std::next(d) == dir.end()) // a trailing separator
          break;
        if (p == path.end() || *p != *d)
          return false;
      }
      return true;
    }
  } // namespace

  // ---- Temporary files and atomic writes ------------------------------------------------------

  std::filesystem::path temporary_path(const std::filesystem::path &path, bool keep_extension)
  {
    return path.string() + ".tmp-" + std::to_string(::getpid()) +
           (keep_extension ? path.extension().string() : std::string());
  }

  TemporaryFile::TemporaryFile(std::filesystem::path final_path, bool keep_extension)
    : final_path_(std::move(final_path))
    , path_(temporary_path(final_path_, keep_extension))
    , slot_(register_cleanup(path_))
  {
  }

  TemporaryFile::TemporaryFile(TemporaryFile &&other) noexcept
    : final_path_(std::move(other.final_path_))
    , path_(std::move(other.path_))
    , slot_(std::exchange(other.slot_, -1))
    , committed_(std::exchange(other.committed_, true))
  {
  }

  TemporaryFile::~TemporaryFile()
  {
    if (!committed_)
      discard();
  }

  void TemporaryFile::discard() noexcept
  {
    if (!path_.empty())
      ::unlink(path_.c_str());
    unregister_cleanup(slot_);
  }

  void TemporaryFile::commit()
  {
    // Noted before the rename, so that a signal between the two cannot leave the new file.
    note_written(final_path_);
    std::error_code error;
    std::filesystem::rename(path_, final_path_, error);
    if (error)
    {
      keep_on_failure(final_path_); // not written: nothing of this run to remove
      discard();
      throw OutputError(fmt::format("{}: renaming '{}' to it failed: {}",
                                    final_path_.string(),
                                    path_.string(),
                                    error.message()));
    }
    committed_ = true;
    unregister_cleanup(slot_);
  }

  int write_all(const int fd, const void *data, const std::size_t size)
  {
    const auto *bytes = static_cast<const char *>(data);
    std::size_t done  = 0;
    while (done < size)
    {
      const ssize_t n = ::write(fd, bytes + done, size - done);
      if (n < 0)
      {
        if (errno == EINTR)
          continue;
        return errno;
      }
      done += static_cast<std::size_t>(n);
    }
    return 0;
  }

  int write_all_and_sync(const int fd, const void *data, const std::size_t size)
  {
    if (const int error = write_all(fd, data, size); error != 0)
      return error;
    return ::fsync(fd) == 0 ? 0 : errno;
  }

  void write_text_atomic(const std::filesystem::path &path, std::string_view text)
  {
    TemporaryFile temporary(path);
    const int fd = ::open(temporary.path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
      throw OutputError(fmt::format("{}: cannot create '{}' for writing: {}",
                                    path.string(),
                                    temporary.path().string(),
                                    std::strerror(errno)));
    const int write_error = write_all_and_sync(fd, text.data(), text.size());
    const int close_error = ::close(fd) == 0 ? 0 : errno;
    if (write_error != 0 || close_error != 0)
      throw OutputError(fmt::format("{}: writing '{}' failed: {}",
                                    path.string(),
                                    temporary.path().string(),
                                    std::strerror(write_error != 0 ? write_error : close_error)));
    temporary.commit();
  }

  // ---- The directory lock ---------------------------------------------------------------------

  namespace detail
  {
    /// An exclusive `flock` on `<dir>/.kimp.lock`, released (file removed) at destruction.
    class DirectoryLock
    {
    public:
      explicit DirectoryLock(const std::filesystem::path &dir)
        : file_(dir / output_lock_name)
      {
        // The holder removes the file on release: a process that opened the old file just
        // before must not keep a lock on the removed one, hence the check of the inode.
        for (int attempt = 0; attempt < 100; ++attempt)
        {
          fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
          if (fd_ < 0)
            throw OutputError(fmt::format("output directory '{}': cannot create the lock file "
                                          "'{}': {}",
                                          dir.string(),
                                          file_.string(),
                                          std::strerror(errno)));
          if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
          {
            const int   error = errno;
            std::string owner(32, '\0');
            const auto  n = ::pread(fd_, owner.data(), owner.size() - 1, 0);
            owner.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
            while (!owner.empty() && (owner.back() == '\n' || owner.back() == ' '))
              owner.pop_back();
            ::close(fd_);
            fd_ = -1;
            if (error == EWOULDBLOCK)
              throw OutputError(fmt::format(
                "output directory '{}' is in use by another kimp{}; wait for it to finish or "
                "choose another output directory",
                dir.string(),
                owner.empty() ? std::string() : " (pid " + owner + ")"));
            throw OutputError(fmt::format("output directory '{}': cannot lock '{}': {}",
                                          dir.string(),
                                          file_.string(),
                                          std::strerror(error)));
          }
          struct stat held
          {
          }, named{};
          if (::fstat(fd_, &held) == 0 && ::stat(file_.c_str(), &named) == 0 &&
              held.st_ino == named.st_ino && held.st_dev == named.st_dev)
          {
            const std::string pid = std::to_string(::getpid()) + "\n";
            if (::ftruncate(fd_, 0) == 0) [[maybe_unused]]
              const auto written = ::pwrite(fd_, pid.data(), pid.size(), 0);
            slot_ = register_cleanup(file_);
            return;
          }
          ::close(fd_);
          fd_ = -1;
        }
        throw OutputError(
          fmt::format("output directory '{}': cannot lock '{}'", dir.string(), file_.string()));
      }

      ~DirectoryLock()
      {
        if (fd_ < 0 || owner_ != ::getpid())
          return;
        unregister_cleanup(slot_);
        ::unlink(file_.c_str());
        ::close(fd_);
      }

      DirectoryLock(const DirectoryLock &)            = delete;
      DirectoryLock &operator=(const DirectoryLock &) = delete;

    private:
      std::filesystem::path file_;
      int                   fd_   = -1;
      int                   slot_ = -1;
      pid_t owner_ = ::getpid(); ///< a forked child inherits the object, not the lock
    };

    /// What the OutputDir objects of one directory share in this process: the lock and the
    /// files written by this run.
    struct OutputState
    {
      struct Written
      {
        std::filesystem::path file;
        int                   slot = -1;
      };

      explicit OutputState(std::filesystem::path canonical_dir)
        : canonical(std::move(canonical_dir))
      {
      }
      OutputState(const OutputState &)            = delete;
      OutputState &operator=(const OutputState &) = delete;

      ~OutputState()
      {
        if (owner != ::getpid())
          return;
        std::size_t removed = 0;
        for (Written &w : written)
        {
          if (failed && ::unlink(w.file.c_str()) == 0)
            ++removed;
          unregister_cleanup(w.slot);
        }
        if (removed > 0)
          base::logger().info("removed the {} file(s) this failed run had written into '{}'",
                              removed,
                              canonical.string());
      }

      std::filesystem::path          canonical;
      std::unique_ptr<DirectoryLock> lock; ///< rank 0 only; destroyed after the files are removed
      std::vector<Written>           written;
      bool                           failed = false;
      pid_t                          owner  = ::getpid();
    };
  } // namespace detail

  namespace
  {
    std::mutex &states_mutex()
    {
      static std::mutex mutex;
      return mutex;
    }

    /// The live output directories of this process, by canonical path (guarded by
    /// states_mutex()).
    std::map<std::string, std::weak_ptr<detail::OutputState>> &states()
    {
      static std::map<std::string, std::weak_ptr<detail::OutputState>> map;
      return map;
    }

    /// The outermost live output directory of this process containing `file` (caller holds
    /// states_mutex()), or null.
    std::shared_ptr<detail::OutputState> owning_state(const std::filesystem::path &file)
    {
      const std::filesystem::path          canonical = canonical_or_absolute(file);
      std::shared_ptr<detail::OutputState> owner;
      for (const auto &[name, weak] : states())
        if (auto state = weak.lock(); state && state->owner == ::getpid() &&
                                      is_inside(canonical, state->canonical) &&
                                      (!owner || is_inside(owner->canonical, state->canonical)))
          owner = std::move(state);
      return owner;
    }

    /// Fails at once if files cannot be created in `dir` (read-only directory or file system,
    /// missing permission), rather than after the computation.
    void check_writable(const std::filesystem::path &dir)
    {
      const std::filesystem::path probe =
        dir / (std::string(".kimp.probe.tmp-") + std::to_string(::getpid()));
      const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (fd < 0)
        throw OutputError(fmt::format("output directory '{}' is not writable: {}",
                                      dir.string(),
                                      std::strerror(errno)));
      ::close(fd);
      ::unlink(probe.c_str());
    }

    /// The pid of a temporary file name `<name>.tmp-<pid>` or `<name>.tmp-<pid>.<extension>`
    /// (temporary_path()), or 0.
    long temporary_owner(const std::string &name)
    {
      const std::size_t at = name.rfind(".tmp-");
      if (at == std::string::npos)
        return 0;
      std::size_t end = name.find('.', at + 5);
      if (end == std::string::npos)
        end = name.size();
      else if (name.find('.', end + 1) != std::string::npos || end + 1 == name.size())
        return 0; // at most one extension after the pid
      if (end == at + 5 || end - (at + 5) > 9)
        return 0;
      long pid = 0;
      for (std::size_t i = at + 5; i < end; ++i)
      {
        if (name[i] < '0' || name[i] > '9')
          return 0;
        pid = pid * 10 + (name[i] - '0');
      }
      return pid;
    }

    /// Whether `dir` holds a lock file that another open file description holds (another kimp,
    /// or another OutputDir of this process, writes there).
    bool locked_by_another(const std::filesystem::path &dir)
    {
      const std::filesystem::path lock = dir / output_lock_name;
      const int                   fd   = ::open(lock.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0)
        return false;
      const bool locked = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
      ::close(fd);
      return locked;
    }
  } // namespace

  void note_written(const std::filesystem::path &file)
  {
    const std::lock_guard<std::mutex> guard(states_mutex());
    if (const auto state = owning_state(file))
    {
      for (const auto &w : state->written)
        if (w.file == file)
          return;
      state->written.push_back({file, register_cleanup(file)});
    }
  }

  void keep_on_failure(const std::filesystem::path &file)
  {
    const std::lock_guard<std::mutex> guard(states_mutex());
    if (const auto state = owning_state(file))
    {
      auto &written = state->written;
      for (auto w = written.begin(); w != written.end(); ++w)
        if (w->file == file)
        {
          unregister_cleanup(w->slot);
          written.erase(w);
          return;
        }
    }
  }

  std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path &dir)
  {
    namespace fs = std::filesystem;
    std::vector<fs::path> stale;
    std::error_code       error;
    for (fs::recursive_directory_iterator
           it(dir, fs::directory_options::skip_permission_denied, error),
         end;
         !error && it != end;
         it.increment(error))
    {
      if (it->is_directory(error))
      {
        // Another kimp's output directory below this one: its temporaries are its own.
        if (locked_by_another(it->path()))
          it.disable_recursion_pending();
        continue;
      }
      const long pid = temporary_owner(it->path().filename().string());
      if (pid > 0 && pid != static_cast<long>(::getpid()) && it->is_regular_file(error))
        stale.push_back(it->path());
    }
    std::vector<fs::path> removed;
    for (const fs::path &file : stale)
      if (fs::remove(file, error))
        removed.push_back(file);
    return removed;
  }

  // ---- OutputDir ------------------------------------------------------------------------------

  OutputDir::OutputDir(std::filesystem::path path)
    : path_(std::move(path))
    , uncaught_(std::uncaught_exceptions())
  {
    std::error_code error;
    if (std::filesystem::exists(path_, error) && !std::filesystem::is_directory(path_, error))
      throw OutputError(
        fmt::format("output directory '{}' exists and is not a directory", path_.string()));
    std::filesystem::create_directories(path_, error);
    if (error)
      throw OutputError(
        fmt::format("cannot create output directory '{}': {}", path_.string(), error.message()));
    check_writable(path_);

    const std::filesystem::path       canonical = canonical_or_absolute(path_);
    const std::lock_guard<std::mutex> guard(states_mutex());
    auto                             &map = states();
    for (auto it = map.begin(); it != map.end();)
      it = it->second.expired() ? map.erase(it) : std::next(it);
    if (auto state = map[canonical.string()].lock(); state && state->owner == ::getpid())
    {
      state_ = std::move(state);
      return;
    }
    auto state = std::make_shared<detail::OutputState>(canonical);
    // Under MPI the ranks of one job share the directory: rank 0 holds the lock for them.
    if (base::rank() == 0)
    {
      state->lock = std::make_unique<detail::DirectoryLock>(path_);
      for (const std::filesystem::path &file : remove_stale_temporaries(path_))
        base::logger().warn("removed '{}', a temporary file left by a kimp run that did not "
                            "finish",
                            file.string());
    }
    map[canonical.string()] = state;
    state_                  = std::move(state);
  }

  OutputDir::~OutputDir()
  {
    // The last OutputDir of the directory going while an exception unwinds: the command failed.
    if (state_ && state_.use_count() == 1 && std::uncaught_exceptions() > uncaught_)
      state_->failed = true;
  }

  OutputDir::OutputDir(const OutputDir &other)
    : path_(other.path_)
    , state_(other.state_)
    , uncaught_(std::uncaught_exceptions())
  {
  }

  OutputDir &OutputDir::operator=(const OutputDir &other)
  {
    if (this != &other)
    {
      OutputDir copy(other);
      std::swap(path_, copy.path_);
      std::swap(state_, copy.state_);
    }
    return *this;
  }

  void OutputDir::keep_written() const
  {
    if (!state_)
      return;
    const std::lock_guard<std::mutex> guard(states_mutex());
    for (auto &w : state_->written)
      unregister_cleanup(w.slot);
    state_->written.clear();
  }

  std::filesystem::path OutputDir::file(const std::filesystem::path &name) const
  {
    const std::filesystem::path full = path_ / name;
    if (full.has_parent_path() && full.parent_path() != path_)
    {
      std::error_code error;
      std::filesystem::create_directories(full.parent_path(), error);
      if (error)
        throw OutputError(fmt::format("cannot create directory '{}': {}",
                                      full.parent_path().string(),
                                      error.message()));
    }
    return full;
  }

  // ---- Signals --------------------------------------------------------------------------------

  void install_signal_handlers()
  {
    ::signal(SIGPIPE, SIG_IGN);
    // A write beyond the file size limit (`ulimit -f`) then fails with EFBIG, reported and
    // cleaned up as a full disk, instead of killing the process with its files half written.
    ::signal(SIGXFSZ, SIG_IGN);
    // A signal ignored when the process started stays ignored (nohup, `&` in a script).
    static const std::array<int, 3>  handled{SIGTERM, SIGINT, SIGHUP};
    static const std::array<bool, 3> ignored_at_start = []
    {
      std::array<bool, 3> ignored{};
      for (std::size_t i = 0; i < handled.size(); ++i)
      {
        struct sigaction current
        {
        };
        ignored[i] =
          ::sigaction(handled[i], nullptr, &current) == 0 && current.sa_handler == SIG_IGN;
      }
      return ignored;
    }();
    sigset_t unblock;
    sigemptyset(&unblock);
    for (std::size_t i = 0; i < handled.size(); ++i)
    {
      if (ignored_at_start[i])
        continue;
      struct sigaction action
      {
      };
      action.sa_handler = on_termination_signal;
      sigemptyset(&action.sa_mask);
      action.sa_flags = 0;
      ::sigaction(handled[i], &action, nullptr);
      sigaddset(&unblock, handled[i]);
    }
    // A parent that blocked them (a server waiting for them with sigwait) passes the mask on.
    ::sigprocmask(SIG_UNBLOCK, &unblock, nullptr);
  }
} // namespace kimp::io
