// How `kimp gui` shows text it did not write itself (a bad value, a message of a lower layer, a
// run's log): the value quoted in at most 80 characters, over-long lines clipped, the machine
// paths of the runs and records folders made relative to them. Every answer goes through it, so
// neither a huge request nor the server's place on the machine is echoed back.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace kimp::server
{
  /// Characters of a value quoted in a message at most (in_quotes()).
  inline constexpr std::size_t quoted_max = 80;

  /// `value` itself, its first quoted_max bytes only, then "... (N bytes)" when longer.
  std::string clipped(std::string_view value);

  /// clipped() `value` in double quotes.
  std::string in_quotes(std::string_view value);

  /// `text` with each word (bytes between spaces and line breaks) longer than 100 bytes cut to
  /// its first quoted_max bytes and "... (N bytes)", then each line still longer than 240 bytes
  /// cut to its first 100 and last 60 bytes around "[... N bytes left out ...]": a message that
  /// echoes a huge value keeps its file, line, key and rule, not the value.
  std::string clip_long_lines(std::string text);

  /// Machine paths of the runs and records folders in text shown to the page.
  class FolderPaths
  {
  public:
    FolderPaths(const std::filesystem::path                &runs_dir,
                const std::optional<std::filesystem::path> &records_dir);

    /// `text` with every path below the runs or records folder written relative to that folder
    /// ("RUNS_DIR/ID/scene.yaml" -> "ID/scene.yaml") and either folder itself by its
    /// name ("kimp-runs"), long lines clipped (clip_long_lines()).
    std::string operator()(std::string text) const;
    /// `text` with the folders' paths made relative as operator() does, no line clipped.
    std::string relative(std::string text) const;

    /// The name a folder is shown by: its last component ("kimp-runs", "records").
    static std::string folder_name(const std::filesystem::path &folder);

  private:
    /// (machine path, name) of each spelling of each folder, longest path first.
    std::vector<std::pair<std::string, std::string>> folders_;
  };
} // namespace kimp::server
