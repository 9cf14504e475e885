// `kimp fit FEM.h5 -o DIR`: the impact laws fitted to every FEM case of a results file
// (fit/fitter.h), written as DIR/fit.h5 (/fit/<case>/<variant>) and DIR/fit_table.csv.
#pragma once

#include <filesystem>

#include "app/laws/cor_key.h"
#include "app/laws/wall_keys.h"
#include "fit/fit_config.h"
#include "fit/fitter.h"
#include "io/fem_results.h"
#include "io/results_file.h"
#include "io/scene_io.h"

namespace kimp::fit
{
  /// The one declaration of the fitting configuration: the study's `fit:` section and the flags
  /// of `kimp fit` (`--separation-fraction 0.25`, ...) are read through it.
  template <class Io>
  void visit(Io &io, FitConfig &s)
  {
    app::visit_cor(io, s.cor, "COR of the fixed-COR Kelvin-Voigt and Jankowski fits");
    app::visit_building_width(io,
                              s.width,
                              "building side width W: k_total = k_per_metre x W (27.78 m gives the "
                              "thesis' Table 2.2 from Table 2.1)");
    io.flag("raw_force", s.raw_force, "fit the raw FEM contact force instead of the smoothed one");
    io.flag("force_only_contact",
            s.force_only_contact,
            "contact window from the force alone (true) or from the FEM indentation (false; "
            "cuts the window at the first bounce of a chattering slab)");
    io.quantity("separation_fraction",
                s.separation_fraction,
                "",
                "a contact ends at a force-free run longer than this fraction of its duration so "
                "far (larger merges the bounces of one impact)",
                io::Range::positive());
    io.quantity("tail_fraction",
                s.tail_fraction,
                "",
                "samples after the FEM separation in the misfit, as a fraction of the contact "
                "duration",
                io::Range::non_negative());
    io.quantity("contact_threshold",
                s.contact_threshold,
                "",
                "force-only contact detection: F > contact_threshold x peak force",
                io::Range::greater(0.0).and_less(1.0));
    io.quantity("displacement_weight",
                s.displacement_weight,
                "",
                "weight of the slab-displacement misfit beside the force misfit (0: force "
                "only, the thesis' choice)",
                io::Range::non_negative());
    io.quantity("peak_tolerance",
                s.peak_tolerance,
                "%",
                "a fit whose peak force misses the FEM's peak by more than this is a warning "
                "(status), since a wall is sized from the peak force",
                io::Range::positive());
  }
} // namespace kimp::fit

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
   * exponent, normalised_rms, model_effective_cor, the fitted/FEM ratios peak_force_ratio,
   * impulse_ratio and contact_duration_ratio, and what `layout` adds. The status is the
   * caller's.
   */
  void write_fit_result(io::ResultsGroup     &group,
                        const fit::FitResult &fit,
                        double                width,
                        FitResultLayout       layout);

  /**
   * Fit `variant` to `fem_case` with the force source and window of `config`: the one fitting
   * path of `kimp fit` and `kimp study`, so both give the same k on the same FEM result. Judge
   * the result with fit::fit_verdict().
   * @throws fit::FitError (and std::invalid_argument) as fit::fit_impact_law().
   */
  fit::FitResult fit_fem_case(const io::FemCase     &fem_case,
                              const fit::FitVariant &variant,
                              const fit::FitConfig  &config);

  /// Apparent COR below which a slab counts as stopped (it leaves with < 1 % of its energy).
  inline constexpr double yielding_wall_cor = 0.1;

  /**
   * The status of `fit` to `fem_case`: fit::fit_verdict() (with `peak_tolerance`), after what
   * the FEM run itself says.
   * An impact stiffness describes a contact the slab rebounds from; a run ends on separation only
   * once the slab comes in at no more than 5 % of its impact speed (apparent COR >= -0.05).
   * When the materials dissipated more than 1 % of the impact energy: a run stopped at its end time
   * with the slab keeping more than a quarter of its kinetic energy moving in (COR < -0.5) is
   * "failed: ..." (the wall broke); a slab that leaves with less than 1 % of the impact energy (COR
   * < yielding_wall_cor, or still moving in at the end time) gives "warning: ..." (the wall yielded
   * and stopped the slab: k is the equivalent stiffness of a yielding wall). Used by `kimp fit` and
   * `kimp study`.
   */
  std::string fem_fit_verdict(const io::FemCase    &fem_case,
                              const fit::FitResult &fit,
                              double                peak_tolerance = fit::default_peak_tolerance);

  /// Settings of one `kimp fit` run (the command-line options).
  struct FitCommandOptions
  {
    std::filesystem::path fem_file; ///< results file holding /fem/<case>
    std::filesystem::path output;   ///< output directory
    fit::FitConfig        config;   ///< the shared fitting configuration (flags)
  };

  /**
   * Fit the standard variants (fit::standard_fit_variants) to every "ok" case of the FEM file and
   * write DIR/fit.h5 and DIR/fit_table.csv (one row per case and variant: wall height, impact
   * velocity, k per metre and total in kN/mm^n, COR, n, 95 % intervals, normalised RMS misfit,
   * fitted/FEM peak force, impulse and contact duration, status). The table is a k source of
   * its own: app::read_k_table() reads it (`kimp export-opensees`, `impact.k_table`). A fit that
   * fails, or whose fit::fit_verdict() is "failed: ..." or "warning: ...", is a row with that
   * status, not an error of the command.
   * @return number of fits whose status is not "ok".
   * @throws ResultsError or OutputError for unreadable input or unwritable output.
   */
  int run_fit_command(const FitCommandOptions &options);

} // namespace kimp::app
