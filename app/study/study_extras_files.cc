// Writers of the extra studies of `kimp study`: study.h5 /accuracy, /stability, /sensitivity and
// accuracy_fem.csv, accuracy_lumped.csv, stability_lumped.csv, stability_fem.csv, sensitivity.csv.
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>

#include "app/study/study_columns.h"
#include "app/study/study_extras.h"
#include "app/study/study_internal.h"
#include "fit/fitter.h"
#include "io/table.h"

namespace kimp::app
{
  using namespace study_internal;

  namespace
  {
    /// A relative error: NAME (1) in study.h5, NAME_percent in the CSV file.
    template <class P>
    StudyColumn<P> error_column(const std::string &name, double P::*error)
    {
      return number_column<P>({name, "1"},
                              {name + "_percent", "1"},
                              times(100),
                              [error](const P &p) { return p.*error; });
    }

    /// The two fitted laws' k per metre in kN/mm^n/m (NaN unless the point is ok), as in the k
    /// table.
    template <class P>
    void append_k_columns(std::vector<StudyColumn<P>> &columns)
    {
      for (const StudyLaw &law : study_laws())
        columns.push_back(
          same_column<P>(law.name(),
                         law.per_metre_unit(),
                         [i = study_law_index(law), n = law.exponent()](const P &p) {
                           return p.ok && i < p.k.size() ? stiffness_to_kn_per_mm(p.k[i], n) : nan;
                         }));
    }

    /// The FEM accuracy points: k against the contact mesh, the penalty and the implicit solver.
    std::vector<StudyColumn<FemAccuracyPoint>> fem_accuracy_columns()
    {
      using P = FemAccuracyPoint;
      std::vector<StudyColumn<P>> columns{
        csv_text_column<P>("series", [](const P &p) { return p.series; }),
        number_column<P>({"h_contact", "m"},
                         {"h_contact", "cm"},
                         times(100),
                         [](const P &p) { return p.h_contact; }),
        same_column<P>("penalty_factor", "1", [](const P &p) { return p.penalty_factor; }),
        hdf5_column<P>("ok", "1", [](const P &p) { return flag(p.ok); }),
        number_column<P>({"seconds", "s"},
                         {"fem_wall_time", "s"},
                         {},
                         [](const P &p) { return p.seconds; }),
        same_column<P>("n_dofs", "1", [](const P &p) { return p.n_dofs; }),
        hdf5_column<P>("n_steps", "1", [](const P &p) { return p.n_steps; })};
      append_k_columns(columns);
      // Each law's error of k: error_<law> (1) in study.h5, error_<law>_percent in the CSV file.
      for (const StudyLaw &law : study_laws())
        columns.push_back(number_column<P>({"error_" + law.name(), "1"},
                                           {"error_" + law.name() + "_percent", "1"},
                                           times(100),
                                           [i = study_law_index(law)](const P &p)
                                           { return i < p.error.size() ? p.error[i] : nan; }));
      columns.push_back(csv_text_column<P>("status", [](const P &p) { return p.status; }));
      return columns;
    }

    /// The lumped accuracy points: peaks of one building run against the time step.
    std::vector<StudyColumn<LumpedAccuracyPoint>> lumped_accuracy_columns()
    {
      using P = LumpedAccuracyPoint;
      return {csv_text_column<P>("method", [](const P &p) { return p.method; }),
              same_column<P>("dt", "s", [](const P &p) { return p.dt; }),
              hdf5_column<P>("ok", "1", [](const P &p) { return flag(p.ok); }),
              number_column<P>({"seconds", "s"},
                               {"wall_time", "s"},
                               {},
                               [](const P &p) { return p.seconds; }),
              number_column<P>({"impact_force", "N"},
                               {"peak_impact_force", "kN"},
                               divided_by(1e3),
                               [](const P &p) { return p.ok ? p.peak_impact_force : nan; }),
              number_column<P>({"base_acceleration", "m/s^2"},
                               {"peak_base_acceleration", "m/s^2"},
                               {},
                               [](const P &p) { return p.ok ? p.base_acceleration : nan; }),
              error_column("error_impact_force", &P::error_force),
              error_column("error_base_acceleration", &P::error_acceleration),
              csv_text_column<P>("status", [](const P &p) { return p.status; })};
    }

