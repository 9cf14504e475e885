// kimp::testing::perfectly_bonded_wall_scene(): the reinforced moat wall of
// data/scenes/fem_reinforced_wall.yaml with its bars perfectly bonded (without the scene's strain
// penetration, crack spacing and tension stiffening), the FEM several tests' numbers were
// measured against (docs/validation.md "perfect bond").
#pragma once

#include <string>

namespace kimp::testing
{
  /// The scene as YAML: H = 1.25 m, f_cm 38 MPa damaged concrete, bars 0.8 % / 0.2 % in the
  /// wall and 0.5 % in the slab, geostatic Mohr-Coulomb medium-dense sand.
  inline std::string perfectly_bonded_wall_scene()
  {
    return R"(wall_heights: ["1.25 m"]
materials:
  concrete:
    model: damage_plasticity
    f_cm: "38 MPa"
    wall_reinforcement: {ratio_y: "0.8 %", ratio_x: "0.2 %"}
    slab_reinforcement: {ratio_x: "0.5 %"}
  soil: {model: mohr_coulomb, preset: medium_dense_sand}
)";
  }
} // namespace kimp::testing
