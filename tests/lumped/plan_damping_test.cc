// Damping in plan: modal damping keeps the given ratio in every mode of the coupled building
// (the damping matrix projected on the modes, and the decay of a free vibration started in one
// mode), where per-direction Rayleigh damping is exact at two modes per direction only.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <stdexcept>

#include "lumped/plan/plan_central_difference.h"
#include "lumped/structure/modal.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double pi   = 3.14159265358979323846;
    constexpr double zeta = 0.05;

    /// Three fixed-base levels on 20 m × 12 m outlines with different mass eccentricities (x, y
    /// and θ couple in every mode), each storey four columns at (±8, ±5) m.
    PlanBuilding eccentric_three_storeys(const PlanDampingModel model)
    {
      PlanBuilding b;
      b.damping        = model;
      b.damping_ratio  = zeta;
      const Point e[3] = {Point(1.5, -0.8), Point(-0.6, 1.1), Point(0.9, 0.4)};
      for (int i = 0; i < 3; ++i)
      {
        PlanLevel l;
        l.mass              = 1e6 - 1e5 * i;
        l.outline           = rectangle(20.0, 12.0);
        l.mass_eccentricity = e[i];
        b.levels.push_back(l);
        PlanStorey s;
        for (const double x : {-8.0, 8.0})
          for (const double y : {-5.0, 5.0})
            s.elements.push_back({Point(x, y), 20e6 * (1.0 - 0.2 * i), 30e6 * (1.0 - 0.2 * i)});
        b.storeys.push_back(s);
      }
      return b;
    }

    /// Ratio of mode k in C: φ_kᵀ·C·φ_k/(2ω_k) (φ mass-normalised).
    double modal_ratio(const Eigen::MatrixXd &c, const ModalProperties &modes, const int k)
    {
      const Eigen::VectorXd phi = modes.shapes.col(k);
      return phi.dot(c * phi) / (2.0 * modes.omega(k));
    }

    /// Free vibration started in mode k (no ground motion): the damping ratio from the decay of
    /// the modal coordinate η = φ_kᵀ·M·u between its first peak and the peak `cycles` later.
    double decay_ratio(const PlanBuilding &b, const int k, const int cycles)
    {
      const ModalProperties modes = plan_modes(b);
      PlanScene             scene;
      scene.building     = b;
      const double omega = modes.omega(k);
      PlanOptions  opt;
      opt.dt              = 2e-3 / omega; // ω·Δt = 0.002: the scheme's own error ~1e-6
      opt.output_interval = opt.dt;
      for (Eigen::Index i = 0; i < modes.shapes.rows(); ++i)
        opt.initial_displacement.push_back(0.01 * modes.shapes(i, k));
      const PlanModel    model(scene);
      const double       period = 2 * pi / omega;
      const PlanResponse r =
        PlanCentralDifference(model, opt)
          .run(along_angle(kimp::testing::zero_motion(opt.dt, (cycles + 1.5) * period), 0.0));
      const Eigen::VectorXd mphi = model.masses().cwiseProduct(modes.shapes.col(k));
      const std::size_t     n    = model.n_dofs();
      std::vector<double>   eta;
      for (std::size_t s = 0; s < r.history.time.size(); ++s)
        eta.push_back(
          mphi.dot(Eigen::Map<const Eigen::VectorXd>(r.history.displacement.data() + s * n,
                                                     static_cast<Eigen::Index>(n))));
      // Peaks of η (local maxima), refined by the parabola through the three samples.
      std::vector<double> peaks;
      for (std::size_t s = 1; s + 1 < eta.size(); ++s)
        if (eta[s] > eta[s - 1] && eta[s] >= eta[s + 1])
        {
          const double a = eta[s - 1], c = eta[s], d = eta[s + 1];
          const double denom = a - 2 * c + d;
          peaks.push_back(denom != 0.0 ? c - 0.125 * (a - d) * (a - d) / denom : c);
        }
      if (peaks.size() < static_cast<std::size_t>(cycles) + 1)
        throw std::logic_error("decay_ratio: too few peaks");
      const double delta = std::log(peaks[0] / peaks[static_cast<std::size_t>(cycles)]) / cycles;
      return delta / std::sqrt(4 * pi * pi + delta * delta); // δ = 2πζ/√(1 − ζ²)
    }
  } // namespace

  TEST(PlanDamping, ModalDampingMatrixHasTheRatioInEveryMode)
  {
    const PlanBuilding    b     = eccentric_three_storeys(PlanDampingModel::modal);
    const PlanDamping     d     = plan_damping(b);
    const ModalProperties modes = plan_modes(b);
    ASSERT_EQ(modes.omega.size(), 9);
    // Φᵀ·C·Φ = diag(2ζω): every ratio ζ, no coupling between modes.
    const Eigen::MatrixXd proj = modes.shapes.transpose() * d.matrix * modes.shapes;
    const double          big  = 2 * zeta * modes.omega.maxCoeff();
    for (int k = 0; k < 9; ++k)
    {
      EXPECT_NEAR(modal_ratio(d.matrix, modes, k), zeta, 1e-9 * zeta) << "mode " << k + 1;
      for (int j = 0; j < 9; ++j)
      {
        if (j != k)
        {
          EXPECT_LE(std::abs(proj(j, k)), 1e-9 * big) << "modes " << j + 1 << ", " << k + 1;
        }
      }
    }
    EXPECT_LE((d.matrix - d.matrix.transpose()).cwiseAbs().maxCoeff(), 0.0);
    // Rayleigh per direction, the same building: exact at no more than two modes per direction
    // block, the coupled middle modes damped less (this is what modal damping is for).
    const PlanDamping ray    = plan_damping(eccentric_three_storeys(PlanDampingModel::rayleigh));
    double            lowest = 1.0;
    for (int k = 0; k < 9; ++k)
      lowest = std::min(lowest, modal_ratio(ray.matrix, modes, k));
    EXPECT_LT(lowest, 0.9 * zeta);
  }

  TEST(PlanDamping, FreeVibrationInOneModeDecaysAtItsRatio)
  {
    // Modes 1, 5 and 9 of the coupled building, ten cycles each: the logarithmic decrement
    // gives ζ within 1e-3 (relative) with modal damping.
    const PlanBuilding b = eccentric_three_storeys(PlanDampingModel::modal);
    for (const int k : {0, 4, 8})
    {
      const double measured = decay_ratio(b, k, 10);
      std::printf("mode %d: zeta from the decay %.6g (given %.6g)\n", k + 1, measured, zeta);
      EXPECT_NEAR(measured, zeta, 1e-3 * zeta) << "mode " << k + 1;
    }
  }

  TEST(PlanDamping, ModalDampingOfAnIsolatedBuildingAddsTheIsolationDashpot)
  {
    // With isolators the modal part is formed with their initial stiffness; c_iso at level 0 is
    // added as with Rayleigh damping, so C − c_iso projects on the modes as diag(2ζω).
    PlanBuilding b = eccentric_three_storeys(PlanDampingModel::modal);
    b.storeys.pop_back(); // isolated: n − 1 storeys
    const auto iso = std::make_shared<PlanBilinearIsolator>(BilinearParameters{50e6, 6e6, 2e5});
    for (const Point &p : rectangle(16.0, 10.0))
      b.isolators.push_back({p, iso});
    b.isolation_damping_ratio = 0.1;
    const PlanDamping d       = plan_damping(b);
    EXPECT_GT(d.c_iso[0], 0.0);
    EXPECT_GT(d.c_iso[2], 0.0);
    Eigen::MatrixXd c = d.matrix;
    for (int dir = 0; dir < 3; ++dir)
      c(dir, dir) -= d.c_iso[dir];
    const ModalProperties modes = plan_modes(b);
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(modal_ratio(c, modes, k), zeta, 1e-9 * zeta) << "mode " << k + 1;
  }

  TEST(PlanDamping, ModalDampingRefusesBadRatios)
  {
    const PlanBuilding    b     = eccentric_three_storeys(PlanDampingModel::modal);
    const ModalProperties modes = plan_modes(b);
    const Eigen::VectorXd m     = plan_masses(b);
    EXPECT_THROW(modal_damping_matrix(m, modes, Eigen::VectorXd::Constant(9, 1.0)),
                 std::invalid_argument);
    EXPECT_THROW(modal_damping_matrix(m, modes, Eigen::VectorXd::Constant(8, 0.05)),
                 std::invalid_argument);
  }
} // namespace kimp::lumped::plan
