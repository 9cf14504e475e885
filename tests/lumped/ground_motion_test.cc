// Ground-motion numerics: processing identities, interpolation bound, trapezoid integration,
// Butterworth magnitude, and the synthetic near-fault record (seeded, exact PGA, zero end
// velocity, closed-form Mavroeidis-Papageorgiou pulse).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lumped/excitation/ground_motion.h"
#include "tests/support/messages.h"

namespace
{
  using kimp::lumped::GroundMotion;
  using kimp::lumped::standard_gravity;
  using kimp::lumped::SyntheticMotionSpec;

  constexpr double pi = 3.14159265358979323846;

  /// "Exact" in the sense of a few roundings.
  constexpr double round_off_rel = 1e-12;
  /// Target PGA is pinned, not just approached.
  constexpr double pga_rel_tolerance = 1e-12;
  /// End velocity / PGV after the baseline correction (trapezoid rule, exact up to round-off).
  constexpr double end_velocity_rel = 1e-10;
  /// Pulse-only record vs the closed-form MP velocity, relative to PGV (trapezoid error
  /// (ω·dt)²/12 ≈ 1e-4 at dt = 0.005 s, T_p = 1 s).
  constexpr double pulse_velocity_rel = 5e-4;
  /// Steady-state filter gain measured on 40+ cycles vs the exact digital Butterworth magnitude.
  constexpr double filter_gain_tolerance = 2e-4;

  double peak_abs(const std::vector<double> &x)
  {
    double peak = 0.0;
    for (const double v : x)
      peak = std::max(peak, std::abs(v));
    return peak;
  }

  GroundMotion sine_record(double dt, double duration, double frequency, double amplitude)
  {
    GroundMotion motion;
    motion.dt    = dt;
    motion.name  = "sine";
    const auto n = static_cast<std::size_t>(std::llround(duration / dt));
    for (std::size_t i = 0; i < n; ++i)
      motion.acceleration.push_back(amplitude *
                                    std::sin(2.0 * pi * frequency * static_cast<double>(i) * dt));
    return motion;
  }

  GroundMotion random_record(unsigned int seed, std::size_t n, double dt)
  {
    std::mt19937                           engine(seed);
    std::uniform_real_distribution<double> uniform(-3.0, 3.0);
    GroundMotion                           motion;
    motion.dt   = dt;
    motion.name = "random";
    for (std::size_t i = 0; i < n; ++i)
      motion.acceleration.push_back(uniform(engine));
    return motion;
  }

  template <class Function>
  std::string invalid_argument_message(Function &&function)
  {
    return kimp::testing::thrown_message<std::invalid_argument>(std::forward<Function>(function));
  }

  /// Steady-state amplitude of y (least-squares fit of a·sin + b·cos at frequency f) over the
  /// samples from i0 on.
  double fitted_amplitude(const std::vector<double> &y, double dt, double f, std::size_t i0)
  {
    double ss = 0, cc = 0, sc = 0, ys = 0, yc = 0;
    for (std::size_t i = i0; i < y.size(); ++i)
    {
      const double s = std::sin(2.0 * pi * f * static_cast<double>(i) * dt);
      const double c = std::cos(2.0 * pi * f * static_cast<double>(i) * dt);
      ss += s * s;
      cc += c * c;
      sc += s * c;
      ys += y[i] * s;
      yc += y[i] * c;
    }
    const double det = ss * cc - sc * sc;
    const double a   = (ys * cc - yc * sc) / det;
    const double b   = (yc * ss - ys * sc) / det;
    return std::hypot(a, b);
  }
} // namespace

TEST(GroundMotionBasics, DurationAndPgaFollowTheSamples)
{
  GroundMotion motion{0.02, {0.1, -0.7, 0.3}, "three"};
  EXPECT_DOUBLE_EQ(motion.duration(), 0.06);
  EXPECT_DOUBLE_EQ(motion.pga(), 0.7);
}

