// Closed-form checks of the contact laws 1-7 (docs/physics.md §1): formulas, first-contact force
// from the total penetration, tension of Kelvin-Voigt, permanent indentation, clipping, loop areas.
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <stdexcept>
#include <string>

#include "lumped/laws/bumper_law.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/hertzdamp_law.h"
#include "lumped/laws/hysteretic_law.h"
#include "lumped/laws/jankowski_law.h"
#include "lumped/laws/kelvin_voigt_law.h"
#include "lumped/laws/modified_kelvin_voigt_law.h"

namespace
{
  using namespace kimp::lumped;

  constexpr double pi        = 3.14159265358979323846;
  constexpr double round_off = 1e-12;                 ///< relative, formulas evaluated the same way
  constexpr double k_linear  = 2.5e9;                 ///< 2500 kN/mm, N/m
  constexpr double k_hertz   = 2.3717e10;             ///< 750 kN/mm^1.5, N/m^1.5
  constexpr double m_eff     = 280e3 * 300e3 / 580e3; ///< kg

  double kilonewton_per_mm_power(double n)
  {
    return 1e3 / std::pow(1e-3, n);
  }

  TEST(BumperStiffness, ThesisRubberBumperGives0089KilonewtonPerMmPower265)
  {
    // 150 x 150 x 50 mm, K_r = 55835 kN/m², n = 2.65 -> 0.089 kN/mm^2.65 (thesis ch. 6, 2 digits).
    constexpr double thesis_rounding = 0.005 / 0.089;
    const double     k_b             = bumper_stiffness(0.15 * 0.15, 55835e3, 0.05, 2.65, 1);
    EXPECT_NEAR(k_b / kilonewton_per_mm_power(2.65), 0.089, 0.089 * thesis_rounding)
      << "k_b = " << k_b << " N/m^2.65";
    const double four = bumper_stiffness(0.15 * 0.15, 55835e3, 0.05, 2.65, 4);
    EXPECT_NEAR(four / kilonewton_per_mm_power(2.65), 0.36, 0.36 * 0.02);
    EXPECT_NEAR(four, 4.0 * k_b, round_off * four);
    EXPECT_THROW(bumper_stiffness(0.0225, 55835e3, 0.05, 2.65, 0), std::invalid_argument);
    EXPECT_THROW(bumper_stiffness(0.0225, 55835e3, -0.05, 2.65, 1), std::invalid_argument);
  }

  TEST(KelvinVoigtDampingRatio, ReturnsTheLinearOscillatorsVelocityRatio)
  {
    // The damped half cycle of a linear oscillator returns with exp(−πξ/sqrt(1 − ξ²)) = COR.
    for (int i = 1; i <= 20; ++i)
    {
      const double cor = 0.05 * i;
      const double xi  = kelvin_voigt_damping_ratio(cor);
      EXPECT_NEAR(std::exp(-pi * xi / std::sqrt(1.0 - xi * xi)), cor, round_off) << cor;
    }
    EXPECT_NEAR(kelvin_voigt_damping_ratio(0.7), 0.1128084507, 1e-10);
    EXPECT_THROW(kelvin_voigt_damping_ratio(0.0), std::invalid_argument);
  }

