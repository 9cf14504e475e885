// Undamped modal analysis K·φ = ω²·M·φ of the lumped models and Rayleigh damping C = a·M + b·K
// fitted to damping ratios at two modes (thesis eq. 3.1-3.2; Chopra, Dynamics of Structures §11.4).
#pragma once

#include <Eigen/Dense>

namespace kimp::lumped
{
  /// Natural frequencies and mass-normalised mode shapes (φᵀ·M·φ = 1), ascending ω.
  struct ModalProperties
  {
    Eigen::VectorXd omega;  ///< circular frequencies, rad/s
    Eigen::VectorXd period; ///< T = 2π/ω, s
    Eigen::MatrixXd shapes; ///< column j = mode j
  };

  /**
   * Solve K·φ = ω²·M·φ (Eigen::GeneralizedSelfAdjointEigenSolver).
   * @param[in] mass      lumped masses, kg (all > 0)
   * @param[in] stiffness symmetric stiffness matrix, N/m (positive definite)
   * @throws std::invalid_argument for a size mismatch, a non-positive mass or a non-positive
   *         eigenvalue (mechanism).
   */
  ModalProperties modal_analysis(const Eigen::VectorXd &mass, const Eigen::MatrixXd &stiffness);

  /// Rayleigh coefficients of C = a·M + b·K.
  struct RayleighCoefficients
  {
    double a = 0.0; ///< mass-proportional, 1/s
    double b = 0.0; ///< stiffness-proportional, s
  };

  /**
   * [a; b] from ζ_n = a/(2ω_n) + b·ω_n/2 at ω_i, ω_j. With ω_i == ω_j (a single-DOF model) the
   * damping is taken stiffness-proportional: a = 0, b = 2ζ_i/ω_i.
   * @throws std::invalid_argument for non-positive frequencies or negative ratios.
   */
  RayleighCoefficients
  rayleigh_coefficients(double omega_i, double omega_j, double zeta_i, double zeta_j);
} // namespace kimp::lumped
