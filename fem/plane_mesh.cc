// The inputs of the static plasticity solver that need no deal.II (see static_plasticity.h):
// tensor-product meshes on given or graded grid lines and the geostatic initial stress.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "fem/static_plasticity.h"

namespace kimp::fem
{
  PlaneMesh tensor_product_mesh(const std::vector<double>                         &xs,
                                const std::vector<double>                         &ys,
                                unsigned int                                       material,
                                const std::function<unsigned int(double, double)> &boundary_id)
  {
    const auto increasing = [](const std::vector<double> &v)
    {
      for (std::size_t i = 1; i < v.size(); ++i)
        if (!(v[i] > v[i - 1]))
          return false;
      return v.size() >= 2;
    };
    if (!increasing(xs) || !increasing(ys))
      throw std::invalid_argument("tensor_product_mesh: xs and ys must hold >= 2 strictly "
                                  "increasing coordinates");
    const unsigned int nx = xs.size() - 1, ny = ys.size() - 1;
    const auto         v = [&](unsigned int i, unsigned int j) { return j * (nx + 1) + i; };
    PlaneMesh          m;
    for (unsigned int j = 0; j <= ny; ++j)
      for (unsigned int i = 0; i <= nx; ++i)
        m.vertices.push_back({{xs[i], ys[j]}});
    for (unsigned int j = 0; j < ny; ++j)
      for (unsigned int i = 0; i < nx; ++i)
        m.cells.push_back({{{v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)}}, material});
    const auto edge = [&](unsigned int a, unsigned int b)
    {
      const double x = 0.5 * (m.vertices[a][0] + m.vertices[b][0]);
      const double y = 0.5 * (m.vertices[a][1] + m.vertices[b][1]);
      m.boundary_edges.push_back({{{a, b}}, boundary_id ? boundary_id(x, y) : 0u});
    };
    for (unsigned int i = 0; i < nx; ++i)
    {
      edge(v(i, 0), v(i + 1, 0));
      edge(v(i, ny), v(i + 1, ny));
    }
    for (unsigned int j = 0; j < ny; ++j)
    {
      edge(v(0, j), v(0, j + 1));
      edge(v(nx, j), v(nx, j + 1));
    }
    return m;
  }

  std::vector<double> graded_coordinates(double a, double b, unsigned int n, double ratio)
  {
    if (!(b > a) || n == 0 || !(ratio > 0))
      throw std::invalid_argument("graded_coordinates: need b > a, n > 0, ratio > 0");
    std::vector<double> x(n + 1);
    const double        h0 =
      ratio == 1 ? (b - a) / n : (b - a) * (1 - ratio) / (1 - std::pow(ratio, double(n)));
    x[0] = a;
    for (unsigned int k = 0; k < n; ++k)
      x[k + 1] = x[k] + h0 * std::pow(ratio, double(k));
    x[n] = b;
    return x;
  }

  InitialStressField geostatic_stress(double surface_y, double unit_weight, double k0)
  {
    return [=](double, double y) -> VoigtStress
    {
      const double z = std::max(0.0, surface_y - y);
      return {{-k0 * unit_weight * z, -unit_weight * z, 0.0}};
    };
  }
} // namespace kimp::fem
