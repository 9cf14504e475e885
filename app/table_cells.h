// Rows of the io::Table tables the commands write.
#pragma once

#include <initializer_list>
#include <vector>

#include "io/table.h"

namespace kimp::app
{
  /**
   * A row of number cells from a braced list of doubles. (Built from the doubles rather than from
   * an initializer list of io::Cell, which trips a false -Wmaybe-uninitialized of GCC 12 at -O3.)
   */
  inline std::vector<io::Cell> number_cells(std::initializer_list<double> values)
  {
    return std::vector<io::Cell>(values.begin(), values.end());
  }

  /// Appends number cells to `row` (as number_cells()).
  inline void append_numbers(std::vector<io::Cell> &row, std::initializer_list<double> values)
  {
    row.insert(row.end(), values.begin(), values.end());
  }
} // namespace kimp::app
