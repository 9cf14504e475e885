// Scene of `kimp study`: defaults, validation and the lumped scenes of the building runs.
#include "pipeline/with_fem/study_scene.h"

#include <filesystem>

#include "pipeline/records.h"
#include "pipeline/units.h"

namespace kimp::pipeline
{
  FemScene default_study_fem_scene()
  {
    FemScene scene;
    scene.wall_heights = {1.00, 1.25, 1.50, 2.00};
    return scene;
  }

  void validate(const StudyScene &scene, ValidationContext &ctx)
  {
    {
      const auto scope = ctx.section("fem");
      validate(scene.fem, ctx);
    }
    {
      const auto scope = ctx.section("fit");
      ctx.check(scene.fit.cor > 0.0 && scene.fit.cor <= 1.0,
                "cor",
                format_quantity(scene.fit.cor, ""),
                "must be in (0, 1]");
      ctx.check(scene.fit.separation_fraction > 0.0,
                "separation_fraction",
                format_quantity(scene.fit.separation_fraction, ""),
                "must be > 0");
      ctx.check(scene.fit.width > 0.0,
                "width",
                format_quantity(scene.fit.width, "m"),
                "must be > 0");
    }
    {
      const auto scope = ctx.section("walls");
      ctx.check(scene.walls.mass > 0.0,
                "mass",
                format_quantity(scene.walls.mass, "t"),
                "must be > 0");
      ctx.check(scene.walls.gap_reduction >= 0.0 && scene.walls.gap_reduction < 1.0,
                "gap_reduction",
                format_quantity(scene.walls.gap_reduction, "%"),
                "must be in [0 %, 100 %)");
      if (scene.walls.gap)
        ctx.check(*scene.walls.gap > 0.0,
                  "gap",
                  format_quantity(*scene.walls.gap, "cm"),
                  "must be > 0");
    }
    // building, isolator and integration are checked by the lumped scene's rules, whose key
    // paths are the same as in a study file.
    LumpedScene building        = study_lumped_scene(scene, GroundMotionScene{});
    building.walls.left.present = building.walls.right.present = true;
    validate(building, ctx);
    ctx.check(scene.building.kind == BuildingKind::isolated,
              "building.kind",
              "fixed_base",
              "must be isolated (the moat walls stand at the isolation level)");
    for (std::size_t i = 0; i < scene.records.size(); ++i)
    {
      const auto scope = ctx.section("records[" + std::to_string(i) + "]");
      validate(scene.records[i], ctx);
    }
  }

  LumpedScene study_lumped_scene(const StudyScene &scene, const GroundMotionScene &record)
  {
    LumpedScene lumped;
    lumped.building            = scene.building;
    lumped.isolator            = scene.isolator;
    lumped.integration         = scene.integration;
    lumped.ground_motion       = record;
    lumped.walls.left.present  = false;
    lumped.walls.right.present = false;
    lumped.walls.left.mass     = scene.walls.mass;
    lumped.walls.right.mass    = scene.walls.mass;
    if (scene.walls.gap)
      lumped.walls.left.gap = lumped.walls.right.gap = *scene.walls.gap;
    return lumped;
  }

  std::vector<GroundMotionScene> study_records(const StudyScene &scene)
  {
    std::vector<GroundMotionScene> records = scene.records;
    if (!scene.peer_records)
      return records;
    const std::optional<std::filesystem::path> directory = records_directory(
      scene.records_dir.empty() ? std::nullopt :
                                  std::optional<std::filesystem::path>(scene.records_dir));
    if (!directory)
      return records;
    // Thesis Table 4.1: Kobe KJMA (NGA-West2 file, trimmed to the thesis' 48 s) and Northridge
    // Sylmar Converter Station (SCS142.AT2: the thesis' own pre-NGA file, 0.897 g, 40 s).
    const std::vector<std::pair<std::string, std::optional<double>>> peer =
      {{"RSN1106_KOBE_KJM000", 48.0}, {"SCS142", std::nullopt}};
    for (const auto &[name, duration] : peer)
    {
      if (!std::filesystem::is_regular_file(*directory / (name + ".AT2")))
        continue;
      GroundMotionScene record;
      record.record      = name;
      record.records_dir = directory->string();
      record.duration    = duration;
      records.push_back(record);
    }
    return records;
  }
} // namespace kimp::pipeline
