// The in-plane eigen-decomposition of a symmetric 2 x 2 tensor that the inelastic plane-strain
// laws share (soil_laws.cc, concrete_damage_law.cc). Allocation-free, plain C++.
#pragma once

#include <cmath>

namespace kimp::fem::detail
{
  /** In-plane eigen-decomposition of a symmetric 2 x 2 tensor {xx, yy, xy}: values a >= b,
   *  unit eigenvector of a = (c, s) = (cos t, sin t), t = atan2(xy, d) / 2 in (-pi/2, pi/2],
   *  from the half-angle formulas (no trigonometric calls; equal to them up to round-off). */
  inline void eigen2(double xx, double yy, double xy, double &a, double &b, double &c, double &s)
  {
    const double m = 0.5 * (xx + yy), d = 0.5 * (xx - yy);
    const double r = std::sqrt(d * d + xy * xy);
    a              = m + r;
    b              = m - r;
    if (!(r > 0))
    {
      c = 1;
      s = 0;
    }
    else if (d >= 0)
    {
      // cos 2t = d / r >= 0: c >= 1 / sqrt(2), s from sin 2t = 2 s c.
      c = std::sqrt(0.5 * (1 + d / r));
      s = xy / (2 * r * c);
    }
    else
    {
      // |t| > pi / 4: |s| >= 1 / sqrt(2) with the sign of xy (t = +-pi/2 at xy = +-0).
      s = std::copysign(std::sqrt(0.5 * (1 - d / r)), xy);
      c = xy / (2 * r * s);
    }
  }

  /** The eigenvalues a >= b of eigen2(), without the eigenvector (no trigonometry). */
  inline void principal2(double xx, double yy, double xy, double &a, double &b)
  {
    const double m = 0.5 * (xx + yy), d = 0.5 * (xx - yy);
    const double r = std::sqrt(d * d + xy * xy);
    a              = m + r;
    b              = m - r;
  }
} // namespace kimp::fem::detail
