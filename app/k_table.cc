// Reader of a study's k_table.csv (RFC 4180 as written by io/summary.h) and its interpolation in
// wall height and impact velocity.
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

    bool same_velocity(double a, double b)
    {
      return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= 1e-9 * std::max(1.0, b);
    }

    /// k of `rows` (one velocity, sorted by height) at `wall_height`, linear in the height.
    double interpolate_in_height(const std::vector<const KTableRow *> &rows,
                                 double                                wall_height,
                                 bool                                  kv,
                                 const std::filesystem::path          &file)
    {
      const auto k = [&](const KTableRow *r)
      { return kv ? r->kelvin_voigt_total : r->jankowski_total; };
      const double low = rows.front()->wall_height, high = rows.back()->wall_height;
      // A relative tolerance so that a height printed to 6 digits still matches its row.
      const double slack = 1e-9 * std::max(1.0, std::abs(high));
      if (!(wall_height >= low - slack && wall_height <= high + slack))
        throw std::invalid_argument(
          fmt::format("wall height {} m is outside the range of {} ({} m to {} m{}); k is not "
                      "extrapolated",
                      wall_height,
                      file.string(),
                      low,
                      high,
                      std::isnan(rows.front()->impact_velocity) ?
                        std::string() :
                        fmt::format(" at {} m/s", rows.front()->impact_velocity)));
      if (rows.size() == 1 || wall_height <= low)
        return k(rows.front());
      for (std::size_t i = 1; i < rows.size(); ++i)
        if (wall_height <= rows[i]->wall_height)
        {
          const double s = (wall_height - rows[i - 1]->wall_height) /
                           (rows[i]->wall_height - rows[i - 1]->wall_height);
          return k(rows[i - 1]) + s * (k(rows[i]) - k(rows[i - 1]));
        }
      return k(rows.back());
    }

    bool kelvin_voigt_column(double exponent, const std::filesystem::path &file)
    {
      if (exponent != 1.0 && exponent != 1.5)
        throw std::invalid_argument(fmt::format("{} holds k for n = 1 (Kelvin-Voigt) and n = 1.5 "
                                                "(Jankowski) only, not n = {}",
                                                file.string(),
                                                exponent));
      return exponent == 1.0;
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
    // Optional columns: tables written before the velocity axis have one velocity (or none).
    const auto optional_column = [&](const std::string &name)
    {
      return static_cast<std::size_t>(
        std::distance(header.begin(), std::find(header.begin(), header.end(), name)));
    };
    const std::size_t velocity  = optional_column("impact_velocity_m_per_s");
    const std::size_t reference = optional_column("reference_velocity");
    int               number    = 1;
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
      if (velocity < f.size())
        row.impact_velocity = to_number(f[velocity]);
      if (reference < f.size())
        row.reference = f[reference] == "yes";
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
              [](const KTableRow &a, const KTableRow &b)
              {
                return a.wall_height < b.wall_height ||
                       (a.wall_height == b.wall_height && a.impact_velocity < b.impact_velocity);
              });
    return table;
  }

  std::vector<double> KTable::velocities() const
  {
    std::vector<double> v;
    for (const KTableRow &r : rows)
      if (std::isfinite(r.impact_velocity) &&
          std::none_of(v.begin(),
                       v.end(),
                       [&](double x) { return same_velocity(x, r.impact_velocity); }))
        v.push_back(r.impact_velocity);
    std::sort(v.begin(), v.end());
    return v;
  }

  double KTable::stiffness(double wall_height, double exponent) const
  {
    const bool                     kv = kelvin_voigt_column(exponent, file);
    std::vector<const KTableRow *> chosen;
    for (const KTableRow &r : rows)
      if (r.reference)
        chosen.push_back(&r);
    if (chosen.empty() && velocities().size() <= 1)
      for (const KTableRow &r : rows)
        chosen.push_back(&r);
    if (chosen.empty())
      throw std::invalid_argument(fmt::format("{} holds several impact velocities and no row of "
                                              "the reference velocity: give the velocity",
                                              file.string()));
    return interpolate_in_height(chosen, wall_height, kv, file);
  }

  double KTable::stiffness(double wall_height, double exponent, double velocity) const
  {
    const bool                kv = kelvin_voigt_column(exponent, file);
    const std::vector<double> v  = velocities();
    if (v.size() <= 1)
    {
      std::vector<const KTableRow *> all;
      for (const KTableRow &r : rows)
        all.push_back(&r);
      return interpolate_in_height(all, wall_height, kv, file);
    }
    const auto at = [&](double speed)
    {
      std::vector<const KTableRow *> level;
      for (const KTableRow &r : rows)
        if (same_velocity(r.impact_velocity, speed))
          level.push_back(&r);
      return interpolate_in_height(level, wall_height, kv, file);
    };
    const double slack = 1e-9 * std::max(1.0, v.back());
    if (!(velocity >= v.front() - slack && velocity <= v.back() + slack))
      throw std::invalid_argument(fmt::format("impact velocity {} m/s is outside the range of {} "
                                              "({} m/s to {} m/s); k is not extrapolated",
                                              velocity,
                                              file.string(),
                                              v.front(),
                                              v.back()));
    if (velocity <= v.front())
      return at(v.front());
    for (std::size_t i = 1; i < v.size(); ++i)
      if (velocity <= v[i])
      {
        const double s = (velocity - v[i - 1]) / (v[i] - v[i - 1]);
        const double a = at(v[i - 1]);
        return a + s * (at(v[i]) - a);
      }
    return at(v.back());
  }
} // namespace kimp::app
