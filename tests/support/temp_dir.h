// kimp::testing::TempDir: a fresh directory under the system temporary directory, removed when
// the test ends; and the per-process names that keep concurrently running tests apart.
#pragma once

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace kimp::testing
{
  /**
   * The path kimp_<tag>_<pid> under the system temporary directory, by default with the id of
   * this process: ctest runs every test in its own process, so the process id keeps concurrent
   * tests apart. Nothing is created.
   */
  inline std::filesystem::path process_temp_path(const std::string &tag, int pid = ::getpid())
  {
    return std::filesystem::temp_directory_path() / ("kimp_" + tag + "_" + std::to_string(pid));
  }

  /**
   * A fresh, empty directory, removed with everything in it by the destructor. Its name is
   * process_temp_path(tag) with a counter appended, so that several directories of one process
   * (one test or the tests of a whole executable run at once) never meet.
   */
  class TempDir
  {
  public:
    explicit TempDir(const std::string &tag = "test")
      : path_(process_temp_path(tag).string() + "_" + std::to_string(next_serial()))
    {
      std::filesystem::remove_all(path_);
      std::filesystem::create_directories(path_);
    }
    ~TempDir()
    {
      std::error_code ignored; // a destructor must not throw
      std::filesystem::remove_all(path_, ignored);
    }
    TempDir(const TempDir &)            = delete;
    TempDir &operator=(const TempDir &) = delete;

    /// The directory.
    const std::filesystem::path &path() const { return path_; }

    /// The path of `name` inside the directory (not created).
    std::filesystem::path file(const std::string &name) const { return path_ / name; }

    /// Writes `bytes` unchanged (no line-end translation) to the file `name` inside the
    /// directory and returns its path.
    std::filesystem::path write(const std::string &name, const std::string &bytes) const
    {
      const std::filesystem::path file = path_ / name;
      std::ofstream               out(file, std::ios::binary);
      out << bytes;
      return file;
    }

  private:
    static unsigned int next_serial()
    {
      static std::atomic<unsigned int> serial{0};
      return serial++;
    }

    std::filesystem::path path_;
  };
} // namespace kimp::testing
