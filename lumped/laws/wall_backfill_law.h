// The wall-and-backfill part of a yielding moat wall (docs/physics.md §2 "Yielding moat wall"):
// the resistance R(w) of a cyclic pushover plus a radiation dashpot between the wall's DOF and the
// ground, F = R(w) + c_r·ẇ, w = the wall's displacement into its backfill.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "lumped/laws/force_law.h"

namespace kimp::lumped
{
  /// Virgin-loading curve of the wall and its backfill.
  enum class WallEnvelope
  {
    bilinear,   ///< E(w) = k·w up to F_y, then F_y + α·k·(w − F_y/k) up to the cap F_u
                ///< (OpenSees ElasticPPGap without a cap)
    hyperbolic, ///< E(w) = w/(1/k + R_f·w/F_ult) (Duncan-Mokwa; OpenSees HyperbolicGapMaterial)
    curve ///< piecewise linear through the points (w_i, F_i) from (0, 0), concave and monotone,
          ///< flat at the last force past the last point (a pushover curve's concave hull)
  };

  /**
   * Parameters of the wall-and-backfill part (SI, whole wall).
   *
   * | parameter            | meaning                                           | unit  | range    |
   * |----------------------|---------------------------------------------------|-------|----------|
   * | envelope             | bilinear (cap with hardening), hyperbolic, curve  | -     |          |
   * | stiffness            | k: initial tangent of the envelope (cracked wall  | N/m   | > 0      |
   * |                      | with its backfill; curve: set from its first      |       |          |
   * |                      | segment)                                          |       |          |
   * | capacity             | bilinear: F_y, the cap; hyperbolic: F_ult; curve: | N     | > 0      |
   * |                      | set to its last force                             |       |          |
   * | curve_displacements  | curve: w_i, from 0, increasing                    | m     |          |
   * | curve_forces         | curve: F_i, from 0, non-decreasing, concave       | N     |          |
   * | hardening_ratio      | α: bilinear post-yield tangent α·k                | -     | [0, 1)   |
   * | ultimate_capacity    | F_u: bilinear, the force the hardening stops at   | N     | >= F_y   |
   * |                      | (+inf: no cap)                                    |       |          |
   * | failure_ratio        | R_f: hyperbolic, the curve tends to F_ult/R_f     | -     | (0, 1]   |
   * | unloading_stiffness  | k_ur: unloading and reloading stiffness (the line | N/m   | > 0      |
   * |                      | is never steeper than needed: at least E/w_max)   |       |          |
   * | tension_capacity     | F_t: largest force pulling the wall towards the   | N     | >= 0     |
   * |                      | building (0: the part acts in compression only)   |       |          |
   * | radiation_damping    | c_r: dashpot to the ground (soil ρ·c over the     | N·s/m | >= 0     |
   * |                      | loaded area)                                      |       |          |
   * | mass                 | the wall DOF's mass (stable step only)            | kg    | > 0      |
   * | failure_displacement | w_fail: the wall has failed once w exceeds it     | m     | > 0      |
   */
  struct WallBackfillParams
  {
    WallEnvelope        envelope             = WallEnvelope::bilinear;
    double              stiffness            = 0.0;
    double              capacity             = 0.0;
    double              hardening_ratio      = 0.0;
    double              ultimate_capacity    = std::numeric_limits<double>::infinity();
    double              failure_ratio        = 1.0;
    double              unloading_stiffness  = 0.0;
    double              tension_capacity     = 0.0;
    double              radiation_damping    = 0.0;
    double              mass                 = 0.0;
    double              failure_displacement = std::numeric_limits<double>::infinity();
    std::vector<double> curve_displacements; ///< curve envelope: w_i, m (first 0)
    std::vector<double> curve_forces;        ///< curve envelope: F_i, N (first 0)
  };

  /// Checks the points of a curve envelope: at least two, the same count, (w_0, F_0) = (0, 0),
  /// w increasing, F non-decreasing, slopes non-increasing (concave; a relative 1e-9 of the first
  /// slope allowed for round-off). Returns "" when valid, else what is wrong, naming the index
  /// ("point 3: ...").
  std::string wall_curve_problem(const std::vector<double> &displacements,
                                 const std::vector<double> &forces);

  /// Trial/committed state of the wall-and-backfill part.
  struct WallBackfillState
  {
    double deformation     = 0.0; ///< w, m (> 0 into the backfill)
    double rate            = 0.0; ///< ẇ, m/s
    double max_deformation = 0.0; ///< w_max, the farthest point reached on the envelope, m (>= 0)
    double spring_force    = 0.0; ///< R(w), N
    double force           = 0.0; ///< R + c_r·ẇ, N
    double stiffness       = 0.0; ///< dR/dw, N/m
    double radiated        = 0.0; ///< ∫c_r·ẇ dw (trapezoid), J
    double peak_spring     = 0.0; ///< max R over the commits so far, N
  };

