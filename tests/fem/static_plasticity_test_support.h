// Shared by the static-solver tests (fem/static_plasticity.h): the boundary ids of their test
// problems and uniform grid lines.
#pragma once

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
} // namespace kimp::fem::testing
