// Reader of a study's k_table.csv (RFC 4180 as written by io/summary.h) and its interpolation in
// wall height and impact velocity.
#include "app/laws/k_table.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <stdexcept>

#include "app/csv_reader.h"

namespace kimp::app
{
  namespace
  {
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

  namespace
  {
    /// A CSV file of kimp opened for reading: its header, its columns by name, then its rows.
    class CsvFile
    {
    public:
      /// @throws std::invalid_argument "<file>: <unreadable>" when the file cannot be read
      ///         (`unreadable` says what was expected).
      CsvFile(const std::filesystem::path &file, const std::string &unreadable)
        : file_(file)
        , in_(file)
      {
        if (!in_)
          throw std::invalid_argument(fmt::format("{}: {}", file.string(), unreadable));
        std::string line;
        std::getline(in_, line);
        header_ = split_csv_record(line);
      }

      /// Index of column `name`; header size (past every row's fields) when there is none.
      std::size_t find(const std::string &name) const
      {
        return static_cast<std::size_t>(
          std::distance(header_.begin(), std::find(header_.begin(), header_.end(), name)));
      }

      bool has(const std::string &name) const { return find(name) < header_.size(); }

      /// The index of column `name`.
      /// @throws std::invalid_argument naming the file, the column and what the file is not
      ///         (`not_a`).
      std::size_t column(const std::string &name, const std::string &not_a) const
      {
        const std::size_t i = find(name);
        if (i == header_.size())
          throw std::invalid_argument(
            fmt::format("{}: no column '{}' ({})", file_.string(), name, not_a));
        return i;
      }

      /// for_each_csv_row() of the rows after the header.
      void for_each_row(const std::function<void(const std::vector<std::string> &, int)> &each)
      {
        for_each_csv_row(in_, header_.size(), file_, each);
      }

    private:
      std::filesystem::path    file_;
      std::ifstream            in_;
      std::vector<std::string> header_;
    };

    /// A Kelvin-Voigt k_total as the tables write it (kN/mm), in N/m.
    double kelvin_voigt_si(const std::string &kn_per_mm)
    {
      return to_number(kn_per_mm) * 1e6;
    }

    /// A Jankowski k_total as the tables write it (kN/mm^1.5), in N/m^1.5: × 1e3 · 1e3^1.5.
    double jankowski_si(const std::string &kn_per_mm_1_5)
    {
      return to_number(kn_per_mm_1_5) * 1e3 * std::pow(1e3, 1.5);
    }

    /// Sort by height, then velocity (the order the interpolation needs).
    void sort_rows(std::vector<KTableRow> &rows)
    {
      std::sort(rows.begin(),
                rows.end(),
                [](const KTableRow &a, const KTableRow &b)
                {
                  return a.wall_height < b.wall_height ||
                         (a.wall_height == b.wall_height && a.impact_velocity < b.impact_velocity);
                });
    }

    /**
     * The k of a fit_table.csv of `kimp fit`: per FEM case, k_total of the variants
     * kelvin_voigt_cor_fixed and jankowski_cor_fixed (the study's two laws). A case needs both
     * (a failed fit leaves it out). Two cases at one height and velocity are ambiguous and
     * refused.
     */
    void read_fit_table(KTable &table, CsvFile &csv)
    {
      const auto column = [&](const std::string &name)
      { return csv.column(name, "not a fit_table.csv of `kimp fit`"); };
      const std::size_t name = column("case"), height = column("wall_height_m"),
                        variant = column("variant"), k_total = column("k_total"),
                        status = column("status");
      // Tables of `kimp fit` before the velocity column have one velocity per case, unknown.
      const std::size_t        velocity = csv.find("impact_velocity_m_per_s");
      std::vector<std::string> cases; // in file order
      std::vector<KTableRow>   rows;
      csv.for_each_row(
        [&](const std::vector<std::string> &f, int)
        {
          const bool kv = f[variant] == "kelvin_voigt_cor_fixed";
          if (!kv && f[variant] != "jankowski_cor_fixed")
            return;
          const auto at = std::find(cases.begin(), cases.end(), f[name]);
          if (at == cases.end())
          {
            cases.push_back(f[name]);
            KTableRow row;
            row.wall_height        = to_number(f[height]);
            row.impact_velocity    = velocity < f.size() ? to_number(f[velocity]) : std::nan("");
            row.kelvin_voigt_total = row.jankowski_total = std::nan("");
            rows.push_back(row);
          }
          KTableRow &row = rows[static_cast<std::size_t>(
            std::distance(cases.begin(), std::find(cases.begin(), cases.end(), f[name])))];
          if (f[status].rfind("failed", 0) == 0)
            return;
          if (kv)
            row.kelvin_voigt_total = kelvin_voigt_si(f[k_total]);
          else
            row.jankowski_total = jankowski_si(f[k_total]);
        });
      std::vector<std::string> kept; // the case of each row of table.rows
      for (std::size_t i = 0; i < rows.size(); ++i)
      {
        const KTableRow &r = rows[i];
        if (!(std::isfinite(r.wall_height) && r.kelvin_voigt_total > 0.0 &&
              r.jankowski_total > 0.0))
          continue;
        for (std::size_t j = 0; j < table.rows.size(); ++j)
          if (table.rows[j].wall_height == r.wall_height &&
              same_velocity(table.rows[j].impact_velocity, r.impact_velocity))
            throw std::invalid_argument(
              fmt::format("{}: cases '{}' and '{}' are both at wall height {} m{}: which k to "
                          "take is ambiguous (fit one of them, or pass explicit k)",
                          table.file.string(),
                          kept[j],
                          cases[i],
                          r.wall_height,
                          std::isnan(r.impact_velocity) ?
                            std::string() :
                            fmt::format(" and {} m/s", r.impact_velocity)));
        table.rows.push_back(r);
        kept.push_back(cases[i]);
      }
      if (table.rows.empty())
        throw std::invalid_argument(fmt::format("{}: no case with both a Kelvin-Voigt and a "
                                                "Jankowski k (every fit failed?)",
                                                table.file.string()));
      // Several velocities: none is the reference, the velocity must be given.
      const bool one_velocity = table.velocities().size() <= 1;
      for (KTableRow &r : table.rows)
        r.reference = one_velocity;
      sort_rows(table.rows);
    }
  } // namespace

