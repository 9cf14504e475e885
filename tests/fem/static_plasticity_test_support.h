// Shared by the static-solver tests (fem/static_plasticity.h): the boundary ids of their test
// problems, uniform grid lines and the sides of a backfill box.
#pragma once

#include <functional>
#include <vector>

#include "fem/static_plasticity.h"

namespace kimp::fem::testing
{
  /** Boundary ids of the test problems. */
  constexpr unsigned int free_surface = 0, wall = 1, base = 2, far_side = 3, symmetry = 4,
                         footing = 5;

  /** n + 1 equally spaced grid lines from a to b. */
  inline std::vector<double> uniform(double a, double b, unsigned int n)
  {
    return graded_coordinates(a, b, n, 1.0);
  }

  /** The boundary ids of a backfill [0, L] x [0, H] pushed at x = 0: `wall` there, `far_side`
   *  at x = L, `base` along y = 0 between them, `free_surface` elsewhere (within `tol`). */
  inline std::function<unsigned int(double, double)> backfill_sides(double L, double tol)
  {
    return [=](double x, double y) {
      return x < tol ? wall : x > L - tol ? far_side : y < tol ? base : free_surface;
    };
  }
} // namespace kimp::fem::testing
