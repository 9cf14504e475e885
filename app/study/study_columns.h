// One declaration per column of a study table, one builder for its two files: study.h5 keeps the
// SI value under its SI name, the CSV file shows it in its display unit under its CSV name. A
// table is declared once as a list of columns and read by both writers (not a public API).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "io/table.h"

namespace kimp::app::study_internal
{
  /// Name and unit of a column in one file; an empty name leaves the column out of that file.
  struct ColumnName
  {
    std::string name;
    std::string unit; ///< "" or "1" dimensionless; "" for text
  };

  /// The SI value of a number cell in the CSV file's display unit.
  using ToDisplay = std::function<double(double)>;

  /// SI value times `factor` (cm from m: times(100)).
  inline ToDisplay times(double factor)
  {
    return [factor](double value) { return value * factor; };
  }

  /// SI value divided by `divisor` (kN from N: divided_by(1e3)).
  inline ToDisplay divided_by(double divisor)
  {
    return [divisor](double value) { return value / divisor; };
  }

  /// One column of a study table over rows of type Row.
  template <class Row>
  struct StudyColumn
  {
    io::ColumnKind                       kind;
    ColumnName                           hdf5;   ///< SI name and unit in study.h5
    ColumnName                           csv;    ///< name and display unit in the CSV file
    std::function<io::Cell(const Row &)> value;  ///< SI number, integer or text of a row
    ToDisplay                            to_csv; ///< of a number: SI to display unit (none: same)
  };

  /// A number column: SI name and unit, CSV name and display unit, the conversion, the value.
  template <class Row>
  StudyColumn<Row> number_column(ColumnName                         hdf5,
                                 ColumnName                         csv,
                                 ToDisplay                          to_csv,
                                 std::function<double(const Row &)> value)
  {
    return {io::ColumnKind::number,
            std::move(hdf5),
            std::move(csv),
            [value = std::move(value)](const Row &row) -> io::Cell { return value(row); },
            std::move(to_csv)};
  }

  /// A number column with one name and unit in both files.
  template <class Row>
  StudyColumn<Row> same_column(const std::string                 &name,
                               const std::string                 &unit,
                               std::function<double(const Row &)> value)
  {
    return number_column<Row>({name, unit}, {name, unit}, {}, std::move(value));
  }

  /// A number column of study.h5 only.
  template <class Row>
  StudyColumn<Row> hdf5_column(const std::string                 &name,
                               const std::string                 &unit,
                               std::function<double(const Row &)> value)
  {
    return number_column<Row>({name, unit}, {}, {}, std::move(value));
  }

  /// A text column of both files.
  template <class Row>
  StudyColumn<Row> text_column(const std::string                      &name,
                               std::function<std::string(const Row &)> value)
  {
    return {io::ColumnKind::text,
            {name, ""},
            {name, ""},
            [value = std::move(value)](const Row &row) -> io::Cell { return value(row); },
            {}};
  }

  /// A text column of the CSV file only (labels and statuses).
  template <class Row>
  StudyColumn<Row> csv_text_column(const std::string                      &name,
                                   std::function<std::string(const Row &)> value)
  {
    return {io::ColumnKind::text,
            {},
            {name, ""},
            [value = std::move(value)](const Row &row) -> io::Cell { return value(row); },
            {}};
  }

  /// A column of whole numbers; `in_hdf5` and `in_csv` say where it stands (`name` in both).
  template <class Row>
  StudyColumn<Row> integer_column(const std::string                       &name,
                                  bool                                     in_hdf5,
                                  bool                                     in_csv,
                                  std::function<std::int64_t(const Row &)> value)
  {
    return {io::ColumnKind::integer,
            in_hdf5 ? ColumnName{name, "1"} : ColumnName{},
            in_csv ? ColumnName{name, "1"} : ColumnName{},
            [value = std::move(value)](const Row &row) -> io::Cell { return value(row); },
            {}};
  }

  /// Which file a table is built for.
  enum class StudyFile
  {
    hdf5, ///< SI names and values
    csv   ///< CSV names, values in display units
  };

  /**
   * The table of `columns` over the rows of `rows` that `keep` accepts, for `file`: the columns
   * that stand in that file, under its names and units.
   */
  template <class Row, class Keep>
  io::Table study_table(const std::vector<StudyColumn<Row>> &columns,
                        const std::vector<Row>              &rows,
                        StudyFile                            file,
                        Keep                                 keep)
  {
    const bool                            csv = file == StudyFile::csv;
    std::vector<const StudyColumn<Row> *> shown;
    io::Table                             t;
    for (const StudyColumn<Row> &c : columns)
    {
      const ColumnName &n = csv ? c.csv : c.hdf5;
      if (n.name.empty())
        continue;
      shown.push_back(&c);
      t.add({n.name, c.kind == io::ColumnKind::text ? "" : n.unit, c.kind, {}, {}});
    }
    for (const Row &row : rows)
    {
      if (!keep(row))
        continue;
      std::vector<io::Cell> cells;
      cells.reserve(shown.size());
      for (const StudyColumn<Row> *c : shown)
      {
        io::Cell cell = c->value(row);
        if (csv && c->to_csv && std::holds_alternative<double>(cell))
          cell = c->to_csv(std::get<double>(cell));
        cells.push_back(std::move(cell));
      }
      t.add_row(std::move(cells));
    }
    return t;
  }

  /// study_table() of every row.
  template <class Row>
  io::Table study_table(const std::vector<StudyColumn<Row>> &columns,
                        const std::vector<Row>              &rows,
                        StudyFile                            file)
  {
    return study_table(columns, rows, file, [](const Row &) { return true; });
  }
} // namespace kimp::app::study_internal
