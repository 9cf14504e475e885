// FNV-1a, 64 bit (offset basis 14695981039346656037, prime 1099511628211).
#include "base/hash.h"

namespace kimp::base
{
  std::uint64_t stable_hash(std::string_view text)
  {
    std::uint64_t hash = 14695981039346656037ULL;
    for (const unsigned char c : text)
    {
      hash ^= c;
      hash *= 1099511628211ULL;
    }
    return hash;
  }
} // namespace kimp::base