    /// The stability map: the explicit lumped time step against k.
    std::vector<StudyColumn<StabilityPoint>> lumped_stability_columns()
    {
      using P = StabilityPoint;
      return {number_column<P>(
                {"stiffness", "N/m"},
                {"k_imp", "kN/mm"},
                [](double k) { return stiffness_to_kn_per_mm(k, 1.0); },
                [](const P &p) { return p.stiffness; }),
              same_column<P>("dt", "s", [](const P &p) { return p.dt; }),
              number_column<P>({"dt_limit", "s"},
                               {"dt_limit_2_over_omega", "s"},
                               {},
                               [](const P &p) { return p.dt_limit; }),
              same_column<P>("dt_limit_damped", "s", [](const P &p) { return p.dt_limit_damped; }),
              same_column<P>("stable", "1", [](const P &p) { return flag(p.stable); }),
              same_column<P>("accurate", "1", [](const P &p) { return flag(p.accurate); }),
              same_column<P>("effective_cor", "1", [](const P &p) { return p.effective_cor; }),
              hdf5_column<P>("peak_force", "N", [](const P &p) { return p.peak_force; })};
    }

    /// The FEM stability map: the explicit FEM time step against the penalty.
    std::vector<StudyColumn<FemStabilityPoint>> fem_stability_columns()
    {
      using P = FemStabilityPoint;
      return {same_column<P>("penalty_factor", "1", [](const P &p) { return p.penalty_factor; }),
              number_column<P>({"dt_factor", "1"},
                               {"dt_over_limit", "1"},
                               {},
                               [](const P &p) { return p.dt_factor; }),
              same_column<P>("dt", "s", [](const P &p) { return p.dt; }),
              same_column<P>("dt_limit", "s", [](const P &p) { return p.dt_limit; }),
              same_column<P>("stable", "1", [](const P &p) { return flag(p.stable); }),
              number_column<P>({"energy_error", "1"},
                               {"max_energy_error", "1"},
                               {},
                               [](const P &p)
                               { return p.energy_error > 0 ? p.energy_error : nan; }),
              csv_text_column<P>("status", [](const P &p) { return p.status; })};
    }

    /// The sensitivity study: k against one scene parameter.
    std::vector<StudyColumn<SensitivityPoint>> sensitivity_columns()
    {
      using P = SensitivityPoint;
      std::vector<StudyColumn<P>> columns{
        csv_text_column<P>("parameter", [](const P &p) { return p.parameter; }),
        same_column<P>("factor", "1", [](const P &p) { return p.factor; }),
        hdf5_column<P>("ok", "1", [](const P &p) { return flag(p.ok); })};
      append_k_columns(columns);
      columns.push_back(csv_text_column<P>("status", [](const P &p) { return p.status; }));
      return columns;
    }

    /**
     * study.h5 /accuracy/`kind`/<series>: for each of `series`, the table of the rows whose
     * `series_of` it is (no group for a series without rows); `annotate` then sets the
     * attributes of /accuracy/`kind`.
     */
    template <class Row>
    void write_accuracy(ResultsGroup                        &root,
                        const char                          *kind,
                        const std::vector<StudyColumn<Row>> &columns,
                        const std::vector<Row>              &rows,
                        std::string Row::                         *series_of,
                        std::initializer_list<const char *>        series,
                        const std::function<void(ResultsGroup &)> &annotate)
    {
      for (const std::string name : series)
      {
        const Table t = study_table(columns,
                                    rows,
                                    StudyFile::hdf5,
                                    [&](const Row &p) { return p.*series_of == name; });
        if (t.n_rows() == 0)
          continue;
        ResultsGroup group = root.group("accuracy").group(kind);
        t.write_hdf5(group, name);
        annotate(group);
      }
    }

