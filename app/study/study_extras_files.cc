// Writers of the extra studies of `kimp study`: study.h5 /accuracy, /stability, /sensitivity and
// accuracy_fem.csv, accuracy_lumped.csv, stability_lumped.csv, stability_fem.csv, sensitivity.csv.
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "app/study/study_extras.h"
#include "app/study/study_internal.h"
#include "fit/fitter.h"
#include "io/table.h"

namespace kimp::app
{
  using namespace study_internal;

  namespace
  {
    /// study.h5 /accuracy/fem/<series>: k against the contact mesh, the penalty and the implicit
    /// solver.
    void write_fem_accuracy(ResultsGroup &root, const StudyExtras &extras)
    {
      for (const char *series : {"mesh", "penalty", "implicit"})
      {
        Table t;
        t.number("h_contact", "m")
          .number("penalty_factor", "1")
          .number("ok", "1")
          .number("seconds", "s")
          .number("n_dofs", "1")
          .number("n_steps", "1")
          .number("kelvin_voigt", "kN/mm/m")
          .number("jankowski", "kN/mm^1.5/m")
          .number("error_kelvin_voigt", "1")
          .number("error_jankowski", "1");
        for (const FemAccuracyPoint &p : extras.fem_accuracy)
          if (p.series == series)
            t.add_row(number_cells({p.h_contact,
                                    p.penalty_factor,
                                    flag(p.ok),
                                    p.seconds,
                                    p.n_dofs,
                                    p.n_steps,
                                    p.ok ? stiffness_to_kn_per_mm(p.k_kelvin_voigt, 1.0) : nan,
                                    p.ok ? stiffness_to_kn_per_mm(p.k_jankowski, 1.5) : nan,
                                    p.error_kelvin_voigt,
                                    p.error_jankowski}));
        if (t.n_rows() > 0)
        {
          ResultsGroup fem = root.group("accuracy").group("fem");
          t.write_hdf5(fem, series);
        }
      }
    }

