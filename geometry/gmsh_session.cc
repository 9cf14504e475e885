// RAII access to the gmsh singleton (see header).
#include "geometry/gmsh_session.h"

#include <algorithm>
#include <cstdio>
#include <fcntl.h>
#include <gmsh.h>
#include <stdexcept>
#include <unistd.h>

namespace kimp::geometry
{
  namespace
  {
    /**
     * Silences file descriptor 2 while alive. gmsh 4.8 reports "Gmsh has not been initialized"
     * on stderr whenever its API is called after a gmsh::finalize that left General.Terminal = 1
     * (a verbose session, or a caller's or deal.II's own initialize / finalize pair), and the
     * probe below must make exactly such a call. Not thread safe, like gmsh itself.
     */
    class SilencedStderr
    {
    public:
      SilencedStderr()
      {
        std::fflush(stderr);
        saved_         = ::dup(STDERR_FILENO);
        const int null = ::open("/dev/null", O_WRONLY);
        if (saved_ >= 0 && null >= 0)
          ::dup2(null, STDERR_FILENO);
        if (null >= 0)
          ::close(null);
      }
      ~SilencedStderr()
      {
        std::fflush(stderr);
        if (saved_ >= 0)
        {
          ::dup2(saved_, STDERR_FILENO);
          ::close(saved_);
        }
      }
      SilencedStderr(const SilencedStderr &)            = delete;
      SilencedStderr &operator=(const SilencedStderr &) = delete;

    private:
      int saved_ = -1;
    };

    // gmsh 4.8 has no gmsh::isInitialized(): model::list() returns no model before the first
    // gmsh::initialize (which always creates one) and throws after gmsh::finalize.
    bool gmsh_is_initialized()
    {
      const SilencedStderr silenced;
      try
      {
        std::vector<std::string> names;
        gmsh::model::list(names);
        return !names.empty();
      }
      catch (...)
      {
        return false;
      }
    }
  } // namespace


  GmshSession::GmshSession(const std::string &model_name, bool verbose)
  {
    if (!gmsh_is_initialized())
    {
      // readConfigFiles = false: a user's ~/.gmshrc must not change the meshes kimp writes.
      gmsh::initialize(0, nullptr, false);
      owns_gmsh_ = true;
    }
    else
    {
      std::vector<std::string> names;
      gmsh::model::list(names);
      gmsh::model::getCurrent(previous_model_);
      had_previous_model_ = !names.empty();
    }
    set_option("General.Terminal", verbose ? 1.0 : 0.0);
    gmsh::model::add(model_name);
  }


  GmshSession::~GmshSession()
  {
    // A destructor must not throw; gmsh reports failures by throwing.
    try
    {
      if (owns_gmsh_)
      {
        // Options are not restored first: General.Terminal = 0 through finalize (also after a
        // verbose session) keeps gmsh quiet when it is probed before the next initialize.
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::finalize();
        return;
      }
      gmsh::model::remove();
      if (had_previous_model_)
        gmsh::model::setCurrent(previous_model_);
      std::for_each(saved_options_.rbegin(),
                    saved_options_.rend(),
                    [](const auto &option)
                    { gmsh::option::setNumber(option.first, option.second); });
    }
    catch (...)
    {
    }
  }


  void GmshSession::set_option(const std::string &name, double value)
  {
    double previous = 0.0;
    gmsh::option::getNumber(name, previous);
    saved_options_.emplace_back(name, previous);
    gmsh::option::setNumber(name, value);
  }
} // namespace kimp::geometry