    /// study.h5 /accuracy/fem/<series> and /accuracy/lumped/<method>.
    void write_accuracy(ResultsGroup &root, const StudyExtras &extras)
    {
      write_accuracy(root,
                     "fem",
                     fem_accuracy_columns(),
                     extras.fem_accuracy,
                     &FemAccuracyPoint::series,
                     {"mesh", "penalty", "implicit"},
                     [](ResultsGroup &) {});
      write_accuracy(root,
                     "lumped",
                     lumped_accuracy_columns(),
                     extras.lumped_accuracy,
                     &LumpedAccuracyPoint::method,
                     {"cdm", "newmark", "cdm_reference"},
                     [&](ResultsGroup &lumped)
                     {
                       lumped.set_attribute("k_total_N_per_m", extras.lumped_k_total);
                       lumped.set_attribute("gap_m", extras.lumped_gap);
                       lumped.set_attribute("record", extras.lumped_record);
                     });
    }

    /// study.h5 /stability/lumped and /stability/fem, each with the attributes of its set-up.
    void write_stability(ResultsGroup &root, const StudyExtras &extras)
    {
      struct StabilityMap
      {
        const char                                  *name;
        Table                                        table;
        std::vector<std::pair<const char *, double>> attributes;
      };
      const StabilityMap maps[] = {
        {"lumped",
         study_table(lumped_stability_columns(), extras.stability, StudyFile::hdf5),
         {{"effective_mass_kg", extras.stability_effective_mass},
          {"study_stiffness_N_per_m", extras.stability_study_k}}},
        {"fem",
         study_table(fem_stability_columns(), extras.fem_stability, StudyFile::hdf5),
         {{"h_contact_m", extras.fem_stability_h_contact},
          {"end_time_s", extras.fem_stability_end_time}}}};
      for (const StabilityMap &map : maps)
      {
        if (map.table.n_rows() == 0)
          continue;
        ResultsGroup stability = root.group("stability");
        map.table.write_hdf5(stability, map.name);
        ResultsGroup group = stability.group(map.name);
        for (const auto &[attribute, value] : map.attributes)
          group.set_attribute(attribute, value);
      }
    }

    /// study.h5 /sensitivity/<parameter>.
    void write_sensitivity(ResultsGroup &root, const StudyExtras &extras)
    {
      if (extras.sensitivity.empty())
        return;
      for (const std::string parameter :
           {"base", "soil_modulus", "slab_mass", "impact_velocity", "wall_thickness"})
      {
        ResultsGroup sensitivity = root.group("sensitivity");
        study_table(sensitivity_columns(),
                    extras.sensitivity,
                    StudyFile::hdf5,
                    [&](const SensitivityPoint &p) { return p.parameter == parameter; })
          .write_hdf5(sensitivity, parameter);
      }
    }

    /// DIR/`file` of `columns` over `rows`, unless there are none.
    template <class Row>
    void write_csv_of(const OutputDir                     &output,
                      const char                          *file,
                      const std::vector<StudyColumn<Row>> &columns,
                      const std::vector<Row>              &rows)
    {
      if (!rows.empty())
        study_table(columns, rows, StudyFile::csv).write_csv(output.file(file));
    }
  } // namespace

  void write_study_extras(ResultsGroup &root, const StudyExtras &extras)
  {
    write_accuracy(root, extras);
    write_stability(root, extras);
    write_sensitivity(root, extras);
  }

  void write_study_extras_csv(const OutputDir &output, const StudyExtras &extras)
  {
    write_csv_of(output, "accuracy_fem.csv", fem_accuracy_columns(), extras.fem_accuracy);
    write_csv_of(output, "accuracy_lumped.csv", lumped_accuracy_columns(), extras.lumped_accuracy);
    write_csv_of(output, "stability_lumped.csv", lumped_stability_columns(), extras.stability);
    write_csv_of(output, "stability_fem.csv", fem_stability_columns(), extras.fem_stability);
    write_csv_of(output, "sensitivity.csv", sensitivity_columns(), extras.sensitivity);
  }
} // namespace kimp::app
