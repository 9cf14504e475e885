// Status rules of a fit (fit::fit_verdict, docs/physics.md §4 "Status of a fit"): an unbounded
// interval or an exponent at its bound is "failed", a misfit window over less than half the
// contact is "warning", never "ok"; and fit_options()/fit_variants() carry the shared config.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <string>
#include <vector>

#include "fit/fit_config.h"
#include "lumped/collision/two_body.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/fit_results.h"

namespace
{
  using kimp::fit::fit_verdict;
  using kimp::fit::FitConfig;
  using kimp::fit::FitResult;
  using kimp::fit::ForceHistory;

  constexpr double infinity = std::numeric_limits<double>::infinity();

  using kimp::testing::good_fit;
  using kimp::testing::starts_with;

  TEST(FitVerdict, WellDeterminedFitIsOk)
  {
    EXPECT_EQ(fit_verdict(good_fit()), "ok");
  }

  TEST(FitVerdict, DegenerateIntervalIsAWarning)
  {
    FitResult f = good_fit();
    f.stiffness = {92.6e6, 92.6e6, 92.6e6, true};
    EXPECT_TRUE(starts_with(fit_verdict(f), "warning: confidence interval of k degenerate"))
      << fit_verdict(f);
    f.stiffness = {92.6e6, 92.59e6, 92.61e6, true}; // 2e-4 relative: a real interval
    EXPECT_EQ(fit_verdict(f), "ok");
  }

  TEST(FitVerdict, UnboundedIntervalFails)
  {
    FitResult f       = good_fit();
    f.stiffness.upper = infinity;
    EXPECT_TRUE(starts_with(fit_verdict(f), "failed: confidence interval of k unbounded"))
      << fit_verdict(f);
    f                 = good_fit();
    f.stiffness.lower = 0.0;
    EXPECT_TRUE(starts_with(fit_verdict(f), "failed: confidence interval of k unbounded"))
      << fit_verdict(f);
  }

  TEST(FitVerdict, ExponentAtItsBoundWithInfiniteIntervalFails)
  {
    // What a free-exponent fit of linear data used to report as "ok": n = 1, CI [0, inf].
    FitResult f = good_fit();
    f.exponent  = {1.0, 0.0, infinity, true};
    EXPECT_TRUE(starts_with(fit_verdict(f), "failed:")) << fit_verdict(f);
    f.exponent = {1.0000001, 1.0, 1.000001, true};
    EXPECT_TRUE(starts_with(fit_verdict(f), "failed: exponent n = 1")) << fit_verdict(f);
  }

  TEST(FitVerdict, CorAtItsBoundFails)
  {
    FitResult f = good_fit();
    f.cor       = {0.99999, 0.9999, 0.999999, true};
    EXPECT_TRUE(starts_with(fit_verdict(f), "failed: COR")) << fit_verdict(f);
  }

  TEST(FitVerdict, WindowOverLessThanHalfTheContactWarns)
  {
    // The indentation-based window of a chattering slab: 0.32 ms of a 33 ms contact.
    FitResult f            = good_fit();
    f.fem_contact_duration = 0.32e-3;
    f.contact_extent       = 33e-3;
    const std::string v    = fit_verdict(f);
    EXPECT_TRUE(starts_with(v, "warning: the misfit window covers 0.97 % of the contact")) << v;
    f.fem_contact_duration = 0.51 * f.contact_extent;
    EXPECT_EQ(fit_verdict(f), "ok");
  }

  /// Kelvin-Voigt history (COR 0.7) of a 3840 kg/m slab at 1 m/s on a rigid wall, then a
  /// second, later bounce of the same shape: the contact spans both.
  ForceHistory two_bounces(double k)
  {
    kimp::lumped::ForceLawSpec spec;
    spec.law            = "kelvin_voigt";
    spec.stiffness      = k;
    spec.cor            = 0.7;
    spec.effective_mass = 3840.0;
    kimp::lumped::TwoBodySetup setup;
    setup.mass_1         = 3840.0;
    setup.mass_2         = infinity;
    setup.velocity_1     = 1.0;
    setup.time_step      = std::sqrt(3840.0 / k) / 2000.0;
    setup.record_history = true;
    const auto r = kimp::lumped::simulate_two_body(*kimp::lumped::make_force_law(spec), setup);
    // Force of one impact at time t after its touch (linear between the recorded steps).
    const auto  &rt       = r.history.time;
    const double duration = rt.back();
    const auto   one      = [&](double t)
    {
      if (t <= rt.front() || t >= duration)
        return 0.0;
      const auto i = static_cast<std::size_t>(
        std::distance(rt.begin(), std::upper_bound(rt.begin(), rt.end(), t)));
      const double s = (t - rt[i - 1]) / (rt[i] - rt[i - 1]);
      return std::max(0.0,
                      r.history.force[i - 1] + s * (r.history.force[i] - r.history.force[i - 1]));
    };
    ForceHistory h;
    const double dt = 10.0 * setup.time_step;
    for (int j = -20; j * dt < 6.0 * duration; ++j)
    {
      const double t = j * dt;
      h.time.push_back(t);
      h.force.push_back(one(t) + 0.5 * one(t - 3.0 * duration));
    }
    return h;
  }