  KTable read_k_table(const std::filesystem::path &path)
  {
    KTable table;
    table.file = path;
    if (std::filesystem::is_directory(path))
    {
      table.file = path / "k_table.csv";
      if (!std::filesystem::exists(table.file) && std::filesystem::exists(path / "fit_table.csv"))
        table.file = path / "fit_table.csv";
    }
    CsvFile csv(table.file,
                "cannot read the k table (expected the k_table.csv of `kimp study`, the "
                "fit_table.csv of `kimp fit`, or the output directory of either)");
    if (csv.has("variant") && csv.has("wall_height_m"))
    {
      read_fit_table(table, csv);
      return table;
    }
    const auto column = [&](const std::string &name) {
      return csv.column(name,
                        "not a k_table.csv of `kimp study` nor a fit_table.csv of `kimp fit`");
    };
    const std::size_t height = column("wall_height_m");
    const std::size_t kv     = column("kelvin_voigt_total_kN_per_mm");
    const std::size_t jk     = column("jankowski_total_kN_per_mm1.5");
    // Optional columns: tables written before the velocity axis have one velocity (or none).
    const std::size_t velocity  = csv.find("impact_velocity_m_per_s");
    const std::size_t reference = csv.find("reference_velocity");
    csv.for_each_row(
      [&](const std::vector<std::string> &f, int)
      {
        KTableRow row;
        row.wall_height        = to_number(f[height]);
        row.kelvin_voigt_total = kelvin_voigt_si(f[kv]);
        row.jankowski_total    = jankowski_si(f[jk]);
        if (velocity < f.size())
          row.impact_velocity = to_number(f[velocity]);
        if (reference < f.size())
          row.reference = f[reference] == "yes";
        if (std::isfinite(row.wall_height) && row.kelvin_voigt_total > 0.0 &&
            row.jankowski_total > 0.0)
          table.rows.push_back(row);
      });
    if (table.rows.empty())
      throw std::invalid_argument(
        fmt::format("{}: no row with a wall height and both k (every fit failed?)",
                    table.file.string()));
    sort_rows(table.rows);
    return table;
  }

  RecordK read_consistent_k(const std::filesystem::path &study_dir,
                            const std::string           &record,
                            double                       wall_height)
  {
    RecordK k;
    k.file = study_dir / "consistent_k.csv";
    CsvFile    csv(k.file,
                "cannot read it (the consistent k of a record needs a study run with "
                   "consistent_k.enabled: true)");
    const auto column = [&](const std::string &name)
    { return csv.column(name, "not a consistent_k.csv of `kimp study`"); };
    const std::size_t c_record = column("record"), c_height = column("wall_height_m"),
                      c_law = column("law"), c_k = column("k_consistent"),
                      c_velocity  = column("impact_velocity_m_per_s"),
                      c_converged = column("converged"), c_status = column("status");
    std::vector<std::string> records, heights;
    const auto               add = [](std::vector<std::string> &list, const std::string &text)
    {
      if (std::find(list.begin(), list.end(), text) == list.end())
        list.push_back(text);
    };
    csv.for_each_row(
      [&](const std::vector<std::string> &f, int number)
      {
        add(records, f[c_record]);
        if (f[c_record] != record)
          return;
        add(heights, f[c_height]);
        const double h = to_number(f[c_height]);
        if (!(std::abs(h - wall_height) <= 1e-9 * std::max(1.0, wall_height)))
          return;
        const bool kv = f[c_law] == "modified_kelvin_voigt";
        if (!kv && f[c_law] != "jankowski")
          return;
        if (f[c_converged] != "yes" || f[c_status] != "ok")
          throw std::invalid_argument(fmt::format("{}:{}: the consistent k of record '{}' at {} m "
                                                  "({}) did not converge (status: {}): no k to "
                                                  "export",
                                                  k.file.string(),
                                                  number,
                                                  record,
                                                  wall_height,
                                                  f[c_law],
                                                  f[c_status]));
        if (kv)
          k.kelvin_voigt_total = kelvin_voigt_si(f[c_k]);
        else
          k.jankowski_total = jankowski_si(f[c_k]);
        if (!kv || std::isnan(k.impact_velocity))
          k.impact_velocity = to_number(f[c_velocity]);
      });
    const auto joined = [](const std::vector<std::string> &list)
    {
      std::string text;
      for (const std::string &item : list)
        text += (text.empty() ? "" : ", ") + item;
      return text.empty() ? std::string("none") : text;
    };
    if (std::find(records.begin(), records.end(), record) == records.end())
      throw std::invalid_argument(
        fmt::format("{}: no record '{}' (records: {})", k.file.string(), record, joined(records)));
    if (std::isnan(k.kelvin_voigt_total) && std::isnan(k.jankowski_total))
      throw std::invalid_argument(fmt::format("{}: record '{}' has no run at wall height {} m "
                                              "(heights: {} m)",
                                              k.file.string(),
                                              record,
                                              wall_height,
                                              joined(heights)));
    return k;
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
