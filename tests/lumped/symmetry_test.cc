// Symmetry (docs/architecture.md "Tests"): symmetric system matrices, and a mirror-symmetric scene
// (walls or neighbours on both sides, equal gaps) under the negated record gives the mirrored
// response.
#include <cmath>
#include <gtest/gtest.h>

#include "lumped/integrators/central_difference.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double mirror_rel_tol = 1e-9;

    GroundMotion negated(GroundMotion g)
    {
      for (double &a : g.acceleration)
        a = -a;
      return g;
    }

    void expect_mirrored(const Response &a, const Response &b, const std::vector<std::size_t> &swap)
    {
      double peak = 0.0;
      for (const double p : a.peak_displacement)
        peak = std::max(peak, p);
      ASSERT_EQ(a.history.displacement.size(), b.history.displacement.size());
      for (std::size_t i = 0; i < a.history.displacement.size(); ++i)
        ASSERT_NEAR(a.history.displacement[i], -b.history.displacement[i], mirror_rel_tol * peak)
          << "sample " << i / a.n_dofs << " dof " << i % a.n_dofs;
      for (std::size_t i = 0; i < a.n_dofs; ++i)
        EXPECT_NEAR(a.peak_absolute_acceleration[i],
                    b.peak_absolute_acceleration[i],
                    mirror_rel_tol * a.peak_absolute_acceleration[i]);
      ASSERT_EQ(a.contacts.size(), swap.size());
      for (std::size_t c = 0; c < swap.size(); ++c)
      {
        const ContactResult &x = a.contacts[c];
        const ContactResult &y = b.contacts[swap[c]];
        EXPECT_NEAR(x.peak_force, y.peak_force, mirror_rel_tol * (x.peak_force + 1.0)) << x.name;
        EXPECT_EQ(x.impacts.size(), y.impacts.size()) << x.name;
      }
    }

    ForceLawSpec kv()
    {
      return kimp::testing::contact_law("modified_kelvin_voigt", 2.5e9);
    }
  } // namespace

  TEST(Symmetry, SystemMatricesAreSymmetric)
  {
    PoundingScene scene;
    scene.building = reference_isolated_building(5);
    AdjacentBuilding nb;
    nb.building          = reference_fixed_base_building(6);
    nb.law               = force_law_factory(kv());
    scene.left_neighbour = nb;
    const PoundingModel   m(scene);
    const Eigen::MatrixXd k = m.initial_stiffness_matrix();
    const Eigen::MatrixXd c = m.damping().to_dense();
    EXPECT_LE((k - k.transpose()).norm(), 1e-15 * k.norm());
    EXPECT_LE((c - c.transpose()).norm(), 1e-15 * c.norm());
    // Positive definite: all modes have ω > 0 (throws otherwise).
    EXPECT_GT(m.modes().omega(0), 0.0);
  }

  TEST(Symmetry, MirroredSceneWithWallsGivesMirroredResponse)
  {
    const GroundMotion g     = kimp::testing::near_fault_motion(10.0);
    PoundingScene      scene = kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, 0.10);
    scene.basement           = true;
    CentralDifferenceOptions opt;
    opt.dt = 2e-4;
    const CentralDifference cdm(PoundingModel(scene), opt);
    const Response          a = cdm.run(g);
    const Response          b = cdm.run(negated(g));
    ASSERT_GT(a.n_impacts(), 0u);
    // contacts: left (floor 0, 1), right (floor 0, 1)
    expect_mirrored(a, b, {2, 3, 0, 1});
    EXPECT_NEAR(a.contacts[0].permanent_indentation, b.contacts[2].permanent_indentation, 1e-12);
  }

  TEST(Symmetry, MirroredSceneWithNeighboursGivesMirroredResponse)
  {
    const GroundMotion g = kimp::testing::near_fault_motion(8.0);
    PoundingScene      scene;
    scene.building = reference_isolated_building(4);
    AdjacentBuilding nb;
    nb.building           = reference_fixed_base_building(4);
    nb.separation         = 0.08;
    nb.law                = force_law_factory(kv());
    scene.left_neighbour  = nb;
    scene.right_neighbour = nb;
    CentralDifferenceOptions opt;
    opt.dt = 2e-4;
    const PoundingModel model(scene);
    const Response      a = CentralDifference(model, opt).run(g);
    const Response      b = CentralDifference(model, opt).run(negated(g));
    ASSERT_GT(a.n_impacts(), 0u);
    // The mirror also swaps the two neighbours' DOF blocks: compare the main building and the
    // swapped neighbours through their peaks.
    for (std::size_t i = 0; i < 5; ++i)
      EXPECT_NEAR(a.peak_displacement[i],
                  b.peak_displacement[i],
                  mirror_rel_tol * a.peak_displacement[i]);
    for (std::size_t i = 0; i < 4; ++i)
    {
      EXPECT_NEAR(a.peak_displacement[5 + i],
                  b.peak_displacement[9 + i],
                  mirror_rel_tol * a.peak_displacement[5 + i]);
      EXPECT_NEAR(a.contacts[i].peak_force,
                  b.contacts[4 + i].peak_force,
                  mirror_rel_tol * (a.contacts[i].peak_force + 1.0));
    }
  }
} // namespace kimp::lumped
