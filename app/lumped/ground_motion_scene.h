// Scene section `ground_motion`: a PEER record (AT2 name or path) or the synthetic near-fault
// motion of lumped/excitation/ground_motion.h, then scaling (to a PGA or by a factor) and trimming.
// Shared by every command that shakes a building (lumped, study, sweeps).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "io/at2_reader.h"
#include "io/scene_io.h"
#include "lumped/excitation/ground_motion.h"

namespace kimp::app
{
  /// The lengths a ground motion may have as run (after trimming): io's plausible record length.
  inline io::Range record_duration_range()
  {
    return io::Range::plausible(io::min_record_duration,
                                io::max_record_duration,
                                "a ground-motion record");
  }

  /// The sampling intervals of a plausible record: those the record readers accept.
  inline io::Range record_dt_range()
  {
    return io::Range::plausible(io::min_record_dt, io::max_record_dt, "a ground-motion record");
  }

  /// A peak ground acceleration key (shown in g, > 0); `doc` says what it sets.
  template <class Io, class Q>
  void visit_pga(Io &io, std::string_view key, Q &pga, std::string_view doc)
  {
    io.quantity(key, pga, "g", doc, io::Range::positive());
  }

  /// A time of the synthetic motion's pulse or window (s, > 0); `doc` says which.
  template <class Io>
  void visit_synthetic_time(Io &io, std::string_view key, double &time, std::string_view doc)
  {
    io.quantity(key, time, "s", doc, io::Range::positive());
  }

  /// A corner frequency of the synthetic motion's noise band (1/s, > 0); `doc` says which.
  template <class Io>
  void visit_noise_corner(Io &io, std::string_view key, double &frequency, std::string_view doc)
  {
    io.quantity(key, frequency, "1/s", doc, io::Range::positive());
  }
} // namespace kimp::app

namespace kimp::lumped
{
  /// Scene section `synthetic`: the engine's own spec, visited in place (in the spec's namespace
  /// so that the io readers find it by argument-dependent lookup); `name` is not a scene key.
  template <class Io>
  void visit(Io &io, SyntheticMotionSpec &s)
  {
    using io::Range;
    app::visit_pga(io, "pga", s.pga, "target peak ground acceleration (met exactly)");
    app::visit_synthetic_time(io,
                              "pulse_period",
                              s.pulse_period,
                              "period T_p of the velocity pulse (>= 4 dt)");
    io.quantity("duration",
                s.duration,
                "s",
                "record length (>= 10 dt)",
                app::record_duration_range());
    io.quantity("dt", s.dt, "s", "sampling interval", app::record_dt_range());
    app::visit_synthetic_time(io,
                              "pulse_time",
                              s.pulse_time,
                              "time of the pulse centre (the pulse must lie within the record)");
    io.quantity("gamma",
                s.gamma,
                "",
                "oscillatory character of the pulse",
                Range::greater(1.0).because("Mavroeidis-Papageorgiou"));
    // Unbounded: a phase, any real number.
    io.quantity("nu", s.nu, "", "phase of the pulse, rad");
    io.quantity("noise_ratio",
                s.noise_ratio,
                "",
                "RMS of the noise / RMS of the pulse",
                Range::non_negative());
    app::visit_noise_corner(io, "noise_f_low", s.noise_f_low, "high-pass corner of the noise band");
    app::visit_noise_corner(io,
                            "noise_f_high",
                            s.noise_f_high,
                            "low-pass corner of the noise band (> noise_f_low, < 1/(2 dt))");
    app::visit_synthetic_time(io,
                              "envelope_duration",
                              s.envelope_duration,
                              "T_w of the Saragoni-Hart window");
    io.quantity("envelope_epsilon",
                s.envelope_epsilon,
                "",
                "window peak at epsilon*T_w",
                Range::greater(0.0).and_less(1.0));
    io.quantity("envelope_eta",
                s.envelope_eta,
                "",
                "window value at T_w",
                Range::greater(0.0).and_less(1.0));
    io.integer("seed", s.seed, "seed of the noise generator (same seed: same record)");
  }
} // namespace kimp::lumped

namespace kimp::app
{
  /**
   * Ground motion of a scene.
   *
   * | key          | unit | default     | meaning                                          |
   * |--------------|------|-------------|--------------------------------------------------|
   * | record       | -    | "synthetic" | "synthetic", a record name in records_dir        |
   * |              |      |             | (e.g. RSN1106_KOBE_KJM000) or a path to a file   |
   * |              |      |             | (relative to the scene file's directory)         |
   * | records_dir  | -    | ""          | "" = --records-dir / KIMP_RECORDS_DIR /          |
   * |              |      |             | ../shared/data/records; relative to the scene    |
   * | record_unit  | -    | ""          | unit of a two-column file's acceleration column  |
   * |              |      |             | ("g", "m/s^2", "cm/s^2"); required for such files|
   * | scale_to_pga | g    | null        | scale the record to this PGA                     |
   * | scale        | -    | 1           | multiply the record (after scale_to_pga)         |
   * | duration     | s    | null        | keep the first `duration` seconds                |
   */
  struct GroundMotionScene
  {
    std::string                 record      = "synthetic";
    std::string                 records_dir = "";
    std::string                 record_unit = "";
    std::optional<double>       scale_to_pga;
    double                      scale = 1.0;
    std::optional<double>       duration;
    lumped::SyntheticMotionSpec synthetic;

