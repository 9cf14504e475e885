// Modal analysis and Rayleigh coefficients against closed forms (Chopra §10-11).
#include <cmath>
#include <gtest/gtest.h>
#include <random>

#include "lumped/structure/modal.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double rel_tol = 1e-12;
  }

  TEST(ModalAnalysis, TwoDofClosedForm)
  {
    // Two equal masses m, two equal springs k (fixed base): ω² = (3 ∓ √5)/2 · k/m.
    const double    m = 2.0e5, k = 3.0e8;
    Eigen::VectorXd mass(2);
    mass << m, m;
    Eigen::MatrixXd K(2, 2);
    K << 2 * k, -k, -k, k;
    const ModalProperties p = modal_analysis(mass, K);
    EXPECT_NEAR(p.omega(0), std::sqrt((3 - std::sqrt(5.0)) / 2 * k / m), rel_tol * p.omega(0));
    EXPECT_NEAR(p.omega(1), std::sqrt((3 + std::sqrt(5.0)) / 2 * k / m), rel_tol * p.omega(1));
    EXPECT_NEAR(p.period(0), 2 * M_PI / p.omega(0), rel_tol);
  }

  TEST(ModalAnalysis, ShapesAreMassOrthonormal)
  {
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> md(1e5, 4e5), kd(1e8, 8e8);
    const int                              n = 6;
    Eigen::VectorXd                        mass(n);
    Eigen::MatrixXd                        K = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
    {
      mass(i)        = md(rng);
      const double k = kd(rng);
      K(i, i) += k;
      if (i > 0)
      {
        K(i - 1, i - 1) += k;
        K(i - 1, i) -= k;
        K(i, i - 1) -= k;
      }
    }
    const ModalProperties p  = modal_analysis(mass, K);
    const Eigen::MatrixXd mo = p.shapes.transpose() * mass.asDiagonal() * p.shapes;
    const Eigen::MatrixXd ko = p.shapes.transpose() * K * p.shapes;
    EXPECT_LT((mo - Eigen::MatrixXd::Identity(n, n)).norm(), 1e-10);
    EXPECT_LT((ko - Eigen::MatrixXd(p.omega.array().square().matrix().asDiagonal())).norm(),
              1e-10 * ko.norm());
  }

  TEST(RayleighCoefficients, ReproduceTargetRatiosAtBothModes)
  {
    const double w1 = 3.7, w2 = 91.2, z1 = 0.02, z2 = 0.05;
    const auto   r = rayleigh_coefficients(w1, w2, z1, z2);
    EXPECT_NEAR(r.a / (2 * w1) + r.b * w1 / 2, z1, rel_tol);
    EXPECT_NEAR(r.a / (2 * w2) + r.b * w2 / 2, z2, rel_tol);
    const auto single = rayleigh_coefficients(5.0, 5.0, 0.05, 0.05);
    EXPECT_NEAR(single.a / 10 + single.b * 2.5, 0.05, rel_tol);
    EXPECT_THROW(rayleigh_coefficients(0.0, 1.0, 0.05, 0.05), std::invalid_argument);
    EXPECT_THROW(modal_analysis(Eigen::VectorXd::Ones(2), Eigen::MatrixXd::Zero(2, 2)),
                 std::invalid_argument);
  }
} // namespace kimp::lumped
