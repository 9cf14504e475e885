// Atomic writes of summary.json / CSV and the output directory; see summary.h.
#include "io/summary.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

#include "base/logging.h"

namespace kimp::io
{
  namespace
  {
    std::string csv_field(const std::string &field)
    {
      if (field.find_first_of(",\"\r\n") == std::string::npos)
        return field;
      std::string quoted = "\"";
      for (const char c : field)
      {
        if (c == '"')
          quoted += '"';
        quoted += c;
      }
      return quoted + "\"";
    }

    std::string csv_text(const std::filesystem::path                 &path,
                         const std::vector<std::string>              &header,
                         const std::vector<std::vector<std::string>> &rows)
    {
      std::string text;
      const auto  add_row = [&text](const std::vector<std::string> &fields)
      {
        for (std::size_t i = 0; i < fields.size(); ++i)
        {
          if (i > 0)
            text += ',';
          text += csv_field(fields[i]);
        }
        text += '\n';
      };
      add_row(header);
      for (std::size_t r = 0; r < rows.size(); ++r)
      {
        if (rows[r].size() != header.size())
          throw OutputError(fmt::format("{}: CSV row {} has {} fields, the header has {}",
                                        path.string(),
                                        r + 1,
                                        rows[r].size(),
                                        header.size()));
        add_row(rows[r]);
      }
      return text;
    }
  } // namespace

