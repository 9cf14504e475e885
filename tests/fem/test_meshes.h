// Structured quadrilateral test meshes written as ASCII MSH 2.2 with material and boundary ids
// (geometry/scene_ids.h numbers), for scenes the scene builder does not make (two bars).
#pragma once

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

namespace kimp::fem::testing
{
  /** A rectangle [x0, x1] x [y0, y1] of nx x ny cells; side ids 0 = untagged. */
  struct Block
  {
    double       x0, x1, y0, y1;
    unsigned int nx, ny;
    unsigned int material;
    unsigned int left = 0, right = 0, bottom = 0, top = 0;
  };

  /** Writes the blocks (nodes shared where blocks share grid points) as MSH 2.2. */
  inline void write_blocks_msh(const std::vector<Block> &blocks, const std::filesystem::path &file)
  {
    std::map<std::pair<long long, long long>, unsigned int> id_of;
    std::vector<std::array<double, 2>>                      nodes;
    constexpr double                                        key_scale = 1e9;
    const auto                                              node      = [&](double x, double y)
    {
      const std::pair<long long, long long> key{std::llround(x * key_scale),
                                                std::llround(y * key_scale)};
      const auto                            it = id_of.find(key);
      if (it != id_of.end())
        return it->second;
      nodes.push_back({{x, y}});
      return id_of[key] = static_cast<unsigned int>(nodes.size());
    };
    std::vector<std::array<unsigned int, 3>> lines; // tag, n0, n1
    std::vector<std::array<unsigned int, 5>> quads; // tag, n0..n3
    for (const auto &b : blocks)
    {
      const auto x = [&](unsigned int i) { return b.x0 + (b.x1 - b.x0) * i / b.nx; };
      const auto y = [&](unsigned int j) { return b.y0 + (b.y1 - b.y0) * j / b.ny; };
      for (unsigned int j = 0; j < b.ny; ++j)
        for (unsigned int i = 0; i < b.nx; ++i)
          quads.push_back({{b.material,
                            node(x(i), y(j)),
                            node(x(i + 1), y(j)),
                            node(x(i + 1), y(j + 1)),
                            node(x(i), y(j + 1))}});
      for (unsigned int j = 0; j < b.ny; ++j)
      {
        if (b.left != 0)
          lines.push_back({{b.left, node(b.x0, y(j)), node(b.x0, y(j + 1))}});
        if (b.right != 0)
          lines.push_back({{b.right, node(b.x1, y(j)), node(b.x1, y(j + 1))}});
      }
      for (unsigned int i = 0; i < b.nx; ++i)
      {
        if (b.bottom != 0)
          lines.push_back({{b.bottom, node(x(i), b.y0), node(x(i + 1), b.y0)}});
        if (b.top != 0)
          lines.push_back({{b.top, node(x(i), b.y1), node(x(i + 1), b.y1)}});
      }
    }
    std::ofstream out(file);
    if (!out)
      throw std::runtime_error("cannot write " + file.string());
    out.precision(17);
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << nodes.size() << '\n';
    for (std::size_t i = 0; i < nodes.size(); ++i)
      out << i + 1 << ' ' << nodes[i][0] << ' ' << nodes[i][1] << " 0\n";
    out << "$EndNodes\n$Elements\n" << lines.size() + quads.size() << '\n';
    std::size_t e = 1;
    for (const auto &l : lines)
      out << e++ << " 1 2 " << l[0] << ' ' << l[0] << ' ' << l[1] << ' ' << l[2] << '\n';
    for (const auto &q : quads)
      out << e++ << " 3 2 " << q[0] << ' ' << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3]
          << ' ' << q[4] << '\n';
    out << "$EndElements\n";
  }
} // namespace kimp::fem::testing