    /// True if the motion is an external record (needs the records directory or a file).
    bool is_record() const { return record != "synthetic"; }

    /// record_unit in m/s² per unit, or nullopt when it is "".
    /// @throws io::UnitError when it is not an acceleration unit.
    std::optional<double> two_column_unit() const;
  };

  /// A factor on a ground motion (no unit, nonzero: a negative factor flips the motion); `doc`
  /// says which motion and after what.
  template <class Io, class Q>
  void visit_motion_scale(Io &io, std::string_view key, Q &scale, std::string_view doc)
  {
    io.quantity(key, scale, "", doc, io::Range::nonzero());
  }

  template <class Io>
  void visit(Io &io, GroundMotionScene &s)
  {
    io.text("record",
            s.record,
            "\"synthetic\" (the embedded near-fault motion), a PEER record name looked up in "
            "records_dir (e.g. RSN1106_KOBE_KJM000) or a path to an AT2 file (relative to the "
            "scene file's directory)");
    io.text("records_dir",
            s.records_dir,
            "directory of PEER records, relative to the scene file's directory; \"\" = "
            "$KIMP_RECORDS_DIR, else ../shared/data/records");
    io.text("record_unit",
            s.record_unit,
            "unit of the acceleration column of a two-column 'time acceleration' record file "
            "(e.g. \"g\", \"m/s^2\", \"cm/s^2\"); required for such files, which do not state "
            "it; \"\" for AT2 files, whose header states it");
    visit_pga(io, "scale_to_pga", s.scale_to_pga, "scale the record to this PGA");
    visit_motion_scale(io,
                       "scale",
                       s.scale,
                       "factor applied after scale_to_pga (negative flips it)");
    io.quantity("duration",
                s.duration,
                "s",
                "trim the record to its first `duration` seconds",
                record_duration_range());
    io.section("synthetic",
               s.synthetic,
               "synthetic near-fault motion (used when record = synthetic)");
  }

  /**
   * `record` as written in a scene file of `directory`, resolved against it: a path (with a
   * directory separator, or naming a file beside the scene) becomes `directory`/record; an
   * absolute path, "synthetic" and a bare record name (looked up in the records directory) stay.
   */
  std::string resolve_record_path(const std::string           &record,
                                  const std::filesystem::path &directory);

  /// The scene's paths (a record file, records_dir) resolved against the scene file's directory.
  void resolve_paths(GroundMotionScene &scene, const std::filesystem::path &directory);

  /// A ground motion whose PGA after scaling exceeds this (5 g, m/s²) is logged as a warning.
  inline constexpr double max_credible_pga = 5.0 * 9.80665;

  /// Rules beyond the keys' ranges: the record unit, the synthetic motion's own rules (relative
  /// key paths; use inside ctx.section("ground_motion")).
  void validate(const GroundMotionScene &scene, io::ValidationContext &ctx);

  /// The record read from a file as a ground motion (its samples, dt and name moved over): the
  /// engine's GroundMotion is the one home of a record's PGA and duration.
  lumped::GroundMotion ground_motion_of(io::AccelerationRecord record);

  /**
   * Load or generate the motion, then scale_to_pga, scale and trim, in that order.
   * @param[in] records_dir_override directory from the command line (wins over the scene's)
   * @throws std::invalid_argument / GroundMotionFileError naming the record and the problem.
   */
  lumped::GroundMotion
  load_ground_motion(const GroundMotionScene                    &scene,
                     const std::optional<std::filesystem::path> &records_dir_override = {});

  /**
   * load_ground_motion() of the section at `key_path` ("ground_motion", "records[1]") of the
   * scene file `file_name` whose text is `scene_text`: a record that cannot be found or read is
   * reported at its key, "FILE:LINE: KEY_PATH.record = 'NAME': <problem>" (with the reader's
   * file:line and the did-you-mean of load_record()).
   * @throws io::SceneError for a record problem; what the generator throws otherwise.
   */
  lumped::GroundMotion
  load_ground_motion_at(const GroundMotionScene                    &scene,
                        const std::optional<std::filesystem::path> &records_dir,
                        const std::string                          &file_name,
                        const std::string                          &scene_text,
                        const std::string                          &key_path);

  /// The records directory the scene would use (override > scene > environment > default).
  std::optional<std::filesystem::path>
  scene_records_directory(const GroundMotionScene                    &scene,
                          const std::optional<std::filesystem::path> &records_dir_override = {});
} // namespace kimp::app
