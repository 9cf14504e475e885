// One-line error texts; see errors.h.
#include "base/errors.h"

#include <new>
#include <stdexcept>

namespace kimp::base
{
  std::string error_text(const std::exception &error)
  {
    if (dynamic_cast<const std::bad_alloc *>(&error) != nullptr)
      return "out of memory: the run needs more memory than is available (shorten the "
             "duration, coarsen the output interval or the mesh, or run fewer cases)";
    if (dynamic_cast<const std::length_error *>(&error) != nullptr)
      return std::string("a size is too large for this machine (") + error.what() +
             "): shorten the duration or coarsen the output interval or the mesh";
    std::string text = error.what();
    for (char &c : text)
      if (c == '\n' || c == '\r')
        c = ' ';
    while (!text.empty() && text.back() == ' ')
      text.pop_back();
    return text;
  }
} // namespace kimp::base
