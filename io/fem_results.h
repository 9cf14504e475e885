// FEM impact results in the HDF5 results file: the contract between `kimp fem` (writer) and
// `kimp fit` (reader). Layout below /fem/<case> (schema 1.x, docs/architecture.md "Results files"),
// all SI, per metre.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/results_file.h"

namespace kimp::io
{
  /**
   * Scalar results of one FEM run (the summary/<key> datasets of FemCase), one typed field per
   * key; a field that is not set is not written, and reading sets the fields the file holds.
   * Counts are integers here and in summary.json (float64 datasets in the HDF5 file).
   */
  struct FemSummary
  {
    // The impact.
    std::optional<double> peak_force;        ///< peak of the smoothed contact force, N/m
    std::optional<double> peak_force_raw;    ///< peak of the raw contact force, N/m
    std::optional<double> contact_start;     ///< time of first contact, s
    std::optional<double> contact_duration;  ///< s
    std::optional<double> impulse;           ///< ∫ F dt over the contact, N·s/m
    std::optional<double> rebound_velocity;  ///< slab velocity after separation, m/s
    std::optional<double> apparent_cor;      ///< rebound/impact velocity
    std::optional<double> energy_error;      ///< relative energy balance error
    std::optional<double> smoothing_window;  ///< moving-average window of the smoothed force, s
    std::optional<double> max_penetration;   ///< m
    std::optional<double> mean_penetration;  ///< m
    std::optional<double> initial_gap;       ///< m
    std::optional<double> penalty_stiffness; ///< contact penalty, N/m per m
    // The run.
    std::optional<std::int64_t> mesh_level;        ///< refinement level of the mesh
    std::optional<double>       penalty_factor;    ///< contact penalty factor of the run
    std::optional<std::int64_t> contact_subcycles; ///< contact sub-steps per step (1: off)
    std::optional<std::int64_t> n_dofs;
    std::optional<std::int64_t> n_cells;
    std::optional<std::int64_t> n_steps;
    std::optional<std::int64_t> n_newton;
    std::optional<std::int64_t> n_step_halvings;
    std::optional<std::int64_t> n_linear_solves;
    std::optional<double>       linear_solver_seconds; ///< s
    std::optional<double>       linear_setup_seconds;  ///< s
    std::optional<std::int64_t> n_ranks;
    std::optional<double>       dt;        ///< time step, s
    std::optional<double>       dt_stable; ///< computed stable time step, s
    std::optional<double>       wall_time; ///< wall time of the run, s
    // After the impact: where the energy went and the wall's state.
    std::optional<double> plastic_dissipation;        ///< J/m
    std::optional<double> damage_dissipation;         ///< J/m
    std::optional<double> contact_dissipation;        ///< J/m
    std::optional<double> residual_energy;            ///< left in the bodies, J/m
    std::optional<double> dissipation_cor;            ///< COR implied by the dissipation
    std::optional<double> permanent_indentation;      ///< m
    std::optional<double> wall_residual_displacement; ///< m
    std::optional<double> stored_energy_share;        ///< in wall and soil at the end / E_0
    std::optional<double> radiated_energy;            ///< absorbing far boundary, J/m
    std::optional<double> slab_damping_dissipation;   ///< slab.damping_ratio > 0, J/m
    std::optional<double> boundary_spring_energy;     ///< viscous-spring boundary, J/m stored
    /// Inelastic materials: plastic work and damage dissipation per body, J/m.
    std::optional<double> plastic_dissipation_slab, plastic_dissipation_wall,
      plastic_dissipation_soil;
    std::optional<double> damage_dissipation_slab, damage_dissipation_wall, damage_dissipation_soil;
    // The engineer's quantities of the record (app/fem/fem_quantities.h, docs/physics.md
    // "Engineer's quantities"); a quantity the record does not show is not set.
    std::optional<double> first_peak_force;             ///< N/m, of the smoothed force
    std::optional<double> first_peak_time;              ///< s after the first contact
    std::optional<double> first_peak_impulse;           ///< N·s/m, ∫F dt of the first pulse
    std::optional<double> max_slab_displacement;        ///< m, slab travel after first contact
    std::optional<double> max_wall_displacement;        ///< m, wall face in the contact range
    std::optional<double> energy_equivalent_resistance; ///< E_0 / max slab travel, N/m
    std::optional<double> time_to_stop;          ///< s from first contact to slab velocity zero
    std::optional<double> time_to_95_travel;     ///< s from first contact to 95 % of the travel
    std::optional<double> max_bar_strain_ratio;  ///< max point bar strain / yield strain
    std::optional<double> max_bar_strain_height; ///< m above the ground
    /// The vertical bars' largest strain averaged over bar_gauge_length / yield strain, the
    /// height of the gauge's centre (m) and the gauge length (m).
    std::optional<double> max_bar_gauge_strain_ratio, max_bar_gauge_strain_height, bar_gauge_length;
    std::optional<double> impulse_momentum_ratio; ///< ∫F dt / (m (v_in + v_out))
    // The geostatic step before the impact.
    std::optional<double>       geostatic_weight;   ///< N/m
    std::optional<double>       geostatic_residual; ///< relative
    std::optional<std::int64_t> geostatic_iterations;
    std::optional<double>       geostatic_plastic_dissipation; ///< J/m
    std::optional<double>       geostatic_wall_displacement;   ///< m
    // The soil-wall interface (contact model).
    std::optional<double> interface_normal_force; ///< N/m
    std::optional<double> friction_dissipation;   ///< J/m
    /// Entries of other writers (key -> value; units in FemCase::summary_units).
    std::map<std::string, double> extra;

    /// Every set entry by key (the fields above under their own names, then `extra`).
    std::map<std::string, double> entries() const;
    /// Set the entry `key`: the field of that name (a count rounded to an integer), else
    /// extra[key].
    void set(const std::string &key, double value);
    /// Every set entry as JSON, in the order above (counts as integers), then `extra`.
    nlohmann::ordered_json json() const;
    /// No entry is set.
    bool empty() const { return entries().empty(); }
    /// Unset every entry.
    void clear() { *this = FemSummary(); }

    bool operator==(const FemSummary &other) const { return entries() == other.entries(); }
    bool operator!=(const FemSummary &other) const { return !(*this == other); }
  };

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
   * | summary/<key>                            | scalar float64           | fem_summary_units() |
   * | labels/<key>                             | scalar UTF-8 string      | 1      |
   *
   * All time series share `time` (s) and `step` (0, 1, ...). An empty vector is not written and
   * reads back empty. A failed case holds only its status and labels.
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
    FemSummary          summary;           ///< peak_force, contact_duration, impulse, ...
    /// Units of summary entries not known to fem_summary_units() (e.g. {"my_key", "N/m"}).
    std::map<std::string, std::string> summary_units;
    std::map<std::string, std::string> labels; ///< mesh level, penalty level, integrator, ...
    std::string                        status = "ok"; ///< "ok" or "failed: <reason>"
  };

  /**
   * Units of a summary key: `fem_case.summary_units` first, then those of the fields of
   * FemSummary (forces N/m, energies J/m, lengths m, times s, impulse N*s/m, penalty_stiffness
   * N/m/m, counts and ratios "1"). On reading, summary_units holds the units of the keys that are
   * not fields or whose units differ from the fields' ones.
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
