// Reader of a study's k_table.csv (RFC 4180 as written by io/summary.h) and its interpolation.
#include "app/k_table.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace kimp::app
{
  namespace
  {
    /// One CSV record (quoted fields with "" escapes; no newlines inside fields in k tables).
    std::vector<std::string> split_csv(const std::string &line)
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

    double to_number(const std::string &text)
    {
      if (text.empty())
        return std::nan("");
      std::size_t used  = 0;
      double      value = std::nan("");
      try
      {
        value = std::stod(text, &used);
      }
      catch (const std::exception &)
      {
        return std::nan("");
      }
      return used == text.size() ? value : std::nan("");
    }
  } // namespace

  KTable read_k_table(const std::filesystem::path &path)
  {
    KTable table;
    table.file = std::filesystem::is_directory(path) ? path / "k_table.csv" : path;
    std::ifstream in(table.file);
    if (!in)
      throw std::invalid_argument(
        fmt::format("{}: cannot read the k table (expected a k_table.csv of `kimp study` or its "
                    "output directory)",
                    table.file.string()));
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = split_csv(line);
    const auto                     column = [&](const std::string &name)
    {
      const auto it = std::find(header.begin(), header.end(), name);
      if (it == header.end())
        throw std::invalid_argument(
          fmt::format("{}: no column '{}' (not a k table of `kimp study`)",
                      table.file.string(),
                      name));
      return static_cast<std::size_t>(std::distance(header.begin(), it));
    };
    const std::size_t height = column("wall_height_m");
    const std::size_t kv     = column("kelvin_voigt_total_kN_per_mm");
    const std::size_t jk     = column("jankowski_total_kN_per_mm1.5");
    int               number = 1;
    while (std::getline(in, line))
    {
      ++number;
      if (line.empty())
        continue;
      const std::vector<std::string> f = split_csv(line);
      if (f.size() != header.size())
        throw std::invalid_argument(fmt::format("{}:{}: {} fields for {} columns",
                                                table.file.string(),
                                                number,
                                                f.size(),
                                                header.size()));
      KTableRow row;
      row.wall_height = to_number(f[height]);
      // kN/mm^n -> N/m^n: × 1e3 · 1e3^n.
      row.kelvin_voigt_total = to_number(f[kv]) * 1e6;
      row.jankowski_total    = to_number(f[jk]) * 1e3 * std::pow(1e3, 1.5);
      if (std::isfinite(row.wall_height) && row.kelvin_voigt_total > 0.0 &&
          row.jankowski_total > 0.0)
        table.rows.push_back(row);
    }
    if (table.rows.empty())
      throw std::invalid_argument(
        fmt::format("{}: no row with a wall height and both k (every fit failed?)",
                    table.file.string()));
    std::sort(table.rows.begin(),
              table.rows.end(),
              [](const KTableRow &a, const KTableRow &b) { return a.wall_height < b.wall_height; });
    return table;
  }

  double KTable::stiffness(double wall_height, double exponent) const
  {
    const bool kv = exponent == 1.0;
    if (!kv && exponent != 1.5)
      throw std::invalid_argument(fmt::format("{} holds k for n = 1 (Kelvin-Voigt) and n = 1.5 "
                                              "(Jankowski) only, not n = {}",
                                              file.string(),
                                              exponent));
    const auto k = [&](const KTableRow &r)
    { return kv ? r.kelvin_voigt_total : r.jankowski_total; };
    const double low = rows.front().wall_height, high = rows.back().wall_height;
    // A relative tolerance so that a height printed to 6 digits still matches its row.
    const double slack = 1e-9 * std::max(1.0, std::abs(high));
    if (!(wall_height >= low - slack && wall_height <= high + slack))
      throw std::invalid_argument(fmt::format("wall height {} m is outside the range of {} ({} m "
                                              "to {} m); k is not extrapolated",
                                              wall_height,
                                              file.string(),
                                              low,
                                              high));
    if (rows.size() == 1 || wall_height <= low)
      return k(rows.front());
    for (std::size_t i = 1; i < rows.size(); ++i)
      if (wall_height <= rows[i].wall_height)
      {
        const double s =
          (wall_height - rows[i - 1].wall_height) / (rows[i].wall_height - rows[i - 1].wall_height);
        return k(rows[i - 1]) + s * (k(rows[i]) - k(rows[i - 1]));
      }
    return k(rows.back());
  }
} // namespace kimp::app
