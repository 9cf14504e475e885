// Shared contract of every contact law (docs/architecture.md "Tests"): idempotent trials, exact
// revert, identical clones, no force with the gap open, exact tangents, non-decreasing dissipation.
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "lumped/laws/bumper_law.h"
#include "lumped/laws/force_law_factory.h"

namespace
{
  using kimp::lumped::ForceLaw;
  using kimp::lumped::ForceLawSpec;
  using kimp::lumped::ForceResponse;

  /// Relative tolerance of the finite-difference tangents (h = 1e-7 of the path amplitude).
  constexpr double fd_tolerance = 1e-5;
  /// Relative jump between one-sided differences that marks a kink (branch change).
  constexpr double kink_threshold = 1e-3;
  /// At most this fraction of the in-contact samples may be kinks (branch changes are rare).
  constexpr double max_kink_fraction = 0.1;

  struct PathSample
  {
    double deformation; ///< m
    double rate;        ///< m/s
  };

  /**
   * δ(t) = A·(sin ωt − offset) over `periods` periods with exact rates: approach, restitution,
   * separation, open gap, re-contact. Turning points are sampled exactly with δ̇ = 0 there, so
   * the trapezoid rule cannot straddle one.
   */
  std::vector<PathSample> make_path(double amplitude, double period, double offset, int periods)
  {
    constexpr int           n_per_period = 400;
    constexpr double        pi           = 3.14159265358979323846;
    const double            omega        = 2.0 * pi / period;
    std::vector<PathSample> path;
    for (int i = 0; i <= periods * n_per_period; ++i)
    {
      const double phase = omega * i * period / n_per_period;
      const bool   turn  = (4 * i) % n_per_period == 0 && ((4 * i) / n_per_period) % 2 == 1;
      path.push_back(
        {amplitude * (std::sin(phase) - offset), turn ? 0.0 : amplitude * omega * std::cos(phase)});
    }
    return path;
  }

  void expect_same_response(const ForceResponse &a, const ForceResponse &b, const std::string &what)
  {
    EXPECT_EQ(a.force, b.force) << what;
    EXPECT_EQ(a.stiffness, b.stiffness) << what;
    EXPECT_EQ(a.damping, b.damping) << what;
  }

  void expect_same_committed(const ForceLaw &a, const ForceLaw &b, const std::string &what)
  {
    EXPECT_EQ(a.dissipated_energy(), b.dissipated_energy()) << what;
    EXPECT_EQ(a.stored_energy(), b.stored_energy()) << what;
    EXPECT_EQ(a.permanent_indentation(), b.permanent_indentation()) << what;
    EXPECT_EQ(a.impact_velocity(), b.impact_velocity()) << what;
    EXPECT_EQ(a.in_contact(), b.in_contact()) << what;
  }

  /// Central difference of the force along δ (wrt_rate false) or δ̇, from the committed state;
  /// sets `kink` when the one-sided differences disagree.
  double finite_difference(ForceLaw &law, const PathSample &s, double h, bool wrt_rate, bool &kink)
  {
    const auto force = [&](double dx)
    {
      return wrt_rate ? law.set_trial(s.deformation, s.rate + dx).force :
                        law.set_trial(s.deformation + dx, s.rate).force;
    };
    const double f_minus = force(-h), f_0 = force(0.0), f_plus = force(h);
    const double forward = (f_plus - f_0) / h, backward = (f_0 - f_minus) / h;
    const double scale = std::abs(forward) + std::abs(backward) + std::abs(f_0) / h * 1e-12;
    kink               = std::abs(forward - backward) > kink_threshold * scale;
    return (f_plus - f_minus) / (2.0 * h);
  }

