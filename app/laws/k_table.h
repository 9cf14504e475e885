// A study's k table (DIR/k_table.csv of `kimp study`) read back: k against wall height and impact
// velocity, linearly interpolated, for lumped scenes (impact.k_table), `kimp export-opensees` and
// the study's consistent-k building runs.
#pragma once

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace kimp::app
{
  /// One row of k_table.csv in SI: k for the whole building side (k_per_metre · W).
  struct KTableRow
  {
    double wall_height        = 0.0; ///< m
    double kelvin_voigt_total = 0.0; ///< N/m (n = 1)
    double jankowski_total    = 0.0; ///< N/m^1.5 (n = 1.5)
    /// Impact velocity of the FEM case, m/s (NaN: a table without the velocity column).
    double impact_velocity = std::numeric_limits<double>::quiet_NaN();
    /// The row is at the table's reference velocity (the one used when none is asked for).
    bool reference = true;
  };

  /// The rows of a k_table.csv with a usable k, sorted by wall height, then impact velocity.
  struct KTable
  {
    std::filesystem::path  file;
    std::vector<KTableRow> rows;

    /**
     * k_total at `wall_height` (m) for the exponent `exponent` (1: Kelvin-Voigt column, 1.5:
     * Jankowski column) at the reference velocity, linearly interpolated between the two
     * neighbouring heights (rows of one velocity: the same as a table without velocities).
     * @throws std::invalid_argument naming the file for a height outside the table's range or
     *         an exponent other than 1 or 1.5.
     */
    double stiffness(double wall_height, double exponent) const;

    /**
     * k_total at `wall_height` (m) and impact velocity `velocity` (m/s): at each velocity of the
     * table interpolated linearly in the wall height, then linearly in the velocity between the
     * two neighbouring velocities. A table without velocities (or with one) gives the same k at
     * every velocity.
     * @throws std::invalid_argument naming the file for a height or velocity outside the
     *         table's range (k is not extrapolated), or an exponent other than 1 or 1.5.
     */
    double stiffness(double wall_height, double exponent, double velocity) const;

    /// The distinct impact velocities of the table, increasing, m/s (empty: no velocity column).
    std::vector<double> velocities() const;
  };

  /**
   * Read `path`: a k_table.csv, or a study output directory holding one. Columns by name:
   * wall_height_m, kelvin_voigt_total_kN_per_mm, jankowski_total_kN_per_mm1.5, and if present
   * impact_velocity_m_per_s and reference_velocity ("yes" marks the rows of the reference
   * velocity; without the column every row is a reference row). Rows whose k is empty or not
   * finite, i.e. failed fits, are left out.
   * @throws std::invalid_argument naming the file (missing, no such column, no usable row).
   */
  KTable read_k_table(const std::filesystem::path &path);

  /// The consistent k of one record at one wall height (consistent_k.csv of `kimp study`), SI.
  struct RecordK
  {
    std::filesystem::path file;
    /// k_total of the modified Kelvin-Voigt run, N/m (NaN: not in the file).
    double kelvin_voigt_total = std::numeric_limits<double>::quiet_NaN();
    /// k_total of the Jankowski run, N/m^1.5 (NaN: not in the file).
    double jankowski_total = std::numeric_limits<double>::quiet_NaN();
    /// The impact velocity the converged k belongs to, m/s (the Jankowski run's, else the
    /// Kelvin-Voigt run's).
    double impact_velocity = std::numeric_limits<double>::quiet_NaN();
  };

  /**
   * The converged k(H, v_imp) of record `record` at wall height `wall_height` (m) from
   * `study_dir`/consistent_k.csv: the k the building's own impact velocity calls for.
   * @throws std::invalid_argument naming the file for a missing file, an unknown record or
   *         height (listing those present), or a run that did not converge.
   */
  RecordK read_consistent_k(const std::filesystem::path &study_dir,
                            const std::string           &record,
                            double                       wall_height);
} // namespace kimp::app
