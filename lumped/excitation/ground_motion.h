// Ground-motion time histories: uniform acceleration samples ü_g(t_i), t_i = i·Δt, and their
// processing (scaling, trimming, resampling, integration) plus a synthetic near-fault record:
// Mavroeidis & Papageorgiou (2003) velocity pulse + enveloped, band-passed stochastic noise.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace kimp::lumped
{
  /// Standard gravity, m/s² (CGPM 1901): kimp's one value of g, for the "g" of PEER records and
  /// of PGA values quoted in g and for weights W = g·m (Q = Q_ratio·W of the isolators); equal
  /// to io::standard_gravity (checked in app/). docs/physics.md §3 "Gravity".
  inline constexpr double standard_gravity = 9.80665;

  /**
   * A ground acceleration record sampled uniformly from t = 0.
   *
   * Sample i is ü_g(i·dt). Between samples the record is piecewise linear (acceleration_at());
   * it is zero before t = 0 and after the last sample.
   */
  struct GroundMotion
  {
    double              dt = 0.0;     ///< sampling interval, s (> 0)
    std::vector<double> acceleration; ///< ü_g at t_i = i·dt, m/s²
    std::string         name;         ///< label for logs and results (e.g. the file stem)

    /// Record length n·dt, s (the PEER convention NPTS × DT).
    double duration() const;

    /// Peak ground acceleration max_i |ü_g(t_i)|, m/s² (0 for an empty record).
    double pga() const;
  };

  /**
   * Check that a record is usable: dt > 0 and finite, at least one sample, all samples finite.
   * @throws std::invalid_argument naming the record, the field, the bad value and the expectation.
   */
  void validate(const GroundMotion &motion);

  /**
   * The record multiplied by `factor` (dimensionless, finite; negative flips the sign).
   * @throws std::invalid_argument for a non-finite factor or an invalid record.
   */
  GroundMotion scaled(const GroundMotion &motion, double factor);

  /**
   * The record scaled so that its PGA equals `target_pga` (m/s², > 0) exactly.
   * @throws std::invalid_argument for target_pga <= 0 or a record whose PGA is 0.
   */
  GroundMotion scaled_to_pga(const GroundMotion &motion, double target_pga);

  /**
   * The first `duration` seconds: the samples t_i = i·dt with i < round(duration/dt), so that the
   * result's duration() is `duration` to within dt/2. A duration at or beyond the record's
   * length returns the whole record.
   * @throws std::invalid_argument for duration < dt/2 or non-finite.
   */
  GroundMotion trimmed(const GroundMotion &motion, double duration);

  /**
   * The record sampled at t_j = j·new_dt by linear interpolation (acceleration_at()), for every
   * t_j within [0, t_last] where t_last = (n−1)·dt is the last original sample, so no sample is
   * invented past the data. Downsampling does not low-pass filter first: peaks above the new
   * Nyquist frequency 1/(2·new_dt) alias or are lost.
   * @throws std::invalid_argument for new_dt <= 0 or non-finite.
   */
  GroundMotion resampled(const GroundMotion &motion, double new_dt);

  /**
   * ü_g(t), m/s²: linear interpolation between samples, 0 for t < 0 and for t > (n−1)·dt.
   * @param[in] t time, s
   */
  double acceleration_at(const GroundMotion &motion, double t);

  /**
   * Ground velocity u̇_g(t_i), m/s, by the trapezoid rule from u̇_g(0) = 0
   * (v_{i+1} = v_i + dt·(a_i + a_{i+1})/2); same length as the record.
   */
  std::vector<double> ground_velocity(const GroundMotion &motion);

  /**
   * Ground displacement u_g(t_i), m: trapezoid rule applied to ground_velocity() from u_g(0) = 0.
   */
  std::vector<double> ground_displacement(const GroundMotion &motion);

  /**
   * Butterworth band-pass filter of order 2·`n_sections` on each side, applied causally
   * (single forward pass) to samples x_i spaced `dt`.
   *
   * Design: a cascade of `n_sections` second-order high-pass sections at `f_low` followed by
   * `n_sections` second-order low-pass sections at `f_high`, each obtained from the analog
   * Butterworth prototype by the bilinear transform with frequency prewarping (so the −3 dB points
   * sit exactly at f_low and f_high). Section k has the quality factor
   * Q_k = 1/(2·cos(π(2k+1)/(4·n_sections))) of the order-2·n_sections Butterworth polynomial.
   * |H(f_low)| = |H(f_high)| = 1/√2 when the two corners are far apart.
   *
   * @param[in] x          input samples
   * @param[in] dt         sampling interval, s (> 0)
   * @param[in] f_low      high-pass corner, Hz (0 < f_low < f_high)
   * @param[in] f_high     low-pass corner, Hz (f_high < 1/(2·dt), the Nyquist frequency)
   * @param[in] n_sections biquads per side (>= 1)
   * @throws std::invalid_argument naming the offending parameter.
   */
  std::vector<double> butterworth_band_pass(const std::vector<double> &x,
                                            double                     dt,
                                            double                     f_low,
                                            double                     f_high,
                                            unsigned int               n_sections = 2);

  /**
   * Parameters of synthetic_near_fault(), SI units. The defaults give a strong forward-directivity
   * record: PGA 0.8 g, pulse period 1 s, 20 s at 0.005 s. With seed 1 the peak ground velocity is
   * 0.95 m/s (1.38 m/s for the pulse alone; 0.95-1.10 m/s over seeds 1-4) and the peak ground
   * displacement 18 cm. A rigid 1530 t mass on the bilinear isolator of docs/physics.md §3 (5 %
   * damping) then peaks at 23.3 cm; the same model gives 19.0 cm for Kobe KJMA (first 48 s), where
   * the thesis' MDOF model gives 16.74 cm, so the reference building reaches a 15 cm moat gap.
   */
  struct SyntheticMotionSpec
  {
    /// Target PGA, m/s² (> 0); met exactly.
    double pga = 0.8 * standard_gravity;
    /// Pulse period T_p = 1/f_p, s (> 0 and >= 4·dt).
    double pulse_period = 1.0;
    /// Record length n·dt, s (>= 10·dt).
    double duration = 20.0;
    /// Sampling interval, s (> 0).
    double dt = 0.005;
    /// t_0, time of the pulse centre, s; the support t_0 ± γ·T_p/2 must lie in [0, (n−1)·dt].
    double pulse_time = 4.0;
    /// γ, oscillatory character of the pulse (> 1; about 2 half-cycles per side at γ = 2).
    double gamma = 2.0;
    /// ν, phase of the pulse, rad (0: symmetric, π/2: antisymmetric).
    double nu = 0.0;
    /// RMS of the noise over [0, T_w] / RMS of the pulse acceleration over its support (>= 0).
    double noise_ratio = 0.2;
    /// High-pass corner of the noise band, Hz (> 0); below it the pulse alone carries energy.
    double noise_f_low = 0.3;
    /// Low-pass corner of the noise band, Hz (> noise_f_low, < 1/(2·dt)).
    double noise_f_high = 12.0;
    /// T_w of the Saragoni-Hart window, s (> 0).
    double envelope_duration = 15.0;
    /// ε of the window, in (0, 1): the window peaks at ε·T_w.
    double envelope_epsilon = 0.2;
    /// η of the window, in (0, 1): its value at t = T_w.
    double envelope_eta = 0.05;
    /// Seed of the std::mt19937 noise generator.
    unsigned int seed = 1;
    /// Name of the resulting GroundMotion.
    std::string name = "synthetic_near_fault";
  };

  /**
   * Check every rule of the SyntheticMotionSpec table.
   * @throws std::invalid_argument "synthetic.<field> = <value> (<expectation>)".
   */
  void validate(const SyntheticMotionSpec &spec);

  /**
   * Mavroeidis & Papageorgiou (2003, BSSA 93(3), 1099-1131, eq. 2) velocity pulse, m/s:
   * v(t) = A/2·[1 + cos(2π f_p (t−t_0)/γ)]·cos(2π f_p (t−t_0) + ν) for |t−t_0| <= γ/(2 f_p),
   * 0 otherwise, with f_p = 1/pulse_period and t_0 = pulse_time. `spec` must pass validate()
   * (not re-checked here: this is evaluated per sample).
   * @param[in] amplitude A, m/s
   */
  double mp_pulse_velocity(const SyntheticMotionSpec &spec, double amplitude, double t);

  /**
   * Its exact time derivative, m/s², inside the support (0 outside), τ = t − t_0:
   * a(t) = −A·π f_p/γ·[sin(2π f_p τ/γ)·cos(2π f_p τ + ν)
   *                    + γ·(1 + cos(2π f_p τ/γ))·sin(2π f_p τ + ν)].
   */
  double mp_pulse_acceleration(const SyntheticMotionSpec &spec, double amplitude, double t);

  /// Closed-form ∫ v(t) dt over the pulse, m (the permanent "fling" displacement; 0 for integer γ):
  /// (A/2)·cos ν·[2 sin(πγ)/ω − sin(πγ)/(ω(1+1/γ)) − sin(πγ)/(ω(1−1/γ))], ω = 2π f_p.
  double mp_pulse_displacement(const SyntheticMotionSpec &spec, double amplitude);

  /**
   * Synthetic near-fault ground acceleration, built in five steps:
   *  1. pulse: mp_pulse_acceleration() with A = 1 m/s, sampled at t_i = i·dt;
   *  2. noise: white Gaussian samples (Box-Muller on the raw std::mt19937 output, so the
   *     sequence is the same with every standard library) times the Saragoni-Hart window of
   *     Boore (2003, PAGEOPH 160, eq. 7) w(t) = a·(t/T_w)^b·exp(−c·t/T_w),
   *     b = −ε ln η/(1 + ε(ln ε − 1)), c = b/ε, a = (e/ε)^b (peak 1 at t = ε·T_w, η at T_w),
   *     then butterworth_band_pass() between noise_f_low and noise_f_high (2 sections per side);
   *  3. the noise is scaled so that its RMS over [0, T_w] is noise_ratio times the RMS of the
   *     pulse acceleration over its support;
   *  4. baseline correction: an acceleration trend α + β·t/T (T = (n−1)·dt) is subtracted so that
   *     the trapezoid-rule velocity at the end is exactly 0 and the end displacement equals the
   *     pulse's closed-form fling (mp_pulse_displacement()); for noise_ratio = 0 the trend only
   *     removes the O(dt²) quadrature error of the sampled pulse;
   *  5. the whole record is scaled so that its PGA equals spec.pga exactly.
   * The pulse amplitude is therefore an output: PGV follows from PGA, T_p, γ, ν and the noise.
   * Same spec (including seed) → bitwise identical record.
   * @throws std::invalid_argument for an invalid spec (see validate()).
   */
  GroundMotion synthetic_near_fault(const SyntheticMotionSpec &spec);
} // namespace kimp::lumped
