// Journal of finished sweep cases (resume without recomputation or lost rows).
// POSIX write + fsync: once append() returns, the line survives a SIGKILL or a power loss.
#include "app/sweep/sweep_journal.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include "io/output_dir.h"
#include "io/summary.h"

namespace kimp::app
{
  using namespace kimp::io;
  namespace
  {
    std::string errno_text()
    {
      return std::strerror(errno);
    }

    void append_text(int fd, const std::string &text, const std::filesystem::path &file)
    {
      if (const int error = io::write_all(fd, text.data(), text.size()); error != 0)
        throw OutputError("cannot append to sweep journal " + file.string() + ": " +
                          std::strerror(error));
    }
  } // namespace

  SweepJournal::SweepJournal(std::filesystem::path file)
    : file_(std::move(file))
  {
    std::error_code error;
    std::filesystem::create_directories(file_.parent_path(), error);
    if (error)
      throw OutputError("cannot create directory " + file_.parent_path().string() + ": " +
                        error.message());
    fd_ = ::open(file_.c_str(), O_RDWR | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw OutputError("cannot open sweep journal " + file_.string() + ": " + errno_text());
    const off_t size = ::lseek(fd_, 0, SEEK_END);
    if (size > 0)
    {
      char last = '\n';
      if (::pread(fd_, &last, 1, size - 1) == 1 && last != '\n')
        append_text(fd_, "\n", file_);
    }
  }

  SweepJournal::~SweepJournal()
  {
    if (fd_ < 0)
      return;
    // A journal that never got a line (the sweep failed first, a full disk) is not left behind.
    struct stat status
    {
    };
    const bool empty = ::fstat(fd_, &status) == 0 && status.st_size == 0;
    ::close(fd_);
    if (empty)
    {
      std::error_code ignored;
      std::filesystem::remove(file_, ignored);
      std::filesystem::remove(file_.parent_path(), ignored); // only if empty
    }
  }

  void SweepJournal::append(const JournalEntry &entry)
  {
    const std::string                 line = to_line(entry) + "\n";
    const std::lock_guard<std::mutex> lock(mutex_);
    const off_t                       before = ::lseek(fd_, 0, SEEK_END);
    try
    {
      append_text(fd_, line, file_);
      if (::fsync(fd_) != 0)
        throw OutputError("cannot fsync sweep journal " + file_.string() + ": " + errno_text());
    }
    catch (const OutputError &)
    {
      // No torn line from a full disk: the journal stays as it was (and an empty one is removed
      // at destruction).
      if (before >= 0 && ::ftruncate(fd_, before) != 0)
        errno = 0;
      throw;
    }
  }

  std::filesystem::path SweepJournal::file_of(const std::filesystem::path &dir, int rank)
  {
    return dir / "journal" / ("rank-" + std::to_string(rank) + ".jsonl");
  }

  std::string SweepJournal::to_line(const JournalEntry &entry)
  {
    nlohmann::ordered_json json;
    json["index"]                  = entry.index;
    json["id"]                     = entry.id;
    json["status"]                 = entry.row.status;
    json["wall_time"]              = entry.wall_time;
    json["rank"]                   = entry.rank;
    nlohmann::ordered_json metrics = nlohmann::ordered_json::array();
    for (const auto &[name, value] : entry.row.metrics)
    {
      if (std::isfinite(value))
        metrics.push_back({name, value});
      else
        metrics.push_back({name, nullptr});
    }
    json["metrics"] = std::move(metrics);
    // Replace invalid UTF-8 in exception texts rather than failing to record the case.
    return json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  }

  bool SweepJournal::from_line(const std::string &line, JournalEntry &entry)
  {
    const nlohmann::json json = nlohmann::json::parse(line, nullptr, false);
    if (json.is_discarded() || !json.is_object())
      return false;
    try
    {
      JournalEntry e;
      e.index      = json.at("index").get<std::size_t>();
      e.id         = json.at("id").get<std::string>();
      e.row.status = json.at("status").get<std::string>();
      e.wall_time  = json.at("wall_time").get<double>();
      e.rank       = json.at("rank").get<int>();
      for (const auto &metric : json.at("metrics"))
      {
        const auto  &value = metric.at(1);
        const double v =
          value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>();
        e.row.metrics.emplace_back(metric.at(0).get<std::string>(), v);
      }
      entry = std::move(e);
      return true;
    }
    catch (const nlohmann::json::exception &)
    {
      return false;
    }
  }

  JournalContents SweepJournal::read_all(const std::filesystem::path &dir)
  {
    JournalContents             contents;
    const std::filesystem::path journal_dir = dir / "journal";
    std::error_code             error;
    if (!std::filesystem::is_directory(journal_dir, error))
      return contents;
    std::vector<std::filesystem::path> files;
    for (const auto &item : std::filesystem::directory_iterator(journal_dir))
      if (item.path().extension() == ".jsonl")
        files.push_back(item.path());
    std::sort(files.begin(), files.end());
    for (const std::filesystem::path &file : files)
    {
      if (!std::filesystem::is_regular_file(file, error))
        throw OutputError("cannot read sweep journal " + file.string() +
                          ": not a regular file (remove it, or choose another output directory)");
      std::string text;
      try
      {
        std::ifstream in(file, std::ios::binary);
        if (!in)
          throw OutputError("cannot open");
        text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
      catch (const std::exception &failure)
      {
        throw OutputError("cannot read sweep journal " + file.string() + ": " + failure.what());
      }
      std::size_t begin = 0;
      while (begin < text.size())
      {
        const std::size_t end = text.find('\n', begin);
        // A line without its newline was cut short by a crash: never trust it.
        if (end == std::string::npos)
        {
          ++contents.n_torn_lines;
          break;
        }
        const std::string line = text.substr(begin, end - begin);
        begin                  = end + 1;
        if (line.empty())
          continue;
        JournalEntry entry;
        if (from_line(line, entry))
          contents.entries.push_back(std::move(entry));
        else
          ++contents.n_torn_lines;
      }
    }
    return contents;
  }
} // namespace kimp::app
