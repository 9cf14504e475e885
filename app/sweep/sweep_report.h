// Post-processing of `kimp sweep` rows (docs/physics.md §2 last bullet): the gap d_req a sweep
// finds necessary to avoid pounding against the SRSS gap, per contact g_c >= sqrt(d_L² + d_R²),
// d_SRSS = max_c (sqrt(d_L,c² + d_R,c²) − (g_c − gap)), and Δd = d_SRSS − d_req.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "app/sweep/sweep_engine.h"
#include "app/sweep/sweep_plan.h"

namespace kimp::app
{
  /// One case of a configuration at one swept gap.
  struct GapSample
  {
    double gap    = 0.0;   ///< swept gap, m
    bool   impact = false; ///< any contact had at least one impact
    bool   ok     = true;  ///< false: the case failed (ignored by required_gap())
  };

  /// Where the required gap lies relative to the swept gaps.
  enum class RequiredGapStatus
  {
    reached,         ///< impacts below d_req, none from d_req on
    at_smallest_gap, ///< no impact at any swept gap: d_req <= the smallest gap (an upper bound)
    not_reached,     ///< impacts at the largest swept gap: d_req > every swept gap
    no_data          ///< no successful case
  };

  /// "reached", "at_smallest_gap", "not_reached", "no_data".
  std::string to_string(RequiredGapStatus status);

  struct RequiredGap
  {
    double            gap    = 0.0; ///< m (NaN unless reached or at_smallest_gap)
    RequiredGapStatus status = RequiredGapStatus::no_data;
  };

  /**
   * d_req: the smallest swept gap from which on (for it and every larger gap) no case has any
   * impact. Gaps equal within 1e-9 m are one gap (impact if any of its cases has one); failed
   * samples are ignored. Non-monotone impact counts are handled: a gap without impacts below a
   * larger gap with impacts does not count.
   */
  RequiredGap required_gap(std::vector<GapSample> samples);

  /// One contact of a case: its clear gap and the gap the SRSS rule asks for it.
  struct ContactGap
  {
    std::string name;
    double      clearance = 0.0; ///< g_c = gap + offset_c, m
    double      srss_gap  = 0.0; ///< sqrt(d_L,c² + d_R,c²) of the run without contacts, m
  };

  /// The gap required by SRSS and the contact that governs it.
  struct SrssGap
  {
    double      gap = 0.0; ///< m
    std::string governing;
  };

  /**
   * d_SRSS = max_c (srss_gap_c − offset_c) with offset_c = clearance_c − gap: the swept gap at
   * which every contact's clearance reaches its SRSS gap.
   * @throws std::invalid_argument when `contacts` is empty
   */
  SrssGap srss_required_gap(const std::vector<ContactGap> &contacts, double gap);

  /// One configuration and record of the d_SRSS table.
  struct DsrssRow
  {
    std::vector<std::string> values;    ///< of the parameters that do not set the gap
    double      clearance_offset = 0.0; ///< max_c (g_c − gap), m (separation − gap)
    std::size_t n_gaps           = 0;   ///< distinct swept gaps
    std::size_t n_cases          = 0;   ///< main runs in the group
    std::size_t n_failed         = 0;   ///< of n_cases
    double      gap_min          = 0.0; ///< m
    double      gap_max          = 0.0; ///< m
    RequiredGap d_req;
    double      d_srss = 0.0; ///< m, at the smallest gap's case
    std::string governing;    ///< contact governing d_srss
    /// max − min of d_SRSS over the group's cases, m (0 up to round-off: no contacts, no gap)
    double d_srss_spread = 0.0;

    /// Δd = d_SRSS − d_req, m (NaN unless d_req is reached or at the smallest gap).
    double delta() const;
  };

  struct DsrssTable
  {
    std::vector<std::string>          parameter_names;   ///< the parameters of DsrssRow::values
    std::vector<SweepParameterColumn> parameter_columns; ///< their CSV columns
    std::vector<DsrssRow>             rows; ///< in order of first appearance in the sweep
  };

  /**
   * Group the main rows of `table` (companion rows are skipped) by every parameter that does not
   * set `gap_key` and by the contacts' clearance offsets g_c − gap (so that a parameter setting
   * gap and separation together still separates +0 / +5 / +10 cm), then compute d_req and
   * d_SRSS per group. Needs the metrics n_impacts, <contact>.clearance [m] and
   * <contact>.srss_gap [m] (lumped scenes with integration.companion: true).
   * @throws SweepError when `gap_key` is set by no parameter or no row has the SRSS metrics.
   */
  DsrssTable
  dsrss_table(const SweepPlan &plan, const SweepTable &table, const std::string &gap_key);

  /// The table as CSV (units in the header) under a temporary name, then renamed.
  void write_dsrss_table(const DsrssTable &dsrss, const std::filesystem::path &file);
} // namespace kimp::app
