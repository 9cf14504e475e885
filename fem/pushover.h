// Static pushover of the moat wall and its backfill (docs/physics.md §6 "Static pushover"): the
// slab's contact band on the wall face pushed by a prescribed displacement through the static
// plasticity solver (fem/static_plasticity.h), with gravity, the geostatic state and the wall-soil
// interface; monotonic or cyclic (unload to zero force, reload, push further). The curve's
// engineering summary (capacity, stiffnesses, permanent set) is what a lumped wall-and-backfill
// element is fitted to. Plain-struct header, no deal.II includes.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "fem/impact.h"
#include "fem/inelastic_laws.h"
#include "fem/static_plasticity.h"
#include "fem/static_step_statistics.h"

namespace kimp::fem
{
  /** Everything run_pushover() needs; SI units, per metre of wall (plane strain). */
  struct PushoverParameters
  {
    /** What the wall is. */
    enum class Wall
    {
      reinforced, ///< concrete damage law; bars in one column of cells at `cover` from each face
      elastic,    ///< linear elastic `wall_elastic`, base clamped
      rigid       ///< translated as a rigid body (base and band pushed together): backfill alone
    };
    Wall   wall           = Wall::reinforced;
    double wall_height    = 1.25; ///< H, m
    double wall_thickness = 0.25; ///< t, m
    /** The slab's contact band on the wall face x = 0: y in [band_bottom, band_top], m. */
    double band_bottom = 1.05;
    double band_top    = 1.25;
    /** Wall::reinforced: concrete and bars. bars.ratio_y is the vertical steel of the whole
     *  section (area / t), half of it at each face; bars.ratio_x (ties) is smeared everywhere. */
    ConcreteParameters      concrete;
    ReinforcementParameters bars;
    double                  cover = 0.05; ///< bar centre to the wall face, m (0 < cover < t / 2)
    /**
     * The concrete's damage update: IMPL-EX (true; ConcreteDamageLaw::DamageUpdate::implex,
     * docs/physics.md §6 "Static pushover": Newton converges in few iterations through cracking,
     * at an extrapolation error controlled by `increment`) or implicit (false: backward Euler,
     * which stalls at the first cracks of a wall under earth pressure).
     */
    bool implex = true;
    /**
     * The wall concrete's crack frame (ConcreteParameters::rotating_crack, which this
     * overrides): rotating (true) or fixed at the first crack. A fixed frame locks tension
     * across the cracks of the wall's hinge and makes the capacity mesh-dependent
     * (docs/physics.md §6 "Crack frame of the pushover").
     */
    bool rotating_crack = true;
    /**
     * The wall concrete's crack band in compression, m (ConcreteParameters::compression_band,
     * which this overrides; 0: the local curve). The MC2010 curve's descending branch read as
     * measured over a 0.3 m crush band, the standard cylinder's height, so that crushing at the
     * hinge's toe dissipates the same energy per unit area on every mesh.
     */
    double compression_band = 0.3;
    /**
     * IMPL-EX step control (with implex): a step after which some point of the concrete let
     * through more than this many f_t of tensile stress beyond the implicit update's (the
     * extrapolated damage lagging a new crack) is halved while the step is above increment / 8
     * (StaticPlasticityParameters::step_error_tolerance; 0: off, >= 0).
     */
    double step_error_tolerance = 1;
    /** Wall::elastic and Wall::rigid (the rigid wall is this material stiffened 1000 times). */
    Material wall_elastic{30e9, 0.2, 2400};
    double   wall_density = 2400; ///< kg/m^3 (gravity of the wall)

    bool with_backfill = true;
    /** The backfill block x in [t, t + backfill_width], y in [0, backfill_height], m, base
     *  fixed, far side on rollers. */
    double backfill_width  = 10;
    double backfill_height = 1.25;
    /** The soil's law: Mohr-Coulomb (perfectly plastic) from these parameters. */
    SoilParameters soil;
    /** Geostatic state: gravity on wall and soil and sigma_h = K0 gamma z in the soil. */
    bool   geostatic = true;
    double k0        = 0.5;
    double gravity   = 9.81; ///< m/s^2
    /** Wall-soil interface: bonded (shared nodes) or unilateral Coulomb contact of node pairs. */
    bool   interface_contact = true;
    double friction          = 0.45; ///< Coulomb mu of the contact
    /** Normal and tangential penalty per pair / (E_soil / h x tributary length) (> 0). */
    double interface_penalty = 10;

    /** Cell size in the wall and the soil next to it, m (> 0). */
    double element_size = 0.025;
    /** Largest soil cell, m (>= element_size); soil cells grow by `grading` away from the wall. */
    double max_element_size = 0.2;
    double grading          = 1.2;

