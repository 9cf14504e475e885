// Mean-dilatation B-bar (the Q1/P0 element of Nagtegaal, Parks & Rice 1974) of a plane-strain
// cell, shared by the static solver (static_plasticity.cc) and the impact solver (fem/impact/):
// the in-plane volumetric strain of every Gauss point is replaced by its cell mean,
//   eps_bar_q = eps_q + 1/2 (theta_mean - theta_q) (1, 1, 0),  theta = eps_xx + eps_yy,
// so that isochoric or nearly isochoric plastic flow does not lock the Q1 element. The same map
// gives the B-bar operator (applied to each DoF's column of B over the points) and, being
// self-adjoint in the JxW-weighted sum over the points, the B-bar internal force:
//   sum_q B_bar_q^T sigma_q w_q = sum_q B_q^T sigma_hat_q w_q with sigma_hat the same map of sigma.
#pragma once

#include <array>

namespace kimp::fem
{
  /** Replaces the in-plane trace v[q][0] + v[q][1] of each of the n Voigt vectors (one per
   *  Gauss point of one cell, weights jxw) by its JxW-weighted cell mean, shared equally between
   *  the xx and yy entries; v[q][2] (shear) is unchanged. */
  inline void average_in_plane_trace(std::array<double, 3> *v, const double *jxw, unsigned int n)
  {
    double mean = 0, area = 0;
    for (unsigned int q = 0; q < n; ++q)
    {
      mean += (v[q][0] + v[q][1]) * jxw[q];
      area += jxw[q];
    }
    mean /= area;
    for (unsigned int q = 0; q < n; ++q)
    {
      const double shift = 0.5 * (mean - (v[q][0] + v[q][1]));
      v[q][0] += shift;
      v[q][1] += shift;
    }
  }
} // namespace kimp::fem
