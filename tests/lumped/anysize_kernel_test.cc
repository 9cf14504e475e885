// The any-size fused kernel of the central difference method (models of more than 8 DOFs) against
// the block-tridiagonal reference kernel: an isolated building between neighbours with walls, a
// basement, bumpers, tall buildings; bitwise equal results for every vector width and blocking.
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <string>
#include <utility>

#include "lumped/integrators/central_difference.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/lumped_scenes.h"
#include "tests/support/response_compare.h"

namespace kimp::lumped
{
  namespace
  {
    using kimp::testing::expect_identical;
    using kimp::testing::max_relative_difference;

    // Against the reference kernel: same physics, different algebra (increment form with dense
    // products vs right-hand side and Thomas/dense block solve), so they differ by round-off,
    // mostly the reference kernel's (integrator_test.cc: on an undamped SDOF its round-off
    // reaches 6.6e-7 at 1e-5 s where the increment form stays at 1e-13), which impacts amplify.
    // Observed over 12 s at 1e-4 s: <= 1.7e-9 without contacts, <= 5.2e-9 with pounding (the
    // <= 8-DOF fused kernel: <= 1.3e-9 and <= 4.5e-9); tolerances: measured × ~5.
    constexpr double linear_tol   = 1e-8;
    constexpr double pounding_tol = 3e-8;
    // Against the <= 8-DOF fused kernel (same algebra, products summed in another order):
    // observed <= 4.7e-14 over 12 s with pounding (25 impacts); tolerance 1e-12.
    constexpr double same_algebra_tol = 1e-12;

    AdjacentBuilding neighbour(const int storeys, const double separation)
    {
      AdjacentBuilding nb;
      nb.building   = reference_fixed_base_building(storeys);
      nb.separation = separation;
      nb.law        = force_law_factory(kimp::testing::contact_law("modified_kelvin_voigt", 2.5e9));
      return nb;
    }

    /// The thesis building between walls at `gap` and neighbours of `left` and `right` storeys
    /// (0: none) at `separation`.
    PoundingScene
    between_neighbours(const double gap, const int left, const int right, const double separation)
    {
      PoundingScene scene = kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, gap);
      if (left > 0)
        scene.left_neighbour = neighbour(left, separation);
      if (right > 0)
        scene.right_neighbour = neighbour(right, separation);
      return scene;
    }