TEST(GroundMotionBasics, ScalingMultipliesEverySampleAndHitsTargetPga)
{
  const GroundMotion motion = random_record(11, 500, 0.01);
  for (const double factor : {-2.5, 0.0, 1e-3, 7.0})
  {
    const GroundMotion result = kimp::lumped::scaled(motion, factor);
    ASSERT_EQ(result.acceleration.size(), motion.acceleration.size());
    for (std::size_t i = 0; i < motion.acceleration.size(); ++i)
      ASSERT_EQ(result.acceleration[i], factor * motion.acceleration[i])
        << "factor " << factor << " sample " << i;
  }
  for (const double target : {0.313 * standard_gravity, 1.0 * standard_gravity, 1e-3, 123.456})
  {
    const GroundMotion result = kimp::lumped::scaled_to_pga(motion, target);
    EXPECT_NEAR(result.pga(), target, pga_rel_tolerance * target) << "target " << target;
    // Shape preserved: the ratio of any two samples is unchanged.
    EXPECT_NEAR(result.acceleration[3] / result.acceleration[7],
                motion.acceleration[3] / motion.acceleration[7],
                round_off_rel * std::abs(motion.acceleration[3] / motion.acceleration[7]));
  }
}

TEST(GroundMotionBasics, ScalingRejectsBadInput)
{
  const GroundMotion motion{0.01, {0.0, 0.0}, "zeros"};
  auto               msg =
    invalid_argument_message([&] { kimp::lumped::scaled_to_pga(motion, standard_gravity); });
  EXPECT_NE(msg.find("'zeros': PGA = 0"), std::string::npos) << msg;
  const GroundMotion ok{0.01, {1.0, -2.0}, "ok"};
  msg = invalid_argument_message([&] { kimp::lumped::scaled_to_pga(ok, -1.0); });
  EXPECT_NE(msg.find("target PGA = -1 m/s^2 (must be finite and > 0)"), std::string::npos) << msg;
  msg = invalid_argument_message([&] { kimp::lumped::scaled(ok, std::nan("")); });
  EXPECT_NE(msg.find("scale factor = nan"), std::string::npos) << msg;
  msg = invalid_argument_message([&] { kimp::lumped::scaled(GroundMotion{0.0, {1.0}, "r"}, 2.0); });
  EXPECT_NE(msg.find("'r': dt = 0 s (must be finite and > 0)"), std::string::npos) << msg;
  msg = invalid_argument_message(
    [&] {
      kimp::lumped::scaled(GroundMotion{0.01, {1.0, INFINITY}, "r"}, 2.0);
    });
  EXPECT_NE(msg.find("acceleration[1] = inf"), std::string::npos) << msg;
  msg = invalid_argument_message([&] { kimp::lumped::scaled(GroundMotion{0.01, {}, "e"}, 2.0); });
  EXPECT_NE(msg.find("'e': no acceleration samples"), std::string::npos) << msg;
}

TEST(GroundMotionBasics, TrimmingKeepsTheFirstSamples)
{
  // Kobe KJMA is 7500 × 0.02 s; the thesis used its first 48 s = 2400 samples.
  const GroundMotion motion  = random_record(5, 7500, 0.02);
  const GroundMotion trimmed = kimp::lumped::trimmed(motion, 48.0);
  ASSERT_EQ(trimmed.acceleration.size(), 2400u);
  EXPECT_DOUBLE_EQ(trimmed.duration(), 48.0);
  EXPECT_TRUE(std::equal(trimmed.acceleration.begin(),
                         trimmed.acceleration.end(),
                         motion.acceleration.begin()));
  EXPECT_EQ(trimmed.dt, motion.dt);
  EXPECT_EQ(kimp::lumped::trimmed(motion, 1e6).acceleration, motion.acceleration);
  const auto msg = invalid_argument_message([&] { kimp::lumped::trimmed(motion, 0.005); });
  EXPECT_NE(msg.find("trim duration = 0.005 s (must be finite and >= dt/2 = 0.01 s)"),
            std::string::npos)
    << msg;
}

TEST(GroundMotionBasics, AccelerationAtInterpolatesLinearlyAndIsZeroOutside)
{
  const GroundMotion motion{0.1, {1.0, 3.0, -1.0}, "tri"};
  EXPECT_EQ(kimp::lumped::acceleration_at(motion, -0.01), 0.0);
  EXPECT_EQ(kimp::lumped::acceleration_at(motion, 0.0), 1.0);
  EXPECT_NEAR(kimp::lumped::acceleration_at(motion, 0.05), 2.0, round_off_rel);
  EXPECT_NEAR(kimp::lumped::acceleration_at(motion, 0.175), 0.0, round_off_rel);
  EXPECT_EQ(kimp::lumped::acceleration_at(motion, 0.2), -1.0);
  EXPECT_EQ(kimp::lumped::acceleration_at(motion, 0.2000001), 0.0);
  EXPECT_EQ(kimp::lumped::acceleration_at(motion, 5.0), 0.0);
}

