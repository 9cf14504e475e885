// The model of a lumped scene without a run (app/lumped/scene_preview.h).
#include "app/lumped/scene_preview.h"

#include <cmath>

#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_run.h"
#include "app/lumped/plan_scene.h"
#include "io/scene_io.h"
#include "io/units.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::app
{
  namespace
  {
    /// A scene in plan: its one building (3 DoFs per level) with the periods of the coupled
    /// modes, the moat's contact points and gaps, and `plan` {damping, faces, yielding faces};
    /// no planar walls or neighbours.
    void add_plan_model(nlohmann::json &j, const LumpedScene &base, const PlanSection &p)
    {
      const lumped::plan::PlanModel model(make_plan_scene(base, p));
      nlohmann::json                periods = nlohmann::json::array();
      const lumped::ModalProperties modes   = lumped::plan::plan_modes(model.building());
      for (Eigen::Index i = 0; i < modes.period.size(); ++i)
        periods.push_back(modes.period[i]);
      j["buildings"] = nlohmann::json::array(
        {{{"name", "building"}, {"n_dofs", model.n_dofs()}, {"periods", periods}}});
      j["contacts"] = nlohmann::json::array();
      for (const lumped::plan::PlanContact &c : model.contacts())
        j["contacts"].push_back({{"name", c.name}, {"gap", c.gap}});
      const nlohmann::json wall      = {{"present", false}, {"gap", 0.0}, {"flexible", false}};
      const nlohmann::json neighbour = {{"present", false}, {"separation", 0.0}, {"n_storeys", 0}};
      j["walls"]                     = {{"left", wall}, {"right", wall}};
      j["neighbours"]                = {{"left", neighbour}, {"right", neighbour}};
      nlohmann::json yielding        = nlohmann::json::array();
      if (model.moat())
        for (const lumped::plan::PlanYieldingWall &y : model.moat()->yielding)
          yielding.push_back(y.segment);
      j["plan"] = {{"damping", damping_name(model.building().damping)},
                   {"damping_ratio", model.building().damping_ratio},
                   {"faces", model.moat() ? model.moat()->wall.size() : 0},
                   {"yielding_faces", yielding}};
    }
  } // namespace

  nlohmann::json scene_model_preview(const std::string &scene_text, const std::string &file_name)
  {
    const io::LoadedScene<PlanLumpedScene> loaded =
      io::read_scene_text<PlanLumpedScene>(scene_text, file_name);
    const LumpedScene &scene   = loaded.scene.base;
    const bool         in_plan = loaded.scene.plan.has_value();
    // A scene in plan has no planar walls: its base building alone (the plan model below).
    LumpedScene planar = scene;
    if (in_plan)
      planar.walls.left.present = planar.walls.right.present = false;
    const lumped::PoundingModel model(make_pounding_scene(planar));
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
    if (in_plan)
      add_plan_model(j, scene, *loaded.scene.plan);
    return j;
  }
} // namespace kimp::app
