// Energy balance E_0 + W_in = E_kin + E_strain + E_viscous + E_hysteretic + W_contact
// (docs/architecture.md "Tests") for the thesis building, without and with impacts, for both
// integrators.
#include <cmath>
#include <gtest/gtest.h>

#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double balance_tol = 0.01; // docs/physics.md: closes to < 1 %

    void expect_balanced(const Response &r, const std::string &what)
    {
      const EnergyBalance &e = r.energy;
      EXPECT_LT(e.relative_error, balance_tol) << what;
      EXPECT_LT(e.max_relative_error, balance_tol) << what;
      EXPECT_GT(e.input, 0.0) << what;
      EXPECT_GE(e.viscous, 0.0) << what;
      EXPECT_GE(e.hysteretic, 0.0) << what;
    }
  } // namespace

  TEST(EnergyBalance, ClosesWithoutImpacts)
  {
    PoundingScene scene;
    scene.building = reference_isolated_building(4);
    CentralDifferenceOptions opt;
    opt.dt = 1e-3;
    const Response r =
      CentralDifference(PoundingModel(scene), opt).run(kimp::testing::near_fault_motion(12.0));
    expect_balanced(r, "no walls, bilinear isolator");
    // The bilinear isolator yields: most of the input goes to hysteresis and viscous damping.
    EXPECT_GT(r.energy.hysteretic, 0.2 * r.energy.input);
    EXPECT_EQ(r.energy.contact_work, 0.0);

    scene.building = reference_isolated_building_linear(4, 25e6);
    const Response lin =
      CentralDifference(PoundingModel(scene), opt).run(kimp::testing::near_fault_motion(12.0));
    expect_balanced(lin, "no walls, linear isolator");
    EXPECT_EQ(lin.energy.hysteretic, 0.0);
  }

  TEST(EnergyBalance, ClosesWithElasticImpacts)
  {
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;
    const Response r =
      CentralDifference(PoundingModel(kimp::testing::walled_scene("linear", 2.5e9, 0.10)), opt)
        .run(kimp::testing::near_fault_motion(12.0));
    ASSERT_GT(r.n_impacts(), 0u);
    expect_balanced(r, "linear law");
    // An elastic law returns what it stores: no net contact work once the walls are free.
    EXPECT_LT(std::abs(r.energy.contact_work), 1e-3 * r.energy.input);
    EXPECT_EQ(r.energy.impact_dissipated, 0.0);
  }

  TEST(EnergyBalance, ClosesWithDissipativeImpacts)
  {
    for (const std::string name : {"kelvin_voigt", "modified_kelvin_voigt"})
    {
      CentralDifferenceOptions opt;
      opt.dt = 1e-4;
      const Response r =
        CentralDifference(PoundingModel(kimp::testing::walled_scene(name, 2.5e9, 0.10)), opt)
          .run(kimp::testing::near_fault_motion(12.0));
      ASSERT_GT(r.n_impacts(), 0u) << name;
      expect_balanced(r, name);
      // The integrator's contact work equals what the laws booked as dissipated.
      EXPECT_GT(r.energy.impact_dissipated, 0.0) << name;
      EXPECT_NEAR(r.energy.contact_work,
                  r.energy.impact_dissipated,
                  0.02 * r.energy.impact_dissipated)
        << name;
    }
    for (const std::string name : {"jankowski", "hysteretic"})
    {
      CentralDifferenceOptions opt;
      opt.dt           = 1e-4;
      const double   k = 750e3 / std::pow(1e-3, 1.5); // 750 kN/mm^1.5
      const Response r =
        CentralDifference(PoundingModel(kimp::testing::walled_scene(name, k, 0.10)), opt)
          .run(kimp::testing::near_fault_motion(12.0));
      ASSERT_GT(r.n_impacts(), 0u) << name;
      expect_balanced(r, name);
    }
  }

  TEST(EnergyBalance, ClosesForTheImplicitMethod)
  {
    NewmarkOptions opt;
    opt.dt = 5e-4;
    const Response r =
      NewmarkIntegrator(PoundingModel(kimp::testing::walled_scene("kelvin_voigt", 2.5e9, 0.10)),
                        opt)
        .run(kimp::testing::near_fault_motion(12.0));
    ASSERT_GT(r.n_impacts(), 0u);
    expect_balanced(r, "Newmark, Kelvin-Voigt");
  }

  TEST(EnergyBalance, ClosesWithAdjacentBuildings)
  {
    PoundingScene scene;
    scene.building = reference_isolated_building(4);
    ForceLawSpec spec;
    spec.law       = "kelvin_voigt";
    spec.stiffness = 2.5e9;
    spec.cor       = 0.7;
    for (const bool right : {false, true})
    {
      AdjacentBuilding nb;
      nb.building   = reference_fixed_base_building(right ? 4 : 3);
      nb.separation = 0.08;
      nb.law        = force_law_factory(spec);
      (right ? scene.right_neighbour : scene.left_neighbour) = nb;
    }
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;
    const Response r =
      CentralDifference(PoundingModel(scene), opt).run(kimp::testing::near_fault_motion(12.0));
    ASSERT_GT(r.n_impacts(), 0u);
    expect_balanced(r, "two neighbours");
  }
} // namespace kimp::lumped
