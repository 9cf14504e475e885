// The scene mesh of docs/physics.md §4 read back with gmsh: element types, physical groups, areas,
// conforming bonded interface, the gap, grading toward the contact, rigid slab, no backfill.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gmsh.h>
#include <gtest/gtest.h>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "geometry/gmsh_session.h"
#include "geometry/graded_spacing.h"
#include "geometry/scene_geometry.h"
#include "geometry/scene_ids.h"
#include "geometry/scene_mesh.h"
#include "tests/geometry/scene_mesh_checks.h"

using namespace kimp::geometry;
using namespace kimp::testing::scene_mesh;


TEST(SceneMesh, RepeatedBuildsAfterAVerboseSessionPrintNothing)
{
  // gmsh 4.8 prints "Gmsh has not been initialized" when called after a finalize that left
  // terminal output on; the study builds many meshes in one process.
  {
    const GmshSession verbose("kimp_verbose_session", true);
  }
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  build_scene_mesh(SceneGeometry{}, test_file("_1"));
  build_scene_mesh(SceneGeometry{}, test_file("_2"));
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.find("not been initialized"), std::string::npos) << err;
  EXPECT_EQ(out.find("not been initialized"), std::string::npos) << out;
}

TEST(SceneMesh, WritesAsciiMsh41)
{
  const auto file = test_file();
  build_scene_mesh(SceneGeometry{}, file);
  std::ifstream in(file);
  std::string   header, version;
  std::getline(in, header);
  std::getline(in, version);
  EXPECT_EQ(header, "$MeshFormat");
  EXPECT_EQ(version, "4.1 0 8") << "expected MSH 4.1, ASCII (file type 0), 8-byte size_t";
}


TEST(SceneMesh, OnlyFourNodeQuadsAndTwoNodeLines)
{
  const auto     file = test_file();
  const MeshFile mesh = read_mesh((build_scene_mesh(SceneGeometry{}, file), file));
  EXPECT_EQ(mesh.element_types, (std::set<int>{1, 3})) << "gmsh types 1 = line2, 3 = quad4";
}


TEST(SceneMesh, PhysicalGroupsCarryTheSceneIds)
{
  const auto     file = test_file();
  const MeshFile mesh = read_mesh((build_scene_mesh(SceneGeometry{}, file), file));
  const std::set<std::pair<int, int>> expected{{2, slab_material},
                                               {2, wall_material},
                                               {2, soil_material},
                                               {1, fixed_base},
                                               {1, soil_far_side},
                                               {1, slab_contact},
                                               {1, wall_contact}};
  EXPECT_EQ(mesh.groups, expected);
  EXPECT_EQ(mesh.names.at({2, slab_material}), "slab");
  EXPECT_EQ(mesh.names.at({2, wall_material}), "wall");
  EXPECT_EQ(mesh.names.at({2, soil_material}), "soil");
  EXPECT_EQ(mesh.names.at({1, fixed_base}), "fixed_base");
  EXPECT_EQ(mesh.names.at({1, wall_contact}), "wall_contact");
  // deal.II's reader takes one physical tag per entity.
  EXPECT_EQ(mesh.n_entities_with_one_group, mesh.n_entities);
}


TEST(SceneMesh, DefaultSceneSatisfiesTheInvariants)
{
  const auto          file = test_file();
  const SceneGeometry g;
  build_scene_mesh(g, file);
  expect_scene_invariants(g, read_mesh(file));
}


TEST(SceneMesh, BoundaryGroupsCoverTheirFaces)
{
  const auto          file = test_file();
  const SceneGeometry g;
  build_scene_mesh(g, file);
  const MeshFile mesh = read_mesh(file);

  const auto total_length = [&](int id, int axis)
  {
    double length = 0.0;
    for (const Line &l : mesh.lines.at(id))
      length += std::abs(mesh.nodes.at(l[1])[axis] - mesh.nodes.at(l[0])[axis]);
    return length;
  };
  const double B = g.backfill_width;
  EXPECT_NEAR(total_length(fixed_base, 0), g.wall_thickness + B, coordinate_tolerance);
  EXPECT_NEAR(total_length(soil_far_side, 1), g.wall_height, coordinate_tolerance);
  EXPECT_NEAR(total_length(slab_contact, 1), g.slab_thickness, coordinate_tolerance);
  EXPECT_NEAR(total_length(wall_contact, 1), g.wall_height, coordinate_tolerance);
  for (const Line &l : mesh.lines.at(fixed_base))
    EXPECT_EQ(mesh.y(l[0]) + mesh.y(l[1]), 0.0);
  for (const Line &l : mesh.lines.at(soil_far_side))
    EXPECT_EQ(mesh.x(l[0]) + mesh.x(l[1]), 2 * (g.wall_thickness + B));
}


