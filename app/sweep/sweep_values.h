// The values of a sweep inside the scenes it varies: scene key paths followed in a YAML tree,
// values written back as YAML, paths in values resolved against the sweep file. Internal to
// app/sweep (sweep_plan.h declares the public get_yaml_value(), set_yaml_value() and
// expand_range()).
#pragma once

#include <string>
#include <utility>
#include <vector>
#include <yaml-cpp/yaml.h>

namespace kimp::app::sweep_values
{
  /// Checks that `key_path` ("walls.left.gap", "cases[0].cor") is well formed.
  /// @throws std::invalid_argument naming the path and the problem.
  void check_key_path(const std::string &key_path);

  /// Sets the scalar at `key_path` inside `root` to the YAML `value` (see set_yaml_value()).
  /// @throws std::invalid_argument naming the path when it cannot be followed.
  void set_node_value(YAML::Node &root, const std::string &key_path, const std::string &value);

  /// The YAML document `text` (named `name` in messages).
  /// @throws SweepError "NAME:LINE: invalid YAML: ..." for a syntax error.
  YAML::Node load(const std::string &text, const std::string &name);

  /// `root` as YAML text, ending with a newline.
  std::string emit(const YAML::Node &root);

  /// Text of a value as it must be written back into YAML (strings that look like numbers or
  /// flags keep their quotes).
  std::string value_text(const YAML::Node &node);

  /// True for the keys that select a ground motion's record (record, records_dir, record_unit).
  bool is_record_key(const std::string &key_path);

  /**
   * A value of the sweep file `file` for `key_path`, with a relative path in it
   * (impact.k_table, a record file, records_dir) made absolute against the sweep file's
   * directory: the case scenes are read relative to the base scene, which may live elsewhere.
   */
  std::string
  resolved_value(const std::string &key_path, const std::string &value, const std::string &file);

  /// @throws SweepError "FILE:LINE: KEY: WHAT" (an error at a key of the sweep file).
  [[noreturn]] void
  fail_at(const std::string &file, int line, const std::string &key, const std::string &what);

  /// Sets every (key path, value of the sweep file `file`) of `settings` inside `root`
  /// (resolved_value(), set_node_value()).
  /// @throws SweepError at `line` naming `key` for a path that cannot be followed.
  void set_values_at(YAML::Node                                             &root,
                     const std::vector<std::pair<std::string, std::string>> &settings,
                     const std::string                                      &file,
                     int                                                     line,
                     const std::string                                      &key);
} // namespace kimp::app::sweep_values
