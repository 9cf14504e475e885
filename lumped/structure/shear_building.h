// Shear-type MDOF buildings (thesis ch. 3, docs/physics.md §2-3): masses lumped at the floors,
// linear storeys, optional isolator between the ground and DOF 0, non-classical damping
// (eq. 3.1-3.3): C = a·M + b·K (Rayleigh at the first and last mode of the whole model) + c_iso at
// C[0,0].
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lumped/isolators/isolator.h"
#include "lumped/structure/modal.h"
#include "lumped/structure/tridiagonal_matrix.h"

namespace kimp::lumped
{
  /**
   * A shear building, plain data in SI units.
   *
   * Isolated (isolator != nullptr): DOF 0 is the isolation level (base mat) of mass
   * floor_masses[0], connected to the ground by the isolator; storey_stiffnesses[i] connects DOF i
   * and DOF i+1 (size n − 1). Fixed base (isolator == nullptr): storey_stiffnesses[i] connects DOF
   * i−1 (the ground for i = 0) and DOF i (size n).
   *
   * | field                     | unit | admissible | meaning                                 |
   * |---------------------------|------|------------|-----------------------------------------|
   * | floor_masses              | kg   | > 0        | lumped masses, bottom to top            |
   * | storey_stiffnesses        | N/m  | > 0        | storey shear stiffnesses                |
   * | damping_ratio             | -    | [0, 1)     | ζ_sstr (isolated) or ζ (fixed base) at  |
   * |                           |      |            | the first and last modes (Rayleigh)     |
   * | isolation_damping_ratio   | -    | >= ζ_sstr  | ζ_iso; c_iso = 2(ζ_iso−ζ_sstr)√(m_tot·k)|
   */
  struct ShearBuilding
  {
    std::string                     name = "building";
    std::vector<double>             floor_masses;
    std::vector<double>             storey_stiffnesses;
    std::shared_ptr<const Isolator> isolator;
    double                          damping_ratio           = 0.02;
    double                          isolation_damping_ratio = 0.05;

    std::size_t n_dofs() const { return floor_masses.size(); }
    bool        is_isolated() const { return isolator != nullptr; }
    /// Σ floor masses including the isolation level, kg.
    double total_mass() const;
  };

  /**
   * Check sizes and ranges.
   * @throws std::invalid_argument "<name>.<field>[i] = value unit (rule)".
   */
  void validate(const ShearBuilding &building);

  /**
   * Storey stiffness matrix (tridiagonal), N/m. With `include_isolator` the isolator's initial
   * stiffness (K1 of a bilinear isolator) is added at K[0,0]; the time integrators use the matrix
   * without it and evaluate the isolator force through its law.
   */
  TridiagonalMatrix stiffness_matrix(const ShearBuilding &building, bool include_isolator);

  /// The damping model of docs/physics.md §2 and its ingredients.
  struct BuildingDamping
  {
    ModalProperties      modes;    ///< of (K with the isolator's initial stiffness, M)
    RayleighCoefficients rayleigh; ///< fitted at modes 1 and n with damping_ratio
    double c_iso = 0.0;       ///< 2(ζ_iso − ζ_sstr)·√(m_tot·k_iso), N·s/m (0 if fixed)
    TridiagonalMatrix matrix; ///< a·M + b·K + (c_iso + isolator c)·e0·e0ᵀ, N·s/m
  };

  /// Modal analysis and damping matrix of the building (thesis eq. 3.1-3.3).
  BuildingDamping building_damping(const ShearBuilding &building);

  /**
   * Thesis Table 4.2 isolated building: isolation level 320 t, floors 320 t, top floor 250 t,
   * storeys 600 MN/m, ζ_sstr 2 %, ζ_iso 5 %, bilinear isolator K1 = 200 MN/m, K2 = 25 MN/m,
   * Q = 0.1·W_tot (W_tot = g·Σm incl. the isolation level, g = standard_gravity).
   * @param[in] n_storeys floors above the isolation level (>= 1)
   */
  ShearBuilding reference_isolated_building(unsigned int n_storeys);

  /// The same building with a linear isolator of stiffness k_iso (N/m) instead of the bilinear one.
  ShearBuilding reference_isolated_building_linear(unsigned int n_storeys, double k_iso);

  /// Thesis fixed-base building: floors 320 t, top 250 t, storeys 600 MN/m, 5 % Rayleigh.
  ShearBuilding reference_fixed_base_building(unsigned int n_storeys);
} // namespace kimp::lumped
