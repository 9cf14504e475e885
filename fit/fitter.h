// Impact-stiffness fitter (docs/physics.md §4 "Fit"): a mass m striking a wall at v_imp
// through a lumped contact law (law 2, 4, or a free-exponent Hertz law) is fitted to an FEM
// contact-force history, min Σ w_i (F_law(t_i) − F_FEM(t_i))², by Levenberg-Marquardt (Eigen).
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lumped/collision/two_body.h"
#include "lumped/laws/force_law_factory.h"

namespace kimp::fit
{
  /// A history that cannot be fitted (empty, non-finite, no contact) or a failed optimisation.
  class FitError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// Building width of the thesis' Table 2.2 (m): k_total = k_per_metre · W.
  inline constexpr double thesis_building_width = 27.78;

  /**
   * The measured impact, SI, per metre of wall. `time` is increasing; the other non-empty
   * vectors have its length.
   */
  struct ForceHistory
  {
    std::vector<double> time;  ///< s
    std::vector<double> force; ///< contact force, N/m (compressive positive)
    /// Optional: slab front − wall face − gap, m. When given, first contact is its zero
    /// crossing and the contact lasts while it is > 0; otherwise the force decides.
    std::vector<double> indentation;
    /// Optional: slab displacement, m; used for the displacement misfit. The lumped δ includes
    /// the wall's whole compliance, so it is compared with the slab's advance since first contact,
    /// not with the FEM's local penetration.
    std::vector<double> slab_displacement;
  };

  /// Options of fit_impact_law(); the law itself (name, fixed or starting COR and exponent) is
  /// the lumped::ForceLawSpec argument.
  struct FitOptions
  {
    bool fit_cor = false; ///< fit the nominal COR too (start: the FEM impulse's COR)
    /// Fit the exponent n too (laws "hertzdamp", "hysteretic"; n = 1 + e^x keeps n > 1).
    bool   fit_exponent        = false;
    double displacement_weight = 0.0; ///< weight of the displacement misfit (>= 0)
    /// Mass of the wall (kg/m) moving freely with the slab; infinity: a fixed rigid wall.
    double wall_mass = std::numeric_limits<double>::infinity();
    /// Model time step = T_c/steps_per_time_scale, T_c = δ_c/v_imp the law's own time scale
    /// (δ_c: undamped maximum indentation), so the discrete model is self-similar in k.
    std::size_t              steps_per_time_scale = 5000;
    lumped::VelocityEstimate velocity_estimate    = lumped::VelocityEstimate::second_order;
    double contact_threshold = 1.0e-3; ///< force-only detection: F > threshold·F_peak, (0, 1)
    /// A contact phase ends at a non-contact run longer than this fraction of its duration so far.
    double separation_fraction = 0.25;
    /// Samples after the FEM separation included in the misfit, as a fraction of the contact
    /// duration (the model may last longer), limited by the record and the next contact.
    double                tail_fraction = 0.5;
    double                confidence    = 0.95; ///< level of the confidence intervals, (0, 1)
    std::optional<double> initial_stiffness;    ///< start value of k (N/m^n per m); else estimated
    double                tolerance                = 1.0e-10; ///< LM ftol and xtol
    std::size_t           max_function_evaluations = 4000;    ///< LM maxfev
  };

  /// A fitted (or fixed) parameter with its confidence interval.
  struct FitParameter
  {
    double value  = 0.0;
    double lower  = 0.0; ///< confidence interval (= value when not fitted)
    double upper  = 0.0;
    bool   fitted = false;
  };

  /// Outcome of fit_impact_law(); k is per metre of wall.
  struct FitResult
  {
    std::string  law;       ///< lumped law name
    FitParameter stiffness; ///< k, N/m^n per metre of wall
    FitParameter cor;       ///< nominal COR of the law
    FitParameter exponent;  ///< n

    double normalised_rms = 0.0; ///< time-RMS of F_law − F_FEM over the window / FEM peak
    double normalised_displacement_rms = 0.0; ///< same for the displacement / its peak (if used)
    int    iterations                  = 0;
    int    function_evaluations        = 0; ///< model simulations, Jacobians included
    int    status_code                 = 0; ///< Eigen LevenbergMarquardtSpace::Status
    std::string status;                     ///< status_code as text

    double fem_peak_force       = 0.0; ///< N/m
    double fem_contact_duration = 0.0; ///< s, the misfit window's contact phase
    /// s, first to last sample whose force exceeds contact_threshold·peak, over the whole record
    /// (bounces included): what the contact phase should span (fit_verdict()).
    double contact_extent = 0.0;
    double fem_impulse    = 0.0; ///< N·s/m over the contact phase
    /// The FEM contact phase lasts to the record's last sample: the fit saw a truncated contact.
    bool   contact_open_at_end    = false;
    double contact_start          = 0.0; ///< first contact in FEM time, s
    double model_peak_force       = 0.0; ///< N/m
    double model_contact_duration = 0.0; ///< s
    double model_impulse          = 0.0; ///< N·s/m, ∫F dt of the model's contact
    double model_effective_cor    = 0.0; ///< separation/approach velocity ratio of the model

