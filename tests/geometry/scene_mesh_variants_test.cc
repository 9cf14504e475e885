// Scene mesh variants read back with gmsh: lower backfill and slab, random valid scenes, the
// fidelity ladder's levels, the refusal of bad parameters, unwritable files and the caller's gmsh
// state.
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


// wall_aspect_max bounds the wall's rows (and the backfill's beside them) by that many times the
// wall's column width, on every ladder level, while the slab and the backfill's columns keep
// their grading to h_max; without it the wall's base rows grow to h_max.
TEST(SceneMesh, WallAspectBoundLimitsTheWallRowsOnly)
{
  SceneGeometry g;
  g.h_contact = 0.05;
  g.h_max     = 0.25;
  g.grading   = 1.5;
  build_scene_mesh(g, test_file("_free"));
  const std::vector<double> free_rows =
    sizes(grid_lines(read_mesh(test_file("_free")), wall_material, 1));
  EXPECT_GT(*std::max_element(free_rows.begin(), free_rows.end()), 3.0 * 0.05)
    << "the graded wall's base rows are tall";
  for (const double aspect : {1.0, 2.0})
    for (int level = 0; level <= 1; ++level)
    {
      g.wall_aspect_max          = aspect;
      const SceneGeometry  r     = refined(g, level);
      const auto           file  = test_file("_aspect");
      const MeshStatistics stats = build_scene_mesh(r, file);
      const MeshFile       mesh  = read_mesh(file);
      const double         width = sizes(grid_lines(mesh, wall_material, 0)).front();
      SCOPED_TRACE(describe(r));
      for (const double dy : sizes(grid_lines(mesh, wall_material, 1)))
        EXPECT_LE(dy, aspect * width * (1 + ratio_tolerance));
      for (const double dy : sizes(grid_lines(mesh, soil_material, 1)))
        EXPECT_LE(dy, aspect * width * (1 + ratio_tolerance));
      const std::vector<double> soil_dx = sizes(grid_lines(mesh, soil_material, 0));
      EXPECT_GT(soil_dx.back(), 3.0 * r.h_contact) << "the backfill's columns still grade";
      EXPECT_LE(stats.max_neighbour_ratio, r.grading * (1 + ratio_tolerance));
    }
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
    {"wall cells wider than tall",
     [](SceneGeometry &g) { g.wall_aspect_max = 0.5; },
     "geometry.wall_aspect_max = 0.5"},
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
