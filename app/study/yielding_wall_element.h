// The yielding wall element of an inelastic `kimp study` (docs/physics.md §2 "Yielding moat wall",
// "Element of a study"): its parameters derived in one place from a wall height's inputs, so that
// a pushover curve can replace the capacity estimate without touching the building runs.
#pragma once

#include <limits>
#include <vector>

#include "app/fem/fem_scene.h"
#include "app/laws/yielding_wall_scene.h"
#include "app/lumped/lumped_scene.h"

namespace kimp::app
{
  /**
   * What the element is derived from, per metre of wall (SI). yielding_wall_inputs() fills it
   * from a FEM scene (the capacity estimate and the materials); a pushover can fill the
   * resistance terms instead.
   */
  struct YieldingWallInputs
  {
    // Wall-and-backfill resistance (the static pushover or its estimate).
    double capacity            = 0.0; ///< F_y, N/m
    double stiffness           = 0.0; ///< k, initial (cracked) tangent, N/m per m
    double unloading_stiffness = 0.0; ///< k_ur (> 0; below k: a cracked wall), N/m per m
    double hardening_ratio     = 0.0; ///< α of the post-yield tangent α·k
    /// F_u, N/m: the force the hardening stops at (a pushover's largest force; +inf: no cap)
    double ultimate_capacity = std::numeric_limits<double>::infinity();
    /// The envelope as a curve (a pushover's concave hull), from (0, 0), m and N/m; empty: the
    /// bilinear of capacity, stiffness, hardening_ratio and ultimate_capacity.
    std::vector<double> envelope_displacements;
    std::vector<double> envelope_forces;
    // Radiation into the backfill.
    double soil_density    = 0.0; ///< ρ_s, kg/m³
    double soil_wave_speed = 0.0; ///< c_s, m/s
    double loaded_height   = 0.0; ///< the backfill height the wall pushes, m
    // The first peak (a wave through slab and wall over the contact band).
    double slab_impedance = 0.0; ///< Z_slab = ρ·c·t_slab, N·s/m per m (+inf: a rigid slab)
    double wall_impedance = 0.0; ///< Z_wall = ρ·c_p·t_w through the wall, N·s/m per m
    double wall_mass      = 0.0; ///< the wall DOF's mass, kg/m
    double striker_mass   = 0.0; ///< the mass that hits the wall, kg/m
    double wall_height    = 0.0; ///< H, m (the failure limit is 10 % of it)
  };

  /// The derived element, per metre of wall except where said.
  struct YieldingWallElement
  {
    YieldingWallScene backfill;                ///< the wall-and-backfill part (width set)
    double            contact_impedance = 0.0; ///< Z_c = 1/(1/Z_slab + 1/Z_wall), N·s/m per m
    double            reduced_mass      = 0.0; ///< m_w·m_s/(m_w + m_s), kg/m
    double            contact_stiffness = 0.0; ///< k_c = Z_c²/m_red, N/m per m
    double            wall_mass         = 0.0; ///< kg/m
    double            radiation_damping = 0.0; ///< c_r, N·s/m per m: ρ_s·c_p·H_b, or fitted
    double            width             = 0.0; ///< W, m
  };

  /**
   * The element of `in` for a wall `width` wide:
   * - wall-and-backfill part: the curve envelope of `in` (its pushover's concave hull) or else
   *   the bilinear of k, F_y, α, F_u; k_ur of `in`, the pull-back equal to the capacity F_y, the
   *   failure limit 10 % of H;
   * - radiation dashpot: c_r = ρ_s·c_s·h (the backfill's plane-wave impedance over the loaded
   *   height);
   * - contact part: a linear spring whose first peak against the wall's mass is the impedance's,
   *   k_c·δ = Z_c·v at the first quarter period: k_c = Z_c²/m_red, Z_c the series impedance of
   *   slab and wall (a bar's end impact), m_red the reduced mass of wall and striker.
   * @throws std::invalid_argument naming the input that is not positive.
   */
  YieldingWallElement derive_yielding_wall(const YieldingWallInputs &in, double width);

  /**
   * The inputs of `scene` at `wall_height` (m), the striker `striker_mass` kg/m:
   * - capacity: wall_capacity_estimate() (M_p + P_p·H_b/3)/h_c;
   * - stiffness: the cracked cantilever loaded at h_c, 3·(½E·I_g)/h_c³, I_g = t³/12 (half the
   *   gross stiffness for a cracked section, EN 1998-1 §4.3.1(7)); k_ur = k; α = 0;
   * - soil: ρ and the P-wave speed √(E(1 − ν)/((1 + ν)(1 − 2ν))/ρ) of materials.soil, h = H_b;
   * - impedances: the slab a plane-strain bar, ρ·c_ps·t_slab with c_ps = √(E/(ρ(1 − ν²))); the
   *   wall ρ·c_p·t_w, the P-wave speed c_p = √(E(1 − ν)/((1 + ν)(1 − 2ν))/ρ) (1D strain: the wall
   *   continues above and below the band) over the wall's thickness, the width the wave has
   *   spread over when the force peaks, after it crossed the wall and back (docs/physics.md:
   *   the dynamic FEM's first peak against a rigid face is ρ·c_p·t_w·v within 1 %);
   * - wall mass: the concrete of the wall above its base, ρ·t·H (the backfill's inertia is the
   *   dashpot's).
   */
  YieldingWallInputs
  yielding_wall_inputs(const FemScene &scene, double wall_height, double striker_mass);

  /**
   * `base` (a building without walls) between two yielding walls of `e` at `gap` (m): the
   * contact part the linear law of k_c·W, the wall DOF of m_w·W, the wall-and-backfill part of
   * e.backfill.
   */
  LumpedScene
  yielding_walled_scene(const LumpedScene &base, double gap, const YieldingWallElement &e);
} // namespace kimp::app
