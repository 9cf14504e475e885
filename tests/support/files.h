// kimp::testing file helpers: the source tree, a whole file as text, as lines or as JSON, and
// writing a file in one call.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
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
} // namespace kimp::testing
