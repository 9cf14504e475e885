// The impact laws' traits (lumped/laws/law_traits.h) against the laws themselves: every law is
// listed, made and checked from its traits entry alone, so a new law needs no other edit here.
#include <cmath>
#include <gtest/gtest.h>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/law_traits.h"

namespace
{
  using kimp::lumped::ForceLawSpec;
  using kimp::lumped::LawTraits;
  using kimp::lumped::make_force_law;

  constexpr double k_any = 2.5e9;   // N/m^n, any k > 0
  constexpr double m_any = 144.8e3; // kg, 280 t against 300 t
  /// Round-off of F(2δ)/F(δ) = 2^n computed through std::pow inside the law.
  constexpr double ratio_tolerance = 1e-12;

  /// A spec with every parameter the traits list at its default (k and m_eff: values > 0).
  ForceLawSpec spec_of(const LawTraits &t)
  {
    ForceLawSpec s;
    s.law = std::string(t.name);
    for (const auto &p : t.parameters)
    {
      if (p.name == "k")
        s.stiffness = k_any;
      else if (p.name == "cor")
        s.cor = *p.default_value;
      else if (p.name == "m_eff")
        s.effective_mass = m_any;
      else if (p.name == "delta_u")
        s.bumper_ultimate_deformation = *p.default_value;
      else if (p.name == "k_w")
        s.bumper_wall_stiffness = *p.default_value;
      else if (p.name == "ye")
        s.hertzdamp_ye = *p.default_value != 0.0;
    }
    return s;
  }

  /// F of the first trial from the virgin state at δ = 1 mm closing at 0.5 m/s.
  double first_force(const ForceLawSpec &s)
  {
    return make_force_law(s)->set_trial(1e-3, 0.5).force;
  }

  /// F along a short impact: approach at 0.5 m/s to δ = 1 mm and 2 mm (committed), then a
  /// trial of the restitution at 1.5 mm opening at 0.3 m/s (laws 6-7 damp only there, law 4
  /// only on approach).
  std::vector<double> impact_forces(const ForceLawSpec &s)
  {
    const auto          law = make_force_law(s);
    std::vector<double> f;
    for (const auto &[delta, rate] : {std::pair{1e-3, 0.5}, std::pair{2e-3, 0.5}})
    {
      f.push_back(law->set_trial(delta, rate).force);
      law->commit();
    }
    f.push_back(law->set_trial(1.5e-3, -0.3).force);
    return f;
  }

  TEST(LawTraits, ListsTheFactorysLawsInOrderWithTheirNumbers)
  {
    const auto &traits = kimp::lumped::law_traits();
    ASSERT_EQ(traits.size(), kimp::lumped::force_law_names().size());
    std::set<std::string> class_names;
    for (std::size_t i = 0; i < traits.size(); ++i)
    {
      EXPECT_EQ(traits[i].name, kimp::lumped::force_law_names()[i]);
      EXPECT_EQ(traits[i].number, static_cast<int>(i) + 1) << traits[i].name;
      EXPECT_TRUE(class_names.insert(std::string(traits[i].class_name)).second);
      EXPECT_EQ(&kimp::lumped::law_traits(traits[i].name), &traits[i]);
      ASSERT_TRUE(traits[i].has_parameter("k")) << traits[i].name;
    }
    EXPECT_THROW(kimp::lumped::law_traits("kelvin-voigt"), std::invalid_argument);
    EXPECT_EQ(kimp::lumped::find_law_traits("kelvin-voigt"), nullptr);
  }

  TEST(LawTraits, EveryLawIsMadeFromItsTraitsAndBearsItsName)
  {
    for (const LawTraits &t : kimp::lumped::law_traits())
    {
      const auto law = make_force_law(spec_of(t));
      EXPECT_EQ(law->name(), t.name);
      EXPECT_GT(first_force(spec_of(t)), 0.0) << t.name;
    }
  }

  TEST(LawTraits, TheDefaultExponentIsTheLawsPowerOfTheDeformation)
  {
    // After a committed first contact, a trial at rest (δ̇ = 0: no damping term in any law)
    // gives F = k·δ^n below δ_u: F(2δ)/F(δ) = 2^n.
    for (const LawTraits &t : kimp::lumped::law_traits())
    {
      const auto law = make_force_law(spec_of(t));
      law->set_trial(1e-4, 0.5);
      law->commit();
      const double f1 = law->set_trial(1e-3, 0.0).force, f2 = law->set_trial(2e-3, 0.0).force;
      EXPECT_NEAR(f2 / f1, std::pow(2.0, t.default_exponent), ratio_tolerance) << t.name;
    }
  }

  TEST(LawTraits, TheExponentIsFixedExactlyWhereTheTraitsSaySo)
  {
    for (const LawTraits &t : kimp::lumped::law_traits())
    {
      ForceLawSpec s = spec_of(t);
      s.exponent     = t.default_exponent + 0.25;
      if (t.fixed_exponent())
      {
        EXPECT_THROW(make_force_law(s), std::invalid_argument) << t.name;
      }
      else
      {
        EXPECT_NE(first_force(s), first_force(spec_of(t))) << t.name;
      }
      s.exponent = t.default_exponent; // the fixed value itself may be given
      EXPECT_NO_THROW(make_force_law(s)) << t.name;
    }
  }

  TEST(LawTraits, ALawUsesTheCorAndTheMassExactlyWhereTheTraitsSaySo)
  {
    for (const LawTraits &t : kimp::lumped::law_traits())
    {
      const ForceLawSpec base = spec_of(t);
      ForceLawSpec       cor = base, mass = base;
      cor.cor             = 0.5;
      mass.effective_mass = 4.0 * m_any;
      EXPECT_EQ(impact_forces(cor) != impact_forces(base), t.uses_cor()) << t.name;
      EXPECT_EQ(impact_forces(mass) != impact_forces(base), t.uses_effective_mass()) << t.name;
    }
  }

  TEST(LawTraits, ParameterDefaultsAreTheThesisOnes)
  {
    for (const LawTraits &t : kimp::lumped::law_traits())
      for (const auto &p : t.parameters)
      {
        EXPECT_EQ(p.required, p.name == "k") << t.name << "." << p.name;
        if (p.name == "cor")
        {
          EXPECT_EQ(*p.default_value, kimp::lumped::thesis_cor);
        }
      }
    EXPECT_EQ(ForceLawSpec{}.cor, kimp::lumped::thesis_cor);
  }
} // namespace
