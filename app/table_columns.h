// Rows of the HDF5 tables the commands write (io::TableColumn, one vector of values per column).
#pragma once

#include <cstddef>
#include <vector>

#include "io/results_file.h"

namespace kimp::app
{
  /// Appends one row to `columns`: row[i] to the values of columns[i] (as many values as columns).
  inline void append_row(std::vector<io::TableColumn> &columns, const std::vector<double> &row)
  {
    for (std::size_t i = 0; i < columns.size(); ++i)
      columns[i].values.push_back(row[i]);
  }
} // namespace kimp::app
