// The moat wall with its backfill as a single-DOF oscillator seen from the slab (docs/physics.md
// §4 "Wall SDOF"): static stiffness under the slab's contact band and the participating mode of
// a modal analysis of the same FE model. Light public header: plain structs, no deal.II includes.
#pragma once

#include <filesystem>
#include <map>
#include <vector>

#include "fem/material.h"
#include "fem/numerical_error.h"

namespace kimp::fem
{
  /** What wall_sdof() needs: the wall (+ backfill) mesh, its materials and the loaded band. */
  struct WallSdofParameters
  {
    /**
     * ASCII MSH file with the material and boundary ids of geometry/scene_ids.h: wall (and
     * soil) cells only (a mesh written with SceneGeometry::mesh_slab = false); fixed_base is
     * clamped, soil_far_side has rollers (u_x = 0), the load acts on wall_contact.
     */
    std::filesystem::path mesh_file;
    /** Linear elastic material per material id; every id of the mesh must be given. */
    std::map<unsigned int, Material> materials;
    /** The slab's contact band on the wall face x = 0, y in [band_y0, band_y1], m. */
    double band_y0 = 0;
    double band_y1 = 0;
    /** Polynomial degree of the displacement (2: Q2, free of the shear locking of Q1 on the
     *  two to ten cells across the wall; >= 1). */
    unsigned int fe_degree = 2;
    /** Lowest modes resolved by the subspace iteration (the block has 2 n_modes + 2 vectors;
     *  >= 1). */
    unsigned int n_modes = 8;
    /** Converged when every resolved eigenvalue changes by less than this, relative (> 0). */
    double tolerance = 1e-10;
    /** Subspace iterations before NumericalError (> 0). */
    unsigned int max_iterations = 200;
  };

  /** One mode of the wall-soil model: frequency and how much of the static deflection it makes. */
  struct WallMode
  {
    double omega     = 0; ///< rad/s
    double frequency = 0; ///< Hz
    /** Share of the static compliance under the band load: (f^T phi)^2 / (omega^2 phi^T M phi)
     *  times k_static, in [0, 1]; the shares of all modes sum to 1. */
    double share = 0;
    /** Generalised mass with the mode scaled to unit load-weighted band displacement,
     *  phi^T M phi / (f^T phi)^2, kg per metre (infinite for a mode without band motion). */
    double band_mass = 0;
  };

  /**
   * The wall SDOF per metre of wall (plane strain), wall_sdof()'s result: k and m_eff match the
   * band's receptance sum_i (f^T phi_i)^2 / (omega_i^2 - omega^2) to second order in omega
   * (static compliance and first inertia term), over all modes.
   */
  struct WallSdof
  {
    /** 1 / (load-weighted mean x displacement of the band) under 1 N/m uniformly spread over
     *  the band, N/m per metre. */
    double static_stiffness = 0;
    /** Participation mass k^2 u_s^T M u_s = k sum_i share_i / omega_i^2 (u_s the static
     *  deflection), kg per metre: Rayleigh's mass of the static shape at unit band motion. */
    double effective_mass = 0;
    double omega          = 0; ///< sqrt(k / m_eff), rad/s: Rayleigh's quotient of u_s
    double frequency      = 0; ///< Hz
    /** k sum_i share_i / omega_i^2 over the computed modes only, kg per metre
     *  (<= effective_mass; the gap is what the higher modes carry). */
    double       modal_sum_mass = 0;
    unsigned int mode           = 0; ///< index in `modes` of the mode with the largest share
    double       mode_frequency = 0; ///< Hz, of that mode
    double       mode_share     = 0; ///< its share (see WallMode)
    /** k / omega_mode^2, kg per metre: the SDOF with the static stiffness and that mode's
     *  frequency (= mode_share times its band mass). */
    double                mode_mass  = 0;
    double                total_mass = 0; ///< kg per metre, of every cell of the mesh
    std::vector<WallMode> modes;          ///< the n_modes lowest, ascending
    unsigned long         n_dofs     = 0;
    unsigned long         n_cells    = 0;
    unsigned int          iterations = 0; ///< subspace iterations
  };

  /**
   * Static stiffness and participating mode of the wall (+ backfill) of `parameters` under the
   * slab band: K u = f (sparse direct), then the lowest n_modes of K phi = omega^2 M phi
   * (consistent mass) by subspace iteration on K^-1 M (one factorization of K; the block is
   * seeded with the static deflection so that the modes the band excites are in it) with
   * Rayleigh-Ritz, for the shares of the static compliance; m_eff from the static deflection.
   * Serial. Bad input throws std::invalid_argument naming the parameter; no convergence throws
   * NumericalError.
   */
  WallSdof wall_sdof(const WallSdofParameters &parameters);

  /**
   * Timoshenko stiffness of a plane-strain cantilever (height H, thickness t, base clamped)
   * under a horizontal load spread uniformly over its top `band` length, as 1 / the
   * load-weighted mean deflection of the band: with b = H - band,
   * 1/k = (3 (H^5 - b^5)/20 - b^3 (H^2 - b^2)/2 + b^4 (H - b)/4) / (3 E' I band^2)
   * + (H - 2 band/3) / (kappa G t); E' = E / (1 - nu^2), I = t^3/12, kappa = 5/6. band -> 0 is
   * timoshenko_tip_stiffness(). N/m per metre.
   */
  double
  timoshenko_band_stiffness(double height, double thickness, const Material &material, double band);
} // namespace kimp::fem
