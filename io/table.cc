// One table written as CSV, Markdown and HDF5; see table.h.
#include "io/table.h"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "io/results_file.h"
#include "io/summary.h"
#include "io/units.h"

namespace kimp::io
{
  namespace
  {
    const char *kind_name(ColumnKind kind)
    {
      switch (kind)
      {
        case ColumnKind::number:
          return "number";
        case ColumnKind::integer:
          return "integer";
        case ColumnKind::text:
          break;
      }
      return "text";
    }

    bool dimensionless(const std::string &unit)
    {
      return unit.empty() || unit == "1";
    }
  } // namespace

  Table &Table::add(Column column)
  {
    for (const Column &c : columns_)
      if (c.name == column.name)
        throw std::invalid_argument(fmt::format("table: column '{}' added twice", column.name));
    if (!rows_.empty())
      throw std::logic_error(
        fmt::format("table: column '{}' added after the first row", column.name));
    columns_.push_back(std::move(column));
    return *this;
  }

  Table &Table::number(std::string name, std::string unit, ColumnFormat format)
  {
    return add({std::move(name), std::move(unit), ColumnKind::number, std::move(format), {}});
  }

  Table &Table::integer(std::string name)
  {
    return add({std::move(name), "1", ColumnKind::integer, {}, {}});
  }

  Table &Table::text(std::string name)
  {
    return add({std::move(name), "", ColumnKind::text, {}, {}});
  }

  void Table::add_row(std::vector<Cell> cells)
  {
    if (cells.size() != columns_.size())
      throw std::invalid_argument(fmt::format("table: row {} has {} cells for {} columns",
                                              rows_.size() + 1,
                                              cells.size(),
                                              columns_.size()));
    for (std::size_t c = 0; c < cells.size(); ++c)
    {
      const ColumnKind kind = columns_[c].kind;
      if (kind == ColumnKind::number && std::holds_alternative<std::int64_t>(cells[c]))
        cells[c] = static_cast<double>(std::get<std::int64_t>(cells[c]));
      const bool fits =
        (kind == ColumnKind::number && std::holds_alternative<double>(cells[c])) ||
        (kind == ColumnKind::integer && std::holds_alternative<std::int64_t>(cells[c])) ||
        (kind == ColumnKind::text && std::holds_alternative<std::string>(cells[c]));
      if (!fits)
        throw std::invalid_argument(
          fmt::format("table: row {}: column '{}' holds a {}, got a {}",
                      rows_.size() + 1,
                      columns_[c].name,
                      kind_name(kind),
                      std::holds_alternative<std::string>(cells[c]) ? "text" : "number"));
    }
    rows_.push_back(std::move(cells));
  }

  std::size_t Table::index(std::string_view name) const
  {
    for (std::size_t c = 0; c < columns_.size(); ++c)
      if (columns_[c].name == name)
        return c;
    throw std::out_of_range(fmt::format("table: no column '{}'", name));
  }

  std::string Table::csv_text(std::size_t row, std::size_t column) const
  {
    const Cell &cell = rows_.at(row).at(column);
    if (const double *v = std::get_if<double>(&cell))
      return std::isfinite(*v) ? fmt::format("{}", *v) : std::string();
    if (const std::int64_t *n = std::get_if<std::int64_t>(&cell))
      return std::to_string(*n);
    return std::get<std::string>(cell);
  }

  std::string Table::display_text(std::size_t row, std::size_t column) const
  {
    const Cell   &cell = rows_.at(row).at(column);
    const double *v    = std::get_if<double>(&cell);
    if (!v)
      return csv_text(row, column);
    if (!std::isfinite(*v))
      return {};
    const Column &c     = columns_[column];
    double        value = *v;
    if (!c.format.display_unit.empty() && c.format.display_unit != c.unit)
      value *= parse_unit(dimensionless(c.unit) ? "" : c.unit).value /
               parse_unit(c.format.display_unit == "1" ? "" : c.format.display_unit).value;
    return c.format.trim_zeros ? fmt::format("{:.{}g}", value, c.format.digits) :
                                 base::sig(value, c.format.digits);
  }

  std::vector<std::string> Table::csv_header() const
  {
    std::vector<std::string> header;
    for (const Column &c : columns_)
      header.push_back(csv_column(c.name, c.kind == ColumnKind::text ? "" : c.unit));
    return header;
  }

  std::vector<std::vector<std::string>> Table::csv_rows() const
  {
    std::vector<std::vector<std::string>> rows;
    rows.reserve(rows_.size());
    for (std::size_t r = 0; r < rows_.size(); ++r)
    {
      std::vector<std::string> row;
      for (std::size_t c = 0; c < columns_.size(); ++c)
        row.push_back(csv_text(r, c));
      rows.push_back(std::move(row));
    }
    return rows;
  }

  void Table::write_csv(const std::filesystem::path &path) const
  {
    write_csv_atomic(path, csv_header(), csv_rows());
  }

  std::string Table::markdown() const
  {
    std::vector<MarkdownColumn> view;
    for (const Column &c : columns_)
    {
      const std::string unit = c.format.display_unit.empty() ? c.unit : c.format.display_unit;
      const std::string name = c.label.empty() ? c.name : c.label;
      view.push_back({c.kind == ColumnKind::number && !dimensionless(unit) ?
                        fmt::format("{} ({})", name, unit) :
                        name,
                      {c.name},
                      {}});
    }
    return markdown(view);
  }

  std::string Table::markdown(const std::vector<MarkdownColumn> &view) const
  {
    std::vector<std::vector<std::size_t>> sources;
    for (const MarkdownColumn &m : view)
    {
      std::vector<std::size_t> indices;
      for (const std::string &name : m.columns)
        indices.push_back(index(name));
      sources.push_back(std::move(indices));
    }
    std::string md   = "|";
    std::string rule = "|";
    for (const MarkdownColumn &m : view)
    {
      md += " " + m.header + " |";
      rule += "---|";
    }
    md += "\n" + rule + "\n";
    for (std::size_t r = 0; r < rows_.size(); ++r)
    {
      md += "|";
      for (std::size_t m = 0; m < view.size(); ++m)
      {
        std::vector<std::string> texts;
        for (const std::size_t c : sources[m])
          texts.push_back(display_text(r, c));
        const std::string text =
          view[m].join ? view[m].join(texts) : (texts.empty() ? std::string() : texts.front());
        md += " " + text + " |";
      }
      md += "\n";
    }
    return md;
  }

  void Table::write_hdf5(ResultsGroup &parent, std::string_view name) const
  {
    ResultsGroup group = parent.group(name);
    std::string  list;
    for (std::size_t c = 0; c < columns_.size(); ++c)
    {
      const Column &column = columns_[c];
      switch (column.kind)
      {
        case ColumnKind::number:
        {
          std::vector<double> values;
          for (const auto &row : rows_)
            values.push_back(std::get<double>(row[c]));
          group.write(column.name, values, dimensionless(column.unit) ? "1" : column.unit);
          break;
        }
        case ColumnKind::integer:
        {
          std::vector<std::int64_t> values;
          for (const auto &row : rows_)
            values.push_back(std::get<std::int64_t>(row[c]));
          group.write(column.name, values, "1");
          break;
        }
        case ColumnKind::text:
        {
          std::vector<std::string> values;
          for (const auto &row : rows_)
            values.push_back(std::get<std::string>(row[c]));
          group.write(column.name, values);
          break;
        }
      }
      list += (list.empty() ? "" : ",") + column.name;
    }
    group.set_attribute("columns", list);
  }
} // namespace kimp::io