    /**
     * The band displacement path, m (toward the backfill positive): push to each entry in turn;
     * an entry below the current displacement unloads until the band force falls to zero (or
     * the entry is reached). Monotonic: {u_max}; cyclic: {u1, 0, u_max}.
     */
    std::vector<double> path{0.05};
    double              increment = 1e-3; ///< largest band displacement step, m (> 0)
    /**
     * Automatic step control (docs/physics.md §6 "Static pushover", "Steps"): a step whose
     * Newton iteration does not converge is halved, down to the smallest halving of
     * `increment` not below this (m, > 0, <= increment: increment itself never halves); a
     * step that still fails there is accepted within loose_tolerance or ends the push with
     * NumericalError.
     */
    double min_increment = 2e-5;
    /**
     * A halved step is kept and doubled again after this many consecutive easy steps (each
     * within max_iterations / 4 Newton iterations), up to `increment`
     * (StaticPlasticityParameters::grow_after); 0: the halves of a halved step are walked and
     * the next step is `increment` again (bisection).
     */
    unsigned int grow_after = 2;
    /** First step (m, > 0, < increment): the initial stiffness is its secant. */
    double first_increment = 2e-5;
    /**
     * Newton converged when the out-of-balance force is at most this fraction of the largest
     * force (> 0). Cracking concrete makes Newton cycle near 1e-4 at a few steps; 1e-4 is still
     * 50 times stricter than the 5e-3 of common commercial defaults.
     */
    double tolerance = 1e-4;
    /** A step that cannot meet `tolerance` even halved is accepted within this (> 0, >=
     *  tolerance); PushoverResult counts such steps. */
    double loose_tolerance = 1e-3;
    /** Newton iterations per (sub)step before it is halved (> 0). */
    unsigned int max_iterations = 40;
  };

  /** One converged step of the pushover. */
  struct PushoverPoint
  {
    double       displacement = 0; ///< band displacement, m
    double       force        = 0; ///< band force beyond the geostatic state, N/m
    unsigned int segment      = 0; ///< index in PushoverParameters::path
    bool         unloading    = false;
  };

  /** The final state of one cell of the pushover mesh: where the wall cracked and yielded, and
   *  what carries its stress (StaticPlasticityResult::CellState, cell means). */
  struct PushoverCell
  {
    StaticPlasticityResult::CellState state;
    bool                              in_wall = false; ///< x < t (the wall is x in [0, t])
    bool in_bars = false; ///< one of the wall's bar columns (Wall::reinforced)
  };

  struct PushoverResult
  {
    std::vector<PushoverPoint> curve; ///< from the geostatic state (0, 0)
    /** Band force of the geostatic state (the at-rest earth pressure the band holds), N/m. */
    double                    geostatic_force     = 0;
    double                    plastic_dissipation = 0; ///< J/m, soil plasticity and bars
    double                    damage_dissipation  = 0; ///< J/m, concrete cracking and crushing
    unsigned long             n_cells             = 0;
    unsigned long             n_dofs              = 0;
    unsigned int              n_interface_pairs   = 0;
    StaticStepStatistics      step_control;
    std::vector<PushoverCell> cells; ///< the final state, one per cell
    /** The smallest converged step of the band displacement after the first one (m). */
    double smallest_increment = 0;
    /** Per converged step (curve[k] for k >= 1): its relative out-of-balance force after each
     *  Newton solve (the last one within `tolerance`). */
    std::vector<std::vector<double>> step_residuals;
  };

  /**
   * What a lumped wall-and-backfill element is fitted to (docs/physics.md §6 "Static pushover").
   * Quantities a curve does not show (no unloading: unloading stiffness and permanent set) are
   * NaN.
   */
  struct PushoverSummary
  {
    double capacity                 = 0; ///< largest band force, N/m
    double displacement_at_capacity = 0; ///< m
    double initial_stiffness        = 0; ///< secant of the first step, N/m per m
    /** Secant through the point where the force first reaches 75 % of the capacity (the
     *  effective cracked stiffness of Priestley's bilinear idealisation), N/m per m. */
    double cracked_stiffness = 0;
    double force_at_1cm      = 0; ///< band force at 10 mm (NaN if the push stops short), N/m
    /** First unloading: secant from its start to zero force, N/m per m. */
    double unloading_stiffness = 0;
    double permanent_set       = 0; ///< band displacement at zero force after that unloading, m
    double unloaded_from       = 0; ///< band displacement where that unloading starts, m
  };

  /**
   * Runs the pushover: step 0 brings gravity and the geostatic stress into equilibrium with the
   * band held; then the band follows `path` in steps of at most `increment`, full Newton per
   * step (run_static_plasticity). One log line per step to *log if not nullptr. Bad parameters
   * throw std::invalid_argument naming them; a step that does not converge throws
   * NumericalError.
   */
  PushoverResult run_pushover(const PushoverParameters &parameters, std::ostream *log = nullptr);

  /** The summary of a curve (see PushoverSummary). */
  PushoverSummary summarise_pushover(const std::vector<PushoverPoint> &curve);

  /** The monotonic envelope's force at band displacement @p u (linear between the loading
   *  points of @p curve; NaN outside them). */
  double envelope_force(const std::vector<PushoverPoint> &curve, double u);
} // namespace kimp::fem
