// Central difference method for a building in plan pounding a moat wall (docs/physics.md
// "Pounding in plan"): the planar method (lumped/integrators/central_difference.h) with DOFs
// (u_x, u_y, θ) per level, dense M⁻¹-free effective matrix A = M/Δt² + C/(2Δt), the isolators
// and the contact points of the moat evaluated explicitly at u_n:
//   M·ü + C·u̇ + K·u + Σ_j T_jᵀ·f_j(T_j·u_0) + Σ_c (n_cᵀ·w_c·F_c(δ_c) + t_cᵀ·φ_c) = −M·(r_x·ü_g,x
//   + r_y·ü_g,y).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/response.h"
#include "lumped/plan/plan_building.h"
#include "lumped/plan/plan_moat.h"
#include "lumped/plan/plan_motion.h"

namespace kimp::lumped::plan
{
  /// A building in plan with an optional moat (plain data).
  struct PlanScene
  {
    PlanBuilding            building;
    std::optional<PlanMoat> moat;
  };

  /// The DOF of a yielding wall face (PlanYieldingWall): w along `normal`, away from the slab.
  struct PlanWallDof
  {
    std::size_t                            segment = 0;
    Point                                  normal  = Point::Zero();
    double                                 mass    = 0.0; ///< kg
    std::shared_ptr<const WallBackfillLaw> law;           ///< prototype
  };

  /**
   * The assembled system: diagonal M, dense K (storeys) and C, the isolators at level 0, the
   * contact points of the moat and the DOFs of its yielding faces.
   */
  class PlanModel
  {
  public:
    /// @throws std::invalid_argument naming the bad field.
    explicit PlanModel(const PlanScene &scene);

    std::size_t            n_dofs() const { return static_cast<std::size_t>(mass_.size()); }
    const PlanBuilding    &building() const { return building_; }
    const Eigen::VectorXd &masses() const { return mass_; }
    const Eigen::MatrixXd &stiffness() const { return stiffness_; }
    const Eigen::MatrixXd &damping() const { return damping_.matrix; }
    const PlanDamping     &damping_model() const { return damping_; }
    const std::vector<PlanContact> &contacts() const { return contacts_; }
    const std::optional<PlanMoat>  &moat() const { return moat_; }
    const std::vector<PlanWallDof> &wall_dofs() const { return walls_; }
    /// T_j (2 × 3) of each isolator relative to level 0's DOFs.
    const std::vector<Eigen::Matrix<double, 2, 3>> &isolator_kinematics() const
    {
      return isolator_t_;
    }
    /// K with the isolators' initial stiffness.
    Eigen::MatrixXd initial_stiffness_matrix() const;

  private:
    PlanBuilding                             building_;
    std::optional<PlanMoat>                  moat_;
    Eigen::VectorXd                          mass_;
    Eigen::MatrixXd                          stiffness_;
    PlanDamping                              damping_;
    std::vector<PlanContact>                 contacts_;
    std::vector<PlanWallDof>                 walls_;
    std::vector<Eigen::Matrix<double, 2, 3>> isolator_t_;
  };

  /**
   * Options as lumped::CentralDifferenceOptions without its kernel (lumped::SteppingOptions: dt
   * (0 = auto), safety, expected_max_penetration, duration (0 = the record's), output_interval,
   * law_velocity, initial_displacement and initial_velocity (empty or one value per DOF), and
   * divergence_energy_factor).
   */
  using PlanOptions = SteppingOptions;

  /// Results of one contact point.
  struct PlanContactResult
  {
    std::string              name;
    std::size_t              segment             = 0;
    double                   peak_normal_force   = 0.0; ///< max w·F, N
    double                   peak_friction_force = 0.0; ///< max |φ|, N
    std::vector<ImpactEvent> impacts;
    double                   dissipated_energy = 0.0; ///< w·(law's dissipated energy), J
    double                   friction_work     = 0.0; ///< ∫ φ ds, J
  };

  /// Results of one yielding wall face.
  struct PlanYieldingWallResult
  {
    std::size_t segment  = 0;
    double      capacity = 0.0; ///< the part's capacity (WallBackfillParams), N
    /// w_max beyond which the wall has failed (WallBackfillParams), m.
    double failure_displacement = 0.0;
    double peak_resistance      = 0.0; ///< max R(w) of the wall-and-backfill part, N
    double peak_displacement    = 0.0; ///< w_max, m
    double permanent_set        = 0.0; ///< w_p at the end, m
    double final_displacement   = 0.0; ///< w at the end, m
    double plastic_work         = 0.0; ///< J
    double radiated_work        = 0.0; ///< J
    /// Time at which w_max first exceeded failure_displacement (unset: not failed), s.
    std::optional<double> failure_time;
  };

