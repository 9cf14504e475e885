// One table, three views: the CSV file (full precision, header convention name_unit), a Markdown
// table for reports (a few significant figures) and an HDF5 table group (one dataset per column
// with its units). A writer builds the rows once and every output reads the same cells.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "base/format.h"

namespace kimp::io
{
  class ResultsGroup;

  /// What a column holds.
  enum class ColumnKind
  {
    number,  ///< double; NaN or ±inf is an empty cell
    integer, ///< std::int64_t (counts)
    text     ///< labels and statuses; never a number with a unit
  };

  /// How a number column is shown in Markdown (CSV and HDF5 keep every digit).
  struct ColumnFormat
  {
    int digits = base::readable_digits; ///< significant figures
    /// Unit of the Markdown value, converted from the column's unit ("" = the column's unit).
    std::string display_unit;
    /// Drop trailing zeros ("%g": 5 cm, penalty 1) instead of showing every figure (57.50).
    bool trim_zeros = false;
  };

  /// One column: `name` is the HDF5 dataset name and, with the unit, the CSV header.
  struct Column
  {
    std::string  name;
    std::string  unit; ///< unit of the values ("1" or "" dimensionless; "" for text)
    ColumnKind   kind = ColumnKind::number;
    ColumnFormat format;
    std::string  label; ///< Markdown header ("" = name)
  };

  /// A cell: a double (number column), an integer (integer column) or text (text column).
  using Cell = std::variant<double, std::int64_t, std::string>;

  /// A Markdown column made of one or more table columns (e.g. a value with its interval).
  struct MarkdownColumn
  {
    std::string              header;
    std::vector<std::string> columns; ///< names of the table columns shown
    /// Joins the display texts of `columns` (empty for an empty cell); default: the first text.
    std::function<std::string(const std::vector<std::string> &)> join;
  };

  /**
   * A table of named columns with units. The CSV header of a column is
   * csv_column(name, unit) (`wall_height_m`, `k_kN_per_mm1.5_per_m`, `status`); numeric columns
   * hold numbers only.
   */
  class Table
  {
  public:
    /// Add a column; names must differ. Returns *this for chaining.
    Table &add(Column column);
    Table &number(std::string name, std::string unit, ColumnFormat format = {});
    Table &integer(std::string name);
    Table &text(std::string name);

    /**
     * Append a row with one cell per column, in column order; an int or std::size_t cell of a
     * number column is accepted as a double.
     * @throws std::invalid_argument naming the column whose cell has the wrong kind, or the
     *         count when it differs from the number of columns.
     */
    void add_row(std::vector<Cell> cells);

    const std::vector<Column>            &columns() const { return columns_; }
    const std::vector<std::vector<Cell>> &rows() const { return rows_; }
    std::size_t                           n_rows() const { return rows_.size(); }
    /// Position of the column `name`. @throws std::out_of_range naming it.
    std::size_t index(std::string_view name) const;

    /// CSV field of a cell: shortest text that reads back to the same double, "" for NaN.
    std::string csv_text(std::size_t row, std::size_t column) const;
    /// Markdown text of a cell: the column's format (significant figures, display unit).
    std::string display_text(std::size_t row, std::size_t column) const;

    std::vector<std::string>              csv_header() const;
    std::vector<std::vector<std::string>> csv_rows() const;
    /// Write the CSV file atomically (write_csv_atomic).
    void write_csv(const std::filesystem::path &path) const;

    /// Markdown table of every column, headers "label (display unit)".
    std::string markdown() const;
    /// Markdown table of `view`. @throws std::out_of_range for an unknown column name.
    std::string markdown(const std::vector<MarkdownColumn> &view) const;

    /**
     * Group `parent/name` with one dataset per column (float64 with its units, int64 "1", or
     * UTF-8 strings) and the attribute `columns` listing the names in order.
     */
    void write_hdf5(ResultsGroup &parent, std::string_view name) const;

  private:
    std::vector<Column>            columns_;
    std::vector<std::vector<Cell>> rows_;
  };
} // namespace kimp::io