  TEST(FitVerdict, WindowCutAtTheFirstBounceIsAWarningAndMergingMakesItOk)
  {
    const double       k = 1.5e8;
    const ForceHistory h = two_bounces(k);
    FitConfig          config;
    config.separation_fraction = 0.25; // cuts at the first bounce: 1/4 of the contact span
    kimp::lumped::ForceLawSpec law;
    law.law                 = "kelvin_voigt";
    law.cor                 = 0.7;
    const FitResult   cut   = kimp::fit::fit_impact_law(h, 3840.0, 1.0, law, fit_options(config));
    const std::string cut_v = fit_verdict(cut);
    EXPECT_TRUE(starts_with(cut_v, "warning: the misfit window covers")) << cut_v;
    EXPECT_NEAR(cut.stiffness.value, k, 1e-2 * k) << "the first bounce alone is the law itself";
    config.separation_fraction = 10.0; // merges both bounces
    const FitResult merged = kimp::fit::fit_impact_law(h, 3840.0, 1.0, law, fit_options(config));
    EXPECT_EQ(fit_verdict(merged), "ok");
  }

  TEST(FitVerdict, ContactOpenAtTheEndOfTheRecordIsAWarning)
  {
    // The first bounce of two_bounces() cut at 60 % of its duration (an FEM run that stopped at
    // its end time while the slab still pushed): the fit says it saw a truncated contact.
    const double               k    = 1.5e8;
    ForceHistory               full = two_bounces(k), cut;
    FitConfig                  config;
    kimp::lumped::ForceLawSpec law;
    law.law               = "kelvin_voigt";
    law.cor               = 0.7;
    const FitResult whole = kimp::fit::fit_impact_law(full, 3840.0, 1.0, law, fit_options(config));
    const double    end_time = whole.contact_start + 0.6 * whole.fem_contact_duration;
    for (std::size_t i = 0; i < full.time.size() && full.time[i] <= end_time; ++i)
    {
      cut.time.push_back(full.time[i]);
      cut.force.push_back(full.force[i]);
    }
    ASSERT_GT(cut.force.back(), 0.0);
    EXPECT_FALSE(whole.contact_open_at_end);
    const FitResult truncated =
      kimp::fit::fit_impact_law(cut, 3840.0, 1.0, law, fit_options(config));
    EXPECT_TRUE(truncated.contact_open_at_end);
    const std::string v = fit_verdict(truncated);
    EXPECT_TRUE(starts_with(v, "warning: the contact lasts to the end of the FEM record")) << v;
  }

  TEST(FitVerdict, PeakForceOffByMoreThanTheToleranceIsAWarning)
  {
    // The site case of a Kelvin-Voigt fit: 452 kN/m against the FEM's 1,234 kN/m.
    FitResult f        = good_fit();
    f.fem_peak_force   = 1234e3;
    f.model_peak_force = 452e3;
    EXPECT_NEAR(f.peak_force_ratio(), 0.3663, 1e-4);
    const std::string v = fit_verdict(f);
    EXPECT_TRUE(starts_with(v,
                            "warning: the fitted peak force is 36.6 % of the FEM's (452 of "
                            "1234 kN/m, tolerance 25 %)"))
      << v;
    EXPECT_EQ(fit_verdict(f, 0.7), "ok"); // a looser tolerance accepts it
    EXPECT_EQ(kimp::fit::default_peak_tolerance, 0.25);
    f.model_peak_force = 1.2 * f.fem_peak_force; // within 25 % either way
    EXPECT_EQ(fit_verdict(f), "ok");
    f.model_peak_force = 1.3 * f.fem_peak_force;
    EXPECT_TRUE(starts_with(fit_verdict(f), "warning: the fitted peak force is 130 %"))
      << fit_verdict(f);
    // With another warning both are named.
    f.contact_open_at_end  = true;
    const std::string both = fit_verdict(f);
    EXPECT_TRUE(starts_with(both, "warning: the contact lasts to the end")) << both;
    EXPECT_NE(both.find("; the fitted peak force is 130 %"), std::string::npos) << both;
  }

