// Extra charts of `kimp study`: accuracy against cost of the FEM levels (error in k vs
// seconds) and of the building's time step (thesis Figs 3.3-3.4), the central-difference stability
// map Δt vs k_imp with 2/ω_imp (thesis eq. 3.12-3.13), and the sensitivity of k to the scene.
#pragma once

#include <string>
#include <vector>

#include "app/study/study_scene.h"
#include "io/results_file.h"
#include "io/summary.h"

namespace kimp::app
{
  /** One FEM run of the accuracy study; k per metre, SI. */
  struct FemAccuracyPoint
  {
    std::string series;               ///< "mesh", "penalty" or "implicit"
    double      h_contact      = 0.0; ///< m
    double      penalty_factor = 1.0;
    bool        ok             = false;
    std::string status         = "ok";
    double      seconds    = 0.0; ///< wall time of the FEM run (as computed, not the cache read)
    bool        from_cache = false;
    double      n_dofs = 0.0, n_steps = 0.0;
    /// Per study law (study_laws() order; empty unless ok): k, N/m^n per metre, and its error
    /// |k/k_ref − 1| against the reference level (NaN: not usable).
    std::vector<double> k, error;
  };

  /** One building run of the time-step study. */
  struct LumpedAccuracyPoint
  {
    std::string method;                  ///< "cdm" or "newmark"
    double      dt                = 0.0; ///< s
    bool        ok                = false;
    std::string status            = "ok";
    double      seconds           = 0.0;
    double      peak_impact_force = 0.0, base_acceleration = 0.0; ///< N, m/s²
    double      error_force = 0.0, error_acceleration = 0.0;      ///< relative to the reference
  };

  /** One two-body collision of the stability map. */
  struct StabilityPoint
  {
    double stiffness       = 0.0;   ///< k_imp, N/m
    double dt              = 0.0;   ///< s
    double dt_limit        = 0.0;   ///< 2/ω_imp, ω_imp = sqrt(k/m_eff), s
    double dt_limit_damped = 0.0;   ///< 2(sqrt(1 + ξ²) − ξ)/ω_imp (Kelvin-Voigt dashpot), s
    bool   stable          = false; ///< finite, energy gain < 0.1 % (effective COR <= 1.001)
    bool   accurate        = false; ///< stable and effective COR within 5 % of the nominal
    double effective_cor   = 0.0;   ///< separation/approach speed (NaN if it diverged)
    double peak_force      = 0.0;   ///< N
  };

  /** One explicit FEM run of the FEM stability map (Δt against the contact penalty). */
  struct FemStabilityPoint
  {
    double      penalty_factor = 0.0;   ///< contact penalty / its default (E/h)
    double      dt_factor      = 0.0;   ///< Δt / the computed stable limit
    double      dt             = 0.0;   ///< s
    double      dt_limit       = 0.0;   ///< the FEM's computed limit 2(sqrt(1+ξ²)−ξ)/ω, s
    bool        stable         = false; ///< ran to the end, energy error within tolerance
    double      energy_error   = 0.0;   ///< max |energy error| of a run that ran to the end
    std::string status         = "ok";
  };

  /** One FEM run of the sensitivity study. */
  struct SensitivityPoint
  {
    std::string parameter;    ///< "soil_modulus", "slab_mass", "impact_velocity", "wall_thickness"
    double      factor = 1.0; ///< parameter / its scene value
    bool        ok     = false;
    std::string status = "ok";
    std::vector<double> k; ///< per study law (study_laws() order; empty unless ok), N/m^n per m
  };

  struct StudyExtras
  {
    std::vector<FemAccuracyPoint>    fem_accuracy;
    double                           lumped_k_total = 0.0; ///< k of the time-step study, N/m
    double                           lumped_gap     = 0.0; ///< m
    std::string                      lumped_record;
    std::vector<LumpedAccuracyPoint> lumped_accuracy;
    double                           stability_effective_mass = 0.0; ///< kg
    double                           stability_study_k        = 0.0; ///< N/m, study's k_KV·W
    std::vector<StabilityPoint>      stability;
    double                           fem_stability_h_contact = 0.0; ///< m
    double                           fem_stability_end_time  = 0.0; ///< s
    std::vector<FemStabilityPoint>   fem_stability;
    std::vector<SensitivityPoint>    sensitivity;
    double                           seconds = 0.0;
  };