  /**
   * Apply the whole force-law contract along `path`. `law` must be in its virgin state.
   */
  void expect_force_law_invariants(ForceLaw &law, const std::vector<PathSample> &path)
  {
    const auto virgin  = law.clone();
    double     scale_d = 0.0, scale_v = 0.0;
    for (const auto &s : path)
    {
      scale_d = std::max(scale_d, std::abs(s.deformation));
      scale_v = std::max(scale_v, std::abs(s.rate));
    }
    const double h_d = 1e-7 * scale_d, h_v = 1e-7 * scale_v;

    std::unique_ptr<ForceLaw> twin;
    double                    previous_dissipation = 0.0;
    int                       n_contact = 0, n_kinks = 0, n_open = 0;
    bool                      recontact = false, was_open_after_contact = false;
    for (std::size_t i = 0; i < path.size(); ++i)
    {
      const PathSample &s     = path[i];
      const std::string where = law.name() + " at sample " + std::to_string(i) +
                                ": delta = " + std::to_string(s.deformation) +
                                " m, rate = " + std::to_string(s.rate) + " m/s";
      const bool gap_open = s.deformation <= law.permanent_indentation();

      // Derivatives first (they only use trials), then the trial that will be committed.
      bool         kink_d = false, kink_v = false;
      const double fd_d = finite_difference(law, s, h_d, false, kink_d);
      const double fd_v = finite_difference(law, s, h_v, true, kink_v);

      law.set_trial(s.deformation + 0.3 * scale_d, std::abs(s.rate) + 0.5 * scale_v); // unrelated
      const ForceResponse r = law.set_trial(s.deformation, s.rate);
      expect_same_response(r, law.set_trial(s.deformation, s.rate), "repeated trial, " + where);
      if (twin)
        expect_same_response(r, twin->set_trial(s.deformation, s.rate), "clone, " + where);

      if (gap_open)
      {
        ++n_open;
        EXPECT_EQ(r.force, 0.0) << where;
        EXPECT_EQ(r.stiffness, 0.0) << where;
        EXPECT_EQ(r.damping, 0.0) << where;
      }
      if (r.force != 0.0 || r.stiffness != 0.0)
      {
        ++n_contact;
        if (kink_d || kink_v)
          ++n_kinks;
        const double tol_d = fd_tolerance * (std::abs(r.stiffness) + std::abs(r.force) / scale_d);
        const double tol_v = fd_tolerance * (std::abs(r.damping) + std::abs(r.force) / scale_v);
        if (!kink_d)
        {
          EXPECT_NEAR(r.stiffness, fd_d, tol_d) << "dF/d(delta), " << where;
        }
        if (!kink_v)
        {
          EXPECT_NEAR(r.damping, fd_v, tol_v) << "dF/d(rate), " << where;
        }
      }

      // The clone copies the trial state too: committing it must give the same history.
      twin = law.clone();
      twin->commit();
      law.commit();
      expect_same_committed(law, *twin, "clone after commit, " + where);

      // A discarded trial leaves the committed state untouched.
      law.set_trial(s.deformation + 0.5 * scale_d, scale_v);
      law.revert_to_last_commit();
      law.commit();
      expect_same_committed(law, *twin, "revert_to_last_commit, " + where);

      EXPECT_GE(law.dissipated_energy(), previous_dissipation) << where;
      EXPECT_GE(law.stored_energy(), 0.0) << where;
      previous_dissipation = law.dissipated_energy();

      if (law.in_contact() && was_open_after_contact)
        recontact = true;
      if (!law.in_contact() && n_contact > 0)
        was_open_after_contact = true;
    }
    std::cout << law.name() << ": " << path.size() << " samples, " << n_open << " open, "
              << n_contact << " with force, " << n_kinks << " at kinks (tangent check skipped)\n";
    // The path must have exercised what it claims to.
    EXPECT_GT(n_open, 0) << law.name();
    EXPECT_GT(n_contact, 20) << law.name();
    EXPECT_TRUE(recontact) << law.name() << ": path never re-entered contact";
    EXPECT_LE(n_kinks, max_kink_fraction * n_contact) << law.name() << ": kinks " << n_kinks;

    // revert_to_start gives the virgin law back, bit for bit, along the first contact.
    law.revert_to_start();
    EXPECT_EQ(law.dissipated_energy(), 0.0);
    EXPECT_EQ(law.permanent_indentation(), 0.0);
    EXPECT_FALSE(law.in_contact());
    for (std::size_t i = 0; i < path.size() / 2; ++i)
    {
      expect_same_response(law.set_trial(path[i].deformation, path[i].rate),
                           virgin->set_trial(path[i].deformation, path[i].rate),
                           "revert_to_start, sample " + std::to_string(i));
      law.commit();
      virgin->commit();
      expect_same_committed(law, *virgin, "revert_to_start, sample " + std::to_string(i));
    }
  }

