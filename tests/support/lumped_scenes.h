// kimp::testing::walled_scene(): the thesis building between two equal moat walls, the lumped
// scene that the lumped tests and bench/lumped_bench.cc share. Only for targets linking
// kimp::lumped.
#pragma once

#include <string>

#include "lumped/laws/force_law_factory.h"
#include "lumped/structure/pounding_model.h"
#include "lumped/structure/shear_building.h"

namespace kimp::testing
{
  /**
   * The 4-storey isolated reference building of docs/physics.md §3 with a moat wall at `gap` [m]
   * on each side, both walls with the contact law `law` (a make_force_law() name) of stiffness
   * `stiffness` [SI units of that law, e.g. N/m or N/m^1.5] and COR `cor`, every other law
   * parameter at its default.
   */
  inline lumped::PoundingScene
  walled_scene(const std::string &law, double stiffness, double gap, double cor = 0.7)
  {
    lumped::ForceLawSpec spec;
    spec.law       = law;
    spec.stiffness = stiffness;
    spec.cor       = cor;
    lumped::MoatWall wall;
    wall.gap = gap;
    wall.law = lumped::force_law_factory(spec);
    lumped::PoundingScene scene;
    scene.building   = lumped::reference_isolated_building(4);
    scene.left_wall  = wall;
    scene.right_wall = wall;
    return scene;
  }
} // namespace kimp::testing