  /**
   * Wall-and-backfill resistance with the memory of a cyclic pushover, in parallel with a
   * radiation dashpot to the ground:
   *
   *   F(w, ẇ) = R(w) + c_r·ẇ,
   *   R(w)    = E(w)                            for w >= w_max (virgin loading; w_max := w),
   *           = max(k̃·(w − w_p), −F_t)         for w <  w_max (unloading and reloading),
   *   k̃       = max(k_ur, E(w_max)/w_max)       (never below the envelope's secant),
   *   w_p     = w_max − E(w_max)/k̃ >= 0        (the permanent set: where R returns to 0).
   *
   * The curve envelope is piecewise linear through (w_i, F_i), i = 0..n, (w_0, F_0) = (0, 0),
   * and flat at F_n past w_n; its k is the first slope and its capacity F_n. Two segments
   * (0, 0), (F_y/k, F_y), (w_u, F_u) are the bilinear envelope with its cap.
   * The bilinear envelope stops hardening at F_u: E = min(F_y + α·k·(w − w_y), F_u), w_y = F_y/k,
   * flat from w_u = w_y + (F_u − F_y)/(α·k) (the pushover's largest force; a wall does not
   * harden without bound). The envelope E (WallEnvelope) is concave with E(0) = 0, so its chords
   * ending at w_max are at most as steep as its secant E(w_max)/w_max; a line through
   * (w_max, E(w_max)) at k̃ >= that secant therefore lies below the envelope and meets it at
   * w_max: reloading rejoins the envelope there (hardening continues). k_ur >= k keeps k̃ = k_ur
   * (OpenSees' materials); k_ur < k is a cracked wall that springs back softer than it was
   * first loaded: elastic back to w = 0 (no set) while the secant is steeper than k_ur, a set
   * w_max − E/k_ur once it is not. A wall pushed back keeps its set: with F_t = 0 it rests at w_p
   * with R = 0 (the next impact comes at a larger gap); F_t > 0 is the wall's elastic pull-back,
   * limited to F_t without changing w_p (no reverse yielding).
   *
   * Energy: the spring's dissipated (plastic) work is path-independent,
   *   W_p(w_max) = ∫₀^w_max E dw − E(w_max)²/(2k̃(w_max)),
   * its stored energy the potential of the current unloading branch about w_p; the radiated work
   * is the trapezoid rule on c_r·ẇ over w. dissipated_energy() = W_p + radiated.
   *
   * Tangent: dF/dw = E'(w) on the envelope, k̃ on the line, 0 on the tension cap; dF/dẇ = c_r.
   * The part is permanently attached: in_contact() is always true (it is evaluated at every step).
   *
   * With F_t = 0 and c_r = 0 the bilinear envelope is OpenSees' ElasticPPGap (E, F_y, η = α,
   * gap 0, "damage" so that the set is kept) and the hyperbolic one HyperbolicGapMaterial
   * (K_max = k, K_ur = k_ur, R_f, F_ult, gap 0); docs/physics.md maps the parameters.
   * Limitations: no reverse yielding, no strength or stiffness degradation under cycles; the
   * part keeps acting after w_fail is passed (failed() reports it).
   */
  class WallBackfillLaw final : public ForceLaw
  {
  public:
    using Params = WallBackfillParams;

    /// @throws std::invalid_argument naming the bad parameter.
    explicit WallBackfillLaw(const Params &params);

    ForceResponse set_trial(double deformation, double rate) override;
    void          commit() override { committed_ = trial_; }
    void          revert_to_last_commit() override { trial_ = committed_; }
    void          revert_to_start() override
    {
      committed_ = WallBackfillState{};
      trial_     = WallBackfillState{};
    }

    /// max(k, k_ur)/(sqrt(1 + ξ²) − ξ)², ξ = c_r/(2·sqrt(max(k, k_ur)·m)), N/m: the largest
    /// tangent, raised for the dashpot (the argument is not used).
    double stability_stiffness(double max_deformation) const override;
    /// Plastic plus radiated work up to the last commit, J.
    double dissipated_energy() const override { return plastic_work() + radiated_work(); }
    /// The permanent set w_p of the last commit, m (0 while virgin).
    double permanent_indentation() const override { return permanent_set(committed_); }
    bool   in_contact() const override { return true; }
    /// Potential of the current branch at the last commit, J.
    double stored_energy() const override;

    std::string               name() const override { return "wall_backfill"; }
    std::unique_ptr<ForceLaw> clone() const override
    {
      return std::make_unique<WallBackfillLaw>(*this);
    }

    /// The spring's dissipated work W_p(w_max) of the last commit, J.
    double plastic_work() const;
    /// ∫c_r·ẇ dw up to the last commit, J.
    double radiated_work() const { return committed_.radiated; }
    /// w_max of the last commit, m.
    double peak_deformation() const { return committed_.max_deformation; }
    /// The largest resistance R (without the dashpot) committed so far, N.
    double peak_resistance() const { return committed_.peak_spring; }
    /// True once the committed w_max exceeds failure_displacement.
    bool failed() const { return committed_.max_deformation > params_.failure_displacement; }

    /// The envelope E(w), N (w >= 0).
    double envelope(double w) const;
    /// dE/dw, N/m (w >= 0).
    double envelope_tangent(double w) const;
    /// ∫₀^w E dw', J (w >= 0).
    double envelope_work(double w) const;
    /// w_u, m: where the bilinear envelope reaches its cap F_u and turns flat (w_y when α = 0 or
    /// F_u = F_y; +inf without a cap or for the hyperbolic envelope); the curve's last w_i.
    double cap_displacement() const;

    const Params            &parameters() const { return params_; }
    const WallBackfillState &committed_state() const { return committed_; }

  private:
    double permanent_set(const WallBackfillState &s) const;
    /// k̃(w_max) = max(k_ur, E(w_max)/w_max) (max(k_ur, k) at w_max = 0), N/m.
    double unloading_stiffness_at(double w_max) const;

    /// The segment of the curve envelope holding w (w_i <= w < w_{i+1}; n past the last point).
    std::size_t curve_segment(double w) const;

    const Params        params_;
    std::vector<double> curve_work_; ///< curve: ∫₀^w_i E dw at each point, J
    WallBackfillState   committed_;
    WallBackfillState   trial_;
  };
} // namespace kimp::lumped