    /// study.h5 /accuracy/lumped/<method>: peaks of one building run against the time step.
    void write_lumped_accuracy(ResultsGroup &root, const StudyExtras &extras)
    {
      for (const char *method : {"cdm", "newmark", "cdm_reference"})
      {
        Table t;
        t.number("dt", "s")
          .number("ok", "1")
          .number("seconds", "s")
          .number("impact_force", "N")
          .number("base_acceleration", "m/s^2")
          .number("error_impact_force", "1")
          .number("error_base_acceleration", "1");
        for (const LumpedAccuracyPoint &p : extras.lumped_accuracy)
          if (p.method == method)
            t.add_row(number_cells({p.dt,
                                    flag(p.ok),
                                    p.seconds,
                                    p.ok ? p.peak_impact_force : nan,
                                    p.ok ? p.base_acceleration : nan,
                                    p.error_force,
                                    p.error_acceleration}));
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

    /// study.h5 /stability/lumped: the explicit lumped time step against k.
    void write_lumped_stability(ResultsGroup &root, const StudyExtras &extras)
    {
      if (extras.stability.empty())
        return;
      Table t;
      t.number("stiffness", "N/m")
        .number("dt", "s")
        .number("dt_limit", "s")
        .number("dt_limit_damped", "s")
        .number("stable", "1")
        .number("accurate", "1")
        .number("effective_cor", "1")
        .number("peak_force", "N");
      for (const StabilityPoint &p : extras.stability)
        t.add_row(number_cells({p.stiffness,
                                p.dt,
                                p.dt_limit,
                                p.dt_limit_damped,
                                flag(p.stable),
                                flag(p.accurate),
                                p.effective_cor,
                                p.peak_force}));
      ResultsGroup stability = root.group("stability");
      t.write_hdf5(stability, "lumped");
      ResultsGroup table = stability.group("lumped");
      table.set_attribute("effective_mass_kg", extras.stability_effective_mass);
      table.set_attribute("study_stiffness_N_per_m", extras.stability_study_k);
    }

    /// study.h5 /stability/fem: the explicit FEM time step against the penalty.
    void write_fem_stability(ResultsGroup &root, const StudyExtras &extras)
    {
      if (extras.fem_stability.empty())
        return;
      Table t;
      t.number("penalty_factor", "1")
        .number("dt_factor", "1")
        .number("dt", "s")
        .number("dt_limit", "s")
        .number("stable", "1")
        .number("energy_error", "1");
      for (const FemStabilityPoint &p : extras.fem_stability)
        t.add_row(number_cells({p.penalty_factor,
                                p.dt_factor,
                                p.dt,
                                p.dt_limit,
                                flag(p.stable),
                                p.energy_error > 0 ? p.energy_error : nan}));
      ResultsGroup stability = root.group("stability");
      t.write_hdf5(stability, "fem");
      ResultsGroup table = stability.group("fem");
      table.set_attribute("h_contact_m", extras.fem_stability_h_contact);
      table.set_attribute("end_time_s", extras.fem_stability_end_time);
    }

    /// study.h5 /sensitivity/<parameter>: k against one scene parameter.
    void write_sensitivity(ResultsGroup &root, const StudyExtras &extras)
    {
      if (extras.sensitivity.empty())
        return;
      for (const char *parameter :
           {"base", "soil_modulus", "slab_mass", "impact_velocity", "wall_thickness"})
      {
        Table t;
        t.number("factor", "1")
          .number("ok", "1")
          .number("kelvin_voigt", "kN/mm/m")
          .number("jankowski", "kN/mm^1.5/m");
        for (const SensitivityPoint &p : extras.sensitivity)
          if (p.parameter == parameter)
            t.add_row(number_cells({p.factor,
                                    flag(p.ok),
                                    p.ok ? stiffness_to_kn_per_mm(p.k_kelvin_voigt, 1.0) : nan,
                                    p.ok ? stiffness_to_kn_per_mm(p.k_jankowski, 1.5) : nan}));
        ResultsGroup sensitivity = root.group("sensitivity");
        t.write_hdf5(sensitivity, parameter);
      }
    }
  } // namespace

  void write_study_extras(ResultsGroup &root, const StudyExtras &extras)
  {
    write_fem_accuracy(root, extras);
    write_lumped_accuracy(root, extras);
    write_lumped_stability(root, extras);
    write_fem_stability(root, extras);
    write_sensitivity(root, extras);
  }

  void write_study_extras_csv(const OutputDir &output, const StudyExtras &extras)
  {
    if (!extras.fem_accuracy.empty())
    {
      std::vector<std::vector<std::string>> rows;
      for (const FemAccuracyPoint &p : extras.fem_accuracy)
        rows.push_back({p.series,
                        number(p.h_contact * 100),
                        number(p.penalty_factor),
                        number(p.seconds),
                        number(p.n_dofs),
                        number(p.ok ? stiffness_to_kn_per_mm(p.k_kelvin_voigt, 1.0) : nan),
                        number(p.ok ? stiffness_to_kn_per_mm(p.k_jankowski, 1.5) : nan),
                        number(p.error_kelvin_voigt * 100),
                        number(p.error_jankowski * 100),
                        p.status});
      write_csv_atomic(output.file("accuracy_fem.csv"),
                       {"series",
                        "h_contact_cm",
                        "penalty_factor",
                        "fem_wall_time_s",
                        "n_dofs",
                        "kelvin_voigt_kN_per_mm_per_m",
                        "jankowski_kN_per_mm1.5_per_m",
                        "error_kelvin_voigt_percent",
                        "error_jankowski_percent",
                        "status"},
                       rows);
    }
    if (!extras.lumped_accuracy.empty())
    {
      std::vector<std::vector<std::string>> rows;
      for (const LumpedAccuracyPoint &p : extras.lumped_accuracy)
        rows.push_back({p.method,
                        number(p.dt),
                        number(p.seconds),
                        number(p.ok ? p.peak_impact_force / 1e3 : nan),
                        number(p.ok ? p.base_acceleration : nan),
                        number(p.error_force * 100),
                        number(p.error_acceleration * 100),
                        p.status});
      write_csv_atomic(output.file("accuracy_lumped.csv"),
                       {"method",
                        "dt_s",
                        "wall_time_s",
                        "peak_impact_force_kN",
                        "peak_base_acceleration_m_per_s2",
                        "error_impact_force_percent",
                        "error_base_acceleration_percent",
                        "status"},
                       rows);
    }
    if (!extras.stability.empty())
    {
      std::vector<std::vector<double>> rows;
      for (const StabilityPoint &p : extras.stability)
        rows.push_back({stiffness_to_kn_per_mm(p.stiffness, 1.0),
                        p.dt,
                        p.dt_limit,
                        p.dt_limit_damped,
                        p.stable ? 1.0 : 0.0,
                        p.accurate ? 1.0 : 0.0,
                        p.effective_cor});
      write_csv_atomic(output.file("stability_lumped.csv"),
                       {"k_imp_kN_per_mm",
                        "dt_s",
                        "dt_limit_2_over_omega_s",
                        "dt_limit_damped_s",
                        "stable",
                        "accurate",
                        "effective_cor"},
                       rows);
    }
    if (!extras.fem_stability.empty())
    {
      std::vector<std::vector<std::string>> rows;
      for (const FemStabilityPoint &p : extras.fem_stability)
        rows.push_back({number(p.penalty_factor),
                        number(p.dt_factor),
                        number(p.dt),
                        number(p.dt_limit),
                        p.stable ? "1" : "0",
                        number(p.energy_error > 0 ? p.energy_error : nan),
                        p.status});
      write_csv_atomic(output.file("stability_fem.csv"),
                       {"penalty_factor",
                        "dt_over_limit",
                        "dt_s",
                        "dt_limit_s",
                        "stable",
                        "max_energy_error",
                        "status"},
                       rows);
    }
    if (!extras.sensitivity.empty())
    {
      std::vector<std::vector<std::string>> rows;
      for (const SensitivityPoint &p : extras.sensitivity)
        rows.push_back({p.parameter,
                        number(p.factor),
                        number(p.ok ? stiffness_to_kn_per_mm(p.k_kelvin_voigt, 1.0) : nan),
                        number(p.ok ? stiffness_to_kn_per_mm(p.k_jankowski, 1.5) : nan),
                        p.status});
      write_csv_atomic(output.file("sensitivity.csv"),
                       {"parameter",
                        "factor",
                        "kelvin_voigt_kN_per_mm_per_m",
                        "jankowski_kN_per_mm1.5_per_m",
                        "status"},
                       rows);
    }
  }
} // namespace kimp::app
