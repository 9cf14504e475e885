// The scene meshes of the geometry tests read back with gmsh (MeshFile), the file each test
// writes, and the invariants every valid scene's mesh satisfies (areas, orientation, the bonded
// interface, the gap, sizes and grading), shared by the scene mesh test files.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <gmsh.h>
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "geometry/gmsh_session.h"
#include "geometry/graded_spacing.h"
#include "geometry/scene_geometry.h"
#include "geometry/scene_ids.h"
#include "tests/support/temp_dir.h"

namespace kimp::testing::scene_mesh
{
  using namespace kimp::geometry;

  constexpr double area_tolerance       = 1e-12; // relative
  constexpr double coordinate_tolerance = 1e-12; // m
  constexpr double ratio_tolerance      = 1e-12; // relative, on size ratios and caps

  using Quad = std::array<std::size_t, 4>;
  using Line = std::array<std::size_t, 2>;

  // The mesh file as gmsh reads it: nodes, quads per material id, lines per boundary id.
  struct MeshFile
  {
    std::map<std::size_t, std::array<double, 2>> nodes;
    std::map<int, std::vector<Quad>>             quads;
    std::map<int, std::vector<Line>>             lines;
    std::set<std::pair<int, int>>                groups; // (dim, tag)
    std::map<std::pair<int, int>, std::string>   names;
    std::set<int>                                element_types;
    std::size_t                                  n_entities_with_one_group = 0;
    std::size_t                                  n_entities                = 0;

    double x(std::size_t node) const { return nodes.at(node)[0]; }
    double y(std::size_t node) const { return nodes.at(node)[1]; }
  };

