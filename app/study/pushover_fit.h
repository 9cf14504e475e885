// The yielding wall element's wall-and-backfill part from a static pushover curve
// (docs/physics.md §2 "Yielding moat wall", "Parameters from a pushover"): the curve's concave
// hull for the envelope, the equal-energy bilinear idealisation of ASCE 41 / FEMA 356 beside it
// (reported), the unloadings for k_ur.
#pragma once

#include <string>
#include <vector>

#include "app/fem/fem_scene.h"
#include "app/study/yielding_wall_element.h"
#include "fem/pushover.h"

namespace kimp::app
{
  /** One unloading of a cyclic pushover curve to zero force, m and N/m. */
  struct PushoverUnloading
  {
    double from          = 0.0; ///< w_un, the band displacement where it starts
    double force         = 0.0; ///< the curve's force there
    double permanent_set = 0.0; ///< the curve's displacement at zero force
    double element_set   = 0.0; ///< the fitted element's (w_un − E(w_un)/k̃, k̃ >= E/w_un)
  };

  /**
   * The bilinear wall-and-backfill part fitted to a pushover curve, per metre of wall (SI).
   * The bilinear E(w) = k·w up to F_y, then F_y + α·k·(w − F_y/k), ends at the curve's target
   * point (Δ_d, V_d) and encloses the same area as the curve up to Δ_d.
   */
  struct PushoverFit
  {
    double capacity            = 0.0; ///< F_y = V_y, the bilinear's yield force, N/m
    double stiffness           = 0.0; ///< k = K_e, secant of the curve at 0.6·V_y, N/m per m
    double hardening_ratio     = 0.0; ///< α: post-yield tangent α·k through (Δ_d, V_d)
    double unloading_stiffness = 0.0; ///< k_ur (> 0; below k: a cracked wall), N/m per m
    double yield_displacement  = 0.0; ///< F_y/k, m
    double target_displacement = 0.0; ///< Δ_d: the envelope's largest force is reached here, m
    double target_force        = 0.0; ///< V_d: the curve's capacity (largest force), N/m; the
                               ///< element's cap (ultimate_capacity): it does not harden past it
    double curve_work = 0.0; ///< ∫₀^Δ_d F dw of the curve (= the bilinear's), J/m
    /** The element's envelope: the concave hull of the virgin loading points from (0, 0) up to
     *  Δ_d (the least concave curve above them; flat at V_d past Δ_d), m and N/m. k_ur and the
     *  element's sets are fitted against it. */
    std::vector<double> hull_displacements;
    std::vector<double> hull_forces;
    /** The first unloading of a cyclic curve (NaN without one): where it starts, the curve's
     *  permanent set there and the element's (w_un − E(w_un)/k̃), m. */
    double unloaded_from          = 0.0;
    double pushover_permanent_set = 0.0;
    double permanent_set          = 0.0;
    /** Every unloading of the curve that reaches zero force, in order. */
    std::vector<PushoverUnloading> unloadings;
    /** What the fit had to assume or clamp, in words ("" when nothing). */
    std::string note;
  };

  /**
   * Fits `curve` (fem::PushoverPoint, from (0, 0), force beyond the geostatic state):
   * - envelope: the virgin loading points (a cyclic curve's reload below the previous largest
   *   displacement is not envelope); target (Δ_d, V_d) its point of largest force (softening past
   *   it is not modelled, and the note says so);
   * - equal energy (ASCE 41-17 §7.4.3.2.5, FEMA 356 §3.3.3.2.5): V_y such that the bilinear with
   *   K_e = 0.6·V_y / w(0.6·V_y) (the curve's secant where it first reaches 0.6·V_y) and the
   *   post-yield line through (Δ_d, V_d) has the curve's area up to Δ_d; fixed-point iteration on
   *   V_y = (2A − V_d·Δ_d)/(Δ_d − V_d/K_e). V_y is at most V_d (then α = 0);
   * - hull: the concave hull of the envelope points up to Δ_d (the element's curve envelope; the
   *   bilinear above is kept for the report and the bilinear element);
   * - unloading, against the hull E: the unloadings' measured permanent sets w_p give k_ur, the
   *   least-squares fit of
   *   1/k_ur to w_un − w_p = E(w_un)/k_ur over the unloadings that leave a set of more than a
   *   tenth of w_un (one: k_ur = E(w_un)/(w_un − w_p) exactly); without such an unloading the
   *   smallest unloading secant E(w_un)/(w_un − w_p). k_ur may be below k (a cracked wall springs
   *   back softer than it was loaded; the element then unloads at max(k_ur, E/w_max), never
   *   leaving a negative set), which the note states with each unloading's set, the curve's and
   *   the element's. Without unloading k_ur = k.
   * @throws std::invalid_argument when the curve cannot be fitted (fewer than three envelope
   *   points, no positive force, or a curve that does not yield before its target), naming why.
   */
  PushoverFit fit_pushover(const std::vector<fem::PushoverPoint> &curve);

