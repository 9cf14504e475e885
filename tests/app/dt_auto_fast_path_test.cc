// `dt: auto`: the fast variable-step path (fixed-size products, a cached inverse per step pair,
// laws skipped while open) against the reference path (dynamic LU solves, every law every step)
// on every shipped lumped scene, over the full runs with histories: the same steps, the same
// impacts, peaks, histories and energies to round-off. Scenes on PEER records are skipped when
// the records are not found.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_scene.h"
#include "lumped/integrators/adaptive_step.h"
#include "lumped/structure/pounding_model.h"
#include "tests/app/shipped_lumped_scenes.h"
#include "tests/support/files.h"
#include "tests/support/response_compare.h"

namespace
{
  using namespace kimp;

  // Same steps and the same physics; the algebra differs in round-off only (an inverse product
  // against an LU solve, reciprocals against divisions, C·v carried from the last step). Measured
  // over the full runs, peaks, histories and energies: <= 4.2e-13 on every shipped scene.
  constexpr double tolerance = 1e-9;
  /// The steps: a step shortened to end where a gap closes is −δ/δ̇ with δ the small difference
  /// of two displacements, so its relative round-off is larger (measured 1.1e-8, the neighbours).
  constexpr double step_tolerance = 1e-6;

  lumped::CentralDifferenceOptions options(const app::IntegrationScene &in)
  {
    lumped::CentralDifferenceOptions opt;
    opt.safety                   = in.safety;
    opt.expected_max_penetration = in.expected_max_penetration;
    opt.duration                 = in.duration.value_or(0.0);
    opt.output_interval          = 0.01; // histories compared too
    return opt;
  }

  TEST(DtAutoFastPath, EveryShippedLumpedSceneAgreesWithTheReferencePath)
  {
    std::size_t compared = 0;
    kimp::testing::for_each_shipped_lumped_case(
      [&](const kimp::testing::ShippedCase &c)
      {
        const lumped::PoundingModel model(app::make_pounding_scene(c.scene));
        lumped::AdaptiveStepOptions adaptive;
        adaptive.contact_steps = c.scene.integration.contact_steps;
        lumped::AdaptiveStepReport fast_report, ref_report;
        std::vector<double>        fast_steps, ref_steps;
        const lumped::Response     fast =
          lumped::AdaptiveCentralDifference(model, options(c.scene.integration), adaptive)
            .run(c.motion, &fast_report, &fast_steps);
        adaptive.reference_kernel = true;
        const lumped::Response ref =
          lumped::AdaptiveCentralDifference(model, options(c.scene.integration), adaptive)
            .run(c.motion, &ref_report, &ref_steps);
        const std::string &what = c.what;
        const double       d    = kimp::testing::max_relative_difference(fast, ref, what);
        std::cout << "  " << what << " (" << model.n_dofs() << " DOFs, " << fast.n_impacts()
                  << " impacts, " << fast.n_steps << " steps): " << d << "\n";
        EXPECT_LT(d, tolerance) << what;
        EXPECT_EQ(fast.n_steps, ref.n_steps) << what;
        ASSERT_EQ(fast_steps.size(), ref_steps.size()) << what;
        double step_difference = 0.0;
        for (std::size_t i = 0; i < ref_steps.size(); ++i)
          step_difference =
            std::max(step_difference, std::abs(fast_steps[i] - ref_steps[i]) / ref_steps[i]);
        EXPECT_LT(step_difference, step_tolerance) << what;
        EXPECT_EQ(fast_report.estimate_steps, ref_report.estimate_steps) << what;
        EXPECT_EQ(fast.history.time, ref.history.time) << what;
        EXPECT_NEAR(fast_report.force_error, ref_report.force_error, 1e-9) << what;
        ++compared;
      });
    std::cout << "  " << compared << " cases compared\n";
    EXPECT_GT(compared, 0U);
  }
} // namespace
