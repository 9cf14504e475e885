// Stable hashes of text (sweep case ids, FEM cache keys): the same value on every platform and run.
#pragma once

#include <cstdint>
#include <string_view>

namespace kimp::base
{
  /// 64-bit FNV-1a hash of `text`.
  std::uint64_t stable_hash(std::string_view text);
} // namespace kimp::base
