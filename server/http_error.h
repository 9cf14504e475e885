// A request that `kimp gui` refuses: its HTTP status and message (the server answers
// {"error": message} with that status).
#pragma once

#include <stdexcept>
#include <string>

namespace kimp::server
{
  /// A request the server refuses, with its HTTP status and message.
  struct HttpError : std::runtime_error
  {
    HttpError(int status_, const std::string &message)
      : std::runtime_error(message)
      , status(status_)
    {
    }
    int status;
  };
} // namespace kimp::server