TEST(SceneMesh, ElementSizeIsHContactAtTheContactAndGrowsAway)
{
  const auto           file = test_file();
  const SceneGeometry  g;
  const MeshStatistics statistics = build_scene_mesh(g, file);
  const MeshFile       mesh       = read_mesh(file);
  SCOPED_TRACE(describe(g));

  // Slab: columns widen monotonically from the front (h_contact) to the far end (coarse).
  const std::vector<double> slab_dx = sizes(grid_lines(mesh, slab_material, 0));
  EXPECT_LE(slab_dx.back(), g.h_contact * (1 + ratio_tolerance));
  EXPECT_GE(slab_dx.back(), g.h_contact / g.grading);
  for (std::size_t i = 1; i < slab_dx.size(); ++i)
    EXPECT_GE(slab_dx[i - 1], slab_dx[i] * (1 - ratio_tolerance)) << "column " << i;
  EXPECT_GE(slab_dx.front(), g.h_max / g.grading);
  for (const double dy : sizes(grid_lines(mesh, slab_material, 1)))
  {
    EXPECT_LE(dy, g.h_contact * (1 + ratio_tolerance));
    EXPECT_GE(dy, g.h_contact / g.grading);
  }

  // Wall face: h_contact within the slab's band, growing with the distance from it.
  const std::vector<double> wall_y = grid_lines(mesh, wall_material, 1);
  const double              y_b    = g.slab_bottom();
  for (std::size_t j = 1; j < wall_y.size(); ++j)
  {
    const double dy = wall_y[j] - wall_y[j - 1];
    if (wall_y[j - 1] >= y_b)
    {
      EXPECT_LE(dy, g.h_contact * (1 + ratio_tolerance)) << "y = " << wall_y[j - 1];
      EXPECT_GE(dy, g.h_contact / g.grading) << "y = " << wall_y[j - 1];
    }
    else if (j > 1)
    {
      EXPECT_LE(dy, (wall_y[j - 1] - wall_y[j - 2]) * (1 + ratio_tolerance))
        << "below the band sizes must grow downward, y = " << wall_y[j - 1];
    }
  }
  EXPECT_GE(wall_y[1] - wall_y[0], g.h_max / g.grading) << "wall base should be coarse";

  // Through the wall: uniform, at most h_contact.
  for (const double dx : sizes(grid_lines(mesh, wall_material, 0)))
    EXPECT_NEAR(dx, g.wall_thickness / std::ceil(g.wall_thickness / g.h_contact - 1e-9), 1e-12);

  EXPECT_LE(statistics.contact_cell_size, g.h_contact * (1 + ratio_tolerance));
  EXPECT_LE(statistics.max_cell_size, g.h_max * (1 + ratio_tolerance));
  EXPECT_LE(statistics.max_neighbour_ratio, g.grading * (1 + ratio_tolerance));
  EXPECT_NEAR(statistics.min_scaled_jacobian, 1.0, 1e-12) << "structured rectangles";
}


TEST(SceneMesh, DefaultSlabFrontNodesFaceWallNodes)
{
  // Band edges are grid lines of the wall when the grading allows it (always for the default
  // scene), and the band is divided as the slab front is: each slab contact node has a wall
  // contact node at the same height, so node-to-segment contact starts node-on-node.
  const auto          file = test_file();
  const SceneGeometry g;
  build_scene_mesh(g, file);
  const MeshFile mesh = read_mesh(file);

  std::vector<double> wall_heights;
  for (const Line &l : mesh.lines.at(wall_contact))
    for (const std::size_t n : l)
      wall_heights.push_back(mesh.y(n));
  for (const Line &l : mesh.lines.at(slab_contact))
    for (const std::size_t n : l)
    {
      const double y       = mesh.y(n);
      double       nearest = HUGE_VAL;
      for (const double w : wall_heights)
        nearest = std::min(nearest, std::abs(w - y));
      EXPECT_LE(nearest, coordinate_tolerance) << "slab contact node at y = " << y;
    }
}


TEST(SceneMesh, StatisticsMatchTheWrittenFile)
{
  const auto           file       = test_file();
  const MeshStatistics statistics = build_scene_mesh(SceneGeometry{}, file);
  const MeshFile       mesh       = read_mesh(file);
  EXPECT_EQ(statistics.n_nodes, mesh.nodes.size());
  EXPECT_EQ(statistics.n_slab_cells, mesh.quads.at(slab_material).size());
  EXPECT_EQ(statistics.n_wall_cells, mesh.quads.at(wall_material).size());
  EXPECT_EQ(statistics.n_soil_cells, mesh.quads.at(soil_material).size());
  EXPECT_EQ(statistics.n_cells,
            statistics.n_slab_cells + statistics.n_wall_cells + statistics.n_soil_cells);
  EXPECT_EQ(statistics.n_slab_contact_faces, mesh.lines.at(slab_contact).size());
  EXPECT_EQ(statistics.n_wall_contact_faces, mesh.lines.at(wall_contact).size());
  std::set<std::size_t> used;
  for (const auto &[material, quads] : mesh.quads)
    for (const Quad &q : quads)
      used.insert(q.begin(), q.end());
  EXPECT_EQ(used.size(), mesh.nodes.size()) << "every written node belongs to a cell";
}


