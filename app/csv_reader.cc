// kimp's own CSV files read back: records and data rows.
#include "app/csv_reader.h"

#include <fmt/format.h>
#include <stdexcept>

namespace kimp::app
{
  std::vector<std::string> split_csv_record(const std::string &line)
  {
    std::vector<std::string> fields(1);
    bool                     quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i)
    {
      const char c = line[i];
      if (quoted)
      {
        if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
          fields.back() += '"', ++i;
        else if (c == '"')
          quoted = false;
        else
          fields.back() += c;
      }
      else if (c == '"')
        quoted = true;
      else if (c == ',')
        fields.emplace_back();
      else if (c != '\r')
        fields.back() += c;
    }
    return fields;
  }

  void for_each_csv_row(std::istream                                                     &in,
                        std::size_t                                                       n_columns,
                        const std::filesystem::path                                      &file,
                        const std::function<void(const std::vector<std::string> &, int)> &each)
  {
    std::string line;
    int         number = 1;
    while (std::getline(in, line))
    {
      ++number;
      if (line.empty())
        continue;
      const std::vector<std::string> f = split_csv_record(line);
      if (f.size() != n_columns)
        throw std::invalid_argument(fmt::format("{}:{}: {} fields for {} columns",
                                                file.string(),
                                                number,
                                                f.size(),
                                                n_columns));
      each(f, number);
    }
  }
} // namespace kimp::app
