// A linear study's estimate of the moat wall's static collapse load (docs/physics.md §2
// "Yielding moat wall", "Capacity estimate"): F = (M_p + M_soil)/h_c per metre, a plastic hinge
// at the wall's base plus the Rankine passive resistance of its backfill, against which the
// building runs' peak impact forces are read.
#pragma once

#include "app/fem/fem_scene.h"

namespace kimp::app
{
  /// The terms of the estimate, per metre of wall (SI).
  struct WallCapacityEstimate
  {
    double plastic_moment = 0.0; ///< M_p of the wall's base section, N·m/m
    double passive_force  = 0.0; ///< Rankine P_p = ½K_p·γ·H_b² + 2c·√K_p·H_b, N/m
    double passive_moment = 0.0; ///< its moment about the base (P_p·H_b/3 for c = 0), N·m/m
    double contact_height = 0.0; ///< h_c: the slab's mid-thickness above the base, m
    double per_metre      = 0.0; ///< (M_p + passive_moment)/h_c, N/m
  };

  /**
   * The estimate for the FEM scene `scene` at `wall_height` (m). M_p: with vertical bars
   * (concrete.wall_reinforcement.ratio_y > 0) the tension half ρ_y·t/2 at d = 0.9t yielding,
   * M_p = A_s·f_y·(d − a/2), a = A_s·f_y/(0.85·f_cm); without bars the plain section's cracking
   * moment f_ctm·t²/6. Soil: φ, c and ρ of materials.soil (its preset resolved), H_b the backfill
   * height.
   */
  WallCapacityEstimate wall_capacity_estimate(const FemScene &scene, double wall_height);
} // namespace kimp::app