TEST(SceneMesh, RigidSlabWritesNoSlabCells)
{
  SceneGeometry rigid;
  rigid.mesh_slab                 = false;
  const auto           file       = test_file();
  const MeshStatistics statistics = build_scene_mesh(rigid, file);
  const MeshFile       mesh       = read_mesh(file);

  EXPECT_EQ(mesh.groups.count({2, slab_material}), 0u);
  EXPECT_EQ(mesh.groups.count({1, slab_contact}), 0u);
  EXPECT_EQ(statistics.n_slab_cells, 0u);
  for (const auto &[tag, xy] : mesh.nodes)
    EXPECT_GE(xy[0], 0.0) << "node " << tag << " left of the wall face";
  expect_scene_invariants(rigid, mesh);

  // Wall and soil are meshed as with the elastic slab.
  const auto           elastic_file       = test_file("_elastic");
  const MeshStatistics elastic_statistics = build_scene_mesh(SceneGeometry{}, elastic_file);
  EXPECT_EQ(statistics.n_wall_cells, elastic_statistics.n_wall_cells);
  EXPECT_EQ(statistics.n_soil_cells, elastic_statistics.n_soil_cells);
}


TEST(SceneMesh, WithoutBackfillTheWallIsABareCantilever)
{
  SceneGeometry bare;
  bare.with_backfill = false;
  const auto file    = test_file();
  build_scene_mesh(bare, file);
  const MeshFile mesh = read_mesh(file);

  EXPECT_EQ(mesh.groups,
            (std::set<std::pair<int, int>>{{2, slab_material},
                                           {2, wall_material},
                                           {1, fixed_base},
                                           {1, slab_contact},
                                           {1, wall_contact}}));
  for (const auto &[tag, xy] : mesh.nodes)
    EXPECT_LE(xy[0], bare.wall_thickness) << "node " << tag << " behind the wall";
  for (const Line &l : mesh.lines.at(fixed_base))
  {
    EXPECT_EQ(mesh.y(l[0]) + mesh.y(l[1]), 0.0);
    EXPECT_LE(std::max(mesh.x(l[0]), mesh.x(l[1])), bare.wall_thickness);
  }
  expect_scene_invariants(bare, mesh);
}


TEST(SceneMesh, ContactInterfaceDuplicatesTheWallSoilNodes)
{
  // interface_contact: the backfill's front column has its own nodes at the places of the wall's
  // back nodes up to H_b (one more node per soil grid row), tagged soil_front and wall_back over
  // [0, H_b]; no quad uses a node of both bodies.
  SceneGeometry bonded;
  bonded.backfill_height           = 1.0;
  SceneGeometry separate           = bonded;
  separate.interface_contact       = true;
  const auto           bonded_file = test_file(), separate_file = test_file("_interface");
  const MeshStatistics bonded_stats   = build_scene_mesh(bonded, bonded_file);
  const MeshStatistics separate_stats = build_scene_mesh(separate, separate_file);
  const MeshFile       mesh           = read_mesh(separate_file);
  const auto           lines          = [&](int id)
  {
    std::vector<std::array<double, 4>> result;
    for (const Line &l : mesh.lines.at(id))
      result.push_back({mesh.x(l[0]), mesh.y(l[0]), mesh.x(l[1]), mesh.y(l[1])});
    std::sort(result.begin(), result.end());
    return result;
  };
  const auto back = lines(wall_back), front = lines(soil_front);
  ASSERT_EQ(back.size(), front.size());
  EXPECT_EQ(back, front);
  std::set<std::size_t> wall_nodes, soil_nodes;
  for (const Quad &q : mesh.quads.at(wall_material))
    wall_nodes.insert(q.begin(), q.end());
  for (const Quad &q : mesh.quads.at(soil_material))
    soil_nodes.insert(q.begin(), q.end());
  for (const std::size_t n : soil_nodes)
    EXPECT_EQ(wall_nodes.count(n), 0u) << "node " << n << " shared";
  double top = 0;
  for (const auto &l : back)
  {
    EXPECT_EQ(l[0], separate.wall_thickness);
    top = std::max(top, std::max(l[1], l[3]));
  }
  EXPECT_EQ(top, 1.0);
  EXPECT_EQ(separate_stats.n_nodes, bonded_stats.n_nodes + back.size() + 1);
  EXPECT_EQ(mesh.n_entities_with_one_group, mesh.n_entities);
}
