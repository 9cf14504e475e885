// The model of a lumped scene without a run (app/lumped/scene_preview.h).
#include "app/lumped/scene_preview.h"

#include <cmath>

#include "app/lumped/lumped_scene.h"
#include "io/scene_io.h"
#include "io/units.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::app
{
  nlohmann::json scene_model_preview(const std::string &scene_text, const std::string &file_name)
  {
    const io::LoadedScene<LumpedScene> loaded =
      io::read_scene_text<LumpedScene>(scene_text, file_name);
    const LumpedScene          &scene = loaded.scene;
    const lumped::PoundingModel model(make_pounding_scene(scene));
    const bool                  isolated = scene.building.kind == BuildingKind::isolated;

    nlohmann::json masses = nlohmann::json::array();
    double         total  = 0.0;
    if (isolated)
    {
      masses.push_back(scene.building.isolation_mass);
      total += scene.building.isolation_mass;
    }
    for (const double m : scene.building.floor_masses())
    {
      masses.push_back(m);
      total += m;
    }
    nlohmann::json j;
    j["building"]        = {{"kind", isolated ? "isolated" : "fixed_base"},
                            {"n_storeys", scene.building.n_storeys},
                            {"masses", masses},
                            {"storey_stiffness", scene.building.storey_stiffness}};
    j["isolated_period"] = nullptr;
    if (isolated && model.isolator())
    {
      const IsolatorScene &iso = scene.isolator;
      j["isolator"]            = {{"kind", model.isolator()->name()},
                                  {"initial_stiffness", model.isolator()->initial_stiffness()}};
      const double two_pi      = 2.0 * M_PI;
      switch (iso.kind)
      {
        case IsolatorKind::bilinear:
        case IsolatorKind::bouc_wen:
          if (iso.K2 > 0.0)
            j["isolated_period"] = two_pi * std::sqrt(total / iso.K2);
          j["isolated_period_basis"] = "post-yield stiffness K2";
          break;
        case IsolatorKind::linear:
          j["isolated_period"]       = two_pi * std::sqrt(total / iso.k);
          j["isolated_period_basis"] = "isolator stiffness k";
          break;
        case IsolatorKind::friction_pendulum:
          j["isolated_period"]       = two_pi * std::sqrt(iso.radius / io::standard_gravity);
          j["isolated_period_basis"] = "pendulum radius R";
          break;
      }
    }
    j["buildings"] = nlohmann::json::array();
    for (const lumped::BuildingBlock &block : model.buildings())
    {
      nlohmann::json periods = nlohmann::json::array();
      for (Eigen::Index i = 0; i < block.damping.modes.period.size(); ++i)
        periods.push_back(block.damping.modes.period[i]);
      j["buildings"].push_back(
        {{"name", block.name}, {"n_dofs", block.n_dofs}, {"periods", periods}});
    }
    j["contacts"] = nlohmann::json::array();
    for (const lumped::ContactPair &c : model.contacts())
      j["contacts"].push_back({{"name", c.name}, {"gap", c.gap}});
    const auto wall = [&](const WallScene &w)
    {
      return nlohmann::json{{"present", isolated && w.present},
                            {"gap", w.gap},
                            {"flexible", w.flexible}};
    };
    j["walls"]           = {{"left", wall(scene.walls.left)}, {"right", wall(scene.walls.right)}};
    const auto neighbour = [](const NeighbourScene &n)
    {
      return nlohmann::json{{"present", n.present},
                            {"separation", n.separation},
                            {"n_storeys", n.n_storeys}};
    };
    j["neighbours"] = {{"left", neighbour(scene.neighbours.left)},
                       {"right", neighbour(scene.neighbours.right)}};
    j["cases"]      = nlohmann::json::array();
    for (const CaseScene &c : scene.cases)
      j["cases"].push_back(c.name);
    return j;
  }
} // namespace kimp::app
