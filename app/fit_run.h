// `kimp fit FEM.h5 -o DIR`: the impact laws fitted to every FEM case of a results file
// (fit/fitter.h), written as DIR/fit.h5 (/fit/<case>/<variant>) and DIR/fit_table.csv.
#pragma once

#include <filesystem>

#include "fit/fitter.h"
#include "io/fem_results.h"
#include "io/results_file.h"

namespace kimp::app
{
  /// The FEM case as a fit::ForceHistory (smoothed or raw contact force, indentation, slab motion).
  /// @throws fit::FitError if the smoothed force is asked for but the case has none.
  fit::ForceHistory force_history(const io::FemCase &fem_case, bool smoothed_force = true);

  /// What write_fit_result() writes besides k, COR, n and the misfit.
  enum class FitResultLayout
  {
    full, ///< `kimp fit`: COR interval, peak forces, contact start, LM attributes; the misfit
          ///< window as time series fem_force and model_force
    study ///< study.h5: the misfit window as plain datasets time, fem_force and model_force
  };

  /**
   * The one writer of a fitted law below /fit/<case>/<variant> (fit.h5 and study.h5): stiffness,
   * stiffness_lower, stiffness_upper (N/m^n per metre), stiffness_total (N/m^n, k·`width`), cor,
   * exponent, normalised_rms, model_effective_cor and what `layout` adds. The status is the
   * caller's.
   */
  void write_fit_result(io::ResultsGroup     &group,
                        const fit::FitResult &fit,
                        double                width,
                        FitResultLayout       layout);

  /// Settings of one `kimp fit` run (the command-line options).
  struct FitCommandOptions
  {
    std::filesystem::path fem_file;                ///< results file holding /fem/<case>
    std::filesystem::path output;                  ///< output directory
    double                cor = 0.7;               ///< COR of the fixed-COR variants (thesis: 0.7)
    double width     = fit::thesis_building_width; ///< building side W, m: k_total = k_per_metre·W
    bool   raw_force = false;                      ///< fit the raw instead of the smoothed force
    double displacement_weight = 0.0;              ///< fit::FitOptions::displacement_weight
  };

  /**
   * Fit the standard variants (fit::standard_fit_variants) to every "ok" case of the FEM file and
   * write DIR/fit.h5 and DIR/fit_table.csv (one row per case and variant, k per metre and total
   * in kN/mm^n, COR, n, 95 % intervals, normalised RMS misfit, status). A fit that fails is a
   * row with status "failed: <reason>", not an error of the command.
   * @return number of failed fits.
   * @throws ResultsError or OutputError for unreadable input or unwritable output.
   */
  int run_fit_command(const FitCommandOptions &options);

  /// Add `kimp fit FEM.h5 -o DIR [--cor C] [--width W] [--raw-force] [--displacement-weight w]`.
} // namespace kimp::app
