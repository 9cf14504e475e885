// The flexible moat wall of `kimp study` (docs/physics.md §4 "Wall SDOF"): each height's wall
// (+ backfill) as a SDOF from its FE model, and the building run against it beside the rigid wall.
#pragma once

#include <string>
#include <vector>

#include "app/lumped/lumped_scene.h"

namespace kimp::app
{
  /** The wall SDOF of one wall height: per metre of wall (FE, plane strain) and for the building
   *  side (times the building width W, as k_total). */
  struct StudyWallSdof
  {
    double      wall_height = 0.0;          ///< m
    std::string name;                       ///< "H1.25"
    std::string status              = "ok"; ///< "ok" or "failed: ..."
    double      stiffness_per_metre = 0.0;  ///< static stiffness at the slab band, N/m per m
    /// The SDOF's mass per metre, kg/m: the participation mass (walls.flexible_mass:
    /// participation) or k / omega_mode^2 (mode)
    double              mass_per_metre               = 0.0;
    double              frequency                    = 0.0; ///< Hz, sqrt(k / m) / 2 pi of the SDOF
    double              participation_mass_per_metre = 0.0; ///< kg/m, k^2 u_s^T M u_s (all modes)
    double              modal_sum_mass_per_metre = 0.0; ///< kg/m, the same over the computed modes
    unsigned int        mode                     = 0;   ///< mode with the largest share (0-based)
    double              mode_frequency           = 0.0; ///< Hz
    double              mode_share               = 0.0; ///< its share of the static deflection
    double              mode_mass_per_metre      = 0.0; ///< kg/m, k / omega_mode^2
    double              total_mass_per_metre     = 0.0; ///< kg/m, wall + backfill of the model
    double              stiffness                = 0.0; ///< k_wall = stiffness_per_metre * W, N/m
    double              mass                     = 0.0; ///< m_wall = mass_per_metre * W, kg
    double              damping_ratio            = 0.0; ///< zeta (scene walls.damping_ratio)
    double              h_contact                = 0.0; ///< m, contact element size of the mesh
    unsigned long       n_dofs                   = 0;
    double              seconds                  = 0.0; ///< s, meshing and solving
    std::vector<double> mode_frequencies;               ///< Hz, lowest modes ascending
    std::vector<double> mode_shares;                    ///< their shares of the static deflection

    bool ok() const { return status == "ok"; }
  };


  /**
   * `rigid` (a study building scene with its walls present) with both walls flexible: the SDOF's
   * stiffness, mass (`sdof_mass`: the wall's inertia) and damping ratio. The walls' `mass` stays
   * the rigid run's, so the impact law keeps its m_eff and dashpot constant.
   */
  LumpedScene flexible_wall_scene(const LumpedScene &rigid, const StudyWallSdof &sdof);
} // namespace kimp::app
