// The scene mesh of docs/physics.md §4 read back with gmsh: element types, physical groups, areas,
// conforming bonded interface, the gap, grading toward the contact, variants and validation.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gmsh.h>
#include <gtest/gtest.h>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/gmsh_session.h"
#include "geometry/graded_spacing.h"
#include "geometry/scene_geometry.h"
#include "geometry/scene_ids.h"
#include "geometry/scene_mesh.h"
#include "tests/support/temp_dir.h"

namespace
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

  MeshFile read_mesh(const std::filesystem::path &file)
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
  std::filesystem::path output_directory()
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
  [[maybe_unused]] ::testing::Environment *const remove_temporary_output =
    ::testing::AddGlobalTestEnvironment(new RemoveTemporaryOutput);

  std::filesystem::path test_file(const std::string &suffix = "")
  {
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    const auto  dir  = output_directory();
    std::filesystem::create_directories(dir);
    return dir / (std::string(info->test_suite_name()) + "_" + info->name() + suffix + ".msh");
  }

  // Shoelace area of a quad in its node order (positive: counter-clockwise).
  double signed_area(const MeshFile &mesh, const Quad &q)
  {
    double twice = 0.0;
    for (int k = 0; k < 4; ++k)
      twice += mesh.x(q[k]) * mesh.y(q[(k + 1) % 4]) - mesh.x(q[(k + 1) % 4]) * mesh.y(q[k]);
    return 0.5 * twice;
  }

  double material_area(const MeshFile &mesh, int material)
  {
    double area = 0.0;
    if (mesh.quads.count(material))
      for (const Quad &q : mesh.quads.at(material))
        area += signed_area(mesh, q);
    return area;
  }

  std::set<std::size_t> material_nodes(const MeshFile &mesh, int material)
  {
    std::set<std::size_t> result;
    if (mesh.quads.count(material))
      for (const Quad &q : mesh.quads.at(material))
        result.insert(q.begin(), q.end());
    return result;
  }

  // Distinct coordinates (grid lines of a structured block) of the nodes of one material.
  std::vector<double> grid_lines(const MeshFile &mesh, int material, int axis)
  {
    std::vector<double> lines;
    for (const std::size_t n : material_nodes(mesh, material))
      lines.push_back(mesh.nodes.at(n)[axis]);
    std::sort(lines.begin(), lines.end());
    lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
    return lines;
  }

  std::string describe(const SceneGeometry &g)
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
  std::vector<double> sizes(const std::vector<double> &lines)
  {
    std::vector<double> result;
    for (std::size_t i = 1; i < lines.size(); ++i)
      result.push_back(lines[i] - lines[i - 1]);
    return result;
  }

  // The checks that hold for every valid scene.
  void expect_scene_invariants(const SceneGeometry &g, const MeshFile &mesh)
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
} // namespace


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


TEST(SceneMesh, LowerBackfillAndLowerSlabKeepTheInvariants)
{
  SceneGeometry g;
  g.backfill_height = 0.8;  // wall back exposed above the soil
  g.slab_top        = 0.95; // slab band in the middle of the wall face
  const auto file   = test_file();
  build_scene_mesh(g, file);
  const MeshFile mesh = read_mesh(file);
  expect_scene_invariants(g, mesh);

  // Soil top is a wall grid line; the wall above it is free (no boundary group on x = t_w).
  for (const auto &[id, lines] : mesh.lines)
    for (const Line &l : lines)
      EXPECT_FALSE(mesh.x(l[0]) == g.wall_thickness && mesh.x(l[1]) == g.wall_thickness)
        << "boundary id " << id << " on the wall back face";
}


TEST(SceneMesh, RandomValidScenesKeepTheInvariants)
{
  std::mt19937                           rng(20261121);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double a, double b) { return a + (b - a) * unit(rng); };

  constexpr int n_scenes = 8;
  for (int k = 0; k < n_scenes; ++k)
  {
    SceneGeometry g;
    g.wall_height     = uniform(0.8, 2.0);
    g.wall_thickness  = uniform(0.15, 0.4);
    g.with_backfill   = unit(rng) < 0.75;
    g.backfill_width  = uniform(0.5, 3.0);
    g.backfill_height = uniform(0.3, 1.0) * g.wall_height;
    g.slab_thickness  = uniform(0.1, 0.3);
    g.slab_top        = uniform(g.slab_thickness, g.wall_height);
    g.slab_length     = uniform(1.0, 9.0);
    g.gap             = uniform(1e-4, 1e-2);
    g.mesh_slab       = unit(rng) < 0.75;
    g.h_contact       = uniform(0.015, 0.05);
    g.h_max           = uniform(g.h_contact, 0.15);
    g.grading         = uniform(1.05, 1.4);
    const auto file   = test_file("_" + std::to_string(k));
    build_scene_mesh(g, file);
    expect_scene_invariants(g, read_mesh(file));
  }
}