  /// A sharp spike on a long, low pulse (a stiff contact ringing on a soft wall): a
  /// Kelvin-Voigt law fitted to the whole pulse in the least-squares sense follows the body and
  /// cuts the spike.
  ForceHistory spike_on_a_pulse()
  {
    const double duration = 0.02, rise = duration / 40.0, peak = 1.37e6; // s, s, N/m
    ForceHistory h;
    for (int j = -50; j <= 1500; ++j)
    {
      const double t = j * 2e-5;
      double       f = 0.0;
      if (t > 0.0 && t < duration)
        f = peak *
            (0.3 * std::sin(M_PI * t / duration) + 0.7 * (t / rise) * std::exp(1.0 - t / rise));
      h.time.push_back(t);
      h.force.push_back(f);
    }
    return h;
  }

  TEST(FitVerdict, KelvinVoigtFittedToASpikeMissesThePeakAndItsStatusSaysSo)
  {
    kimp::lumped::ForceLawSpec law;
    law.law                 = "kelvin_voigt";
    law.cor                 = 0.7;
    const FitResult   fit   = kimp::fit::fit_impact_law(spike_on_a_pulse(), 3840.0, 1.0, law);
    const double      ratio = fit.peak_force_ratio();
    const std::string state = fit_verdict(fit);
    EXPECT_LT(ratio, 0.75) << state;
    EXPECT_NEAR(ratio, fit.model_peak_force / fit.fem_peak_force, 1e-12);
    EXPECT_NE(state.find("the fitted peak force is"), std::string::npos) << state;
    EXPECT_TRUE(starts_with(state, "warning: ")) << state;
    EXPECT_TRUE(std::isfinite(fit.impulse_ratio()));
    EXPECT_TRUE(std::isfinite(fit.contact_duration_ratio()));
    // The same fit judged with a tolerance wider than its miss says nothing of the peak.
    EXPECT_EQ(fit_verdict(fit, 1.0 - ratio + 0.01).find("peak force"), std::string::npos);
  }

  TEST(FitVerdict, ALawFittedToItsOwnHistoryReproducesPeakImpulseAndDuration)
  {
    const ForceHistory h = two_bounces(1.5e8);
    // Only the first impact: its own force history.
    ForceHistory first;
    for (std::size_t i = 0; i < h.time.size() && h.time[i] < 2.5 * M_PI * std::sqrt(3840.0 / 1.5e8);
         ++i)
    {
      first.time.push_back(h.time[i]);
      first.force.push_back(h.force[i]);
    }
    kimp::lumped::ForceLawSpec law;
    law.law             = "kelvin_voigt";
    law.cor             = 0.7;
    const FitResult fit = kimp::fit::fit_impact_law(first, 3840.0, 1.0, law);
    EXPECT_NEAR(fit.peak_force_ratio(), 1.0, 0.02);
    EXPECT_NEAR(fit.impulse_ratio(), 1.0, 0.02);
    // The model's contact lasts until δ = 0, through the Kelvin-Voigt tension the data clip at
    // zero force: about 8 % longer.
    EXPECT_GT(fit.contact_duration_ratio(), 1.0);
    EXPECT_LT(fit.contact_duration_ratio(), 1.1);
    EXPECT_EQ(fit_verdict(fit).find("peak force"), std::string::npos) << fit_verdict(fit);
  }

  TEST(FitConfig, OptionsAndVariantsCarryTheSharedConfiguration)
  {
    FitConfig config;
    config.cor                 = 0.6;
    config.separation_fraction = 3.0;
    config.tail_fraction       = 0.25;
    config.contact_threshold   = 2e-3;
    config.displacement_weight = 0.5;
    const auto variants        = kimp::fit::fit_variants(config);
    ASSERT_EQ(variants.size(), 5u);
    for (const auto &variant : variants)
    {
      EXPECT_EQ(variant.law.cor, 0.6) << variant.name;
      EXPECT_EQ(variant.options.separation_fraction, 3.0) << variant.name;
      EXPECT_EQ(variant.options.tail_fraction, 0.25) << variant.name;
      EXPECT_EQ(variant.options.contact_threshold, 2e-3) << variant.name;
      EXPECT_EQ(variant.options.displacement_weight, 0.5) << variant.name;
    }
    EXPECT_TRUE(variants.back().options.fit_exponent);
  }
} // namespace
