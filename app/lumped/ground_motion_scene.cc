// Ground-motion scene section: validation, loading (record or synthetic), scaling and trimming.
#include "app/lumped/ground_motion_scene.h"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "base/format.h"
#include "base/logging.h"
#include "io/records.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::io;
  using kimp::base::logger;
  std::optional<double> GroundMotionScene::two_column_unit() const
  {
    if (record_unit.empty())
      return std::nullopt;
    return parse_quantity_as("1 " + record_unit, "m/s^2");
  }

  void validate(const GroundMotionScene &scene, ValidationContext &ctx)
  {
    try
    {
      scene.two_column_unit();
    }
    catch (const UnitError &error)
    {
      ctx.fail("record_unit",
               "'" + scene.record_unit + "'",
               std::string("must be an acceleration unit such as g, m/s^2 or cm/s^2 (") +
                 error.what() + ")");
    }
    ctx.check(!scene.record.empty(),
              "record",
              "\"\"",
              "must be \"synthetic\", a record name or a path");
    if (!scene.is_record())
    {
      // The generator's own rules, reported at the synthetic section's key.
      try
      {
        lumped::validate(scene.synthetic);
      }
      catch (const std::invalid_argument &error)
      {
        // Messages read "synthetic.<key> = <value> <unit> (<rule>)": split them so that the
        // report points at the key's line.
        const std::string message = error.what();
        const std::size_t equals  = message.find(" = ");
        const std::size_t paren   = message.find(" (", equals == std::string::npos ? 0 : equals);
        if (message.rfind("synthetic.", 0) == 0 && equals != std::string::npos &&
            paren != std::string::npos && message.back() == ')')
          ctx.fail(message.substr(0, equals),
                   message.substr(equals + 3, paren - equals - 3),
                   message.substr(paren + 2, message.size() - paren - 3));
        else
          ctx.fail("synthetic", "(invalid)", message);
      }
      if (scene.duration)
        ctx.check(*scene.duration <= scene.synthetic.duration,
                  "duration",
                  format_quantity(*scene.duration, "s"),
                  "must be <= synthetic.duration = " +
                    format_quantity(scene.synthetic.duration, "s"));
    }
  }

  std::string resolve_record_path(const std::string &record, const std::filesystem::path &directory)
  {
    if (record.empty() || record == "synthetic" || directory.empty())
      return record;
    if (record.find('/') != std::string::npos)
      return resolve_scene_path(record, directory);
    std::error_code ec;
    if (std::filesystem::is_regular_file(directory / record, ec))
      return (directory / record).lexically_normal().string();
    return record;
  }

  void resolve_paths(GroundMotionScene &scene, const std::filesystem::path &directory)
  {
    scene.record      = resolve_record_path(scene.record, directory);
    scene.records_dir = resolve_scene_path(scene.records_dir, directory);
  }

  lumped::GroundMotion
  load_ground_motion_at(const GroundMotionScene                    &scene,
                        const std::optional<std::filesystem::path> &records_dir,
                        const std::string                          &file_name,
                        const std::string                          &scene_text,
                        const std::string                          &key_path)
  {
    if (!scene.is_record())
      return load_ground_motion(scene, records_dir);
    try
    {
      return load_ground_motion(scene, records_dir);
    }
    catch (const std::exception &error)
    {
      const std::string key  = key_path + ".record";
      const int         line = key_line(scene_text, key);
      // load_record() names the record itself: said once, at the key.
      std::string       problem = error.what();
      const std::string echo    = "record = '" + scene.record + "' ";
      if (problem.rfind(echo, 0) == 0)
        problem = problem.substr(echo.size());
      // "synthetic" is a name of the scene, not of the records directory: suggested here.
      const std::string written = std::filesystem::path(scene.record).filename().string();
      if (problem.find("did you mean") == std::string::npos &&
          edit_distance(written, "synthetic") <= 3)
        problem += "; did you mean 'synthetic'?";
      throw SceneError(fmt::format("{}{}: {} = '{}': {}",
                                   file_name,
                                   line > 0 ? ":" + std::to_string(line) : std::string(),
                                   key,
                                   scene.record,
                                   problem));
    }
  }

  std::optional<std::filesystem::path>
  scene_records_directory(const GroundMotionScene                    &scene,
                          const std::optional<std::filesystem::path> &records_dir_override)
  {
    std::optional<std::filesystem::path> flag = records_dir_override;
    if (!flag && !scene.records_dir.empty())
      flag = std::filesystem::path(scene.records_dir);
    return records_directory(flag);
  }

  lumped::GroundMotion ground_motion_of(io::AccelerationRecord record)
  {
    lumped::GroundMotion motion;
    motion.dt           = record.dt;
    motion.acceleration = std::move(record.acceleration);
    motion.name         = std::move(record.name);
    return motion;
  }

  lumped::GroundMotion
  load_ground_motion(const GroundMotionScene                    &scene,
                     const std::optional<std::filesystem::path> &records_dir_override)
  {
    lumped::GroundMotion motion;
    if (scene.is_record())
    {
      motion = ground_motion_of(load_record(scene.record,
                                            scene_records_directory(scene, records_dir_override),
                                            scene.two_column_unit()));
    }
    else
      motion = lumped::synthetic_near_fault(scene.synthetic);
    if (scene.scale_to_pga)
      motion = lumped::scaled_to_pga(motion, *scene.scale_to_pga);
    if (scene.scale != 1.0)
      motion = lumped::scaled(motion, scene.scale);
    if (scene.duration)
      motion = lumped::trimmed(motion, *scene.duration);
    // A record read with a wrong sampling interval, or trimmed to nothing, is no ground motion.
    if (const double length = motion.duration();
        !(length >= io::min_record_duration && length <= io::max_record_duration))
      throw std::invalid_argument(fmt::format(
        "record = '{}' lasts {} s{} (expected {:g} s to {:g} s: a shorter or longer ground motion is "
        "implausible; check the record's DT and ground_motion.duration)",
        scene.is_record() ? scene.record : std::string("synthetic"),
        base::sig(length),
        scene.duration ? " after trimming to duration = " + format_quantity(*scene.duration, "s") :
                         std::string(),
        io::min_record_duration,
        io::max_record_duration));
    // The largest recorded peaks are below about 4 g: a bigger one is almost surely a wrong scale
    // (the run's plausibility limits then catch the response).
    if (const double pga = motion.pga(); pga > max_credible_pga)
      logger().warn("ground motion {}: PGA {:.4g} g after scale_to_pga = {} and scale = {:.4g} "
                    "is above {} g, beyond any recorded motion: is the scale intended?",
                    motion.name,
                    pga / standard_gravity,
                    scene.scale_to_pga ?
                      fmt::format("{:.4g} g", *scene.scale_to_pga / standard_gravity) :
                      std::string("null"),
                    scene.scale,
                    max_credible_pga / standard_gravity);
    return motion;
  }
} // namespace kimp::app
