// Ground-motion processing and the synthetic near-fault record (see ground_motion.h):
// MP pulse (Mavroeidis & Papageorgiou 2003) + Saragoni-Hart-windowed (Boore 2003) Butterworth
// noise.
#include "lumped/excitation/ground_motion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

namespace kimp::lumped
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// Slack for "t sits on a sample" decisions, relative to dt: absorbs i·dt rounding.
    constexpr double sample_time_slack = 1e-9;

    std::string format_value(double value)
    {
      std::ostringstream out;
      out.precision(10);
      out << value;
      return out.str();
    }

    [[noreturn]] void
    reject(const std::string &key, double value, const std::string &unit, const std::string &rule)
    {
      throw std::invalid_argument(key + " = " + format_value(value) + (unit.empty() ? "" : " ") +
                                  unit + " (" + rule + ")");
    }

    std::string record_label(const GroundMotion &motion)
    {
      return "ground motion '" + (motion.name.empty() ? std::string("<unnamed>") : motion.name) +
             "'";
    }

    std::vector<double> trapezoid_integral(const std::vector<double> &f, double dt)
    {
      std::vector<double> integral(f.size(), 0.0);
      for (std::size_t i = 1; i < f.size(); ++i)
        integral[i] = integral[i - 1] + 0.5 * dt * (f[i - 1] + f[i]);
      return integral;
    }

    /// One second-order section, direct form II transposed.
    struct Biquad
    {
      double b0, b1, b2, a1, a2; // normalised by a0

      void apply(std::vector<double> &x) const
      {
        double z1 = 0.0, z2 = 0.0;
        for (double &value : x)
        {
          const double in  = value;
          const double out = b0 * in + z1;
          z1               = b1 * in - a1 * out + z2;
          z2               = b2 * in - a2 * out;
          value            = out;
        }
      }
    };

    // Bilinear transform of H(s) = 1/(s² + s/Q + 1) (low-pass) or s²/(s² + s/Q + 1) (high-pass)
    // with the analog corner prewarped to tan(ω0/2), so the digital corner is exactly f0.
    Biquad butterworth_section(double f0, double dt, double q, bool high_pass)
    {
      const double w0    = 2.0 * pi * f0 * dt;
      const double cosw  = std::cos(w0);
      const double alpha = std::sin(w0) / (2.0 * q);
      const double a0    = 1.0 + alpha;
      Biquad       s{};
      if (high_pass)
      {
        s.b0 = 0.5 * (1.0 + cosw) / a0;
        s.b1 = -(1.0 + cosw) / a0;
      }
      else
      {
        s.b0 = 0.5 * (1.0 - cosw) / a0;
        s.b1 = (1.0 - cosw) / a0;
      }
      s.b2 = s.b0;
      s.a1 = -2.0 * cosw / a0;
      s.a2 = (1.0 - alpha) / a0;
      return s;
    }

    /// Uniform deviate in (0, 1) from the raw 32-bit engine output (portable across libraries).
    double open_unit_interval(std::mt19937 &engine)
    {
      return (static_cast<double>(engine()) + 0.5) / 4294967296.0;
    }

    std::vector<double> gaussian_white_noise(std::size_t n, unsigned int seed)
    {
      std::mt19937        engine(seed);
      std::vector<double> z(n);
      for (std::size_t i = 0; i < n; i += 2)
      {
        const double r     = std::sqrt(-2.0 * std::log(open_unit_interval(engine)));
        const double theta = 2.0 * pi * open_unit_interval(engine);
        z[i]               = r * std::cos(theta);
        if (i + 1 < n)
          z[i + 1] = r * std::sin(theta);
      }
      return z;
    }

    double saragoni_hart_window(double t, double t_w, double epsilon, double eta)
    {
      if (t <= 0.0)
        return 0.0;
      const double b = -epsilon * std::log(eta) / (1.0 + epsilon * (std::log(epsilon) - 1.0));
      const double c = b / epsilon;
      const double x = t / t_w;
      // a·x^b·exp(−c·x) with a = (e/ε)^b, evaluated in logs to stay finite for large b.
      return std::exp(b * (1.0 - std::log(epsilon) + std::log(x)) - c * x);
    }

    double rms(const std::vector<double> &x, std::size_t begin, std::size_t end)
    {
      double sum = 0.0;
      for (std::size_t i = begin; i < end; ++i)
        sum += x[i] * x[i];
      return end > begin ? std::sqrt(sum / static_cast<double>(end - begin)) : 0.0;
    }

    std::size_t n_samples(const SyntheticMotionSpec &spec)
    {
      return static_cast<std::size_t>(std::llround(spec.duration / spec.dt));
    }
  } // namespace

  double GroundMotion::duration() const
  {
    return static_cast<double>(acceleration.size()) * dt;
  }

  double GroundMotion::pga() const
  {
    double peak = 0.0;
    for (const double a : acceleration)
      peak = std::max(peak, std::abs(a));
    return peak;
  }

  void validate(const GroundMotion &motion)
  {
    const std::string label = record_label(motion);
    if (!(std::isfinite(motion.dt) && motion.dt > 0.0))
      reject(label + ": dt", motion.dt, "s", "must be finite and > 0");
    if (motion.acceleration.empty())
      throw std::invalid_argument(label + ": no acceleration samples (expected at least 1)");
    for (std::size_t i = 0; i < motion.acceleration.size(); ++i)
      if (!std::isfinite(motion.acceleration[i]))
        reject(label + ": acceleration[" + std::to_string(i) + "]",
               motion.acceleration[i],
               "m/s^2",
               "must be finite");
  }

  GroundMotion scaled(const GroundMotion &motion, double factor)
  {
    validate(motion);
    if (!std::isfinite(factor))
      reject(record_label(motion) + ": scale factor", factor, "", "must be finite");
    GroundMotion result = motion;
    for (double &a : result.acceleration)
      a *= factor;
    return result;
  }

  GroundMotion scaled_to_pga(const GroundMotion &motion, double target_pga)
  {
    validate(motion);
    if (!(std::isfinite(target_pga) && target_pga > 0.0))
      reject(record_label(motion) + ": target PGA", target_pga, "m/s^2", "must be finite and > 0");
    const double pga = motion.pga();
    if (pga == 0.0)
      throw std::invalid_argument(record_label(motion) +
                                  ": PGA = 0 m/s^2, cannot scale to a target PGA (expected a "
                                  "record with at least one non-zero sample)");
    GroundMotion result = scaled(motion, target_pga / pga);
    // The product a·(target/pga) can miss target by an ulp; pin the peak sample(s) so the
    // requested PGA holds exactly, which users compare against scaled tables.
    double &peak = *std::max_element(result.acceleration.begin(),
                                     result.acceleration.end(),
                                     [](double x, double y) { return std::abs(x) < std::abs(y); });
    peak         = std::copysign(target_pga, peak);
    for (double &a : result.acceleration)
      if (std::abs(a) > target_pga)
        a = std::copysign(target_pga, a);
    return result;
  }

  GroundMotion trimmed(const GroundMotion &motion, double duration)
  {
    validate(motion);
    if (!(std::isfinite(duration) && duration >= 0.5 * motion.dt))
      reject(record_label(motion) + ": trim duration",
             duration,
             "s",
             "must be finite and >= dt/2 = " + format_value(0.5 * motion.dt) + " s");
    const auto n_keep =
      std::min<std::size_t>(static_cast<std::size_t>(std::llround(duration / motion.dt)),
                            motion.acceleration.size());
    GroundMotion result = motion;
    result.acceleration.resize(n_keep);
    return result;
  }

  double acceleration_at(const GroundMotion &motion, double t)
  {
    const std::vector<double> &a = motion.acceleration;
    if (a.empty() || !(motion.dt > 0.0))
      return 0.0;
    const double x      = t / motion.dt;
    const auto   i_last = static_cast<double>(a.size() - 1);
    if (x < -sample_time_slack || x > i_last + sample_time_slack)
      return 0.0;
    if (x >= i_last)
      return a.back();
    if (x <= 0.0)
      return a.front();
    const auto   i    = static_cast<std::size_t>(std::floor(x));
    const double frac = x - static_cast<double>(i);
    return a[i] + frac * (a[i + 1] - a[i]);
  }

  GroundMotion resampled(const GroundMotion &motion, double new_dt)
  {
    validate(motion);
    if (!(std::isfinite(new_dt) && new_dt > 0.0))
      reject(record_label(motion) + ": new dt", new_dt, "s", "must be finite and > 0");
    const double t_last = static_cast<double>(motion.acceleration.size() - 1) * motion.dt;
    const auto   n_new =
      static_cast<std::size_t>(std::floor(t_last / new_dt + sample_time_slack)) + 1;
    GroundMotion result;
    result.dt   = new_dt;
    result.name = motion.name;
    result.acceleration.resize(n_new);
    for (std::size_t j = 0; j < n_new; ++j)
      result.acceleration[j] = acceleration_at(motion, static_cast<double>(j) * new_dt);
    return result;
  }

  std::vector<double> ground_velocity(const GroundMotion &motion)
  {
    return trapezoid_integral(motion.acceleration, motion.dt);
  }

  std::vector<double> ground_displacement(const GroundMotion &motion)
  {
    return trapezoid_integral(ground_velocity(motion), motion.dt);
  }

  std::vector<double> butterworth_band_pass(const std::vector<double> &x,
                                            double                     dt,
                                            double                     f_low,
                                            double                     f_high,
                                            unsigned int               n_sections)
  {
    if (!(std::isfinite(dt) && dt > 0.0))
      reject("band-pass dt", dt, "s", "must be finite and > 0");
    if (!(std::isfinite(f_low) && f_low > 0.0))
      reject("band-pass f_low", f_low, "Hz", "must be finite and > 0");
    const double nyquist = 0.5 / dt;
    if (!(std::isfinite(f_high) && f_high > f_low && f_high < nyquist))
      reject("band-pass f_high",
             f_high,
             "Hz",
             "must be > f_low = " + format_value(f_low) +
               " Hz and < the Nyquist frequency 1/(2 dt) = " + format_value(nyquist) + " Hz");
    if (n_sections == 0)
      throw std::invalid_argument("band-pass n_sections = 0 (must be >= 1)");

    const double        order = 2.0 * n_sections;
    std::vector<double> y     = x;
    for (const bool high_pass : {true, false})
      for (unsigned int k = 0; k < n_sections; ++k)
      {
        const double q = 1.0 / (2.0 * std::cos(pi * (2.0 * k + 1.0) / (2.0 * order)));
        butterworth_section(high_pass ? f_low : f_high, dt, q, high_pass).apply(y);
      }
    return y;
  }

  void validate(const SyntheticMotionSpec &spec)
  {
    auto positive = [](const char *key, double value, const char *unit)
    {
      if (!(std::isfinite(value) && value > 0.0))
        reject(std::string("synthetic.") + key, value, unit, "must be finite and > 0");
    };
    positive("pga", spec.pga, "m/s^2");
    positive("dt", spec.dt, "s");
    positive("pulse_period", spec.pulse_period, "s");
    positive("duration", spec.duration, "s");
    if (spec.pulse_period < 4.0 * spec.dt)
      reject("synthetic.pulse_period",
             spec.pulse_period,
             "s",
             "must be >= 4 dt = " + format_value(4.0 * spec.dt) + " s to resolve the pulse");
    if (n_samples(spec) < 10)
      reject("synthetic.duration",
             spec.duration,
             "s",
             "must be >= 10 dt = " + format_value(10.0 * spec.dt) + " s");
    if (!(std::isfinite(spec.gamma) && spec.gamma > 1.0))
      reject("synthetic.gamma", spec.gamma, "", "must be finite and > 1 (Mavroeidis-Papageorgiou)");
    if (!std::isfinite(spec.nu))
      reject("synthetic.nu", spec.nu, "rad", "must be finite");
    const double half_width = 0.5 * spec.gamma * spec.pulse_period;
    const double t_last     = static_cast<double>(n_samples(spec) - 1) * spec.dt;
    if (!(std::isfinite(spec.pulse_time) && spec.pulse_time - half_width >= 0.0 &&
          spec.pulse_time + half_width <= t_last))
      reject("synthetic.pulse_time",
             spec.pulse_time,
             "s",
             "the pulse support t0 ± gamma·Tp/2 = t0 ± " + format_value(half_width) +
               " s must lie within [0, " + format_value(t_last) + "] s");
    if (!(std::isfinite(spec.noise_ratio) && spec.noise_ratio >= 0.0))
      reject("synthetic.noise_ratio", spec.noise_ratio, "", "must be finite and >= 0");
    if (spec.noise_ratio > 0.0)
    {
      positive("noise_f_low", spec.noise_f_low, "Hz");
      const double nyquist = 0.5 / spec.dt;
      if (!(std::isfinite(spec.noise_f_high) && spec.noise_f_high > spec.noise_f_low &&
            spec.noise_f_high < nyquist))
        reject("synthetic.noise_f_high",
               spec.noise_f_high,
               "Hz",
               "must be > noise_f_low = " + format_value(spec.noise_f_low) +
                 " Hz and < 1/(2 dt) = " + format_value(nyquist) + " Hz");
      positive("envelope_duration", spec.envelope_duration, "s");
      if (!(spec.envelope_epsilon > 0.0 && spec.envelope_epsilon < 1.0))
        reject("synthetic.envelope_epsilon", spec.envelope_epsilon, "", "must be in (0, 1)");
      if (!(spec.envelope_eta > 0.0 && spec.envelope_eta < 1.0))
        reject("synthetic.envelope_eta", spec.envelope_eta, "", "must be in (0, 1)");
    }
  }

  namespace
  {
    /// The pulse's phase 2π·f_p·(t − t_0) at t; none outside its support |t − t_0| <= γ/(2·f_p).
    std::optional<double> mp_pulse_phase(const SyntheticMotionSpec &spec, double t)
    {
      const double fp  = 1.0 / spec.pulse_period;
      const double tau = t - spec.pulse_time;
      if (std::abs(tau) > 0.5 * spec.gamma / fp)
        return std::nullopt;
      return 2.0 * pi * fp * tau;
    }
  } // namespace

  double mp_pulse_velocity(const SyntheticMotionSpec &spec, double amplitude, double t)
  {
    const std::optional<double> phase = mp_pulse_phase(spec, t);
    if (!phase)
      return 0.0;
    return 0.5 * amplitude * (1.0 + std::cos(*phase / spec.gamma)) * std::cos(*phase + spec.nu);
  }

  double mp_pulse_acceleration(const SyntheticMotionSpec &spec, double amplitude, double t)
  {
    const std::optional<double> phase = mp_pulse_phase(spec, t);
    if (!phase)
      return 0.0;
    const double fp = 1.0 / spec.pulse_period;
    return -amplitude * pi * fp / spec.gamma *
           (std::sin(*phase / spec.gamma) * std::cos(*phase + spec.nu) +
            spec.gamma * (1.0 + std::cos(*phase / spec.gamma)) * std::sin(*phase + spec.nu));
  }

  double mp_pulse_displacement(const SyntheticMotionSpec &spec, double amplitude)
  {
    const double omega = 2.0 * pi / spec.pulse_period;
    const double g     = spec.gamma;
    const double s     = std::sin(pi * g);
    return 0.5 * amplitude * std::cos(spec.nu) *
           (2.0 * s / omega - s / (omega * (1.0 + 1.0 / g)) - s / (omega * (1.0 - 1.0 / g)));
  }

  GroundMotion synthetic_near_fault(const SyntheticMotionSpec &spec)
  {
    validate(spec);
    const std::size_t n = n_samples(spec);

    std::vector<double> a(n);
    for (std::size_t i = 0; i < n; ++i)
      a[i] = mp_pulse_acceleration(spec, 1.0, static_cast<double>(i) * spec.dt);

    if (spec.noise_ratio > 0.0)
    {
      std::vector<double> noise = gaussian_white_noise(n, spec.seed);
      for (std::size_t i = 0; i < n; ++i)
        noise[i] *= saragoni_hart_window(static_cast<double>(i) * spec.dt,
                                         spec.envelope_duration,
                                         spec.envelope_epsilon,
                                         spec.envelope_eta);
      noise = butterworth_band_pass(noise, spec.dt, spec.noise_f_low, spec.noise_f_high, 2);

      const double half_width = 0.5 * spec.gamma * spec.pulse_period;
      const auto   pulse_begin =
        static_cast<std::size_t>(std::ceil((spec.pulse_time - half_width) / spec.dt));
      const auto pulse_end =
        std::min(n,
                 static_cast<std::size_t>(std::floor((spec.pulse_time + half_width) / spec.dt)) +
                   1);
      const auto window_end =
        std::min(n, static_cast<std::size_t>(std::llround(spec.envelope_duration / spec.dt)) + 1);
      const double noise_rms = rms(noise, 0, window_end);
      const double pulse_rms = rms(a, pulse_begin, pulse_end);
      if (noise_rms > 0.0)
        for (std::size_t i = 0; i < n; ++i)
          a[i] += spec.noise_ratio * pulse_rms / noise_rms * noise[i];
    }

    // Baseline: subtract α + β·s (s = t/T) so that the discrete end velocity is 0 and the end
    // displacement is the pulse's fling. Both end values are linear in the acceleration, so the
    // 2×2 system below is exact for the trapezoid rule used by ground_velocity().
    {
      const double        t_end = static_cast<double>(n - 1) * spec.dt;
      std::vector<double> ones(n, 1.0), ramp(n);
      for (std::size_t i = 0; i < n; ++i)
        ramp[i] = static_cast<double>(i) * spec.dt / t_end;
      auto end_values = [&](const std::vector<double> &x)
      {
        const std::vector<double> v = trapezoid_integral(x, spec.dt);
        const std::vector<double> d = trapezoid_integral(v, spec.dt);
        return std::array<double, 2>{{v.back(), d.back()}};
      };
      const auto   e1    = end_values(ones);
      const auto   es    = end_values(ramp);
      const auto   ea    = end_values(a);
      const double r_v   = ea[0];
      const double r_d   = ea[1] - mp_pulse_displacement(spec, 1.0);
      const double det   = e1[0] * es[1] - es[0] * e1[1];
      const double alpha = (r_v * es[1] - es[0] * r_d) / det;
      const double beta  = (e1[0] * r_d - r_v * e1[1]) / det;
      for (std::size_t i = 0; i < n; ++i)
        a[i] -= alpha + beta * ramp[i];
    }

    GroundMotion motion;
    motion.dt           = spec.dt;
    motion.acceleration = std::move(a);
    motion.name         = spec.name;
    return scaled_to_pga(motion, spec.pga);
  }
} // namespace kimp::lumped
