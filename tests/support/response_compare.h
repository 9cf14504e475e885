// Comparing two lumped Responses: bitwise (expect_identical) and by the largest relative
// difference of peaks, histories and energies (max_relative_difference), for kernel tests; and a
// run against itself at every SIMD width (expect_independent_of_vector_width); the kernel a
// central difference stepper picks (uses_fused_kernel, stepped_run).
#pragma once

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <string>

#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/response.h"

namespace kimp::testing
{
  using kimp::lumped::Response;

  /// Every recorded number of two responses is bitwise equal (same operations in the same
  /// order: a restart or a different stepping pattern must not change a single bit).
  inline void expect_identical(const Response &a, const Response &b, const std::string &what)
  {
    EXPECT_EQ(a.n_steps, b.n_steps) << what;
    EXPECT_EQ(a.peak_displacement, b.peak_displacement) << what;
    EXPECT_EQ(a.peak_absolute_acceleration, b.peak_absolute_acceleration) << what;
    EXPECT_EQ(a.peak_interstorey_drift, b.peak_interstorey_drift) << what;
    EXPECT_EQ(a.history.time, b.history.time) << what;
    EXPECT_EQ(a.history.displacement, b.history.displacement) << what;
    EXPECT_EQ(a.history.absolute_acceleration, b.history.absolute_acceleration) << what;
    EXPECT_EQ(a.history.contact_force, b.history.contact_force) << what;
    EXPECT_EQ(a.history.energy_error, b.history.energy_error) << what;
    EXPECT_EQ(a.energy.input, b.energy.input) << what;
    EXPECT_EQ(a.energy.viscous, b.energy.viscous) << what;
    EXPECT_EQ(a.energy.hysteretic, b.energy.hysteretic) << what;
    EXPECT_EQ(a.energy.contact_work, b.energy.contact_work) << what;
    EXPECT_EQ(a.energy.max_relative_error, b.energy.max_relative_error) << what;
    ASSERT_EQ(a.contacts.size(), b.contacts.size()) << what;
    for (std::size_t c = 0; c < a.contacts.size(); ++c)
    {
      EXPECT_EQ(a.contacts[c].peak_force, b.contacts[c].peak_force) << what;
      EXPECT_EQ(a.contacts[c].permanent_indentation, b.contacts[c].permanent_indentation) << what;
      ASSERT_EQ(a.contacts[c].impacts.size(), b.contacts[c].impacts.size()) << what;
      for (std::size_t i = 0; i < a.contacts[c].impacts.size(); ++i)
        EXPECT_EQ(a.contacts[c].impacts[i].time, b.contacts[c].impacts[i].time) << what;
    }
  }

  /// Largest relative difference between two responses: peaks (per DOF, storey and contact),
  /// displacement histories (relative to the peak of each DOF), energy terms (relative to
  /// W_in); the number of impacts must agree.
  inline double
  max_relative_difference(const Response &a, const Response &b, const std::string &what)
  {
    double     worst = 0.0;
    const auto rel   = [&](const double x, const double y, const double scale)
    {
      const double d = std::abs(x - y) / std::max(scale, 1e-300);
      worst          = std::max(worst, d);
      return d;
    };
    EXPECT_EQ(a.n_impacts(), b.n_impacts()) << what;
    for (std::size_t i = 0; i < a.peak_displacement.size(); ++i)
    {
      rel(a.peak_displacement[i], b.peak_displacement[i], b.peak_displacement[i]);
      rel(a.peak_absolute_acceleration[i],
          b.peak_absolute_acceleration[i],
          b.peak_absolute_acceleration[i]);
    }
    for (std::size_t s = 0; s < a.peak_interstorey_drift.size(); ++s)
      rel(a.peak_interstorey_drift[s], b.peak_interstorey_drift[s], b.peak_interstorey_drift[s]);
    for (std::size_t c = 0; c < a.contacts.size() && c < b.contacts.size(); ++c)
      if (b.contacts[c].peak_force > 0.0)
        rel(a.contacts[c].peak_force, b.contacts[c].peak_force, b.contacts[c].peak_force);
    const std::size_t n = a.n_dofs;
    EXPECT_EQ(a.history.displacement.size(), b.history.displacement.size()) << what;
    for (std::size_t q = 0; q < a.history.displacement.size() && q < b.history.displacement.size();
         ++q)
      rel(a.history.displacement[q], b.history.displacement[q], b.peak_displacement[q % n]);
    const double w = b.energy.input;
    rel(a.energy.input, b.energy.input, w);
    rel(a.energy.viscous, b.energy.viscous, w);
    rel(a.energy.hysteretic, b.energy.hysteretic, w);
    rel(a.energy.contact_work, b.energy.contact_work, w);
    rel(a.energy.kinetic, b.energy.kinetic, w);
    rel(a.energy.strain, b.energy.strain, w);
    return worst;
  }

  /// Whether the central difference stepper of `model` with `opt` picks a fused kernel for `g`.
  inline bool uses_fused_kernel(const lumped::PoundingModel            &model,
                                const lumped::CentralDifferenceOptions &opt,
                                const lumped::GroundMotion             &g)
  {
    const lumped::CentralDifference  cdm(model, opt);
    lumped::CentralDifferenceStepper stepper(cdm);
    stepper.init(g);
    return stepper.uses_fused_kernel();
  }

  /// The central difference run of `model` under `g` with `opt` through a stepper, which is
  /// expected to pick a fused kernel if `fused` and the reference kernel otherwise.
  inline Response stepped_run(const lumped::PoundingModel            &model,
                              const lumped::CentralDifferenceOptions &opt,
                              const lumped::GroundMotion             &g,
                              bool                                    fused,
                              const std::string                      &what)
  {
    const lumped::CentralDifference  cdm(model, opt);
    lumped::CentralDifferenceStepper stepper(cdm);
    stepper.init(g);
    EXPECT_EQ(stepper.uses_fused_kernel(), fused) << what;
    stepper.advance(stepper.last_step() + 1);
    return stepper.response();
  }

  /**
   * The central difference run of `model` under `g` with `opt` and vector_lanes 2 (SSE2), which
   * must pound, is bitwise identical to the runs with 4 (AVX2), 8 (AVX-512F) and 0 (the widest
   * the processor has) lanes: the same per-lane operations without FMA contraction. The SSE2
   * run is left in `sse2`. Call it inside ASSERT_NO_FATAL_FAILURE().
   */
  inline void expect_independent_of_vector_width(const lumped::PoundingModel     &model,
                                                 lumped::CentralDifferenceOptions opt,
                                                 const lumped::GroundMotion      &g,
                                                 Response                        &sse2)
  {
    opt.vector_lanes = 2;
    sse2             = lumped::CentralDifference(model, opt).run(g);
    ASSERT_GT(sse2.n_impacts(), 0u);
    for (const int lanes : {4, 8, 0})
    {
      opt.vector_lanes = lanes;
      expect_identical(lumped::CentralDifference(model, opt).run(g),
                       sse2,
                       "vector_lanes = " + std::to_string(lanes));
    }
  }

} // namespace kimp::testing