  /// Where a yielding wall element's wall-and-backfill part came from (see pushover_resistance()).
  struct PushoverResistance
  {
    std::string                     source = "estimate"; ///< "pushover" or "estimate"
    std::string                     reason; ///< the pushover's failure, or the fit's note
    PushoverFit                     fit;    ///< source "pushover" only
    std::vector<fem::PushoverPoint> curve;  ///< the pushover's curve (source "pushover" only)
    double        seconds = 0.0;            ///< the pushover's wall time (also when it failed), s
    unsigned long cells   = 0;              ///< cells of the pushover's mesh
  };

  /// The mesh of a study's pushover, m: 5 cells through a 0.25 m wall, where the pushover's
  /// closed forms hold within 3 % and a height takes seconds; independent of the impact's mesh.
  inline constexpr double study_pushover_h_contact = 0.05;
  inline constexpr double study_pushover_h_max     = 0.25;
  /// The largest step of the IMPL-EX fallback, m: the reinforced wall with its backfill at
  /// H = 1.25 m has F_y 128.1 / 116.2 / 113.1 kN/m at 1 / 0.5 / 0.25 mm steps (docs/physics.md
  /// §2 "element of a study"), so the scene's 1 mm default would overstate it by 13 %.
  inline constexpr double study_pushover_implex_increment = 0.25e-3;
  /// The push of a study's pushover without `pushover.displacement`: 5 % of H (the scene's
  /// default, app/fem/pushover_run.cc).
  inline constexpr double study_pushover_drift = 0.05;
  /// Where a study's pushover of a reinforced wall unloads to zero force and reloads when the
  /// scene's `pushover.unload_at` is empty, as drifts (fractions of H): the cracked wall's spring
  /// back, k_ur (docs/physics.md §2 "element of a study"; at H = 1.25 m 12.5 and 25 mm, where an
  /// impact of the isolation's mass pushes the wall).
  inline constexpr double study_pushover_unload_drifts[] = {0.01, 0.02};

  /**
   * The static pushover of `scene` at `wall_height` (run_scene_pushover() on the mesh
   * study_pushover_h_contact / study_pushover_h_max, mesh level 0, the scene's `pushover`
   * section for the path; a reinforced wall's path without `unload_at` unloads to zero force at
   * study_pushover_unload_drifts of H, for k_ur), fitted by fit_pushover(). A reinforced wall is
   * pushed with the
   * implicit damage update first and, only where Newton stalls with it, again with IMPL-EX at
   * steps of at most study_pushover_implex_increment (docs/physics.md §6 "Static pushover":
   * IMPL-EX's lagging damage puts a cracking wall's knee high, the implicit update does not);
   * the reason names the fallback and the stall. On success the capacity, stiffness, hardening
   * ratio, unloading stiffness and cap (ultimate_capacity = V_d) of `in` are the fit's, and its
   * envelope the fit's concave hull (source "pushover"); when the pushover or
   * the fit fails `in` is left as it is (the estimate) and the reason says why (source "estimate").
   * Never throws for a pushover that fails.
   */
  PushoverResistance
  pushover_resistance(const FemScene &scene, double wall_height, YieldingWallInputs &in);
} // namespace kimp::app
