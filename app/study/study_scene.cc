// Scene of `kimp study`: defaults, validation and the lumped scenes of the building runs.
#include "app/study/study_scene.h"

#include <filesystem>

#include "io/records.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::io;
  using namespace kimp::fit;
  namespace
  {
    /// A ladder: non-empty, strictly decreasing (or increasing), at most `largest` (its values'
    /// range, > 0, is declared with the key).
    void check_ladder(ValidationContext         &ctx,
                      const std::string         &key,
                      const std::vector<double> &values,
                      const std::string         &unit,
                      bool                       decreasing,
                      double                     largest)
    {
      ctx.check(!values.empty(), key, "[]", "must list at least one level");
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        const std::string item = key + "[" + std::to_string(i) + "]";
        if (largest > 0.0)
          ctx.check(values[i] <= largest,
                    item,
                    format_quantity(values[i], unit),
                    "must be <= mesh.h_max = " + format_quantity(largest, unit));
        if (i > 0)
          ctx.check(decreasing ? values[i] < values[i - 1] : values[i] > values[i - 1],
                    item,
                    format_quantity(values[i], unit),
                    decreasing ? "must be below the previous level" :
                                 "must be above the previous level");
      }
    }
  } // namespace

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
      validate(static_cast<const FemScene &>(scene.fem), ctx);
      check_ladder(ctx,
                   "fidelity_h_contact",
                   scene.fem.fidelity_h_contact,
                   "cm",
                   true,
                   scene.fem.geometry.h_max);
      check_ladder(ctx,
                   "fidelity_penalty_factors",
                   scene.fem.fidelity_penalty_factors,
                   "",
                   false,
                   0.0);
      if (!scene.fem.velocities.empty())
        check_ladder(ctx, "velocities", scene.fem.velocities, "m/s", false, 0.0);
      ctx.check(scene.fem.solver.penalty_step_ratio == 0.0,
                "contact.penalty_step_ratio",
                format_quantity(scene.fem.solver.penalty_step_ratio, ""),
                "must be 0 in a study: its levels set the penalty factor "
                "(fidelity_penalty_factors, accuracy.penalty_factors)");
    }
    {
      const auto scope = ctx.section("accuracy");
      check_ladder(ctx,
                   "h_contact",
                   scene.accuracy.h_contact,
                   "cm",
                   true,
                   scene.fem.geometry.h_max);
      check_ladder(ctx, "penalty_factors", scene.accuracy.penalty_factors, "", false, 0.0);
      check_ladder(ctx, "lumped_dt", scene.accuracy.lumped_dt, "s", true, 0.0);
      const double finest_dt =
        scene.accuracy.lumped_dt.empty() ? 0.0 : scene.accuracy.lumped_dt.back();
      ctx.check(finest_dt == 0.0 || scene.accuracy.lumped_reference_dt < finest_dt,
                "lumped_reference_dt",
                format_quantity(scene.accuracy.lumped_reference_dt, "s"),
                "must be below every lumped_dt (the finest is " + format_quantity(finest_dt, "s") +
                  ")");
    }
    // sensitivity_study, fit and walls: single-key ranges are declared in visit().
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

  namespace
  {
    // Thesis Table 4.1: Kobe KJMA (NGA-West2 file, trimmed to the thesis' 48 s) and Northridge
    // Sylmar Converter Station (SCS142.AT2: the thesis' own pre-NGA file, 0.897 g, 40 s).
    const std::vector<std::pair<std::string, std::optional<double>>> peer_study_records =
      {{"RSN1106_KOBE_KJM000", 48.0}, {"SCS142", std::nullopt}};

    std::optional<std::filesystem::path> study_records_directory(const StudyScene &scene)
    {
      return records_directory(scene.records_dir.empty() ?
                                 std::nullopt :
                                 std::optional<std::filesystem::path>(scene.records_dir));
    }
  } // namespace

  void resolve_paths(StudyScene &scene, const std::filesystem::path &directory)
  {
    for (GroundMotionScene &record : scene.records)
      resolve_paths(record, directory);
    scene.records_dir = resolve_scene_path(scene.records_dir, directory);
  }

  void check_study_records(const io::LoadedScene<StudyScene> &loaded)
  {
    const std::vector<GroundMotionScene> &records = loaded.scene.records;
    for (std::size_t i = 0; i < records.size(); ++i)
      if (records[i].is_record())
        load_ground_motion_at(records[i],
                              std::nullopt,
                              loaded.file_name,
                              loaded.text,
                              "records[" + std::to_string(i) + "]");
  }

  std::vector<std::string> missing_study_records(const StudyScene &scene)
  {
    std::vector<std::string> missing;
    if (!scene.peer_records)
      return missing;
    const std::optional<std::filesystem::path> directory = study_records_directory(scene);
    for (const auto &[name, duration] : peer_study_records)
      if (!directory)
        missing.push_back("record " + name +
                          " is not run: no records directory found (expected --records-dir, "
                          "records_dir in the scene, KIMP_RECORDS_DIR or ../shared/data/records)");
      else if (!std::filesystem::is_regular_file(*directory / (name + ".AT2")))
        missing.push_back("record " + name + " is not run: " + name + ".AT2 is not in '" +
                          directory->string() + "'");
    return missing;
  }

  std::vector<GroundMotionScene> study_records(const StudyScene &scene)
  {
    std::vector<GroundMotionScene> records = scene.records;
    if (!scene.peer_records)
      return records;
    const std::optional<std::filesystem::path> directory = study_records_directory(scene);
    if (!directory)
      return records;
    for (const auto &[name, duration] : peer_study_records)
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
} // namespace kimp::app
