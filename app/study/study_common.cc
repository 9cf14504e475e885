// Small helpers shared by the stages of `kimp study` (k in display units, the FEM level used)
// and thesis Table 2.1, read from data/reference/thesis_table_2_1.csv.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "app/csv_reader.h"
#include "app/study/study_fem.h"
#include "app/study/study_internal.h"

namespace kimp::app::study_internal
{
  std::optional<ThesisStiffness> thesis_row(double wall_height)
  {
    for (const ThesisStiffness &row : thesis_table_2_1())
      if (std::abs(row.wall_height - wall_height) < 1e-9)
        return row;
    return std::nullopt;
  }

  double per_metre(const std::optional<FitResult> &fit)
  {
    return fit ? fit->stiffness_per_metre_display() : nan;
  }
  double per_metre_bound(const std::optional<FitResult> &fit, bool upper)
  {
    return fit ? stiffness_to_kn_per_mm(upper ? fit->stiffness.upper : fit->stiffness.lower,
                                        fit->exponent.value) :
                 nan;
  }

  double numerical_error(const StudyHeight &h, const StudyLaw &law)
  {
    return stiffness_to_kn_per_mm(h.ladder.error_of(study_law_index(law)), law.exponent());
  }


  double thesis_k(const std::optional<ThesisStiffness> &row, const StudyLaw &law)
  {
    return row && law.thesis ? (*row).*law.thesis : nan;
  }

  double used_h_contact(const StudyScene &scene, const StudyHeight &h)
  {
    return h.auto_fidelity ? h.ladder.used_level().h_contact :
                             scene.fem.geometry.h_contact / std::pow(2.0, scene.fem.mesh_level);
  }

  double used_penalty(const StudyScene &scene, const StudyHeight &h)
  {
    return h.auto_fidelity ? h.ladder.used_level().penalty_factor : scene.fem.solver.penalty_factor;
  }

  void set_fits(StudyHeight &h, StudyFits fits)
  {
    for (std::size_t i = 0; i < h.laws.size(); ++i)
    {
      h.laws[i].fit    = std::move(fits.laws[i].fit);
      h.laws[i].status = std::move(fits.laws[i].status);
    }
  }

  nlohmann::ordered_json
  law_json(const StudyHeight &h, const StudyLawFit &law, std::optional<double> width)
  {
    nlohmann::ordered_json f;
    f["status"] = law.status;
    if (const std::optional<FitResult> &fit = law.fit)
    {
      f["k_per_metre"] = per_metre(fit);
      f["k_lower"]     = per_metre_bound(fit, false);
      f["k_upper"]     = per_metre_bound(fit, true);
      if (width)
        f["k_total"] = per_metre(fit) * *width;
      f["unit"] = fit->per_metre_unit();
      if (width)
        f["normalised_rms"] = fit->normalised_rms;
      f["peak_force_ratio"]       = fit->peak_force_ratio();
      f["impulse_ratio"]          = fit->impulse_ratio();
      f["contact_duration_ratio"] = fit->contact_duration_ratio();
      const double error          = numerical_error(h, *law.law);
      if (std::isfinite(error))
        f["k_numerical_error"] = error;
    }
    return f;
  }

  void add_k_columns(Table &t, const StudyLaw &law)
  {
    const std::string name = law.name();
    const std::string unit = law.per_metre_unit();
    t.number(name, unit).number(name + "_lower", unit).number(name + "_upper", unit);
  }

  void add_k_cells(std::vector<Cell> &row, const std::optional<FitResult> &fit)
  {
    append_numbers(row, {per_metre(fit), per_metre_bound(fit, false), per_metre_bound(fit, true)});
  }

  std::string law_table_header(const std::string                                  &lead,
                               std::size_t                                         lead_columns,
                               std::size_t                                         law_columns,
                               const std::function<std::string(const StudyLaw &)> &titles)
  {
    std::string header = lead;
    std::size_t n      = lead_columns + 1; // and the status
    for (const StudyLaw &law : study_laws())
    {
      header += titles(law);
      n += law_columns;
    }
    std::string rule = "|";
    for (std::size_t i = 0; i < n; ++i)
      rule += "---|";
    return header + " status |\n" + rule + "\n";
  }

  std::vector<double> scale(std::vector<double> values, double factor)
  {
    for (double &v : values)
      v *= factor;
    return values;
  }

  std::string number(double value)
  {
    // Shortest text that reads back to the same double, as io::Table writes: a value that stands
    // in two files (building_response.csv, flexible_wall.csv) reads the same in both.
    return std::isfinite(value) ? fmt::format("{}", value) : "";
  }

  std::string readable(double value)
  {
    return std::isfinite(value) ? base::sig(value) : std::string();
  }
} // namespace kimp::app::study_internal

namespace kimp::app
{
  const std::vector<StudyLaw> &study_laws()
  {
    static const std::vector<StudyLaw> laws = {{&lumped::law_traits("kelvin_voigt"),
                                                "Kelvin-Voigt",
                                                "KV",
                                                "KV",
                                                {"modified_kelvin_voigt"},
                                                &ThesisStiffness::kelvin_voigt},
                                               {&lumped::law_traits("jankowski"),
                                                "Jankowski",
                                                "Jankowski",
                                                "J",
                                                {"jankowski", "hysteretic"},
                                                &ThesisStiffness::jankowski}};
    return laws;
  }

