// Writers of the extra studies of `kimp study`: study.h5 /accuracy, /stability, /sensitivity and
// accuracy_fem.csv, accuracy_lumped.csv, stability_lumped.csv, stability_fem.csv, sensitivity.csv.
#include <cmath>
#include <fmt/format.h>
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
    /// k per metre of a fitted law in kN/mm^n/m (NaN unless `ok`).
    double k_display(bool ok, double k, double exponent)
    {
      return ok ? stiffness_to_kn_per_mm(k, exponent) : nan;
    }

    /// The FEM accuracy points: k against the contact mesh, the penalty and the implicit solver.
    std::vector<StudyColumn<FemAccuracyPoint>> fem_accuracy_columns()
    {
      using P = FemAccuracyPoint;
      return {csv_text_column<P>("series", [](const P &p) { return p.series; }),
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
              hdf5_column<P>("n_steps", "1", [](const P &p) { return p.n_steps; }),
              same_column<P>("kelvin_voigt",
                             "kN/mm/m",
                             [](const P &p) { return k_display(p.ok, p.k_kelvin_voigt, 1.0); }),
              same_column<P>("jankowski",
                             "kN/mm^1.5/m",
                             [](const P &p) { return k_display(p.ok, p.k_jankowski, 1.5); }),
              number_column<P>({"error_kelvin_voigt", "1"},
                               {"error_kelvin_voigt_percent", "1"},
                               times(100),
                               [](const P &p) { return p.error_kelvin_voigt; }),
              number_column<P>({"error_jankowski", "1"},
                               {"error_jankowski_percent", "1"},
                               times(100),
                               [](const P &p) { return p.error_jankowski; }),
              csv_text_column<P>("status", [](const P &p) { return p.status; })};
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
              number_column<P>({"error_impact_force", "1"},
                               {"error_impact_force_percent", "1"},
                               times(100),
                               [](const P &p) { return p.error_force; }),
              number_column<P>({"error_base_acceleration", "1"},
                               {"error_base_acceleration_percent", "1"},
                               times(100),
                               [](const P &p) { return p.error_acceleration; }),
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
      return {csv_text_column<P>("parameter", [](const P &p) { return p.parameter; }),
              same_column<P>("factor", "1", [](const P &p) { return p.factor; }),
              hdf5_column<P>("ok", "1", [](const P &p) { return flag(p.ok); }),
              same_column<P>("kelvin_voigt",
                             "kN/mm/m",
                             [](const P &p) { return k_display(p.ok, p.k_kelvin_voigt, 1.0); }),
              same_column<P>("jankowski",
                             "kN/mm^1.5/m",
                             [](const P &p) { return k_display(p.ok, p.k_jankowski, 1.5); }),
              csv_text_column<P>("status", [](const P &p) { return p.status; })};
    }

    /// study.h5 /accuracy/fem/<series>.
    void write_fem_accuracy(ResultsGroup &root, const StudyExtras &extras)
    {
      for (const std::string series : {"mesh", "penalty", "implicit"})
      {
        const Table t = study_table(fem_accuracy_columns(),
                                    extras.fem_accuracy,
                                    StudyFile::hdf5,
                                    [&](const FemAccuracyPoint &p) { return p.series == series; });
        if (t.n_rows() > 0)
        {
          ResultsGroup fem = root.group("accuracy").group("fem");
          t.write_hdf5(fem, series);
        }
      }
    }

    /// study.h5 /accuracy/lumped/<method>.
    void write_lumped_accuracy(ResultsGroup &root, const StudyExtras &extras)
    {
      for (const std::string method : {"cdm", "newmark", "cdm_reference"})
      {
        const Table t =
          study_table(lumped_accuracy_columns(),
                      extras.lumped_accuracy,
                      StudyFile::hdf5,
                      [&](const LumpedAccuracyPoint &p) { return p.method == method; });
        if (t.n_rows() > 0)
        {
          ResultsGroup lumped = root.group("accuracy").group("lumped");
          t.write_hdf5(lumped, method);
          lumped.set_attribute("k_total_N_per_m", extras.lumped_k_total);
          lumped.set_attribute("gap_m", extras.lumped_gap);
          lumped.set_attribute("record", extras.lumped_record);
        }
      }
    }

    /// study.h5 /stability/lumped and /stability/fem.
    void write_stability(ResultsGroup &root, const StudyExtras &extras)
    {
      if (!extras.stability.empty())
      {
        ResultsGroup stability = root.group("stability");
        study_table(lumped_stability_columns(), extras.stability, StudyFile::hdf5)
          .write_hdf5(stability, "lumped");
        ResultsGroup table = stability.group("lumped");
        table.set_attribute("effective_mass_kg", extras.stability_effective_mass);
        table.set_attribute("study_stiffness_N_per_m", extras.stability_study_k);
      }
      if (!extras.fem_stability.empty())
      {
        ResultsGroup stability = root.group("stability");
        study_table(fem_stability_columns(), extras.fem_stability, StudyFile::hdf5)
          .write_hdf5(stability, "fem");
        ResultsGroup table = stability.group("fem");
        table.set_attribute("h_contact_m", extras.fem_stability_h_contact);
        table.set_attribute("end_time_s", extras.fem_stability_end_time);
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
    write_fem_accuracy(root, extras);
    write_lumped_accuracy(root, extras);
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
