// The in-plane eigen-decomposition of a symmetric 2 x 2 tensor and the rotation of a Voigt tangent
// out of a rotated frame, which the inelastic plane-strain laws share (soil_laws.cc,
// concrete_damage_law.cc). Allocation-free, plain C++.
#pragma once

#include <cmath>

#include "fem/material_law.h"

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

  /** The plane-strain Voigt tangent in x, y of a tangent `frame` given in the frame of unit
   *  vectors (c, s) and (-s, c): C = R^T C' R, R the engineering-strain rotation into the frame
   *  (the strain {xx, yy, gamma_xy} -> {aa, bb, gamma_ab}). */
  inline VoigtTangent tangent_from_frame(const VoigtTangent &frame, double c, double s)
  {
    const double cc = c * c, ss = s * s, cs = c * s;
    const double R[3][3] = {{cc, ss, cs}, {ss, cc, -cs}, {-2 * cs, 2 * cs, cc - ss}};
    VoigtTangent out{};
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        double v = 0;
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = 0; l < 3; ++l)
            v += R[k][i] * frame[3 * k + l] * R[l][j];
        out[3 * i + j] = v;
      }
    return out;
  }
} // namespace kimp::fem::detail