  /**
   * Energy terms, J (relative formulation as lumped::EnergyBalance), with the friction work and
   * the work done on the yielding walls' wall-and-backfill parts:
   *   E_0 + W_in = E_kin + E_strain + E_viscous + E_hysteretic + W_contact + W_friction + W_wall
   * (E_kin and W_in include the walls' DOFs).
   */
  struct PlanEnergy
  {
    double initial           = 0.0;
    double input             = 0.0;
    double kinetic           = 0.0;
    double strain            = 0.0;
    double viscous           = 0.0;
    double hysteretic        = 0.0;
    double contact_work      = 0.0;
    double impact_dissipated = 0.0;
    double friction          = 0.0;
    double wall_work         = 0.0; ///< Σ ∫F dw of the wall-and-backfill parts (trapezoid)
    double wall_plastic      = 0.0; ///< their plastic work
    double wall_radiated     = 0.0; ///< their radiated work
    /// |residual| / max over the check points of (E_0 + W_in), at the end and its maximum.
    double relative_error     = 0.0;
    double max_relative_error = 0.0;
  };

  /// Decimated histories; row-major [sample][index].
  struct PlanHistory
  {
    double              interval = 0.0;
    std::vector<double> time;                  ///< s
    std::vector<double> displacement;          ///< [sample][dof], m and rad
    std::vector<double> absolute_acceleration; ///< [sample][dof], m/s² (+ ü_g) and rad/s²
    std::vector<double> corner_displacement;   ///< [sample][corner of level 0][x, y], m
    std::vector<double> contact_force;         ///< [sample][contact], w·F, N
    std::vector<double> friction_force;        ///< [sample][contact], φ, N
    std::vector<double> energy_error;          ///< [sample]
  };

  struct PlanResponse
  {
    double      dt       = 0.0;
    long        n_steps  = 0;
    double      duration = 0.0;
    std::size_t n_levels = 0;

    std::vector<double> peak_displacement;          ///< per DOF, m and rad
    std::vector<double> peak_absolute_acceleration; ///< per DOF, m/s² and rad/s²
    /// Per level, the largest |T·q| over the outline's corners, m.
    std::vector<double> peak_corner_displacement;
    /// Per level, the largest |(ü_x + ü_g,x, ü_y + ü_g,y)| at the centre of mass, m/s².
    std::vector<double> peak_horizontal_acceleration;
    /// Per storey, the drift (upper − lower at the upper level's centre of mass) along x, y, and
    /// the largest drift magnitude over the upper level's corners, m.
    std::vector<double> peak_drift_x, peak_drift_y, peak_corner_drift;
    /// max |Σ_j f_j|, the resultant of the isolators, N.
    double                              peak_isolator_force = 0.0;
    std::vector<PlanContactResult>      contacts;
    std::vector<PlanYieldingWallResult> yielding_walls;
    /// Per wall face, max over time of Σ w·F of its contact points, N.
    std::vector<double> peak_wall_force;
    PlanEnergy          energy;
    PlanHistory         history;

    std::size_t n_impacts() const;
  };

  /**
   * The central difference method of lumped::CentralDifference for a PlanModel: the same step
   * (in increment form, Δu_{n+1} = Δu_n − A⁻¹(C/Δt + K)·Δu_n − z_{n−1} − A⁻¹M·(r_x·ü_g,x +
   * r_y·ü_g,y) − A⁻¹·f_n, z_n = z_{n−1} + A⁻¹K·Δu_n), the same law velocities, the same
   * handling of laws whose gap is open, the same interpolation of the record and the same
   * choice of Δt; the stability limit includes every contact point closed at its weighted
   * stability stiffness. Friction: φ = μ·w·F·sat(v_t/v_r), v_t the backward-difference sliding
   * velocity, v_r = max(stick_velocity, μ·w·F·Δt/m_t) (the regularised dashpot μ·w·F/v_r then
   * never exceeds m_t/Δt, so that the explicit friction force cannot reverse the sliding in one
   * step).
   */
  class PlanCentralDifference : public CentralDifferenceMethod<PlanModel, PlanOptions>
  {
  public:
    /// @throws std::invalid_argument for invalid options.
    explicit PlanCentralDifference(PlanModel model, PlanOptions options = {});

    /// Integrate from the initial conditions. @throws TimeStepError, DivergenceError.
    PlanResponse run(const PlanGroundMotion &motion) const;
  };
} // namespace kimp::lumped::plan
