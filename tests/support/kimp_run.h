// Helpers shared by the end-to-end tests: a temporary directory, reading a file, and running the
// built `kimp` binary (KIMP_BINARY_DIR "/kimp") with its output captured.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace kimp::e2e
{
  /// A fresh directory, removed at the end of the test.
  class TempDir
  {
  public:
    explicit TempDir(const std::string &tag)
      : path_(std::filesystem::temp_directory_path() /
              ("kimp_" + tag + "_" + std::to_string(::getpid())))
    {
      std::filesystem::remove_all(path_);
      std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    TempDir(const TempDir &)                                = delete;
    TempDir                     &operator=(const TempDir &) = delete;
    const std::filesystem::path &path() const { return path_; }

  private:
    std::filesystem::path path_;
  };

  inline std::string read_text(const std::filesystem::path &file)
  {
    std::ifstream      in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  struct KimpRun
  {
    int         exit_code = -1;
    std::string out; ///< stdout
    std::string err; ///< stderr (the log)
  };

  /// `kimp <arguments>` run in `dir`, stdout and stderr captured to files there.
  inline KimpRun kimp(const std::string &arguments, const std::filesystem::path &dir)
  {
    const std::string command = "cd '" + dir.string() + "' && " KIMP_BINARY_DIR "/kimp " +
                                arguments + " > stdout.txt 2> stderr.txt";
    const int status = std::system(command.c_str());
    KimpRun   run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out       = read_text(dir / "stdout.txt");
    run.err       = read_text(dir / "stderr.txt");
    return run;
  }
} // namespace kimp::e2e