  /**
   * FEM accuracy against cost at scene.accuracy.wall_height: explicit mesh levels (reference: the
   * finest), penalty levels, implicit Newmark (if asked). Runs go through the study's FEM cache
   * (files "H1.25_h2.5cm_p1" as the fidelity ladder's, so levels already climbed are reused;
   * their `seconds` are those of the original run). A failing run is a point with its status.
   */
  std::vector<FemAccuracyPoint> run_fem_accuracy(const StudyScene    &scene,
                                                 const io::OutputDir &output);

  /**
   * The study's building with walls at `gap` shaken by `record`, modified Kelvin-Voigt with
   * `k_total` (N/m) at scene.fit.cor: central difference at every scene.accuracy.lumped_dt and at
   * lumped_reference_dt (the reference), Newmark at every lumped_dt; errors of the peak impact
   * force and of the peak base absolute acceleration against the reference.
   */
  std::vector<LumpedAccuracyPoint> run_lumped_accuracy(const StudyScene        &scene,
                                                       const GroundMotionScene &record,
                                                       double                   k_total,
                                                       double                   gap);

  /**
   * Stability map of the central difference method for a contact: two-body collisions (the
   * isolation-level mass against the wall mass, both free, so ω_imp = sqrt(k/m_eff) exactly) with
   * modified Kelvin-Voigt at `cor`, over k = k_study·{0.01 ... 100} and Δt = 1e-4 ... 0.3 s
   * (29 steps per k), without any stability guard.
   */
  std::vector<StabilityPoint>
  lumped_stability_map(double mass_1, double mass_2, double cor, double k_study);

  /// Penalty factors, Δt / limit and simulated time of fem_stability_map().
  inline constexpr double fem_stability_penalty_factors[] = {0.3, 1.0, 3.0, 10.0, 30.0};
  inline constexpr double fem_stability_dt_factors[]      = {0.5, 0.9, 1.1, 1.5, 2.0};
  inline constexpr double fem_stability_end_time          = 3e-3; ///< s
  /// A run whose energy balance drifts by more than this is counted unstable (stable runs
  /// stay below 1e-3; growing modes reach it within the simulated time).
  inline constexpr double fem_stability_energy_tolerance = 1e-2;

  /**
   * Stability map of the explicit FEM: the impact at scene.accuracy.wall_height on the coarsest
   * accuracy mesh level, for every penalty factor of fem_stability_penalty_factors and Δt =
   * fem_stability_dt_factors × the computed limit (fem::ExplicitOptions::dt_over_limit, no
   * refusal), over the first fem_stability_end_time of the contact. A run is unstable when the
   * FEM's divergence guard (energy error > 50 % or not finite) stops it or when its energy error
   * exceeds fem_stability_energy_tolerance. Runs on MPI_COMM_SELF.
   */
  std::vector<FemStabilityPoint>
  fem_stability_map(const StudyScene &scene, const io::OutputDir &output, double &h_contact);

  /**
   * k at scene.sensitivity_study.wall_height with each of soil modulus, slab mass (slab length),
   * impact velocity and wall thickness at (1 ∓ variation) times its value, and the base case, on
   * the scene's fixed mesh level (fem.mesh, fem.contact).
   */
  std::vector<SensitivityPoint> run_sensitivity(const StudyScene    &scene,
                                                const io::OutputDir &output);

  /** HDF5 /accuracy/fem/<series>, /accuracy/lumped/<method>, /stability/{lumped,fem},
   *  /sensitivity. */
  void write_study_extras(io::ResultsGroup &root, const StudyExtras &extras);

  /** accuracy_fem.csv, accuracy_lumped.csv, stability_lumped.csv, stability_fem.csv,
   *  sensitivity.csv (if any). */
  void write_study_extras_csv(const io::OutputDir &output, const StudyExtras &extras);
} // namespace kimp::app
