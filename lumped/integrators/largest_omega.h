// The largest circular frequency of a lumped model, ω_max of (K, M) with M diagonal: the
// stability limit Δt_cr = 2/ω_max of the central difference method (planar and in plan).
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace kimp::lumped
{
  /// √λ_max of K·φ = λ·M·φ for the lumped masses `m` (kg) and the stiffness `k` (N/m), rad/s;
  /// 0 when k has no positive eigenvalue.
  inline double largest_omega(const Eigen::Ref<const Eigen::VectorXd> &m, const Eigen::MatrixXd &k)
  {
    const Eigen::VectorXd inv_sqrt_m = m.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd a          = inv_sqrt_m.asDiagonal() * k * inv_sqrt_m.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(solver.eigenvalues().maxCoeff(), 0.0));
  }
} // namespace kimp::lumped
