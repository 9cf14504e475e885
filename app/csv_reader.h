// kimp's own CSV files read back (the RFC 4180 of io::write_csv_atomic, one record a line): the
// fields of a record, and every data row after the header with its line number.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <istream>
#include <string>
#include <vector>

namespace kimp::app
{
  /// The fields of one CSV record: quoted fields with "" escapes; a '\r' outside quotes is
  /// dropped (fields hold no line breaks in kimp's files).
  std::vector<std::string> split_csv_record(const std::string &line);

  /**
   * Calls `each(fields, line)` for every non-empty data row of `in`, read past the header of
   * `file` with `n_columns` fields (`line`: the row's line number, the header's is 1).
   * @throws std::invalid_argument naming the file and the line of a row with another number of
   *         fields.
   */
  void for_each_csv_row(std::istream                                                     &in,
                        std::size_t                                                       n_columns,
                        const std::filesystem::path                                      &file,
                        const std::function<void(const std::vector<std::string> &, int)> &each);
} // namespace kimp::app
