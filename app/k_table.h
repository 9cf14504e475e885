// A study's k table (DIR/k_table.csv of `kimp study`) read back: k against wall height, linearly
// interpolated, for lumped scenes (impact.k_table) and `kimp export-opensees`.
#pragma once

#include <filesystem>
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
  };

  /// The rows of a k_table.csv with a usable k, sorted by wall height.
  struct KTable
  {
    std::filesystem::path  file;
    std::vector<KTableRow> rows;

    /**
     * k_total at `wall_height` (m) for the exponent `exponent` (1: Kelvin-Voigt column, 1.5:
     * Jankowski column), linearly interpolated between the two neighbouring heights.
     * @throws std::invalid_argument naming the file for a height outside the table's range or
     *         an exponent other than 1 or 1.5.
     */
    double stiffness(double wall_height, double exponent) const;
  };

  /**
   * Read `path`: a k_table.csv, or a study output directory holding one. Columns by name:
   * wall_height_m, kelvin_voigt_total_kN_per_mm, jankowski_total_kN_per_mm1.5 (rows whose k is
   * empty or not finite, i.e. failed fits, are left out).
   * @throws std::invalid_argument naming the file (missing, no such column, no usable row).
   */
  KTable read_k_table(const std::filesystem::path &path);
} // namespace kimp::app