  TEST(JankowskiDampingRatio, MatchesEquation212AndRejectsZeroCor)
  {
    EXPECT_NEAR(jankowski_damping_ratio(0.7), 0.2981090815, 1e-10);
    EXPECT_EQ(jankowski_damping_ratio(1.0), 0.0);
    try
    {
      jankowski_damping_ratio(0.0);
      ADD_FAILURE() << "COR = 0 accepted";
    }
    catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("jankowski law: cor = 0"), std::string::npos)
        << e.what();
    }
  }

  TEST(ImpactDampingCoefficient, MatchesEquation223WithMassInKilograms)
  {
    // 1.55·(1 − 0.49)/(0.7^0.7076 · 144828^0.0025 · 1^0.9755), evaluated independently.
    EXPECT_NEAR(impact_damping_coefficient(0.7, m_eff, 1.0), 0.98766206409, 1e-10);
    EXPECT_EQ(impact_damping_coefficient(1.0, m_eff, 1.0), 0.0);
    EXPECT_THROW(impact_damping_coefficient(0.7, m_eff, 0.0), std::invalid_argument);
  }

  /// A law first committed with the gap open at −5 mm, then a trial 1 mm into contact at 1 m/s.
  ForceResponse first_contact(ForceLaw &law, double delta = 1e-3, double rate = 1.0)
  {
    law.set_trial(-5e-3, rate);
    law.commit();
    return law.set_trial(delta, rate);
  }

  TEST(FirstContact, UsesTheTotalPenetrationNotTheTravelSinceLastCommit)
  {
    constexpr double d = 1e-3, v = 1.0;
    ForceLawSpec     s;
    s.cor            = 0.7;
    s.effective_mass = m_eff;

    s.law       = "linear";
    s.stiffness = k_linear;
    EXPECT_NEAR(first_contact(*make_force_law(s)).force, k_linear * d, round_off * k_linear * d);

    s.law          = "kelvin_voigt";
    const double c = 2.0 * kelvin_voigt_damping_ratio(0.7) * std::sqrt(k_linear * m_eff);
    EXPECT_NEAR(first_contact(*make_force_law(s)).force, k_linear * d + c * v, round_off * 1e7);

    s.law       = "jankowski";
    s.stiffness = k_hertz;
    const double c_j =
      2.0 * jankowski_damping_ratio(0.7) * std::sqrt(k_hertz * std::sqrt(d) * m_eff);
    const double hertz_d = k_hertz * std::pow(d, 1.5);
    EXPECT_NEAR(first_contact(*make_force_law(s)).force, hertz_d + c_j * v, round_off * 1e7);

    s.law                   = "hertzdamp";
    const ForceResponse r_h = first_contact(*make_force_law(s));
    EXPECT_NEAR(r_h.force, hertz_d * (1.0 + 0.75 * (1.0 - 0.49)), round_off * 1e7);
    EXPECT_EQ(r_h.damping, 0.0) << "v_imp follows δ̇ at the first contact trial";

    s.law = "hysteretic";
    EXPECT_NEAR(first_contact(*make_force_law(s)).force, hertz_d, round_off * hertz_d);
  }

  TEST(FirstContact, LawsThatNeedImpactVelocityRefuseEnteringWhileOpening)
  {
    HertzdampLaw law({k_hertz, 1.5, 0.7, false});
    law.set_trial(-1e-3, 0.5);
    law.commit();
    EXPECT_THROW(law.set_trial(1e-3, -0.5), std::domain_error);
    EXPECT_FALSE(law.in_contact());
  }

  TEST(KelvinVoigt, ForceTurnsTensileBeforeSeparation)
  {
    KelvinVoigtLaw law({k_linear, 0.5, m_eff});
    first_contact(law, 5e-3, 1.0);
    law.commit();
    const ForceResponse r = law.set_trial(1e-4, -1.0); // nearly separated, opening at 1 m/s
    EXPECT_NEAR(r.force, k_linear * 1e-4 - law.damping_coefficient(), round_off * 1e7);
    EXPECT_LT(r.force, 0.0) << "Kelvin-Voigt's tension is the model, not a bug";
  }

  TEST(ModifiedKelvinVoigt, KeepsTheRemainingDeformationAsPermanentIndentation)
  {
    ModifiedKelvinVoigtLaw law({k_linear, 0.5, m_eff});
    first_contact(law, 5e-3, 1.0);
    law.commit();
    law.set_trial(5e-3, 0.0); // turning point: the dashpot does no work across it
    law.commit();
    const double c = law.damping_coefficient();
    // At δ = 2 mm opening at 1 m/s, k·δ + c·δ̇ < 0: the contact ends there.
    ASSERT_LT(k_linear * 2e-3 - c, 0.0);
    const ForceResponse r = law.set_trial(2e-3, -1.0);
    EXPECT_EQ(r.force, 0.0);
    EXPECT_EQ(r.stiffness, 0.0);
    const double dissipated_before = law.dissipated_energy();
    law.commit();
    EXPECT_FALSE(law.in_contact());
    EXPECT_EQ(law.permanent_indentation(), 2e-3);
    // The spring energy ½k·(2 mm)² is lost with the permanent set; the dashpot did no work (its
    // force was 0 at the turning point and is 0 after the switch).
    EXPECT_NEAR(law.dissipated_energy() - dissipated_before,
                0.5 * k_linear * 4e-6,
                round_off * 1e4);
    // The gap is wider by δ_p from now on.
    EXPECT_EQ(law.set_trial(1.5e-3, 0.5).force, 0.0);
    law.commit();
    EXPECT_NEAR(law.set_trial(3e-3, 0.5).force, k_linear * 1e-3 + c * 0.5, round_off * 1e7);
  }

  TEST(Hysteretic, RestitutionForceIsReducedByTheRateAndClippedAtZero)
  {
    HystereticLaw law({k_hertz, 1.5, 0.7, m_eff, std::nullopt});
    first_contact(law, 5e-3, 1.0);
    law.commit();
    const double c_imp  = impact_damping_coefficient(0.7, m_eff, 1.0);
    const double spring = k_hertz * std::pow(4e-3, 1.5);
    EXPECT_NEAR(law.set_trial(4e-3, -0.3).force, spring * (1.0 - 0.3 * c_imp), round_off * 1e7);
    EXPECT_EQ(law.set_trial(4e-3, -1.1 / c_imp).force, 0.0);
    EXPECT_EQ(law.set_trial(4e-3, -1.1 / c_imp).damping, 0.0);
    EXPECT_EQ(law.impact_velocity(), 1.0);
  }

  TEST(Hysteretic, QuasiStaticLoopAreaEqualsClosedForm)
  {
    // Load at +r to δ_m, unload at −r: area = C·r·k·δ_m^(n+1)/(n+1) (for C·r < 1).
    constexpr double a1 = 0.8, cor = 0.6, r = 0.5, delta_m = 8e-3;
    constexpr int    n_steps     = 100000;
    constexpr double trapezoid_o = 1e-4; ///< the rate jumps at the turn: O(1/n_steps) error
    HystereticLaw    law({k_hertz, 1.5, cor, m_eff, a1});
    const double     c_imp = a1 * (1.0 - cor * cor);
    for (int i = 0; i <= 2 * n_steps + 1; ++i)
    {
      const bool   loading = i <= n_steps;
      const double delta = loading ? delta_m * i / n_steps : delta_m * (2 * n_steps - i) / n_steps;
      law.set_trial(delta, i == n_steps ? 0.0 : (loading ? r : -r));
      law.commit();
    }
    EXPECT_FALSE(law.in_contact());
    const double area = c_imp * r * k_hertz * std::pow(delta_m, 2.5) / 2.5;
    EXPECT_NEAR(law.dissipated_energy(), area, trapezoid_o * area);
  }

  TEST(Hertzdamp, YeOptionUsesItsOwnDampingFactor)
  {
    HertzdampLaw md({k_hertz, 1.5, 0.6, false});
    HertzdampLaw ye({k_hertz, 1.5, 0.6, true});
    EXPECT_NEAR(md.damping_factor(), 0.75 * (1.0 - 0.36), round_off);
    EXPECT_NEAR(ye.damping_factor(), 8.0 * 0.4 / (5.0 * 0.6), round_off);
    // Later in the contact: F = k·δ^n·(1 + β·δ̇/v_imp).
    first_contact(ye, 5e-3, 2.0);
    ye.commit();
    const double spring = k_hertz * std::pow(4e-3, 1.5);
    EXPECT_NEAR(ye.set_trial(4e-3, 1.0).force,
                spring * (1.0 + ye.damping_factor() * 0.5),
                round_off * 1e7);
  }

  TEST(Bumper, WallTakesOverBeyondUltimateDeformationContinuously)
  {
    const double k_b = bumper_stiffness(0.0225, 55835e3, 0.05, 2.65, 4);
    BumperLaw    law({k_b, 2.65, 0.0375, 1.5e9, 0.7, m_eff, std::nullopt});
    first_contact(law, 0.01, 1.0);
    law.commit();
    const double f_u   = k_b * std::pow(0.0375, 2.65);
    const double below = law.set_trial(0.0375 * (1.0 - 1e-12), 0.5).force;
    const double above = law.set_trial(0.0375 * (1.0 + 1e-12), 0.5).force;
    EXPECT_NEAR(below, f_u, 1e-9 * f_u);
    EXPECT_NEAR(above, f_u, 1e-9 * f_u);
    EXPECT_NEAR(law.set_trial(0.04, 0.5).force, f_u + 1.5e9 * 0.0025, round_off * 1e8);
    EXPECT_EQ(law.set_trial(0.04, 0.5).stiffness, 1.5e9);
    EXPECT_EQ(law.stability_stiffness(0.05), std::max(2.65 * k_b * std::pow(0.0375, 1.65), 1.5e9));
  }

  TEST(StoredEnergy, IsThePotentialOfTheElasticPart)
  {
    ForceLawSpec s;
    s.law       = "linear";
    s.stiffness = k_linear;
    auto linear = make_force_law(s);
    first_contact(*linear, 4e-3);
    linear->commit();
    EXPECT_NEAR(linear->stored_energy(), 0.5 * k_linear * 16e-6, round_off * 1e4);
    s.law            = "hysteretic";
    s.stiffness      = k_hertz;
    s.effective_mass = m_eff;
    auto hertz       = make_force_law(s);
    first_contact(*hertz, 4e-3);
    hertz->commit();
    EXPECT_NEAR(hertz->stored_energy(), k_hertz * std::pow(4e-3, 2.5) / 2.5, round_off * 1e4);
  }

  TEST(InitialStiffness, BoundsTheTangentAndIncludesTheDashpotForLinearViscousLaws)
  {
    // Kelvin-Voigt: k/(sqrt(1+ξ²) − ξ)² so that 2/sqrt(k_t/m) is the damped CDM limit.
    KelvinVoigtLaw kv({k_linear, 0.3, m_eff});
    const double   xi = kelvin_voigt_damping_ratio(0.3);
    EXPECT_NEAR(kv.stability_stiffness(0.01),
                k_linear / std::pow(std::sqrt(1.0 + xi * xi) - xi, 2),
                round_off * k_linear);
    // Hertz-type laws: n·k·δ_max^(n−1) (times 1 + β for Hertzdamp).
    HystereticLaw hy({k_hertz, 1.5, 0.7, m_eff, std::nullopt});
    EXPECT_NEAR(hy.stability_stiffness(0.01), 1.5 * k_hertz * 0.1, round_off * k_hertz);
    HertzdampLaw hd({k_hertz, 1.5, 0.7, false});
    EXPECT_NEAR(hd.stability_stiffness(0.01),
                1.5 * k_hertz * 0.1 * (1.0 + hd.damping_factor()),
                round_off * k_hertz);
    EXPECT_THROW(hy.stability_stiffness(0.0), std::invalid_argument);
  }
} // namespace

