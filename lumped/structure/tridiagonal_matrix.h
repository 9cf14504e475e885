// Symmetric tridiagonal matrices (stiffness and damping of shear buildings; block-tridiagonal
// when several buildings are stacked) and their pre-factorised Thomas solver.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <vector>

namespace kimp::lumped
{
  /// Symmetric tridiagonal matrix: diag[i] = A(i,i), upper[i] = A(i,i+1) = A(i+1,i).
  struct TridiagonalMatrix
  {
    std::vector<double> diag;
    std::vector<double> upper; ///< size diag.size() − 1 (empty for a 1×1 matrix)

    TridiagonalMatrix() = default;
    explicit TridiagonalMatrix(const std::size_t n)
      : diag(n, 0.0)
      , upper(n > 0 ? n - 1 : 0, 0.0)
    {
    }

    std::size_t size() const { return diag.size(); }

    /// y = A·x (x, y of length size(); y may not alias x).
    void multiply(const double *x, double *y) const
    {
      const std::size_t n = diag.size();
      for (std::size_t i = 0; i < n; ++i)
        y[i] = diag[i] * x[i];
      for (std::size_t i = 0; i + 1 < n; ++i)
      {
        y[i] += upper[i] * x[i + 1];
        y[i + 1] += upper[i] * x[i];
      }
    }

    /// xᵀ·A·x.
    double quadratic_form(const double *x) const
    {
      double            s = 0.0;
      const std::size_t n = diag.size();
      for (std::size_t i = 0; i < n; ++i)
        s += diag[i] * x[i] * x[i];
      for (std::size_t i = 0; i + 1 < n; ++i)
        s += 2.0 * upper[i] * x[i] * x[i + 1];
      return s;
    }

    Eigen::MatrixXd to_dense() const
    {
      const auto      n = static_cast<Eigen::Index>(diag.size());
      Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
      for (Eigen::Index i = 0; i < n; ++i)
        a(i, i) = diag[static_cast<std::size_t>(i)];
      for (Eigen::Index i = 0; i + 1 < n; ++i)
        a(i, i + 1) = a(i + 1, i) = upper[static_cast<std::size_t>(i)];
      return a;
    }
  };

  /**
   * Thomas algorithm for a symmetric tridiagonal system, factorised once (no pivoting: valid for
   * the diagonally dominant / positive definite matrices M/Δt² + C/(2Δt) of the integrators).
   */
  class TridiagonalSolver
  {
  public:
    TridiagonalSolver() = default;
    explicit TridiagonalSolver(const TridiagonalMatrix &a)
      : upper_(a.upper)
      , c_prime_(a.size(), 0.0)
      , inv_denominator_(a.size(), 0.0)
    {
      const std::size_t n = a.size();
      for (std::size_t i = 0; i < n; ++i)
      {
        const double denominator = a.diag[i] - (i > 0 ? a.upper[i - 1] * c_prime_[i - 1] : 0.0);
        inv_denominator_[i]      = 1.0 / denominator;
        c_prime_[i]              = i + 1 < n ? a.upper[i] * inv_denominator_[i] : 0.0;
      }
    }

    /// Overwrite x (holding the right-hand side on entry) with A⁻¹·x.
    void solve_in_place(double *x) const
    {
      const std::size_t n = inv_denominator_.size();
      x[0] *= inv_denominator_[0];
      for (std::size_t i = 1; i < n; ++i)
        x[i] = (x[i] - upper_[i - 1] * x[i - 1]) * inv_denominator_[i];
      for (std::size_t i = n - 1; i-- > 0;)
        x[i] -= c_prime_[i] * x[i + 1];
    }

  private:
    std::vector<double> upper_;
    std::vector<double> c_prime_;
    std::vector<double> inv_denominator_;
  };
} // namespace kimp::lumped
