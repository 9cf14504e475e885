// Modal analysis and Rayleigh damping coefficients (thesis eq. 3.2).
#include "lumped/structure/modal.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kimp::lumped
{
  ModalProperties modal_analysis(const Eigen::VectorXd &mass, const Eigen::MatrixXd &stiffness)
  {
    const Eigen::Index n = mass.size();
    if (n == 0 || stiffness.rows() != n || stiffness.cols() != n)
    {
      std::ostringstream msg;
      msg << "modal analysis: " << n << " masses but a " << stiffness.rows() << "x"
          << stiffness.cols() << " stiffness matrix (must be square of the same size, n > 0)";
      throw std::invalid_argument(msg.str());
    }
    for (Eigen::Index i = 0; i < n; ++i)
      if (!(mass(i) > 0.0))
      {
        std::ostringstream msg;
        msg << "modal analysis: mass[" << i << "] = " << mass(i) << " kg (must be > 0)";
        throw std::invalid_argument(msg.str());
      }

    const Eigen::MatrixXd                                     m = mass.asDiagonal();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, m);
    if (solver.info() != Eigen::Success)
      throw std::invalid_argument("modal analysis: generalized eigensolver failed");

    ModalProperties result;
    result.omega.resize(n);
    result.period.resize(n);
    for (Eigen::Index j = 0; j < n; ++j)
    {
      const double lambda = solver.eigenvalues()(j);
      if (!(lambda > 0.0))
      {
        std::ostringstream msg;
        msg << "modal analysis: eigenvalue " << j << " = " << lambda
            << " 1/s^2 (must be > 0: the stiffness matrix is singular or indefinite)";
        throw std::invalid_argument(msg.str());
      }
      result.omega(j)  = std::sqrt(lambda);
      result.period(j) = 2.0 * M_PI / result.omega(j);
    }
    // Eigen normalises generalized eigenvectors to φᵀ·M·φ = 1.
    result.shapes = solver.eigenvectors();
    return result;
  }

  RayleighCoefficients rayleigh_coefficients(const double omega_i,
                                             const double omega_j,
                                             const double zeta_i,
                                             const double zeta_j)
  {
    if (!(omega_i > 0.0 && omega_j > 0.0))
    {
      std::ostringstream msg;
      msg << "Rayleigh damping: omega_i = " << omega_i << ", omega_j = " << omega_j
          << " rad/s (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
    if (!(zeta_i >= 0.0 && zeta_j >= 0.0))
    {
      std::ostringstream msg;
      msg << "Rayleigh damping: zeta_i = " << zeta_i << ", zeta_j = " << zeta_j
          << " (must be >= 0)";
      throw std::invalid_argument(msg.str());
    }
    if (std::abs(omega_j - omega_i) <= 1e-12 * omega_i)
      return {0.0, 2.0 * zeta_i / omega_i};
    // Closed form of [[1/(2ω_i), ω_i/2]; [1/(2ω_j), ω_j/2]]⁻¹·[ζ_i; ζ_j].
    const double det = (omega_j / omega_i - omega_i / omega_j) / 4.0;
    const double a   = (zeta_i * omega_j / 2.0 - zeta_j * omega_i / 2.0) / det;
    const double b   = (zeta_j / (2.0 * omega_i) - zeta_i / (2.0 * omega_j)) / det;
    return {a, b};
  }

  Eigen::MatrixXd modal_damping_matrix(const Eigen::VectorXd &mass,
                                       const ModalProperties &modes,
                                       const Eigen::VectorXd &zeta)
  {
    const Eigen::Index n = mass.size();
    if (modes.omega.size() != n || modes.shapes.rows() != n || modes.shapes.cols() != n ||
        zeta.size() != n)
    {
      std::ostringstream msg;
      msg << "modal damping: " << n << " masses, " << modes.omega.size() << " modes ("
          << modes.shapes.rows() << "x" << modes.shapes.cols() << " shapes) and " << zeta.size()
          << " damping ratios (must all be " << n << ")";
      throw std::invalid_argument(msg.str());
    }
    for (Eigen::Index k = 0; k < n; ++k)
      if (!(zeta(k) >= 0.0 && zeta(k) < 1.0))
      {
        std::ostringstream msg;
        msg << "modal damping: damping ratio of mode " << k + 1 << " = " << zeta(k)
            << " (must be in [0, 1))";
        throw std::invalid_argument(msg.str());
      }
    // M·Φ, then (M·Φ)·diag(2ζω)·(M·Φ)ᵀ, symmetrised against round-off.
    const Eigen::MatrixXd mphi  = mass.asDiagonal() * modes.shapes;
    const Eigen::VectorXd coeff = 2.0 * zeta.cwiseProduct(modes.omega);
    const Eigen::MatrixXd c     = mphi * coeff.asDiagonal() * mphi.transpose();
    return 0.5 * (c + c.transpose());
  }
} // namespace kimp::lumped
