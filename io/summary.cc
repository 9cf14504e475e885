// Atomic writes of summary.json and CSV; see summary.h.
#include "io/summary.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "base/version.h"

namespace kimp::io
{
  nlohmann::ordered_json summary_preamble(std::string_view command)
  {
    nlohmann::ordered_json preamble;
    preamble["command"] = command;
    preamble["kimp"]    = base::version_line();
    return preamble;
  }

  namespace
  {
    std::string csv_field(const std::string &field)
    {
      if (field.find_first_of(",\"\r\n") == std::string::npos)
        return field;
      std::string quoted = "\"";
      for (const char c : field)
      {
        if (c == '"')
          quoted += '"';
        quoted += c;
      }
      return quoted + "\"";
    }

    std::string csv_text(const std::filesystem::path                 &path,
                         const std::vector<std::string>              &header,
                         const std::vector<std::vector<std::string>> &rows)
    {
      std::string text;
      const auto  add_row = [&text](const std::vector<std::string> &fields)
      {
        for (std::size_t i = 0; i < fields.size(); ++i)
        {
          if (i > 0)
            text += ',';
          text += csv_field(fields[i]);
        }
        text += '\n';
      };
      add_row(header);
      for (std::size_t r = 0; r < rows.size(); ++r)
      {
        if (rows[r].size() != header.size())
          throw OutputError(fmt::format("{}: CSV row {} has {} fields, the header has {}",
                                        path.string(),
                                        r + 1,
                                        rows[r].size(),
                                        header.size()));
        add_row(rows[r]);
      }
      return text;
    }
  } // namespace

  std::string csv_column(std::string_view name, std::string_view unit)
  {
    std::string column(name);
    if (unit.empty() || unit == "1")
      return column;
    column += '_';
    for (const char c : unit)
    {
      if (c == '/')
        column += "_per_";
      else if (c == '*')
        column += '_';
      else if (c != '^' && c != ' ')
        column += c;
    }
    return column;
  }

  std::string csv_column(std::string_view label)
  {
    const std::size_t open = label.rfind(" [");
    if (open == std::string_view::npos || label.back() != ']')
      return std::string(label);
    return csv_column(label.substr(0, open), label.substr(open + 2, label.size() - open - 3));
  }

  void write_json_atomic(const std::filesystem::path &path, const nlohmann::json &value)
  {
    write_text_atomic(path, value.dump(2) + "\n");
  }

  void write_csv_atomic(const std::filesystem::path                 &path,
                        const std::vector<std::string>              &header,
                        const std::vector<std::vector<std::string>> &rows)
  {
    write_text_atomic(path, csv_text(path, header, rows));
  }

  void write_csv_atomic(const std::filesystem::path            &path,
                        const std::vector<std::string>         &header,
                        const std::vector<std::vector<double>> &rows)
  {
    std::vector<std::vector<std::string>> text_rows;
    text_rows.reserve(rows.size());
    for (const auto &row : rows)
    {
      std::vector<std::string> fields;
      fields.reserve(row.size());
      for (const double v : row)
        fields.push_back(fmt::format("{}", v));
      text_rows.push_back(std::move(fields));
    }
    write_csv_atomic(path, header, text_rows);
  }
} // namespace kimp::io
