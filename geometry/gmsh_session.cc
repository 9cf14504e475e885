// RAII access to the gmsh singleton (see header).
#include "geometry/gmsh_session.h"

#include <algorithm>
#include <gmsh.h>
#include <stdexcept>

namespace kimp::geometry
{
  namespace
  {
    // gmsh 4.8 has no gmsh::isInitialized(), and probing it through its API is not safe: after
    // a gmsh::finalize (kimp's, or deal.II's own pair inside GridIn::read_msh) such a call can
    // end the process from inside gmsh's error handler. kimp is the only caller that keeps gmsh
    // initialized across calls, so the live owning sessions are counted here instead.
    int live_owning_sessions = 0;
  } // namespace


  GmshSession::GmshSession(const std::string &model_name, bool verbose)
  {
    std::vector<std::string> names;
    if (live_owning_sessions == 0)
    {
      // readConfigFiles = false: a user's ~/.gmshrc must not change the meshes kimp writes. When
      // the caller has initialised gmsh already this is a no-op (gmsh warns on its terminal,
      // which a caller that keeps it quiet does not show); then its models are listed below. A
      // fresh gmsh lists exactly one model, the unnamed one initialize() creates.
      gmsh::initialize(0, nullptr, false);
      gmsh::model::list(names);
      owns_gmsh_ = names.size() == 1 && names.front().empty();
    }
    else
      gmsh::model::list(names);
    if (owns_gmsh_)
      ++live_owning_sessions;
    else
    {
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
        --live_owning_sessions;
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
