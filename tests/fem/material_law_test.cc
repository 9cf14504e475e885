// The constitutive-law interface of kimp::fem: plane-strain linear elasticity in Voigt form,
// per-quadrature-point trial / committed history (commit and revert), and the impact solver's
// quadrature-point internal force (used for history laws) against its K u fast path.
#include <gtest/gtest.h>
#include <iostream>
#include <random>

#include "fem/material_law.h"
#include "tests/fem/impact_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  /**
   * Test-only history law: elastic with a modulus reduced by the committed peak axial strain,
   * E_eff = E / (1 + peak / eps_ref); history[0] = peak |eps_xx| (trial: including this strain).
   * The stress depends on the committed history only, so commit / revert are observable.
   */
  class PeakStrainSofteningLaw final : public MaterialLaw
  {
  public:
    PeakStrainSofteningLaw(const Material &m, double eps_ref)
      : elastic_(m)
      , eps_ref_(eps_ref)
    {
    }
    unsigned int n_history() const override { return 1; }
    VoigtStress
    stress(const VoigtStrain &strain, const double *committed, double *trial) const override
    {
      trial[0]       = std::max(committed[0], std::abs(strain[0]));
      VoigtStress  s = elastic_.stress(strain, nullptr, nullptr);
      const double f = factor(committed);
      for (double &x : s)
        x *= f;
      return s;
    }
    VoigtTangent tangent(const VoigtStrain &strain, const double *committed) const override
    {
      VoigtTangent d = elastic_.tangent(strain, nullptr);
      for (double &x : d)
        x *= factor(committed);
      return d;
    }

  private:
    double factor(const double *committed) const { return 1 / (1 + committed[0] / eps_ref_); }
    LinearElasticLaw elastic_;
    double           eps_ref_;
  };

  /** Linear elasticity through the quadrature-point path: not is_linear(), one history value. */
  class CellwiseElasticLaw final : public MaterialLaw
  {
  public:
    explicit CellwiseElasticLaw(const Material &m)
      : elastic_(m)
    {
    }
    unsigned int n_history() const override { return 1; }
    VoigtStress
    stress(const VoigtStrain &strain, const double *committed, double *trial) const override
    {
      trial[0] = std::max(committed[0], std::abs(strain[0]));
      return elastic_.stress(strain, nullptr, nullptr);
    }
    VoigtTangent tangent(const VoigtStrain &strain, const double *) const override
    {
      return elastic_.tangent(strain, nullptr);
    }

  private:
    LinearElasticLaw elastic_;
  };

  TEST(LinearElasticLaw, StressIsLamePlaneStrainAndTangentTimesStrain)
  {
    constexpr double tolerance = 1e-12;
    const Material   m{30e9, 0.2, 2400};
    const double     lambda =
      m.youngs_modulus * m.poisson_ratio / ((1 + m.poisson_ratio) * (1 - 2 * m.poisson_ratio));
    const double                           mu = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
    const LinearElasticLaw                 law(m);
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> strain(-1e-3, 1e-3);
    EXPECT_TRUE(law.is_linear());
    EXPECT_EQ(law.n_history(), 0u);
    for (int trial = 0; trial < 5; ++trial)
    {
      const VoigtStrain  e{{strain(rng), strain(rng), strain(rng)}};
      const VoigtStress  s     = law.stress(e, nullptr, nullptr);
      const VoigtTangent d     = law.tangent(e, nullptr);
      const double       scale = m.youngs_modulus * 1e-3;
      // sigma = lambda tr(eps) I + 2 mu eps, with gamma_xy = 2 eps_xy.
      EXPECT_NEAR(s[0], lambda * (e[0] + e[1]) + 2 * mu * e[0], tolerance * scale);
      EXPECT_NEAR(s[1], lambda * (e[0] + e[1]) + 2 * mu * e[1], tolerance * scale);
      EXPECT_NEAR(s[2], mu * e[2], tolerance * scale);
      for (unsigned int r = 0; r < 3; ++r)
        EXPECT_NEAR(s[r],
                    d[3 * r] * e[0] + d[3 * r + 1] * e[1] + d[3 * r + 2] * e[2],
                    tolerance * scale)
          << "row " << r << ", trial " << trial;
    }
  }

  TEST(QuadraturePointHistory, CommitAndRevertActPerQuadraturePoint)
  {
    constexpr double             tolerance = 1e-12;
    const Material               m{30e9, 0.2, 2400};
    constexpr double             eps_ref = 1e-3;
    const PeakStrainSofteningLaw law(m, eps_ref);
    const LinearElasticLaw       elastic(m);
    QuadraturePointHistory       h;
    h.reinit(2, 4, law.n_history());
    h.initialize_cell(0, law);
    h.initialize_cell(1, law);
    const VoigtStrain e{{2e-3, 0, 0}};
    const double      s_elastic = elastic.stress(e, nullptr, nullptr)[0];

    // A trial evaluation leaves the committed history and the stress of the next one unchanged.
    EXPECT_NEAR(law.stress(e, h.committed(0, 1), h.trial(0, 1))[0],
                s_elastic,
                tolerance * s_elastic);
    EXPECT_DOUBLE_EQ(h.trial(0, 1)[0], 2e-3);
    EXPECT_DOUBLE_EQ(h.committed(0, 1)[0], 0.0);
    h.revert();
    EXPECT_DOUBLE_EQ(h.trial(0, 1)[0], 0.0);
    EXPECT_NEAR(law.stress(e, h.committed(0, 1), h.trial(0, 1))[0],
                s_elastic,
                tolerance * s_elastic);

    // Committed: this point (only) remembers the peak and is softer, by 1 / (1 + 2e-3 / 1e-3).
    h.commit();
    EXPECT_DOUBLE_EQ(h.committed(0, 1)[0], 2e-3);
    for (const auto &[cell, q] : {std::pair{0u, 0u}, std::pair{0u, 2u}, std::pair{1u, 1u}})
    {
      EXPECT_DOUBLE_EQ(h.committed(cell, q)[0], 0.0) << "cell " << cell << ", q " << q;
      EXPECT_NEAR(law.stress(e, h.committed(cell, q), h.trial(cell, q))[0],
                  s_elastic,
                  tolerance * s_elastic)
        << "cell " << cell << ", q " << q;
    }
    EXPECT_NEAR(law.stress(e, h.committed(0, 1), h.trial(0, 1))[0],
                s_elastic / 3,
                tolerance * s_elastic);

    // A smaller strain afterwards keeps the committed peak (memory), a rejected larger one is
    // forgotten by revert().
    const VoigtStrain small{{0.5e-3, 0, 0}};
    law.stress(small, h.committed(0, 1), h.trial(0, 1));
    h.commit();
    EXPECT_DOUBLE_EQ(h.committed(0, 1)[0], 2e-3);
    law.stress({{5e-3, 0, 0}}, h.committed(0, 1), h.trial(0, 1));
    h.revert();
    EXPECT_DOUBLE_EQ(h.committed(0, 1)[0], 2e-3);
    EXPECT_DOUBLE_EQ(h.trial(0, 1)[0], 2e-3);
  }

  TEST(MaterialLaw, QuadraturePointInternalForceMatchesStiffnessMatrixPath)
  {
    // The same elastic law through the history path (stress at every Gauss point, commit per
    // step) and through K u gives the same force history, explicit and implicit.
    constexpr double tolerance_explicit = 1e-10;
    constexpr double tolerance_implicit = 1e-6; // Newton stops at a relative residual of 1e-10
    auto             p = bar_parameters(write_two_bars(1.0, 0.1, 1e-4, 4, "bars_law.msh"));
    for (const auto integrator : {ImpactParameters::Integrator::explicit_central_difference,
                                  ImpactParameters::Integrator::implicit_newmark})
    {
      p.integrator = integrator;
      p.material_laws.clear();
      const auto reference = run_impact(p, MPI_COMM_WORLD, nullptr);
      for (const unsigned int id : {kimp::geometry::slab_material, kimp::geometry::wall_material})
        p.material_laws[id] = std::make_shared<const CellwiseElasticLaw>(bar_material);
      const auto   cellwise  = run_impact(p, MPI_COMM_WORLD, nullptr);
      const bool   implicit  = integrator == ImpactParameters::Integrator::implicit_newmark;
      const double tolerance = implicit ? tolerance_implicit : tolerance_explicit;
      ASSERT_EQ(cellwise.history.time.size(), reference.history.time.size());
      const double f_max = reference.summary.peak_force_raw;
      double       worst = 0;
      for (std::size_t i = 0; i < reference.history.time.size(); ++i)
        worst = std::max(worst,
                         std::abs(cellwise.history.contact_force[i] -
                                  reference.history.contact_force[i]));
      EXPECT_LT(worst, tolerance * f_max) << (implicit ? "implicit" : "explicit");
      if (rank() == 0)
        std::cout << (implicit ? "implicit" : "explicit")
                  << ": max |dF| / F_max = " << worst / f_max << ", wall time K u "
                  << reference.summary.wall_seconds << " s, quadrature points "
                  << cellwise.summary.wall_seconds << " s\n";
    }
  }

  TEST(MaterialLaw, SofteningWallLowersTheContactForce)
  {
    // A wall that softens with its committed peak strain has a lower impedance once loaded: the
    // two-bar plateau rho c A v / 2 (c ~ sqrt(E)) drops below the elastic one, the impulse
    // (momentum exchange) stays close.
    auto       p       = bar_parameters(write_two_bars(1.0, 0.1, 1e-4, 4, "bars_soft.msh"));
    const auto elastic = run_impact(p, MPI_COMM_WORLD, nullptr);
    // Plateau strain v / (2 c) = 1 m/s / (2 * 3536 m/s) = 1.4e-4: eps_ref = 1e-4 softens a lot.
    p.material_laws[kimp::geometry::wall_material] =
      std::make_shared<const PeakStrainSofteningLaw>(bar_material, 1e-4);
    const auto soft = run_impact(p, MPI_COMM_WORLD, nullptr);
    if (rank() == 0)
      std::cout << "elastic wall:   " << summary_line(elastic)
                << "\nsoftening wall: " << summary_line(soft) << '\n';
    EXPECT_LT(soft.summary.peak_force, 0.9 * elastic.summary.peak_force);
    EXPECT_GT(soft.summary.contact_duration, elastic.summary.contact_duration);
  }
} // namespace
