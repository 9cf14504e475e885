// The model of a lumped scene without a run: what `kimp gui` draws before a run (the buildings
// with their masses and periods, the isolator, the moat walls and neighbours with their gaps).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace kimp::app
{
  /**
   * The model a run of the lumped scene text `scene_text` (named `file_name` in messages) would
   * assemble, in SI: `building` {kind, n_storeys, masses [DOF] (kg, isolation level first),
   * storey_stiffness (N/m)}, `isolator` {kind, initial_stiffness (N/m)} and `isolated_period`
   * (s: 2π√(Σm/K2) of a bilinear or Bouc-Wen isolator, 2π√(Σm/k) of a linear one, 2π√(R/g) of a
   * friction pendulum; null for a fixed base), `buildings` [{name, n_dofs, periods (s), from the
   * modal analysis with the isolator's initial stiffness}], `contacts` [{name, gap (m)}],
   * `walls` and `neighbours` {left, right: {present, gap or separation, n_storeys}}, and `cases`
   * (names). A scene in plan has one building of 3 DoFs per level (periods of the coupled modes),
   * the moat's contact points as `contacts`, no planar walls or neighbours, and `plan` {damping
   * ("rayleigh" or "modal"), damping_ratio, faces (of the moat wall), yielding_faces [face]}.
   * The scene is read and validated as `kimp lumped` reads it.
   * @throws io::SceneError for an invalid scene (the message of `kimp lumped --check`)
   */
  nlohmann::json scene_model_preview(const std::string &scene_text, const std::string &file_name);
} // namespace kimp::app
