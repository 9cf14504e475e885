// Undamped modal analysis K·φ = ω²·M·φ of the lumped models and Rayleigh damping C = a·M + b·K
// fitted to damping ratios at two modes (thesis eq. 3.1-3.2; Chopra, Dynamics of Structures §11.4),
// or classical damping given mode by mode (Chopra §11.5).
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

  /**
   * Classical damping with ratio ζ_k in mode k (Chopra, Dynamics of Structures §11.5):
   *   C = M·Φ·diag(2·ζ_k·ω_k)·Φᵀ·M,
   * Φ the mass-normalised shapes of `modes` (modal_analysis of the same `mass`), so that
   * Φᵀ·C·Φ = diag(2·ζ_k·ω_k): every mode keeps its own ratio, whatever the frequencies (unlike
   * Rayleigh damping, exact at two modes only). Symmetric, positive semi-definite for ζ >= 0.
   * @param[in] zeta one ratio per mode (size of modes.omega), each in [0, 1)
   * @throws std::invalid_argument for a size mismatch or a ratio outside [0, 1).
   */
  Eigen::MatrixXd modal_damping_matrix(const Eigen::VectorXd &mass,
                                       const ModalProperties &modes,
                                       const Eigen::VectorXd &zeta);
} // namespace kimp::lumped
