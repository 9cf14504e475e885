// The yielding wall element's wall-and-backfill part from a static pushover curve
// (docs/physics.md §2 "Yielding moat wall", "Parameters from a pushover"): the equal-energy
// bilinear idealisation of ASCE 41 / FEMA 356 for the envelope, the first unloading for k_ur.
#pragma once

#include <string>
#include <vector>

#include "fem/pushover.h"

namespace kimp::app
{
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
    double unloading_stiffness = 0.0; ///< k_ur (>= k), N/m per m
    double yield_displacement  = 0.0; ///< F_y/k, m
    double target_displacement = 0.0; ///< Δ_d: the envelope's largest force is reached here, m
    double target_force        = 0.0; ///< V_d: the curve's capacity (largest force), N/m
    double curve_work          = 0.0; ///< ∫₀^Δ_d F dw of the curve (= the bilinear's), J/m
    /** The first unloading of a cyclic curve (NaN without one): where it starts, the curve's
     *  permanent set there and the element's (w_un − E(w_un)/k_ur), m. */
    double unloaded_from          = 0.0;
    double pushover_permanent_set = 0.0;
    double permanent_set          = 0.0;
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
   * - unloading: the first unloading's measured permanent set w_p gives k_ur = E(w_un)/(w_un −
   * w_p), so that the element leaves the curve's set; k_ur is at least k (the element's law), which
   *   the note states with the set the element leaves instead. Without unloading k_ur = k.
   * @throws std::invalid_argument when the curve cannot be fitted (fewer than three envelope
   *   points, no positive force, or a curve that does not yield before its target), naming why.
   */
  PushoverFit fit_pushover(const std::vector<fem::PushoverPoint> &curve);
} // namespace kimp::app
