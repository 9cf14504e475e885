// The laws `kimp study` fits at every wall height (laws 2 and 4 of docs/physics.md §1 at the
// study COR) as one list, and the fit of each: every table, summary and building run of the study
// loops over this list, so a further study law is one more entry of study_laws().
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fit/fitter.h"
#include "lumped/laws/law_traits.h"

namespace kimp::app
{
  struct ThesisStiffness;

  /** One law the study fits at every wall height, and where the study's inputs keep it. */
  struct StudyLaw
  {
    const lumped::LawTraits *traits = nullptr; ///< its name and exponent (law_traits.h)
    std::string_view         title;            ///< "Kelvin-Voigt" (summary.json statuses)
    std::string_view         short_name;       ///< "KV" (log lines and report headings)
    std::string_view         symbol;           ///< "KV", "J" (narrow report columns)
    /// The building runs that take k from this law's fit (a law of lumped/laws).
    std::vector<std::string_view> building_laws;
    /// Its k in thesis Table 2.1, kN/mm^n per metre (nullptr: the thesis gives none).
    double ThesisStiffness::*thesis = nullptr;

    /// "kelvin_voigt": the name of its columns, groups and keys.
    std::string name() const { return std::string(traits->name); }
    /// n of k in N/m^n.
    double exponent() const { return traits->default_exponent; }
    /// The fit variant of fit::fit_variants() the study takes ("kelvin_voigt_cor_fixed").
    std::string fit_variant() const { return name() + "_cor_fixed"; }
    /// kN/mm^n per metre of wall ("kN/mm/m").
    std::string per_metre_unit() const { return fit::stiffness_display_unit(exponent(), true); }
    /// kN/mm^n of the whole wall ("kN/mm").
    std::string total_unit() const { return fit::stiffness_display_unit(exponent()); }
  };

  /// Kelvin-Voigt, then Jankowski's, in the order of every table and summary.
  const std::vector<StudyLaw> &study_laws();
  /// The position of `law` (an entry of study_laws()) in that list: the index of its values in
  /// per-law vectors (LevelOutcome::k, LadderResult::error).
  std::size_t study_law_index(const StudyLaw &law);

  /** The fit of one study law to one FEM case. */
  struct StudyLawFit
  {
    const StudyLaw               *law = nullptr;
    std::optional<fit::FitResult> fit;           ///< at the study COR (unset: failed)
    std::string                   status = "ok"; ///< "ok", "warning: ..." or "failed: ..."
    /// The fit with linear materials at the same FEM level (inelastic cases only).
    std::optional<fit::FitResult> linear;

    bool ok() const { return status == "ok"; }
  };

  /// "k_KV 123.4 kN/mm/m, k_Jankowski 5678 kN/mm^1.5/m": `k` per study law (N/m^n per m, NaN or
  /// missing: not known) in display units, each named `prefix` and the law's short name.
  std::string k_text(const std::vector<double> &k, std::string_view prefix);

  /// One unfitted entry per study law, in the order of study_laws().
  std::vector<StudyLawFit> unfitted_study_laws();

  /// Every entry fitted.
  bool all_fitted(const std::vector<StudyLawFit> &laws);
  /// Every entry's status is "ok".
  bool all_ok(const std::vector<StudyLawFit> &laws);
  /// The statuses joined by " / " ("ok / failed: ...").
  std::string joined_status(const std::vector<StudyLawFit> &laws);
  /// The entry of the law named `name` ("kelvin_voigt").
  /// @throws std::out_of_range when no entry is named so.
  const StudyLawFit &law_fit(const std::vector<StudyLawFit> &laws, std::string_view name);
} // namespace kimp::app
