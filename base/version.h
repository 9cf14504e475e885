// kimp's version and the git revision it was built from (`kimp --version`, /meta of every result,
// the study's cache keys). The values live in a source file that the build rewrites whenever the
// checked-out revision changes (cmake/write_version.cmake), so a rebuilt binary never carries the
// revision of an older configure.
#pragma once

#include <string>

namespace kimp::base
{
  extern const char *const version;      ///< "0.1.0"
  extern const char *const git_revision; ///< 12 hex digits, or "unknown" outside a git checkout

  /// "kimp 0.1.0 (git <revision>)".
  std::string version_line();
} // namespace kimp::base