namespace
{
  /// max |u| over the last 100 of n steps of the CDM with backward-difference damping,
  /// u_{n+1} = 2u_n − u_{n−1} − Ω²·u_n − 2ξΩ·(u_n − u_{n−1}), Ω = ω·Δt, from u_0 = u_{−1} = 1.
  double late_amplitude(double omega_dt, double xi, int n)
  {
    double u_nm1 = 1.0, u_n = 1.0, late = 0.0;
    for (int i = 0; i < n; ++i)
    {
      const double u_np1 =
        2.0 * u_n - u_nm1 - omega_dt * omega_dt * u_n - 2.0 * xi * omega_dt * (u_n - u_nm1);
      u_nm1 = u_n;
      u_n   = u_np1;
      if (!std::isfinite(u_n))
        return std::numeric_limits<double>::infinity();
      if (i >= n - 100)
        late = std::max(late, std::abs(u_n));
    }
    return late;
  }

  TEST(CdmDampingFactor, IsTheStabilityLimitOfTheBackwardDifferenceDashpot)
  {
    // Stable just below Ω_cr = 2·(sqrt(1 + ξ²) − ξ), unstable just above: the reason why
    // stability_stiffness() of laws 2-4 divides k by the factor squared.
    constexpr double margin = 0.01;
    for (const double cor : {0.1, 0.3, 0.7, 0.95})
    {
      const double xi       = kimp::lumped::kelvin_voigt_damping_ratio(cor);
      const double omega_cr = 2.0 * kimp::lumped::cdm_damping_factor(xi);
      EXPECT_LT(late_amplitude((1.0 - margin) * omega_cr, xi, 20000), 1.0) << "COR " << cor;
      EXPECT_GT(late_amplitude((1.0 + margin) * omega_cr, xi, 20000), 1e3) << "COR " << cor;
    }
  }
} // namespace