TEST(GroundMotionBasics, ResamplingASineStaysWithinTheInterpolationBound)
{
  // Linear interpolation error <= h²/8·max|a''| = (ω·dt)²/8·A between samples of A·sin(ωt).
  const double       frequency = 2.0, amplitude = 3.0, dt = 0.01;
  const GroundMotion sine  = sine_record(dt, 10.0, frequency, amplitude);
  const double       omega = 2.0 * pi * frequency;
  const double       bound = amplitude * std::pow(omega * dt, 2) / 8.0;
  for (const double new_dt : {0.0037, 0.005, 0.013, 0.02})
  {
    const GroundMotion result = kimp::lumped::resampled(sine, new_dt);
    const double       t_last = static_cast<double>(sine.acceleration.size() - 1) * dt;
    EXPECT_EQ(result.acceleration.size(),
              static_cast<std::size_t>(std::floor(t_last / new_dt + 1e-9)) + 1)
      << "new_dt " << new_dt;
    double max_error = 0.0;
    for (std::size_t j = 0; j < result.acceleration.size(); ++j)
    {
      const double t = static_cast<double>(j) * new_dt;
      max_error =
        std::max(max_error, std::abs(result.acceleration[j] - amplitude * std::sin(omega * t)));
    }
    EXPECT_LE(max_error, bound * (1.0 + 1e-9)) << "new_dt " << new_dt;
    EXPECT_NEAR(result.pga(), amplitude, 2.0 * bound) << "new_dt " << new_dt;
  }
  // Downsampling by an integer factor picks every other sample exactly.
  const GroundMotion halved = kimp::lumped::resampled(sine, 2.0 * dt);
  for (std::size_t j = 0; j < halved.acceleration.size(); ++j)
    ASSERT_NEAR(halved.acceleration[j], sine.acceleration[2 * j], round_off_rel * amplitude)
      << "sample " << j;
}

TEST(GroundMotionBasics, TrapezoidIntegrationIsExactForConstantAcceleration)
{
  // a = a0: v = a0·t exactly; the trapezoid rule on linear v is exact too: u = a0·t²/2.
  const double       a0 = -2.5, dt = 0.01;
  const GroundMotion motion{dt, std::vector<double>(1001, a0), "constant"};
  const auto         v = kimp::lumped::ground_velocity(motion);
  const auto         u = kimp::lumped::ground_displacement(motion);
  for (std::size_t i = 0; i < v.size(); i += 100)
  {
    const double t = static_cast<double>(i) * dt;
    EXPECT_NEAR(v[i], a0 * t, round_off_rel * 100.0) << "t " << t;
    EXPECT_NEAR(u[i], 0.5 * a0 * t * t, round_off_rel * 1000.0) << "t " << t;
  }
}

TEST(ButterworthBandPass, GainMatchesTheDigitalButterworthMagnitude)
{
  // Bilinear transform with prewarping: |H_lp(f)|² = 1/(1 + (tan(πf·dt)/tan(πf_c·dt))^(2N)),
  // |H_hp(f)|² = 1/(1 + (tan(πf_c·dt)/tan(πf·dt))^(2N)), N = 2·n_sections.
  const double dt = 0.005, f_low = 0.3, f_high = 12.0;
  const int    order         = 4;
  auto         expected_gain = [&](double f)
  {
    const double w   = std::tan(pi * f * dt);
    const double low = std::tan(pi * f_low * dt), high = std::tan(pi * f_high * dt);
    return 1.0 /
           std::sqrt((1.0 + std::pow(w / high, 2 * order)) * (1.0 + std::pow(low / w, 2 * order)));
  };
  for (const double f : {0.15, 0.3, 1.0, 3.0, 12.0, 24.0})
  {
    // 60 s of input; fit the amplitude after a transient of 20 s (slowest pole ~ 0.3 Hz).
    const GroundMotion input = sine_record(dt, 60.0, f, 1.0);
    const auto         output =
      kimp::lumped::butterworth_band_pass(input.acceleration, dt, f_low, f_high, 2);
    const double gain = fitted_amplitude(output, dt, f, static_cast<std::size_t>(20.0 / dt));
    EXPECT_NEAR(gain, expected_gain(f), filter_gain_tolerance) << "f = " << f << " Hz";
  }
  EXPECT_NEAR(expected_gain(f_high), 1.0 / std::sqrt(2.0), 1e-6);
}

