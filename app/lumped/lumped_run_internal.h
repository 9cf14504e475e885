// Parts of `kimp lumped` shared by its translation units (not a public API): the integrator
// options and the cost estimate of a case (lumped_estimate.cc), the k a case takes from a k table
// and the files of a run (lumped_files.cc).
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/lumped/lumped_run.h"
#include "base/stopwatch.h"
#include "lumped/integrators/newmark_integrator.h"

namespace kimp::io
{
  class ResultsGroup;
} // namespace kimp::io

namespace kimp::app::lumped_internal
{
  using Clock = std::chrono::steady_clock;

  using base::seconds_since;

  // lumped_estimate.cc
  /// The central difference options of integration (its time step `dt`, nullopt: the
  /// integrator's own).
  lumped::CentralDifferenceOptions cdm_options(const IntegrationScene      &in,
                                               const std::optional<double> &dt);
  /// The Newmark options of integration (its time step `dt`, nullopt: the record's).
  lumped::NewmarkOptions newmark_options(const IntegrationScene      &in,
                                         const std::optional<double> &dt);
  /// The integrator of an integration section: its method and options. One entry point,
  /// integrate(), runs it for the main run, the companion run without contacts and (through
  /// planned_step()) the cost estimate, so that these cannot take different paths.
  struct Integration
  {
    IntegrationMethod                method   = IntegrationMethod::cdm;
    bool                             variable = false; ///< cdm with dt: auto (variable steps)
    lumped::CentralDifferenceOptions cdm;              ///< cdm (fixed and variable steps)
    lumped::AdaptiveStepOptions      adaptive;         ///< cdm with variable steps
    lumped::NewmarkOptions           newmark;          ///< newmark
  };
  /// The integration of `in` at the step `dt` (nullopt: the integrator's own).
  Integration integration_of(const IntegrationScene &in, const std::optional<double> &dt);
  /// The same integration for the companion run of a main run that gave `main`: a fixed
  /// central-difference step is the main run's (variable steps choose their own).
  Integration companion_integration(Integration integration, const lumped::Response &main);
  /// The (largest) step `integration` takes on `model` under a record sampled at `record_dt`, s:
  /// the step the cost estimate and the step budget count.
  double planned_step(const lumped::PoundingModel &model,
                      const Integration           &integration,
                      double                       record_dt);
  /// What one run gives: the response and, with variable steps, their report.
  struct Integrated
  {
    lumped::Response                          response;
    std::optional<lumped::AdaptiveStepReport> adaptive;
  };
  /// `model` under `motion` with `integration`.
  Integrated integrate(const lumped::PoundingModel &model,
                       const Integration           &integration,
                       const lumped::GroundMotion  &motion);

  /// The estimate for a step `dt` chosen by the integrator (the integrators' own rule for N).
  RunEstimate make_estimate(double                      dt,
                            const IntegrationScene     &in,
                            const lumped::GroundMotion &motion,
                            std::size_t                 n_dofs);

  // lumped_files.cc
  /// The k a case takes from a study's k table (impact.k_table at impact.wall_height): the
  /// table, the height, k in SI with its unit and in the display unit; nullopt when the case
  /// gives k itself or cannot resolve it (run_lumped_case() then records why).
  std::optional<nlohmann::json> k_from_table(const ImpactScene &impact);
  /// DIR/lumped.h5, DIR/summary.json (its wall_time counted from `start`) and DIR/peaks.csv of
  /// the cases of `run`.
  void write_lumped_files(const io::LoadedScene<LumpedScene> &loaded,
                          const io::OutputDir                &output,
                          const LumpedCasesRun               &run,
                          Clock::time_point                   start);

  /// A yielding wall's datasets (with units) and the attribute `failed` in the group `g` of
  /// lumped.h5.
  void write_yielding_wall(io::ResultsGroup &g, const YieldingWallRecord &w);
  /// A yielding wall's entry of summary.json (`failure_time` only when it failed).
  nlohmann::json yielding_wall_json(const YieldingWallRecord &w);
} // namespace kimp::app::lumped_internal
