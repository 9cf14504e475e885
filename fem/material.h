// Linear elastic isotropic material of the plane-strain FEM (the impact, the static and wall-SDOF
// solvers and the material laws share it): plain struct, no deal.II includes.
#pragma once

namespace kimp::fem
{
  /** Linear elastic isotropic material (plane strain). */
  struct Material
  {
    double youngs_modulus = 0; ///< E, Pa (> 0)
    double poisson_ratio  = 0; ///< nu, - (in [0, 0.5))
    double density        = 0; ///< rho, kg/m^3 (> 0)
  };
} // namespace kimp::fem
