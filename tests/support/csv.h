// kimp::testing CSV reading: the files kimp writes (io/summary.h quotes a field only when it holds
// a comma, a quote or a line end), read back as rows of fields or as header -> value records.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/files.h"

namespace kimp::testing
{
  /// The fields of one CSV line: quotes removed, "" inside quotes read as one quote, an empty
  /// field kept after a trailing comma.
  inline std::vector<std::string> split_csv_line(const std::string &line)
  {
    std::vector<std::string> fields;
    std::string              field;
    bool                     quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i)
    {
      const char c = line[i];
      if (c == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"')
        field += line[++i];
      else if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
      {
        fields.push_back(field);
        field.clear();
      }
      else
        field += c;
    }
    fields.push_back(field);
    return fields;
  }

  /// A CSV file split into its header and its rows of fields.
  struct CsvTable
  {
    std::vector<std::string>              header;
    std::vector<std::vector<std::string>> rows;

    /// The index of column `name` (throws std::out_of_range if the header has none).
    std::size_t column(const std::string &name) const
    {
      for (std::size_t i = 0; i < header.size(); ++i)
        if (header[i] == name)
          return i;
      throw std::out_of_range("no column " + name);
    }
  };

  /// `file` as header and rows (both empty if it cannot be read).
  inline CsvTable read_csv(const std::filesystem::path &file)
  {
    CsvTable table;
    for (const std::string &line : read_lines(file))
      if (table.header.empty())
        table.header = split_csv_line(line);
      else
        table.rows.push_back(split_csv_line(line));
    return table;
  }

  /// Every line of `file`, the header included, as its fields.
  inline std::vector<std::vector<std::string>> read_csv_lines(const std::filesystem::path &file)
  {
    std::vector<std::vector<std::string>> lines;
    for (const std::string &line : read_lines(file))
      lines.push_back(split_csv_line(line));
    return lines;
  }

  /// The rows of `file` as records header -> field (a missing trailing field is left out).
  inline std::vector<std::map<std::string, std::string>>
  read_csv_records(const std::filesystem::path &file)
  {
    const CsvTable                                  table = read_csv(file);
    std::vector<std::map<std::string, std::string>> records;
    for (const auto &row : table.rows)
    {
      std::map<std::string, std::string> record;
      for (std::size_t i = 0; i < table.header.size() && i < row.size(); ++i)
        record[table.header[i]] = row[i];
      records.push_back(record);
    }
    return records;
  }
} // namespace kimp::testing
