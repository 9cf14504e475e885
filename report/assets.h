// The page files of `kimp gui` and `kimp report` (gui/src and uPlot), embedded into the binary at
// build time (gui/assets.cmake): the pages need no network and no files beside the binary.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

namespace kimp::report
{
  namespace detail
  {
    struct EmbeddedAsset
    {
      const char *name;
      const char *bytes;
      std::size_t size;
    };
    /// Generated table, ended by {nullptr, nullptr, 0}.
    extern const EmbeddedAsset embedded_assets[];
  } // namespace detail

  /// Contents of the embedded file `name` (a base name such as "kimp.js"), if there is one.
  std::optional<std::string_view> asset(std::string_view name);
  /// Base names of every embedded file.
  std::vector<std::string_view> asset_names();
} // namespace kimp::report