  inline MeshFile read_mesh(const std::filesystem::path &file)
  {
    GmshSession session("kimp_test_reader");
    gmsh::merge(file.string());

    MeshFile                 mesh;
    std::vector<std::size_t> node_tags;
    std::vector<double>      coordinates, parametric;
    gmsh::model::mesh::getNodes(node_tags, coordinates, parametric);
    for (std::size_t k = 0; k < node_tags.size(); ++k)
      mesh.nodes[node_tags[k]] = {coordinates[3 * k], coordinates[3 * k + 1]};

    std::vector<int>                      all_types;
    std::vector<std::vector<std::size_t>> all_elements, all_nodes;
    gmsh::model::mesh::getElements(all_types, all_elements, all_nodes);
    mesh.element_types.insert(all_types.begin(), all_types.end());

    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities);
    for (const auto &[dim, tag] : entities)
    {
      std::vector<int> physicals;
      gmsh::model::getPhysicalGroupsForEntity(dim, tag, physicals);
      ++mesh.n_entities;
      mesh.n_entities_with_one_group += physicals.size() == 1 ? 1 : 0;
    }

    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    for (const auto &[dim, tag] : groups)
    {
      mesh.groups.insert({dim, tag});
      gmsh::model::getPhysicalName(dim, tag, mesh.names[{dim, tag}]);
      std::vector<int> group_entities;
      gmsh::model::getEntitiesForPhysicalGroup(dim, tag, group_entities);
      for (const int entity : group_entities)
      {
        std::vector<int>                      types;
        std::vector<std::vector<std::size_t>> elements, element_nodes;
        gmsh::model::mesh::getElements(types, elements, element_nodes, dim, entity);
        for (std::size_t t = 0; t < types.size(); ++t)
        {
          const std::vector<std::size_t> &n = element_nodes[t];
          if (types[t] == 3)
            for (std::size_t e = 0; e < elements[t].size(); ++e)
              mesh.quads[tag].push_back({n[4 * e], n[4 * e + 1], n[4 * e + 2], n[4 * e + 3]});
          if (types[t] == 1)
            for (std::size_t e = 0; e < elements[t].size(); ++e)
              mesh.lines[tag].push_back({n[2 * e], n[2 * e + 1]});
        }
      }
    }
    return mesh;
  }

  // Output directory: the build tree's (KIMP_BINARY_DIR) or a per-process temporary one that is
  // removed at exit, so that concurrent test runs never share a file.
  inline std::filesystem::path output_directory()
  {
    if (const char *binary = std::getenv("KIMP_BINARY_DIR"))
      return std::filesystem::path(binary) / "test_output" / "geometry";
    return kimp::testing::process_temp_path("geometry_test");
  }

  class RemoveTemporaryOutput : public ::testing::Environment
  {
  public:
    void TearDown() override
    {
      if (std::getenv("KIMP_BINARY_DIR") == nullptr)
      {
        std::error_code ignored;
        std::filesystem::remove_all(output_directory(), ignored);
      }
    }
  };
  inline ::testing::Environment *const remove_temporary_output =
    ::testing::AddGlobalTestEnvironment(new RemoveTemporaryOutput);

  inline std::filesystem::path test_file(const std::string &suffix = "")
  {
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    const auto  dir  = output_directory();
    std::filesystem::create_directories(dir);
    return dir / (std::string(info->test_suite_name()) + "_" + info->name() + suffix + ".msh");
  }

  // Shoelace area of a quad in its node order (positive: counter-clockwise).
  inline double signed_area(const MeshFile &mesh, const Quad &q)
  {
    double twice = 0.0;
    for (int k = 0; k < 4; ++k)
      twice += mesh.x(q[k]) * mesh.y(q[(k + 1) % 4]) - mesh.x(q[(k + 1) % 4]) * mesh.y(q[k]);
    return 0.5 * twice;
  }

  inline double material_area(const MeshFile &mesh, int material)
  {
    double area = 0.0;
    if (mesh.quads.count(material))
      for (const Quad &q : mesh.quads.at(material))
        area += signed_area(mesh, q);
    return area;
  }

  inline std::set<std::size_t> material_nodes(const MeshFile &mesh, int material)
  {
    std::set<std::size_t> result;
    if (mesh.quads.count(material))
      for (const Quad &q : mesh.quads.at(material))
        result.insert(q.begin(), q.end());
    return result;
  }

  // Distinct coordinates (grid lines of a structured block) of the nodes of one material.
  inline std::vector<double> grid_lines(const MeshFile &mesh, int material, int axis)
  {
    std::vector<double> lines;
    for (const std::size_t n : material_nodes(mesh, material))
      lines.push_back(mesh.nodes.at(n)[axis]);
    std::sort(lines.begin(), lines.end());
    lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
    return lines;
  }

  inline std::string describe(const SceneGeometry &g)
  {
    std::ostringstream out;
    out << "H = " << g.wall_height << ", t_w = " << g.wall_thickness
        << ", backfill = " << g.with_backfill << " (B = " << g.backfill_width
        << ", H_b = " << g.resolved_backfill_height() << "), L = " << g.slab_length
        << ", t_s = " << g.slab_thickness << ", top = " << g.resolved_slab_top()
        << ", gap = " << g.gap << ", mesh_slab = " << g.mesh_slab << ", h_contact = " << g.h_contact
        << ", h_max = " << g.h_max << ", grading = " << g.grading;
    return out.str();
  }

  // Sizes between consecutive grid lines.
  inline std::vector<double> sizes(const std::vector<double> &lines)
  {
    std::vector<double> result;
    for (std::size_t i = 1; i < lines.size(); ++i)
      result.push_back(lines[i] - lines[i - 1]);
    return result;
  }

  // The checks that hold for every valid scene.
  inline void expect_scene_invariants(const SceneGeometry &g, const MeshFile &mesh)
  {
    SCOPED_TRACE(describe(g));
    const double t_w = g.wall_thickness;
    const double H   = g.wall_height;
    const double H_b = g.resolved_backfill_height();

    // Areas per material.
    EXPECT_NEAR(material_area(mesh, wall_material), H * t_w, area_tolerance * H * t_w);
    if (g.with_backfill)
    {
      EXPECT_NEAR(material_area(mesh, soil_material),
                  g.backfill_width * H_b,
                  area_tolerance * g.backfill_width * H_b);
    }
    if (g.mesh_slab)
    {
      EXPECT_NEAR(material_area(mesh, slab_material),
                  g.slab_length * g.slab_thickness,
                  area_tolerance * g.slab_length * g.slab_thickness);
    }

    // Every cell positively oriented.
    for (const auto &[material, quads] : mesh.quads)
      for (const Quad &q : quads)
        ASSERT_GT(signed_area(mesh, q), 0.0) << "material " << material << ", cell nodes " << q[0]
                                             << ' ' << q[1] << ' ' << q[2] << ' ' << q[3];

    // Bonded interface: the soil nodes on x = t_w are exactly the wall nodes there with y <= H_b.
    if (g.with_backfill)
    {
      std::set<std::size_t> wall_side, soil_side;
      for (const std::size_t n : material_nodes(mesh, wall_material))
        if (std::abs(mesh.x(n) - t_w) <= coordinate_tolerance &&
            mesh.y(n) <= H_b + coordinate_tolerance)
          wall_side.insert(n);
      for (const std::size_t n : material_nodes(mesh, soil_material))
        if (std::abs(mesh.x(n) - t_w) <= coordinate_tolerance)
          soil_side.insert(n);
      EXPECT_EQ(wall_side, soil_side);
      EXPECT_GE(wall_side.size(), 2u);
    }

    // Every tagged line is an edge of exactly one cell: no group on an interior (bonded) face.
    std::map<std::pair<std::size_t, std::size_t>, int> edge_count;
    for (const auto &[material, quads] : mesh.quads)
      for (const Quad &q : quads)
        for (int k = 0; k < 4; ++k)
          ++edge_count[std::minmax(q[k], q[(k + 1) % 4])];
    for (const auto &[id, lines] : mesh.lines)
      for (const Line &l : lines)
        EXPECT_EQ(edge_count[std::minmax(l[0], l[1])], 1)
          << "boundary id " << id << " on edge (" << mesh.x(l[0]) << ", " << mesh.y(l[0]) << ") - ("
          << mesh.x(l[1]) << ", " << mesh.y(l[1]) << ")";

    // The gap between the contact faces.
    ASSERT_TRUE(mesh.lines.count(wall_contact));
    double wall_face_x = HUGE_VAL, wall_low = HUGE_VAL, wall_high = -HUGE_VAL;
    for (const Line &l : mesh.lines.at(wall_contact))
      for (const std::size_t n : l)
      {
        wall_face_x = std::min(wall_face_x, mesh.x(n));
        wall_low    = std::min(wall_low, mesh.y(n));
        wall_high   = std::max(wall_high, mesh.y(n));
      }
    EXPECT_EQ(wall_face_x, 0.0);
    EXPECT_EQ(wall_low, 0.0);
    EXPECT_NEAR(wall_high, H, coordinate_tolerance);
    if (g.mesh_slab)
    {
      ASSERT_TRUE(mesh.lines.count(slab_contact));
      double slab_face_x = -HUGE_VAL, slab_low = HUGE_VAL, slab_high = -HUGE_VAL;
      for (const Line &l : mesh.lines.at(slab_contact))
        for (const std::size_t n : l)
        {
          slab_face_x = std::max(slab_face_x, mesh.x(n));
          slab_low    = std::min(slab_low, mesh.y(n));
          slab_high   = std::max(slab_high, mesh.y(n));
        }
      EXPECT_NEAR(wall_face_x - slab_face_x, g.gap, coordinate_tolerance);
      EXPECT_NEAR(slab_low, g.slab_bottom(), coordinate_tolerance);
      EXPECT_NEAR(slab_high, g.resolved_slab_top(), coordinate_tolerance);
    }

    // Sizes capped by h_max and neighbour ratios bounded by the grading on every grid axis.
    std::vector<std::vector<double>> axes{grid_lines(mesh, wall_material, 1)};
    std::vector<double>              horizontal = grid_lines(mesh, wall_material, 0);
    if (g.with_backfill)
    {
      const std::vector<double> soil_x = grid_lines(mesh, soil_material, 0);
      horizontal.insert(horizontal.end(), soil_x.begin() + 1, soil_x.end());
    }
    axes.push_back(horizontal);
    if (g.mesh_slab)
    {
      axes.push_back(grid_lines(mesh, slab_material, 0));
      axes.push_back(grid_lines(mesh, slab_material, 1));
    }
    for (const std::vector<double> &axis : axes)
    {
      EXPECT_LE(max_neighbour_ratio(axis), g.grading * (1 + ratio_tolerance))
        << "axis from " << axis.front() << " to " << axis.back() << " m";
      for (const double s : sizes(axis))
        EXPECT_LE(s, g.h_max * (1 + ratio_tolerance));
    }
  }
} // namespace kimp::testing::scene_mesh