  std::size_t study_law_index(const StudyLaw &law)
  {
    return static_cast<std::size_t>(&law - study_laws().data());
  }

  std::string k_text(const std::vector<double> &k, std::string_view prefix)
  {
    std::string text;
    for (const StudyLaw &law : study_laws())
    {
      const std::size_t i = study_law_index(law);
      text += fmt::format("{}{}{} {:.4g} {}",
                          text.empty() ? "" : ", ",
                          prefix,
                          law.short_name,
                          fit::stiffness_to_kn_per_mm(i < k.size() ?
                                                        k[i] :
                                                        std::numeric_limits<double>::quiet_NaN(),
                                                      law.exponent()),
                          law.per_metre_unit());
    }
    return text;
  }
  std::vector<StudyLawFit> unfitted_study_laws()
  {
    std::vector<StudyLawFit> fits;
    for (const StudyLaw &law : study_laws())
      fits.push_back({&law, std::nullopt, "ok", std::nullopt});
    return fits;
  }

  bool all_fitted(const std::vector<StudyLawFit> &laws)
  {
    return std::all_of(laws.begin(),
                       laws.end(),
                       [](const StudyLawFit &l) { return l.fit.has_value(); });
  }

  bool all_ok(const std::vector<StudyLawFit> &laws)
  {
    return std::all_of(laws.begin(), laws.end(), [](const StudyLawFit &l) { return l.ok(); });
  }

  std::string joined_status(const std::vector<StudyLawFit> &laws)
  {
    std::string text;
    for (const StudyLawFit &l : laws)
      text += (text.empty() ? "" : " / ") + l.status;
    return text;
  }

  const StudyLawFit &law_fit(const std::vector<StudyLawFit> &laws, std::string_view name)
  {
    for (const StudyLawFit &l : laws)
      if (l.law->traits->name == name)
        return l;
    throw std::out_of_range("no study law '" + std::string(name) + "'");
  }

  namespace
  {
    /// One number of the table; the whole cell must be a finite number.
    double
    table_number(const std::filesystem::path &file, std::size_t line, const std::string &cell)
    {
      std::size_t used  = 0;
      double      value = std::numeric_limits<double>::quiet_NaN();
      try
      {
        value = std::stod(cell, &used);
      }
      catch (const std::exception &)
      {
        used = 0;
      }
      if (used == 0 || used != cell.size() || !std::isfinite(value))
        throw std::runtime_error(
          fmt::format("{}:{}: '{}' is not a number", file.string(), line, cell));
      return value;
    }
  } // namespace

  std::filesystem::path thesis_table_2_1_file()
  {
    const std::filesystem::path name = "thesis_table_2_1.csv";
    if (const char *data_dir = std::getenv("KIMP_DATA_DIR"); data_dir != nullptr && *data_dir)
      for (const std::filesystem::path &directory :
           {std::filesystem::path(data_dir) / "data" / "reference",
            std::filesystem::path(data_dir) / "reference"})
        if (std::filesystem::is_regular_file(directory / name))
          return directory / name;
    return std::filesystem::path(KIMP_SOURCE_TREE) / "data" / "reference" / name;
  }

  std::vector<ThesisStiffness> read_thesis_table_2_1(const std::filesystem::path &file)
  {
    std::ifstream in(file);
    if (!in)
      throw std::runtime_error(fmt::format("thesis Table 2.1: cannot open {} (set KIMP_DATA_DIR "
                                           "to the kimp source tree)",
                                           file.string()));
    const std::vector<std::string> columns = {"wall_height_m",
                                              "kelvin_voigt_kN_per_mm_per_m",
                                              "jankowski_kN_per_mm1.5_per_m"};
    std::string                    line;
    std::getline(in, line);
    const std::vector<std::string> header = split_csv_record(line);
    if (header.size() < columns.size() ||
        !std::equal(columns.begin(), columns.end(), header.begin()))
      throw std::runtime_error(fmt::format("{}:1: header '{}' (expected the columns {}, ...)",
                                           file.string(),
                                           line,
                                           fmt::join(columns, ",")));
    std::vector<ThesisStiffness> table;
    for_each_csv_row(in,
                     header.size(),
                     file,
                     [&](const std::vector<std::string> &cells, int number)
                     {
                       const auto line_number = static_cast<std::size_t>(number);
                       table.push_back({table_number(file, line_number, cells[0]),
                                        table_number(file, line_number, cells[1]),
                                        table_number(file, line_number, cells[2])});
                     });
    if (table.empty())
      throw std::runtime_error(fmt::format("{}: no rows", file.string()));
    return table;
  }

  const std::vector<ThesisStiffness> &thesis_table_2_1()
  {
    static const std::vector<ThesisStiffness> table =
      read_thesis_table_2_1(thesis_table_2_1_file());
    return table;
  }
} // namespace kimp::app
