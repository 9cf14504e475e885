// make_force_law (docs/physics.md §1 laws 1-7): names, defaults, and rejection of invalid
// parameters with a message naming the parameter, its value and the admissible range.
#include <cmath>
#include <gtest/gtest.h>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lumped/laws/force_law_factory.h"

namespace
{
  using kimp::lumped::ForceLawSpec;
  using kimp::lumped::make_force_law;

  /// Parameters every law accepts (the COR at its default, 0.7).
  ForceLawSpec valid_spec(const std::string &law)
  {
    ForceLawSpec s;
    s.law                         = law;
    s.stiffness                   = 2.5e9;
    s.effective_mass              = 144.8e3;
    s.bumper_ultimate_deformation = 0.0375;
    s.bumper_wall_stiffness       = 1.5e9;
    return s;
  }

  /// make_force_law(spec) must throw std::invalid_argument whose message contains every piece.
  void expect_rejected(const ForceLawSpec &spec, const std::vector<std::string> &pieces)
  {
    try
    {
      make_force_law(spec);
      ADD_FAILURE() << "law '" << spec.law << "' accepted invalid input, expected: " << pieces[0];
    }
    catch (const std::invalid_argument &e)
    {
      for (const auto &piece : pieces)
        EXPECT_NE(std::string(e.what()).find(piece), std::string::npos)
          << "message '" << e.what() << "' lacks '" << piece << "'";
    }
  }

  TEST(ForceLawFactory, CreatesEveryNamedLawWithThatName)
  {
    ASSERT_EQ(kimp::lumped::force_law_names().size(), 7u);
    for (const auto &name : kimp::lumped::force_law_names())
    {
      const auto law = make_force_law(valid_spec(name));
      EXPECT_EQ(law->name(), name);
      EXPECT_FALSE(law->in_contact()) << name;
      EXPECT_EQ(law->dissipated_energy(), 0.0) << name;
    }
  }

  TEST(ForceLawFactory, UnknownNameListsTheKnownNames)
  {
    ForceLawSpec s = valid_spec("kelvin-voigt");
    expect_rejected(s,
                    {"'kelvin-voigt'",
                     "'linear'",
                     "'kelvin_voigt'",
                     "'modified_kelvin_voigt'",
                     "'jankowski'",
                     "'hertzdamp'",
                     "'hysteretic'",
                     "'bumper'"});
  }

  TEST(ForceLawFactory, RejectsNonPositiveStiffnessForEveryLaw)
  {
    for (const auto &name : kimp::lumped::force_law_names())
      for (const double k : {0.0, -3.0e6})
      {
        ForceLawSpec s = valid_spec(name);
        s.stiffness    = k;
        expect_rejected(s, {name, "= " + (k == 0.0 ? std::string("0") : "-3e+06"), "> 0"});
      }
  }

  TEST(ForceLawFactory, RejectsCorOutsideZeroOne)
  {
    for (const auto &name : kimp::lumped::force_law_names())
    {
      if (name == "linear")
        continue; // no COR
      for (const double cor : {0.0, -0.2, 1.3})
      {
        ForceLawSpec s = valid_spec(name);
        s.cor          = cor;
        expect_rejected(s, {name, "cor", "(0, 1]"});
      }
    }
  }

  TEST(ForceLawFactory, RejectsMissingEffectiveMassWhereTheLawNeedsIt)
  {
    for (const char *name :
         {"kelvin_voigt", "modified_kelvin_voigt", "jankowski", "hysteretic", "bumper"})
    {
      ForceLawSpec s   = valid_spec(name);
      s.effective_mass = 0.0;
      expect_rejected(s, {name, "m_eff = 0 kg", "> 0"});
    }
    ForceLawSpec s   = valid_spec("hertzdamp"); // Hertzdamp does not use m_eff
    s.effective_mass = 0.0;
    EXPECT_NO_THROW(make_force_law(s));
  }

  TEST(ForceLawFactory, RejectsExponentBelowOneAndChangedFixedExponents)
  {
    for (const char *name : {"hertzdamp", "hysteretic", "bumper"})
    {
      ForceLawSpec s = valid_spec(name);
      s.exponent     = 0.9;
      expect_rejected(s, {name, "exponent n = 0.9", ">= 1"});
    }
    ForceLawSpec linear = valid_spec("kelvin_voigt");
    linear.exponent     = 1.5;
    expect_rejected(linear, {"kelvin_voigt", "exponent n = 1.5", "fixed at 1"});
    ForceLawSpec jankowski = valid_spec("jankowski");
    jankowski.exponent     = 2.0;
    expect_rejected(jankowski, {"jankowski", "exponent n = 2", "fixed at 1.5"});
    jankowski.exponent = 1.5;
    EXPECT_NO_THROW(make_force_law(jankowski));
  }

  TEST(ForceLawFactory, RejectsBadBumperAndImpactCoefficientParameters)
  {
    ForceLawSpec s                = valid_spec("bumper");
    s.bumper_ultimate_deformation = -0.01;
    expect_rejected(s, {"bumper", "delta_u = -0.01 m"});
    s                       = valid_spec("bumper");
    s.bumper_wall_stiffness = 0.0;
    expect_rejected(s, {"bumper", "k_w = 0 N/m"});
    s           = valid_spec("hysteretic");
    s.impact_a1 = -1.0;
    expect_rejected(s, {"hysteretic", "a1 = -1 s/m"});
  }

  TEST(ForceLawFactory, RejectsNaNParameters)
  {
    ForceLawSpec s = valid_spec("hysteretic");
    s.cor          = std::nan("");
    expect_rejected(s, {"hysteretic", "cor"});
    s           = valid_spec("linear");
    s.stiffness = std::nan("");
    expect_rejected(s, {"linear", "k = nan"});
  }

  TEST(ForceLawFactory, DefaultExponentsFollowPhysicsSpec)
  {
    // Laws without damping on approach give F = k·δ^n there, which reveals n.
    constexpr double delta = 1e-3, rate = 1e-9;
    for (const auto &[name, n] : std::vector<std::pair<std::string, double>>{{"linear", 1.0},
                                                                             {"hysteretic", 1.5},
                                                                             {"bumper", 2.65}})
    {
      auto law = make_force_law(valid_spec(name));
      law->set_trial(-1e-3, rate);
      law->commit();
      const double expected = 2.5e9 * std::pow(delta, n);
      EXPECT_NEAR(law->set_trial(delta, rate).force, expected, 1e-12 * expected) << name;
    }
  }
} // namespace
