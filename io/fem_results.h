// FEM impact results in the HDF5 results file: the contract between `kimp fem` (writer) and
// `kimp fit` (reader). Layout below /fem/<case> (schema 1.x, docs/architecture.md "Results files"),
// all SI, per metre.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/results_file.h"

namespace kimp::io
{
  /**
   * One FEM impact run (one wall height, one mesh/penalty level), SI units, per metre of wall.
   *
   * HDF5 layout of `/fem/<name>` (every dataset has a `units` attribute):
   * | object                                   | kind                     | units  |
   * |------------------------------------------|--------------------------|--------|
   * | attribute `status`                       | "ok" or "failed: ..."    |        |
   * | wall_height, slab_mass, impact_velocity  | scalar float64           | m, kg/m, m/s |
   * | contact_force, smoothed_contact_force    | time series {step,time,value} | N/m |
   * | indentation, slab_displacement, wall_displacement | time series     | m      |
   * | slab_velocity                            | time series              | m/s    |
   * | summary/<key>                            | scalar float64           | see fem_summary_units()
   * | | labels/<key>                             | scalar UTF-8 string      | 1      | All time
   * series share `time` (s) and `step` (0, 1, ...). An empty vector is not written and reads back
   * empty. A failed case holds only its status and labels.
   */
  struct FemCase
  {
    std::string         name;                   ///< group name below /fem, e.g. "H1.25"
    double              wall_height     = 0.0;  ///< H, m
    double              slab_mass       = 0.0;  ///< kg per metre of wall
    double              impact_velocity = 0.0;  ///< slab velocity at first contact, m/s
    std::vector<double> time;                   ///< s
    std::vector<double> contact_force;          ///< total contact force, N/m (raw)
    std::vector<double> smoothed_contact_force; ///< N/m (moving average of contact_force)
    std::vector<double> indentation; ///< slab front − wall face displacement − initial gap, m
    std::vector<double> slab_displacement; ///< mass-weighted mean x displacement of the slab, m
    std::vector<double> slab_velocity;     ///< m/s
    std::vector<double> wall_displacement; ///< mean x displacement of the wall face at contact, m
    std::map<std::string, double> summary; ///< peak_force, contact_duration, impulse, ...
    /// Units of summary entries not known to fem_summary_units() (e.g. {"my_key", "N/m"}).
    std::map<std::string, std::string> summary_units;
    std::map<std::string, std::string> labels; ///< mesh level, penalty level, integrator, ...
    std::string                        status = "ok"; ///< "ok" or "failed: <reason>"
  };

  /**
   * Units of a summary key: `fem_case.summary_units` first, then the known keys (peak_force,
   * peak_force_raw "N/m"; impulse "N*s/m"; contact_start, contact_duration, dt, dt_stable,
   * smoothing_window, wall_seconds "s"; max_penetration, mean_penetration, initial_gap "m";
   * rebound_velocity "m/s"; penalty_stiffness "N/m/m"; apparent_cor, energy_error, n_dofs,
   * n_steps, n_cells "1"). On reading, summary_units holds the units of the keys that are not
   * known or whose units differ from the known ones.
   * @throws ResultsError naming the case and key if neither knows it.
   */
  std::string fem_summary_units(const FemCase &fem_case, const std::string &key);

  /**
   * Write `fem_case` as group `fem_root/<name>` with the layout of FemCase and set its status.
   * @param[in,out] fem_root the /fem group of an open ResultsFile
   * @throws std::invalid_argument for an empty name or a series whose length differs from
   *         `time` (message names the field and both lengths); ResultsError on HDF5 failure or
   *         a summary key without units.
   */
  void write_fem_case(ResultsGroup &fem_root, const FemCase &fem_case);

  /**
   * Read every case below /fem of a committed results file, in name order.
   * Checks /meta/schema_version (major must be results_schema_major), the presence of the
   * required objects of an "ok" case (scalars, contact_force) and each dataset's units.
   * @throws ResultsError naming the file and the object for a missing file, group, dataset or
   *         attribute, a wrong schema major version or unexpected units.
   */
  std::vector<FemCase> read_fem_cases(const std::filesystem::path &file);
} // namespace kimp::io