  struct ContractCase
  {
    std::string  label;
    ForceLawSpec spec;
    double       amplitude; ///< m
    double       period;    ///< s
  };

  std::vector<ContractCase> contract_cases()
  {
    constexpr double          k_linear = 2.5e9;     // 2500 kN/mm
    constexpr double          k_hertz  = 2.3717e10; // 750 kN/mm^1.5
    constexpr double          m_eff    = 144.8e3;   // 280 t against 300 t
    std::vector<ContractCase> cases;
    const auto add = [&](const std::string &label, ForceLawSpec spec, double amplitude)
    {
      spec.effective_mass = m_eff;
      cases.push_back({label, spec, amplitude, 0.1});
    };
    ForceLawSpec s;
    s.cor       = 0.5;
    s.stiffness = k_linear;
    for (const char *name : {"linear", "kelvin_voigt", "modified_kelvin_voigt"})
    {
      s.law = name;
      add(name, s, 0.01);
    }
    s.stiffness = k_hertz;
    for (const char *name : {"jankowski", "hertzdamp", "hysteretic"})
    {
      s.law = name;
      add(name, s, 0.01);
    }
    s.law          = "hertzdamp";
    s.hertzdamp_ye = true;
    add("hertzdamp_ye", s, 0.01);
    s.hertzdamp_ye = false;
    s.law          = "hysteretic";
    s.impact_a1    = 2.0;
    add("hysteretic_a1", s, 0.01);
    s.impact_a1 = std::nullopt;
    s.law       = "bumper";
    s.stiffness = kimp::lumped::bumper_stiffness(0.15 * 0.15, 55835e3, 0.05, 2.65, 4);
    s.bumper_ultimate_deformation = 0.75 * 0.05;
    s.bumper_wall_stiffness       = 1.5e9;
    add("bumper", s, 0.05); // reaches past δ_u = 37.5 mm into the wall branch
    return cases;
  }

  void PrintTo(const ContractCase &c, std::ostream *os)
  {
    *os << c.label;
  }

  class ForceLawContract : public ::testing::TestWithParam<ContractCase>
  {
  };

  TEST_P(ForceLawContract, InvariantsHoldAlongApproachRestitutionSeparationRecontact)
  {
    const ContractCase &c   = GetParam();
    const auto          law = kimp::lumped::make_force_law(c.spec);
    expect_force_law_invariants(*law, make_path(c.amplitude, c.period, 0.2, 2));
  }

  /// A new law of law_traits() comes with its contract case above.
  TEST(ForceLawContract, EveryLawOfTheTraitsHasAContractCase)
  {
    for (const kimp::lumped::LawTraits &t : kimp::lumped::law_traits())
    {
      bool found = false;
      for (const ContractCase &c : contract_cases())
        found = found || c.spec.law == t.name;
      EXPECT_TRUE(found) << "law " << t.name << " has no case in contract_cases()";
    }
  }

  INSTANTIATE_TEST_SUITE_P(AllLaws,
                           ForceLawContract,
                           ::testing::ValuesIn(contract_cases()),
                           [](const ::testing::TestParamInfo<ContractCase> &param_info)
                           { return param_info.param.label; });
} // namespace
