// `fidelity: auto` of `kimp study`: climb a ladder of FEM mesh sizes h_contact and then
// penalty factors until the fitted k of both laws changes by less than a tolerance between
// consecutive levels; the numerical error of k is the change to the previous level. Beside k,
// the engineer's quantities of the records (first peak, resistance, displacements, time to stop,
// bar strain) and their change between the two finest levels, against a 5 % target.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace kimp::app
{
  /** One rung of the ladder: an FEM discretisation. */
  struct FidelityLevel
  {
    double h_contact      = 0.0; ///< element size at the contact, m
    double penalty_factor = 1.0; ///< fem::ImpactParameters::penalty_factor

    /// "h2.5cm_p1": part of the FEM cache file name of the level.
    std::string label() const;
  };

  /**
   * One of the engineer's quantities the ladder converges on (docs/physics.md "Engineer's
   * quantities"): its key in io::FemSummary, SI unit, and the absolute difference below which
   * two levels agree whatever their relative change (a quantity near zero, or one that the
   * record resolves only to its sampling).
   */
  struct LadderQuantity
  {
    const char *key;
    const char *unit;
    double      floor;
  };

  /** The quantities of the ladder, in the order of its tables. */
  const std::vector<LadderQuantity> &ladder_quantities();

  /** The target of the quantities' numerical error between the two finest levels: 5 %. */
  constexpr double ladder_quantity_tolerance = 0.05;

  /** The numerical error of one quantity: its change between two levels. */
  struct QuantityError
  {
    std::string key, unit;
    double      coarse   = std::numeric_limits<double>::quiet_NaN(); ///< SI
    double      fine     = std::numeric_limits<double>::quiet_NaN(); ///< SI, the finer level
    double      relative = std::numeric_limits<double>::quiet_NaN(); ///< |coarse - fine| / |fine|
    /// Within the target: relative <= ladder_quantity_tolerance, or |coarse - fine| <= floor.
    bool        pass = false;
    std::string verdict; ///< "pass", "fail" or "not shown" (a level lacks the quantity)
  };

  /** What the caller computed on one level (FEM + both fits). */
  struct LevelOutcome
  {
    bool        ok     = false;
    std::string status = "ok"; ///< "ok" or why the level is unusable
    /// k of each study law (study_laws() order), N/m^n per m; NaN: not fitted
    std::vector<double> k;
    double              seconds    = 0.0;   ///< s spent on the level (FEM + fits)
    bool                from_cache = false; ///< FEM read from the study's cache
    /// The engineer's quantities of the level's record (ladder_quantities() keys, SI); a key
    /// the record does not show is absent.
    std::map<std::string, double> quantities;
  };

  /** The ladder as climbed. */
  struct LadderResult
  {
    std::vector<FidelityLevel> levels;   ///< levels run, in order
    std::vector<LevelOutcome>  outcomes; ///< one per level
    /// Index of the level whose k is reported (npos: no usable level).
    std::size_t used      = std::numeric_limits<std::size_t>::max();
    bool        converged = false; ///< the tolerance was met in the mesh and the penalty phase
    std::string reason;            ///< why the climb stopped (for the log and the report)
    /// Numerical error estimates of the reported k of each law (the order of LevelOutcome::k),
    /// N/m^n per m: change to the previous mesh level and to the previous penalty level (NaN: not
    /// estimated, a phase with one level), and their quadrature sum (NaN if neither phase could
    /// estimate it). Empty before the ladder ran; error_of() reads them.
    std::vector<double> mesh_error;
    std::vector<double> penalty_error;
    std::vector<double> error;

    /// The engineer's quantities between the two finest levels run (the reported level and
    /// the one before it in the climb), one per ladder_quantities() entry; empty with one level.
    std::vector<QuantityError> quantity_errors;
    /// Every quantity_errors entry passes.
    bool quantities_converged = false;
    /// fidelity_far_side_spread: the quantities of the reported level with the other far side
    /// (QuantityError::coarse) against the scene's own (fine), and that far side's name.
    std::vector<QuantityError> far_side_spread;
    std::string                other_far_side;

    bool has_usable_level() const { return used < outcomes.size(); }
    /// error[law], NaN when not estimated.
    double error_of(std::size_t law) const
    {
      return law < error.size() ? error[law] : std::numeric_limits<double>::quiet_NaN();
    }
    const LevelOutcome  &used_outcome() const { return outcomes.at(used); }
    const FidelityLevel &used_level() const { return levels.at(used); }
  };

  /**
   * Climb the fidelity ladder. Mesh phase: run (h, p₀) for h in `h_contact_levels` (coarse to
   * fine, p₀ = penalty_levels[0]) and stop at the first level whose k of every law
   * differs by at most `tolerance` (relative to the finer value) from the previous level. Penalty
   * phase (if more than one penalty level): at the mesh level reached, run the further penalty
   * factors with the same rule. The reported level is the last one run; its error per phase is
   * |k − k_previous| (not a Richardson extrapolation: convergence need not be monotone, and for
   * order p >= 1 at ratio 2 the difference bounds the Richardson estimate |Δ|/(2^p − 1)). A
   * level that fails stops the climb at the previous usable level (converged = false); a ladder
   * exhausted without meeting the tolerance reports its last level with converged = false.
   * @param[in] run computes one level; its exceptions propagate
   * @throws std::invalid_argument for empty level lists, non-positive values, h not decreasing,
   *         penalties not increasing or tolerance <= 0 (message names the argument and value).
   */
  LadderResult climb_fidelity_ladder(const std::vector<double> &h_contact_levels,
                                     const std::vector<double> &penalty_levels,
                                     double                     tolerance,
                                     const std::function<LevelOutcome(const FidelityLevel &)> &run);

  /**
   * The numerical error of each of ladder_quantities() between a coarse and a fine level, with
   * its verdict against ladder_quantity_tolerance.
   */
  std::vector<QuantityError> quantity_errors(const LevelOutcome &coarse, const LevelOutcome &fine);

  /**
   * Relative difference |a − b| / |b| (b the finer level); infinity if b == 0 and a != b.
   */
  double relative_change(double coarse, double fine);

  /**
   * Uncertainty of k_total = k_per_metre · W with independent errors of k (fit interval
   * half-width or numerical error) and of W: σ_total = sqrt((W·σ_k)² + (k·σ_W)²).
   */
  double
  total_stiffness_error(double k_per_metre, double k_error, double width, double width_error = 0.0);
} // namespace kimp::app