    /// Misfit window (FEM time) with the FEM and fitted-law forces, for plots.
    std::vector<double> time;
    std::vector<double> fem_force;
    std::vector<double> model_force;

    /// How the fitted law reproduces the FEM impact (1: exactly): fitted / FEM peak force,
    /// impulse (∫F dt over the contact) and contact duration. NaN without an FEM value.
    double peak_force_ratio() const;
    double impulse_ratio() const;
    double contact_duration_ratio() const;

    /// k in kN/mm^n per metre of wall (the thesis' Table 2.1 unit).
    double stiffness_per_metre_display() const;
    /// k·W in kN/mm^n (Table 2.2) for a building side of width W (m).
    double total_stiffness_display(double width = thesis_building_width) const;
    /// "kN/mm/m", "kN/mm^1.5/m", ...
    std::string per_metre_unit() const;
  };

  /// SI stiffness (N/m^n, or N/m^n per metre) in kN/mm^n (per metre): k·1e-3^(n+1).
  double stiffness_to_kn_per_mm(double stiffness, double exponent);
  /// The one formatter of stiffness units: "kN/mm" for n = 1, "kN/mm^1.5" otherwise (n to 6
  /// significant digits); "kN/mm/m", "kN/mm^1.5/m" per metre of wall.
  std::string stiffness_display_unit(double exponent, bool per_metre_of_wall = false);
  /// The SI unit of a stiffness: "N/m" for n = 1, "N/m^1.5" otherwise (n to 6 significant
  /// digits); "N/m/m", "N/m^1.5/m" per metre of wall.
  std::string stiffness_si_unit(double exponent, bool per_metre_of_wall = false);

  /**
   * Fit `law` to `history`: simulate mass `mass` hitting the wall at `impact_velocity` with
   * lumped::simulate_two_body, align both at first contact, interpolate the model force onto
   * the FEM samples of the contact window (model force 0 after its separation) and minimise the
   * time-weighted squared misfit by Levenberg-Marquardt over ln k (and logit COR, ln(n − 1)).
   * The confidence intervals come from cov = s²(JᵀJ)⁻¹ at the optimum (s² = Σr²/(N − p)),
   * mapped through the parameter transforms; they assume independent errors, so for FEM data
   * they measure the law's misfit, not the FEM's discretisation error (see level_uncertainty).
   * @param[in] law              law name ("kelvin_voigt", "jankowski", "hertzdamp",
   *                             "hysteretic"), fixed or starting cor and exponent; stiffness and
   *                             effective_mass are ignored (k is fitted, m_eff from the masses)
   * @param[in] mass             slab mass, kg per metre of wall (> 0)
   * @param[in] impact_velocity  v_imp, m/s (> 0)
   * @throws FitError for an unusable history (empty, mismatched lengths, non-finite values,
   *         no contact, too few samples) or an optimisation that fails or ends non-finite;
   *         std::invalid_argument for bad options, mass, velocity or law.
   */
  FitResult fit_impact_law(const ForceHistory         &history,
                           double                      mass,
                           double                      impact_velocity,
                           const lumped::ForceLawSpec &law,
                           const FitOptions           &options = {});

  /// A named fit configuration (one column of the k table).
  struct FitVariant
  {
    std::string          name; ///< e.g. "kelvin_voigt_cor_fixed"
    lumped::ForceLawSpec law;
    FitOptions           options;
  };

  /**
   * The study's fits: Kelvin-Voigt and Jankowski with COR fixed at `cor` (the thesis' choice)
   * and with COR free, and a free-exponent Hertz fit (hysteretic law 6, k and n, COR fixed).
   * @param[in] base options shared by all variants (fit_cor, fit_exponent are overridden)
   */
  std::vector<FitVariant> standard_fit_variants(const FitOptions &base = {},
                                                double            cor  = lumped::thesis_cor);

  /// Estimate of the numerical error of a quantity computed on a sequence of refined levels.
  struct LevelEstimate
  {
    double finest          = 0.0; ///< value on the finest level
    double previous        = 0.0; ///< value on the level before
    double relative_change = 0.0; ///< |finest − previous|/|finest|
    double extrapolated    = 0.0; ///< Richardson: finest + (finest − previous)/(r^p − 1)
    double error_estimate  = 0.0; ///< |extrapolated − finest|
    double relative_error  = 0.0; ///< error_estimate/|finest|
    /// Observed order from the three finest levels (NaN if fewer levels or not monotone).
    double observed_order = std::numeric_limits<double>::quiet_NaN();
    double order_used     = 0.0; ///< p in the extrapolation
  };

  /**
   * Richardson-style error of the finest of `values` (ordered coarse to fine, refinement ratio
   * r between levels). With three or more levels converging monotonically the observed order
   * p = ln((f₃ − f₂)/(f₂ − f₁))/ln r is used when it lies in [0.5, 4]; otherwise
   * `assumed_order`. Penalty levels converge like 1/penalty (p = 1), mesh levels like h^p.
   * @throws std::invalid_argument for fewer than two values, non-finite values, r <= 1 or
   *         assumed_order <= 0.
   */
  LevelEstimate level_uncertainty(const std::vector<double> &values,
                                  double                     refinement_ratio = 2.0,
                                  double                     assumed_order    = 1.0);
} // namespace kimp::fit