TEST(ButterworthBandPass, RejectsCornersOutsideTheBand)
{
  const std::vector<double> x(100, 1.0);
  auto                      msg =
    invalid_argument_message([&] { kimp::lumped::butterworth_band_pass(x, 0.01, 0.5, 60.0, 2); });
  EXPECT_NE(msg.find("band-pass f_high = 60 Hz"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Nyquist frequency 1/(2 dt) = 50 Hz"), std::string::npos) << msg;
  msg =
    invalid_argument_message([&] { kimp::lumped::butterworth_band_pass(x, 0.01, 0.0, 10.0, 2); });
  EXPECT_NE(msg.find("band-pass f_low = 0 Hz"), std::string::npos) << msg;
}

TEST(MavroeidisPapageorgiouPulse, AccelerationIsTheDerivativeOfVelocity)
{
  SyntheticMotionSpec spec;
  constexpr double    h = 1e-6, derivative_tolerance = 1e-6;
  for (const double gamma : {1.5, 2.0, 3.3})
    for (const double nu : {0.0, 0.7, pi / 2.0})
    {
      spec.gamma        = gamma;
      spec.nu           = nu;
      const double half = 0.5 * gamma * spec.pulse_period;
      for (double t = spec.pulse_time - half + 0.01; t < spec.pulse_time + half; t += 0.037)
      {
        const double fd = (kimp::lumped::mp_pulse_velocity(spec, 1.3, t + h) -
                           kimp::lumped::mp_pulse_velocity(spec, 1.3, t - h)) /
                          (2.0 * h);
        EXPECT_NEAR(kimp::lumped::mp_pulse_acceleration(spec, 1.3, t), fd, derivative_tolerance)
          << "gamma " << gamma << " nu " << nu << " t " << t;
      }
      // The velocity vanishes at both ends of the support, so the pulse adds no end velocity.
      EXPECT_NEAR(kimp::lumped::mp_pulse_velocity(spec, 1.3, spec.pulse_time + half), 0.0, 1e-14);
      EXPECT_EQ(kimp::lumped::mp_pulse_velocity(spec, 1.3, spec.pulse_time + half + 1e-9), 0.0);
    }
}

TEST(MavroeidisPapageorgiouPulse, FlingMatchesQuadratureOfTheVelocity)
{
  SyntheticMotionSpec spec;
  constexpr double    quadrature_tolerance = 1e-9;
  for (const double gamma : {1.5, 2.0, 2.5, 3.3})
    for (const double nu : {0.0, 1.0, pi})
    {
      spec.gamma = gamma;
      spec.nu    = nu;
      // Composite Simpson on 20000 intervals over the support.
      const double half = 0.5 * gamma * spec.pulse_period;
      const double a = spec.pulse_time - half, h = 2.0 * half / 20000.0;
      double       sum = 0.0;
      for (int k = 0; k <= 20000; ++k)
      {
        const double w = (k == 0 || k == 20000) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
        sum += w * kimp::lumped::mp_pulse_velocity(spec, 1.0, a + k * h);
      }
      EXPECT_NEAR(kimp::lumped::mp_pulse_displacement(spec, 1.0),
                  sum * h / 3.0,
                  quadrature_tolerance)
        << "gamma " << gamma << " nu " << nu;
    }
}

TEST(SyntheticNearFault, SameSeedIsBitwiseIdenticalOtherSeedDiffers)
{
  SyntheticMotionSpec spec;
  spec.seed            = 42;
  const GroundMotion a = kimp::lumped::synthetic_near_fault(spec);
  const GroundMotion b = kimp::lumped::synthetic_near_fault(spec);
  ASSERT_EQ(a.acceleration.size(), b.acceleration.size());
  EXPECT_EQ(std::memcmp(a.acceleration.data(),
                        b.acceleration.data(),
                        a.acceleration.size() * sizeof(double)),
            0);
  spec.seed                         = 43;
  const GroundMotion c              = kimp::lumped::synthetic_near_fault(spec);
  double             max_difference = 0.0;
  for (std::size_t i = 0; i < a.acceleration.size(); ++i)
    max_difference = std::max(max_difference, std::abs(a.acceleration[i] - c.acceleration[i]));
  EXPECT_GT(max_difference, 0.1 * a.pga()) << "seeds 42 and 43";
}

TEST(SyntheticNearFault, HitsTargetPgaAndEndsAtRest)
{
  for (const double pga_g : {0.3, 0.8, 1.2})
    for (const unsigned int seed : {1u, 2u, 3u})
      for (const double noise_ratio : {0.0, 0.2, 0.6})
      {
        SyntheticMotionSpec spec;
        spec.pga            = pga_g * standard_gravity;
        spec.seed           = seed;
        spec.noise_ratio    = noise_ratio;
        const auto   motion = kimp::lumped::synthetic_near_fault(spec);
        const auto   v      = kimp::lumped::ground_velocity(motion);
        const auto   u      = kimp::lumped::ground_displacement(motion);
        const double pgv = peak_abs(v), pgd = peak_abs(u);
        EXPECT_EQ(motion.acceleration.size(), 4000u);
        EXPECT_NEAR(motion.pga(), spec.pga, pga_rel_tolerance * spec.pga)
          << "pga " << pga_g << " g, seed " << seed << ", noise " << noise_ratio;
        EXPECT_LE(std::abs(v.back()), end_velocity_rel * pgv)
          << "pga " << pga_g << " g, seed " << seed << ", noise " << noise_ratio;
        // γ = 2 is an integer: no fling, the ground returns to its start.
        EXPECT_LE(std::abs(u.back()), end_velocity_rel * pgd)
          << "pga " << pga_g << " g, seed " << seed << ", noise " << noise_ratio;
      }
}

TEST(SyntheticNearFault, DefaultsAreAStrongPulseLikeRecord)
{
  // docs/physics.md §3 building, 15 cm moat: a near-fault record with PGV of order 1 m/s whose peak
  // velocity is the pulse, and little residual drift after the strong motion.
  for (const unsigned int seed : {1u, 2u, 3u, 4u, 5u, 6u})
  {
    SyntheticMotionSpec spec;
    spec.seed         = seed;
    const auto motion = kimp::lumped::synthetic_near_fault(spec);
    const auto v      = kimp::lumped::ground_velocity(motion);
    const auto u      = kimp::lumped::ground_displacement(motion);
    const auto i_pgv  = static_cast<std::size_t>(
      std::max_element(v.begin(),
                       v.end(),
                       [](double x, double y) { return std::abs(x) < std::abs(y); }) -
      v.begin());
    const double pgv = std::abs(v[i_pgv]), pgd = peak_abs(u);
    EXPECT_NEAR(motion.pga(), 0.8 * standard_gravity, 1e-12);
    EXPECT_GT(pgv, 0.8) << "seed " << seed;
    EXPECT_LT(pgv, 1.4) << "seed " << seed;
    EXPECT_NEAR(static_cast<double>(i_pgv) * spec.dt, spec.pulse_time, 0.5 * spec.pulse_period)
      << "seed " << seed << ": peak velocity is not the pulse";
    double tail_drift = 0.0;
    for (std::size_t i = static_cast<std::size_t>(17.0 / spec.dt); i < u.size(); ++i)
      tail_drift = std::max(tail_drift, std::abs(u[i]));
    EXPECT_LT(tail_drift, 0.05 * pgd) << "seed " << seed << " pgd " << pgd;
  }
}

TEST(SyntheticNearFault, PulseAloneMatchesClosedFormVelocityAtSecondOrder)
{
  // noise_ratio = 0: the record is the sampled MP acceleration scaled to the target PGA, so its
  // trapezoid velocity must match A·v_MP(t) with A = PGA / max|a_MP(t_i; A = 1)|, the error
  // falling as dt².
  std::vector<double> errors;
  for (const double dt : {0.01, 0.005, 0.0025})
    for (const double gamma : {2.5})
    {
      SyntheticMotionSpec spec;
      spec.noise_ratio     = 0.0;
      spec.dt              = dt;
      spec.gamma           = gamma;
      spec.nu              = 0.4;
      const auto motion    = kimp::lumped::synthetic_near_fault(spec);
      double     peak_unit = 0.0;
      for (std::size_t i = 0; i < motion.acceleration.size(); ++i)
        peak_unit =
          std::max(peak_unit,
                   std::abs(
                     kimp::lumped::mp_pulse_acceleration(spec, 1.0, static_cast<double>(i) * dt)));
      const double amplitude = spec.pga / peak_unit;
      const auto   v         = kimp::lumped::ground_velocity(motion);
      const auto   u         = kimp::lumped::ground_displacement(motion);
      double       error     = 0.0;
      for (std::size_t i = 0; i < v.size(); ++i)
        error =
          std::max(error,
                   std::abs(v[i] - kimp::lumped::mp_pulse_velocity(spec,
                                                                   amplitude,
                                                                   static_cast<double>(i) * dt)));
      const double pgv = peak_abs(v);
      EXPECT_LE(error, pulse_velocity_rel * pgv * (dt / 0.005) * (dt / 0.005))
        << "dt " << dt << " pgv " << pgv;
      errors.push_back(error / pgv);
      // γ = 2.5 leaves a fling: the end displacement is the closed form, the end velocity 0.
      const double fling = kimp::lumped::mp_pulse_displacement(spec, amplitude);
      EXPECT_GT(std::abs(fling), 0.01) << "dt " << dt;
      EXPECT_NEAR(u.back(), fling, 1e-3 * std::abs(fling)) << "dt " << dt;
      EXPECT_LE(std::abs(v.back()), end_velocity_rel * pgv) << "dt " << dt;
    }
  for (std::size_t k = 1; k < errors.size(); ++k)
  {
    const double rate = std::log2(errors[k - 1] / errors[k]);
    EXPECT_GT(rate, 1.9) << "errors " << errors[k - 1] << " -> " << errors[k];
  }
}

TEST(SyntheticNearFault, InvalidSpecsNameTheParameter)
{
  struct Case
  {
    void (*mutate)(SyntheticMotionSpec &);
    const char *expected;
  };
  const Case cases[] = {
    {[](SyntheticMotionSpec &s) { s.pga = -1.0; }, "synthetic.pga = -1 m/s^2 (must be finite"},
    {[](SyntheticMotionSpec &s) { s.dt = 0.0; }, "synthetic.dt = 0 s"},
    {[](SyntheticMotionSpec &s) { s.pulse_period = std::nan(""); }, "synthetic.pulse_period = nan"},
    {[](SyntheticMotionSpec &s) { s.pulse_period = 0.01; },
     "synthetic.pulse_period = 0.01 s (must be >= 4 dt"},
    {[](SyntheticMotionSpec &s) { s.duration = 0.02; },
     "synthetic.duration = 0.02 s (must be >= 10 dt"},
    {[](SyntheticMotionSpec &s) { s.gamma = 1.0; }, "synthetic.gamma = 1 (must be finite and > 1"},
    {[](SyntheticMotionSpec &s) { s.nu = INFINITY; }, "synthetic.nu = inf rad"},
    {[](SyntheticMotionSpec &s) { s.pulse_time = 0.5; },
     "synthetic.pulse_time = 0.5 s (the pulse support"},
    {[](SyntheticMotionSpec &s) { s.pulse_time = 19.5; }, "synthetic.pulse_time = 19.5 s"},
    {[](SyntheticMotionSpec &s) { s.noise_ratio = -0.1; }, "synthetic.noise_ratio = -0.1 (must be"},
    {[](SyntheticMotionSpec &s) { s.noise_f_low = 0.0; }, "synthetic.noise_f_low = 0 Hz"},
    {[](SyntheticMotionSpec &s) { s.noise_f_high = 150.0; },
     "synthetic.noise_f_high = 150 Hz (must be > noise_f_low = 0.3 Hz and < 1/(2 dt) = 100 Hz)"},
    {[](SyntheticMotionSpec &s) { s.envelope_duration = -1.0; },
     "synthetic.envelope_duration = -1 s"},
    {[](SyntheticMotionSpec &s) { s.envelope_epsilon = 1.0; },
     "synthetic.envelope_epsilon = 1 (must be in (0, 1))"},
    {[](SyntheticMotionSpec &s) { s.envelope_eta = 0.0; },
     "synthetic.envelope_eta = 0 (must be in (0, 1))"},
  };
  for (const Case &c : cases)
  {
    SyntheticMotionSpec spec;
    c.mutate(spec);
    const auto msg = invalid_argument_message([&] { kimp::lumped::synthetic_near_fault(spec); });
    EXPECT_NE(msg.find(c.expected), std::string::npos)
      << "message: " << msg << "\nexpected: " << c.expected;
  }
  // Noise parameters are irrelevant, hence unchecked, without noise.
  SyntheticMotionSpec quiet;
  quiet.noise_ratio  = 0.0;
  quiet.noise_f_high = 1e6;
  EXPECT_NO_THROW(kimp::lumped::synthetic_near_fault(quiet));
}
