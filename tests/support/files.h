// kimp::testing file helpers: the source tree, a whole file as text, as lines or as JSON,
// writing a file in one call, the files below a directory, and waiting for a file to appear.
#pragma once

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace kimp::testing
{
  /// The source tree: $KIMP_SOURCE_DIR (ctest sets it) or else the current directory (ctest runs
  /// the tests in the source tree).
  inline std::filesystem::path source_dir()
  {
    const char *dir = std::getenv("KIMP_SOURCE_DIR");
    return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::current_path();
  }

  /// The bytes of `file` ("" if it cannot be read, so that a failure message can print it).
  inline std::string read_text(const std::filesystem::path &file)
  {
    std::ifstream      in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// The lines of `file` without their line ends (none if it cannot be read).
  inline std::vector<std::string> read_lines(const std::filesystem::path &file)
  {
    std::ifstream            in(file);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
      lines.push_back(line);
    return lines;
  }

  /// `file` parsed as JSON (throws nlohmann::json::parse_error if it is missing or malformed).
  inline nlohmann::json read_json(const std::filesystem::path &file)
  {
    return nlohmann::json::parse(read_text(file));
  }

  /// Writes `bytes` to `file` unchanged (no line-end translation) and returns `file`.
  inline std::filesystem::path write_text(const std::filesystem::path &file,
                                          const std::string           &bytes)
  {
    std::ofstream out(file, std::ios::binary);
    out << bytes;
    return file;
  }

  /// The regular files below `dir` (recursively), as paths relative to it; none if `dir` does not
  /// exist.
  inline std::vector<std::string> files_below(const std::filesystem::path &dir)
  {
    std::vector<std::string> files;
    if (!std::filesystem::exists(dir))
      return files;
    for (const auto &entry : std::filesystem::recursive_directory_iterator(dir))
      if (entry.is_regular_file())
        files.push_back(std::filesystem::relative(entry.path(), dir).string());
    return files;
  }

  /// Whether `file` exists now (false, not an exception, when it cannot be told).
  inline bool exists_now(const std::filesystem::path &file)
  {
    std::error_code error;
    return std::filesystem::exists(file, error);
  }

  /// Waits up to `seconds` for `file` to exist and be non-empty; whether it did.
  inline bool wait_for_file(const std::filesystem::path &file, double seconds)
  {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end)
    {
      std::error_code error;
      if (std::filesystem::exists(file, error) && std::filesystem::file_size(file, error) > 0 &&
          !error)
        return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }
} // namespace kimp::testing
