// One-line error texts for users: the standard library's own words for out-of-memory and size
// errors ("std::bad_alloc", "vector::reserve") become sentences, line breaks become spaces.
#pragma once

#include <exception>
#include <string>

namespace kimp::base
{
  /// The message of `error` on one line, with out-of-memory and too-large-size errors explained.
  std::string error_text(const std::exception &error);
} // namespace kimp::base