    /// The same run with the any-size kernel (which must be chosen) and the reference kernel.
    double anysize_against_reference(const PoundingModel     &model,
                                     CentralDifferenceOptions opt,
                                     const GroundMotion      &g,
                                     const std::string       &what)
    {
      EXPECT_GT(model.n_dofs(), 8u) << what;
      const Response any = kimp::testing::stepped_run(model, opt, g, true, what);
      opt.kernel         = CdmKernel::reference;
      const Response ref = CentralDifference(model, opt).run(g);
      const double   d   = max_relative_difference(any, ref, what);
      std::cout << "  any-size vs reference, " << what << " (" << model.n_dofs() << " DOFs): " << d
                << " (impacts " << any.n_impacts() << ")\n";
      return d;
    }
  } // namespace

  TEST(AnySizeKernel, AgreesWithTheReferenceKernel)
  {
    const GroundMotion       g = kimp::testing::near_fault_motion(12.0);
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;

    PoundingScene tall;
    tall.building = reference_fixed_base_building(12);
    EXPECT_LT(anysize_against_reference(PoundingModel(tall), opt, g, "fixed base, 12 storeys"),
              linear_tol);
    PoundingScene iso_tall;
    iso_tall.building = reference_isolated_building(15);
    EXPECT_LT(
      anysize_against_reference(PoundingModel(iso_tall), opt, g, "isolated, 15 storeys, no walls"),
      linear_tol);
    CentralDifferenceOptions moving = opt;
    moving.initial_displacement.assign(13, 0.01);
    moving.initial_velocity.assign(13, 0.3);
    EXPECT_LT(anysize_against_reference(PoundingModel(between_neighbours(0.10, 4, 4, 0.10)),
                                        moving,
                                        g,
                                        "initial conditions, both neighbours"),
              pounding_tol);

    struct Neighbours
    {
      double      gap;
      int         left, right;
      double      separation;
      const char *what;
    };
    for (const Neighbours &c :
         {Neighbours{0.10, 4, 4, 0.10, "walls and both neighbours, 4 + 4 storeys"},
          Neighbours{0.10, 6, 6, 0.10, "walls and both neighbours, 6 + 6 storeys"},
          Neighbours{0.12, 2, 5, 0.17, "walls and both neighbours, 2 + 5 storeys"},
          Neighbours{0.10, 0, 6, 0.10, "wall and a 6-storey neighbour"}})
      EXPECT_LT(anysize_against_reference(
                  PoundingModel(between_neighbours(c.gap, c.left, c.right, c.separation)),
                  opt,
                  g,
                  c.what),
                pounding_tol);
    PoundingScene basement = between_neighbours(0.10, 4, 4, 0.12);
    basement.basement      = true;
    EXPECT_LT(anysize_against_reference(PoundingModel(basement), opt, g, "basement, neighbours"),
              pounding_tol);
    // The bumper example of the scenes with a smaller gap (see integrator_test.cc).
    PoundingScene bumpers = between_neighbours(0.12, 4, 4, 0.14);
    bumpers.left_wall     = kimp::testing::bumper_wall(0.12);
    bumpers.right_wall    = kimp::testing::bumper_wall(0.12);
    EXPECT_LT(anysize_against_reference(PoundingModel(bumpers), opt, g, "bumpers, neighbours"),
              pounding_tol);
  }

  TEST(AnySizeKernel, AgreesWithTheFusedKernelOnSmallModels)
  {
    // Forced onto <= 8-DOF models (CdmKernel::any_size), the any-size kernel does the fused
    // kernel's arithmetic with the products summed in another order: round-off apart, equal.
    const GroundMotion       g = kimp::testing::near_fault_motion(12.0);
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;
    for (const auto &[what, scene] :
         {std::pair{std::string("walls both sides"),
                    kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, 0.10)},
          std::pair{std::string("wall and a 3-storey neighbour"),
                    between_neighbours(0.10, 0, 3, 0.04)}})
    {
      const PoundingModel model(scene);
      opt.kernel              = CdmKernel::automatic;
      const Response fused    = CentralDifference(model, opt).run(g);
      opt.kernel              = CdmKernel::any_size;
      const Response any_size = CentralDifference(model, opt).run(g);
      const double   d        = max_relative_difference(any_size, fused, what);
      std::cout << "  any-size vs fused, " << what << ": " << d << " (impacts " << fused.n_impacts()
                << ")\n";
      EXPECT_LT(d, same_algebra_tol) << what;
    }
  }

  TEST(AnySizeKernel, AutomaticChoiceLeavesLargeBlocksToTheReferenceKernel)
  {
    // Dense products per building block pay up to 16 DOFs per block (the 15-storey isolated
    // building); a 30-storey building runs the reference kernel's Thomas sweeps unless asked.
    const GroundMotion       g = kimp::testing::near_fault_motion(6.0);
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;
    for (const auto &[storeys, fused] : {std::pair{15u, true}, std::pair{30u, false}})
    {
      PoundingScene scene;
      scene.building = reference_isolated_building(storeys);
      EXPECT_EQ(kimp::testing::uses_fused_kernel(PoundingModel(scene), opt, g), fused)
        << storeys << " storeys";
    }
    opt.kernel = CdmKernel::any_size;
    PoundingScene scene;
    scene.building = reference_isolated_building(30);
    EXPECT_TRUE(kimp::testing::uses_fused_kernel(PoundingModel(scene), opt, g));
  }

  TEST(AnySizeKernel, IsBitwiseIndependentOfTheVectorWidthAndTheStepping)
  {
    // SSE2, AVX2 and AVX-512F variants (those the processor has): the same operations per DOF
    // lane in the same order, and the columns a wider vector adds are exact zeros.
    const GroundMotion       g = kimp::testing::near_fault_motion(6.0);
    CentralDifferenceOptions opt;
    opt.dt = 1e-4;
    const PoundingModel model(between_neighbours(0.06, 5, 3, 0.06));
    Response            sse2;
    ASSERT_NO_FATAL_FAILURE(kimp::testing::expect_independent_of_vector_width(model, opt, g, sse2));
    // Step by step equals the whole run.
    opt.vector_lanes = 0;
    const CentralDifference  cdm(model, opt);
    CentralDifferenceStepper stepper(cdm);
    stepper.init(g);
    while (!stepper.finished())
      stepper.advance(37);
    expect_identical(stepper.response(), sse2, "advance(37)");
  }
} // namespace kimp::lumped