TEST(SceneMesh, LadderLevelsHalveTheElementSize)
{
  constexpr double    halving_tolerance = 0.06; // relative, from rounding element counts up
  const SceneGeometry coarse;
  MeshStatistics      previous = build_scene_mesh(coarse, test_file("_0"));
  for (int level = 1; level <= 2; ++level)
  {
    const SceneGeometry  g       = refined(coarse, level);
    const MeshStatistics current = build_scene_mesh(g, test_file("_" + std::to_string(level)));
    EXPECT_DOUBLE_EQ(g.h_contact, coarse.h_contact / std::pow(2.0, level));
    EXPECT_DOUBLE_EQ(g.h_max, coarse.h_max / std::pow(2.0, level));
    EXPECT_NEAR(previous.contact_cell_size / current.contact_cell_size, 2.0, 2 * halving_tolerance)
      << "level " << level;
    EXPECT_NEAR(previous.max_cell_size / current.max_cell_size, 2.0, 2 * halving_tolerance)
      << "level " << level;
    EXPECT_NEAR(previous.min_cell_size / current.min_cell_size, 2.0, 2 * halving_tolerance)
      << "level " << level;
    // Halving sizes in 2D multiplies the cell count by about 4 (a little less: the graded
    // zones grow by a fixed ratio, so their cell count grows only logarithmically).
    const double growth = double(current.n_cells) / double(previous.n_cells);
    EXPECT_GT(growth, 3.0) << "level " << level;
    EXPECT_LE(growth, 4.2) << "level " << level;
    EXPECT_LE(current.max_neighbour_ratio, g.grading * (1 + ratio_tolerance));
    std::cout << "level " << level << ": " << current << " (cell count x" << growth << ")\n";
    previous = current;
  }
  EXPECT_THROW(refined(coarse, -1), std::invalid_argument);
}


TEST(SceneGeometryValidation, RefusesEachBadParameterByName)
{
  struct Case
  {
    std::string                          what;
    std::function<void(SceneGeometry &)> change;
    std::string                          message;
  };
  const std::vector<Case> cases{
    {"touching slab", [](SceneGeometry &g) { g.gap = 0.0; }, "geometry.gap = 0"},
    {"overlapping slab", [](SceneGeometry &g) { g.gap = -1e-3; }, "geometry.gap = -0.001"},
    {"slab above the wall top", [](SceneGeometry &g) { g.slab_top = 1.3; }, "geometry.slab_top"},
    {"slab below the ground", [](SceneGeometry &g) { g.slab_top = 0.1; }, "geometry.slab_top"},
    {"zero contact size", [](SceneGeometry &g) { g.h_contact = 0.0; }, "geometry.h_contact = 0"},
    {"negative contact size", [](SceneGeometry &g) { g.h_contact = -0.01; }, "geometry.h_contact"},
    {"contact size above h_max", [](SceneGeometry &g) { g.h_contact = 0.2; }, "geometry.h_contact"},
    {"contact size above the wall thickness",
     [](SceneGeometry &g)
     {
       g.h_max     = 1.0;
       g.h_contact = 0.3;
     },
     "wall_thickness"},
    {"grading below 1", [](SceneGeometry &g) { g.grading = 0.9; }, "geometry.grading"},
    {"backfill above the wall",
     [](SceneGeometry &g) { g.backfill_height = 1.5; },
     "geometry.backfill_height"},
    {"no backfill width",
     [](SceneGeometry &g) { g.backfill_width = 0.0; },
     "geometry.backfill_width"},
    {"NaN wall height",
     [](SceneGeometry &g) { g.wall_height = std::nan(""); },
     "geometry.wall_height"},
    {"negative slab length",
     [](SceneGeometry &g) { g.slab_length = -8.0; },
     "geometry.slab_length"},
  };
  for (const Case &c : cases)
  {
    SceneGeometry g;
    c.change(g);
    try
    {
      g.validate();
      ADD_FAILURE() << c.what << ": no exception";
    }
    catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
        << c.what << ": message '" << e.what() << "' lacks '" << c.message << "'";
    }
    const auto file = test_file("_refused");
    std::filesystem::remove(file);
    EXPECT_THROW(build_scene_mesh(g, file), std::invalid_argument) << c.what;
    EXPECT_FALSE(std::filesystem::exists(file)) << c.what << ": a refused scene wrote a mesh";
  }
  EXPECT_NO_THROW(SceneGeometry{}.validate());
}


TEST(SceneMesh, UnwritableFileThrowsNamingThePath)
{
  const auto blocker = test_file("_blocker");
  std::ofstream(blocker) << "a file where build_scene_mesh needs a directory\n";
  const auto target = blocker / "scene.msh";
  try
  {
    build_scene_mesh(SceneGeometry{}, target);
    ADD_FAILURE() << "no exception for " << target;
  }
  catch (const std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(build_scene_mesh(SceneGeometry{}, test_file())) << "gmsh usable afterwards";
}


TEST(GmshSession, LeavesTheCallersGmshStateAlone)
{
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("caller");
  gmsh::option::setNumber("Mesh.MshFileVersion", 2.2);
  {
    GmshSession session("inner");
    EXPECT_FALSE(session.owns_gmsh());
  }
  build_scene_mesh(SceneGeometry{}, test_file());

  std::string current;
  gmsh::model::getCurrent(current);
  EXPECT_EQ(current, "caller");
  double version = 0;
  gmsh::option::getNumber("Mesh.MshFileVersion", version);
  EXPECT_EQ(version, 2.2);
  std::vector<std::string> models;
  gmsh::model::list(models);
  EXPECT_EQ(std::count(models.begin(), models.end(), "kimp_scene"), 0);
  gmsh::finalize();

  GmshSession own("after");
  EXPECT_TRUE(own.owns_gmsh());
}
