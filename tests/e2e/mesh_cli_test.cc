// `kimp mesh` end to end: the mesh files, the deal.II reading of them (areas of every region equal
// the scene's rectangles), previews, summary.json, and a refused overlapping scene.
#ifdef KIMP_WITH_FEM

#  include <cmath>
#  include <filesystem>
#  include <gtest/gtest.h>
#  include <nlohmann/json.hpp>
#  include <string>

#  include "tests/support/files.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  constexpr double area_tolerance = 1e-10; ///< relative: rectangles meshed exactly

  bool matplotlib_available()
  {
    return command_succeeds("/usr/bin/python3 -c 'import matplotlib, numpy'");
  }

  /// `kimp <options> mesh scene.yaml -o out` in `dir`, `scene` written to scene.yaml first.
  KimpRun run_mesh(const TempDir &dir, const std::string &scene, const std::string &options = "")
  {
    dir.write("scene.yaml", scene);
    return run_kimp(options + "mesh scene.yaml -o out", dir.path());
  }

  TEST(MeshCli, WritesMeshesWhoseRegionsHaveTheSceneAreas)
  {
    const TempDir dir("mesh_cli");
    const KimpRun run = run_mesh(dir,
                                 "wall_heights: [\"1.0 m\", \"1.5 m\"]\n"
                                 "mesh: {h_contact: \"5 cm\", h_max: \"20 cm\", grading: 1.5}\n");
    ASSERT_EQ(run.exit_code, 0) << run.err;

    const nlohmann::json summary = read_json(dir.path() / "out/summary.json");
    EXPECT_EQ(summary.at("command"), "mesh");
    const double wall_thickness = 0.25, backfill_width = 2.0, slab_length = 8.0,
                 slab_thickness = 0.20;
    std::size_t previous_cells  = 0;
    // `cases` is a list of objects with "name", in the order of the wall heights.
    ASSERT_EQ(summary.at("cases").size(), 2u) << summary.dump(2);
    std::size_t index = 0;
    for (const auto &[name, height] : {std::pair{"H1.00", 1.0}, std::pair{"H1.50", 1.5}})
    {
      const nlohmann::json &entry = summary.at("cases").at(index++);
      EXPECT_EQ(entry.at("name"), name);
      const auto msh = dir.path() / "out" / entry.at("mesh_file").get<std::string>();
      ASSERT_TRUE(std::filesystem::is_regular_file(msh)) << msh;
      EXPECT_EQ(read_text(msh).rfind("$MeshFormat\n4.1 0 8", 0), 0u) << "ASCII MSH 4.1: " << msh;
      EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "out" /
                                                   entry.at("vtu_preview").get<std::string>()));

      // deal.II's reading of the file: material id 1 slab, 2 wall, 3 soil (geometry/scene_ids.h).
      const nlohmann::json &area        = entry.at("area_by_material");
      const auto            expect_area = [&](const char *id, double expected)
      {
        ASSERT_TRUE(area.contains(id)) << area.dump();
        EXPECT_NEAR(area.at(id).get<double>(), expected, area_tolerance * expected)
          << name << " material " << id;
      };
      expect_area("1", slab_length * slab_thickness);
      expect_area("2", wall_thickness * height);
      expect_area("3", backfill_width * height);

      const std::size_t n_cells = entry.at("statistics").at("n_cells").get<std::size_t>();
      EXPECT_GT(n_cells, previous_cells) << "a higher wall has more cells";
      previous_cells = n_cells;
      EXPECT_LE(entry.at("statistics").at("contact_cell_size").get<double>(), 0.05 + 1e-12);

      if (matplotlib_available())
      {
        ASSERT_TRUE(entry.at("png_preview").is_string()) << entry.dump(2);
        const auto png = dir.path() / "out" / entry.at("png_preview").get<std::string>();
        ASSERT_TRUE(std::filesystem::is_regular_file(png)) << png;
        EXPECT_EQ(read_text(png).substr(1, 3), "PNG");
      }
      else
        EXPECT_TRUE(entry.at("png_preview").is_null());
    }
  }

  TEST(MeshCli, RigidSlabMeshHasNoSlabCells)
  {
    const TempDir dir("mesh_cli_rigid");
    const KimpRun run = run_mesh(dir,
                                 "slab: {rigid: true}\ngeometry: {with_backfill: false}\n"
                                 "mesh: {h_contact: \"5 cm\", h_max: \"20 cm\"}\n",
                                 "-q ");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const nlohmann::json  summary = read_json(dir.path() / "out/summary.json");
    const nlohmann::json &entry   = summary.at("cases").at(0);
    EXPECT_EQ(entry.at("name"), "H1.25");
    EXPECT_EQ(entry.at("statistics").at("n_slab_cells"), 0);
    EXPECT_EQ(entry.at("statistics").at("n_soil_cells"), 0);
    EXPECT_FALSE(entry.at("area_by_material").contains("1"));
    EXPECT_NEAR(entry.at("area_by_material").at("2").get<double>(),
                0.25 * 1.25,
                area_tolerance * 0.25 * 1.25);
  }

  TEST(MeshCli, OverlappingSlabIsRefusedWithFileLineAndKey)
  {
    const TempDir dir("mesh_cli_overlap");
    const KimpRun run = run_mesh(dir, "geometry:\n  gap: \"-1 mm\"\n");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.err.find("scene.yaml:2: geometry.gap = -1 mm"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out/mesh")) << run.err;
  }
} // namespace

#endif // KIMP_WITH_FEM