  namespace
  {
    /// Write all of `text` to `fd` and sync it; returns 0 or the errno of the failure.
    int write_all(int fd, std::string_view text)
    {
      std::size_t done = 0;
      while (done < text.size())
      {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0)
        {
          if (errno == EINTR)
            continue;
          return errno;
        }
        done += static_cast<std::size_t>(n);
      }
      return ::fsync(fd) == 0 ? 0 : errno;
    }
  } // namespace

  void write_text_atomic(const std::filesystem::path &path, std::string_view text)
  {
    const std::filesystem::path temporary = path.string() + ".tmp-" + std::to_string(::getpid());
    std::error_code             ignored;
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
      throw OutputError(fmt::format("{}: cannot create '{}' for writing: {}",
                                    path.string(),
                                    temporary.string(),
                                    std::strerror(errno)));
    const int write_error = write_all(fd, text);
    const int close_error = ::close(fd) == 0 ? 0 : errno;
    if (write_error != 0 || close_error != 0)
    {
      std::filesystem::remove(temporary, ignored);
      throw OutputError(fmt::format("{}: writing '{}' failed: {}",
                                    path.string(),
                                    temporary.string(),
                                    std::strerror(write_error != 0 ? write_error : close_error)));
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
    {
      std::filesystem::remove(temporary, ignored);
      throw OutputError(fmt::format("{}: renaming '{}' to it failed: {}",
                                    path.string(),
                                    temporary.string(),
                                    error.message()));
    }
  }

  std::string csv_column(std::string_view name, std::string_view unit)
  {
    std::string column(name);
    if (unit.empty() || unit == "1")
      return column;
    column += '_';
    for (const char c : unit)
    {
      if (c == '/')
        column += "_per_";
      else if (c == '*')
        column += '_';
      else if (c != '^' && c != ' ')
        column += c;
    }
    return column;
  }

  std::string csv_column(std::string_view label)
  {
    const std::size_t open = label.rfind(" [");
    if (open == std::string_view::npos || label.back() != ']')
      return std::string(label);
    return csv_column(label.substr(0, open), label.substr(open + 2, label.size() - open - 3));
  }

  void write_json_atomic(const std::filesystem::path &path, const nlohmann::json &value)
  {
    write_text_atomic(path, value.dump(2) + "\n");
  }

  void write_csv_atomic(const std::filesystem::path                 &path,
                        const std::vector<std::string>              &header,
                        const std::vector<std::vector<std::string>> &rows)
  {
    write_text_atomic(path, csv_text(path, header, rows));
  }

  void write_csv_atomic(const std::filesystem::path            &path,
                        const std::vector<std::string>         &header,
                        const std::vector<std::vector<double>> &rows)
  {
    std::vector<std::vector<std::string>> text_rows;
    text_rows.reserve(rows.size());
    for (const auto &row : rows)
    {
      std::vector<std::string> fields;
      fields.reserve(row.size());
      for (const double v : row)
        fields.push_back(fmt::format("{}", v));
      text_rows.push_back(std::move(fields));
    }
    write_csv_atomic(path, header, text_rows);
  }

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
            return;
          }
          ::close(fd_);
          fd_ = -1;
        }
        throw OutputError(
          fmt::format("output directory '{}': cannot lock '{}'", dir.string(), file_.string()));
      }

      /// The process that took the lock (a forked child inherits the object, not the lock).
      pid_t owner() const { return owner_; }

      ~DirectoryLock()
      {
        if (fd_ < 0 || owner_ != ::getpid())
          return;
        ::unlink(file_.c_str());
        ::close(fd_);
      }

      DirectoryLock(const DirectoryLock &)            = delete;
      DirectoryLock &operator=(const DirectoryLock &) = delete;

    private:
      std::filesystem::path file_;
      int                   fd_    = -1;
      pid_t                 owner_ = ::getpid();
    };
  } // namespace detail

  namespace
  {
    /// The locks this process holds, by canonical directory: several OutputDir objects of one
    /// process may name the same directory (flock would refuse the second open of the file).
    std::shared_ptr<detail::DirectoryLock> lock_directory(const std::filesystem::path &dir)
    {
      static std::mutex                                                  mutex;
      static std::map<std::string, std::weak_ptr<detail::DirectoryLock>> held;
      std::error_code                                                    error;
      std::filesystem::path canonical = std::filesystem::weakly_canonical(dir, error);
      if (error)
        canonical = std::filesystem::absolute(dir);
      const std::lock_guard<std::mutex> guard(mutex);
      if (auto lock = held[canonical.string()].lock(); lock && lock->owner() == ::getpid())
        return lock;
      auto lock                = std::make_shared<detail::DirectoryLock>(dir);
      held[canonical.string()] = lock;
      return lock;
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

    /// The pid of a temporary file name `<name>.tmp-<pid>`, or 0.
    long temporary_owner(const std::string &name)
    {
      const std::size_t at = name.rfind(".tmp-");
      if (at == std::string::npos || at + 5 >= name.size() || name.size() - at > 5 + 9)
        return 0;
      long pid = 0;
      for (std::size_t i = at + 5; i < name.size(); ++i)
      {
        if (name[i] < '0' || name[i] > '9')
          return 0;
        pid = pid * 10 + (name[i] - '0');
      }
      return pid;
    }
  } // namespace

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
      const long pid = temporary_owner(it->path().filename().string());
      if (pid <= 0 || pid == static_cast<long>(::getpid()) || !it->is_regular_file(error))
        continue;
      if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
        stale.push_back(it->path());
    }
    std::vector<fs::path> removed;
    for (const fs::path &file : stale)
      if (fs::remove(file, error))
        removed.push_back(file);
    return removed;
  }

  OutputDir::OutputDir(std::filesystem::path path)
    : path_(std::move(path))
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
    // Under MPI the ranks of one job share the directory: rank 0 holds the lock for them.
    if (base::rank() != 0)
      return;
    lock_ = lock_directory(path_);
    for (const std::filesystem::path &file : remove_stale_temporaries(path_))
      base::logger().warn("removed '{}', a temporary file left by a kimp run that ended before "
                          "finishing it",
                          file.string());
  }

  OutputDir::~OutputDir()                            = default;
  OutputDir::OutputDir(const OutputDir &)            = default;
  OutputDir &OutputDir::operator=(const OutputDir &) = default;

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
} // namespace kimp::io
