// A building of rigid diaphragms in plan (docs/physics.md "Pounding in plan"): each level has
// three DOFs (u_x, u_y, θ) of its centre of mass, storeys join consecutive levels with lateral
// stiffnesses at plan positions and a torsional stiffness, isolators at plan positions join the
// ground and the isolation level. Linear (small-rotation) kinematics throughout.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lumped/plan/plan_geometry.h"
#include "lumped/plan/plan_isolators.h"
#include "lumped/structure/modal.h"

namespace kimp::lumped::plan
{
  /**
   * One floor (or the isolation level): a rigid diaphragm.
   *
   * | field             | unit  | admissible      | meaning                                    |
   * |-------------------|-------|-----------------|--------------------------------------------|
   * | mass              | kg    | > 0             | lumped mass                                |
   * | outline           | m     | simple polygon  | plan of the slab (default 20 m × 20 m at   |
   * |                   |       |                 | the origin); its corners are reported      |
   * | mass_eccentricity | m     | finite          | centre of mass minus the outline centroid  |
   * | polar_inertia     | kg·m² | > 0 or unset    | about the centre of mass; unset: m·J/A of  |
   * |                   |       |                 | the outline about its centroid (uniform    |
   * |                   |       |                 | slab radius of gyration)                   |
   */
  struct PlanLevel
  {
    double                mass              = 0.0;
    Polygon               outline           = rectangle(20.0, 20.0);
    Point                 mass_eccentricity = Point::Zero();
    std::optional<double> polar_inertia;

    /// Centre of mass, m.
    Point centre_of_mass() const { return centroid(outline) + mass_eccentricity; }
    /// Polar inertia about the centre of mass, kg·m².
    double inertia() const;
  };

  /// A column or wall of a storey at a plan position, with its lateral stiffnesses, N/m.
  struct StoreyElement
  {
    Point  position = Point::Zero(); ///< m
    double k_x      = 0.0;           ///< N/m, >= 0
    double k_y      = 0.0;           ///< N/m, >= 0
  };

  /**
   * A storey between two levels: lateral elements at plan positions and a torsional stiffness
   * k_θ (N·m/rad) of its own. Given directly, a storey is one element (k_x, k_y) at its stiffness
   * centre plus k_θ about that centre (storey()); given by its layout, the elements' positions
   * make its torsional stiffness Σ k_x·(y − y_s)² + k_y·(x − x_s)² (k_theta then usually 0).
   */
  struct PlanStorey
  {
    std::vector<StoreyElement> elements;
    double                     k_theta = 0.0;
  };

  /// A storey given directly: k_x, k_y (N/m) at `stiffness_centre` and k_θ (N·m/rad) about it.
  PlanStorey
  storey(double k_x, double k_y, double k_theta, const Point &stiffness_centre = Point::Zero());

  /// An isolator at a plan position (the law's prototype; integrators clone it).
  struct PlanIsolatorSpec
  {
    Point                               position = Point::Zero(); ///< m
    std::shared_ptr<const PlanIsolator> law;
  };

  /**
   * A building in plan, plain data in SI units.
   *
   * Isolated (isolators not empty): level 0 is the isolation level, storeys[i] joins levels i
   * and i + 1 (n − 1 storeys). Fixed base: storeys[i] joins level i − 1 (the ground for i = 0)
   * and level i (n storeys).
   *
   * | field                   | unit | admissible | meaning                                   |
   * |-------------------------|------|------------|-------------------------------------------|
   * | damping                 | -    | rayleigh,  | the superstructure's damping model        |
   * |                         |      | modal      | (plan_damping())                          |
   * | damping_ratio           | -    | [0, 1)     | ζ per direction (Rayleigh) or of every    |
   * |                         |      |            | mode (modal), see plan_damping()          |
   * | isolation_damping_ratio | -    | >= ζ, < 1  | ζ_iso; c_iso per direction at level 0     |
   */
  /// The superstructure's damping model (plan_damping()).
  enum class PlanDampingModel
  {
    rayleigh, ///< per direction, fitted at the direction's first and last modes
    modal     ///< classical damping, ζ in every mode of the coupled building
  };

  struct PlanBuilding
  {
    std::string                   name = "building";
    std::vector<PlanLevel>        levels;
    std::vector<PlanStorey>       storeys;
    std::vector<PlanIsolatorSpec> isolators;
    PlanDampingModel              damping                 = PlanDampingModel::rayleigh;
    double                        damping_ratio           = 0.02;
    double                        isolation_damping_ratio = 0.05;

    std::size_t n_levels() const { return levels.size(); }
    std::size_t n_dofs() const { return 3 * levels.size(); }
    bool        is_isolated() const { return !isolators.empty(); }
  };

  /**
   * Check sizes, ranges and polygons.
   * @throws std::invalid_argument "<name>.<field>[i]... = value unit (rule)".
   */
  void validate(const PlanBuilding &building);

  /// Diagonal of the mass matrix, DOF 3i + (0, 1, 2) = (u_x, u_y, θ) of level i: m, m, I.
  Eigen::VectorXd plan_masses(const PlanBuilding &building);

  /**
   * Stiffness matrix (dense, 3n × 3n) of the storeys; with `include_isolators` each isolator's
   * initial stiffness acts as a linear spring at its position (modal analysis, Rayleigh damping,
   * stable step).
   */
  Eigen::MatrixXd plan_stiffness(const PlanBuilding &building, bool include_isolators);

  /// The damping model in plan and its ingredients (docs/physics.md "Pounding in plan").
  struct PlanDamping
  {
    /// Rayleigh coefficients per direction x, y, θ, fitted at the first and last modes of that
    /// direction's block (K with isolators, M) with damping_ratio (zero with modal damping).
    RayleighCoefficients rayleigh[3];
    /// Modal damping: the modes of (K with isolators, M) whose ratios C keeps (else empty).
    ModalProperties modes;
    /// c_iso per direction at level 0: 2(ζ_iso − ζ)·√(m_tot·k_iso) in x and y (N·s/m), and
    /// 2(ζ_iso − ζ)·√(J_tot·k_iso,θ) in θ (N·m·s/rad), about the centre of mass of level 0.
    double c_iso[3] = {0.0, 0.0, 0.0};
    /// Rayleigh: C = S_a·M·S_a + S_b·K·S_b + c_iso + Σ devices' c·TᵀT, S = diag(√a_d),
    /// diag(√b_d) by direction: per-direction Rayleigh, symmetric and positive semi-definite also
    /// when the directions couple. Modal: C = M·Φ·diag(2ζω_k)·Φᵀ·M + c_iso + Σ devices' c·TᵀT
    /// (lumped::modal_damping_matrix, ζ = damping_ratio in every mode; dense).
    Eigen::MatrixXd matrix;
  };

  /// The damping of the building (planar building_damping() direction by direction).
  PlanDamping plan_damping(const PlanBuilding &building);

  /// Modes of (K with the isolators' initial stiffness, M).
  ModalProperties plan_modes(const PlanBuilding &building);

  /**
   * The kinematics T (2 × 3) of the material point at rest at `point` of level `level`
   * relative to that level's DOFs (its centre of mass): displacement = T·q_level.
   */
  Eigen::Matrix<double, 2, 3>
  level_kinematics(const PlanBuilding &building, std::size_t level, const Point &point);
} // namespace kimp::lumped::plan
