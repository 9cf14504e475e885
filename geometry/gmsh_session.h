// RAII access to the process-wide gmsh library state (gmsh::initialize / gmsh::finalize), with a
// private model and option values restored on exit so that a caller's gmsh use is left untouched.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace kimp::geometry
{
  /**
   * Scoped use of gmsh. The constructor initialises gmsh unless the caller already has, adds a
   * fresh model named @p model_name and makes it current; it silences gmsh (General.Terminal = 0)
   * unless @p verbose. The destructor removes that model, restores the previously current model
   * and every option changed through set_option(), and finalises gmsh only if this session
   * initialised it.
   *
   * gmsh is a global singleton and not thread safe: at most one GmshSession may be alive at a
   * time in a process, and no other thread may call gmsh meanwhile. Not copyable or movable.
   */
  class GmshSession
  {
  public:
    explicit GmshSession(const std::string &model_name = "kimp", bool verbose = false);
    ~GmshSession();

    GmshSession(const GmshSession &)            = delete;
    GmshSession &operator=(const GmshSession &) = delete;

    /** Sets a numeric gmsh option for the lifetime of this session (restored afterwards). */
    void set_option(const std::string &name, double value);

    /** True if this session called gmsh::initialize (and will call gmsh::finalize). */
    bool owns_gmsh() const { return owns_gmsh_; }

  private:
    bool                                        owns_gmsh_ = false;
    std::string                                 previous_model_;
    bool                                        had_previous_model_ = false;
    std::vector<std::pair<std::string, double>> saved_options_;
  };
} // namespace kimp::geometry
