// The traits table of the impact laws 1-7 (docs/physics.md §1): one entry per law.
#include "lumped/laws/law_traits.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "lumped/laws/bumper_law.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/hertzdamp_law.h"
#include "lumped/laws/hysteretic_law.h"
#include "lumped/laws/jankowski_law.h"
#include "lumped/laws/kelvin_voigt_law.h"
#include "lumped/laws/linear_elastic_law.h"
#include "lumped/laws/modified_kelvin_voigt_law.h"

namespace kimp::lumped
{
  namespace
  {
    // The parameters by keyword, shared by the entries below.
    const LawParameter k{"k", "N/m^n", true, std::nullopt, "stiffness k"};
    const LawParameter cor{"cor", "", false, thesis_cor, "nominal coefficient of restitution"};
    const LawParameter m_eff{"m_eff", "kg", false, 0.0, "effective mass m1·m2/(m1 + m2)"};
    const LawParameter exponent{"exponent", "", false, std::nullopt, "exponent n"};
    const LawParameter ye{"ye", "flag", false, 0.0, "Ye et al.'s damping instead"};
    const LawParameter a1{"a1", "s/m", false, std::nullopt, "C_imp = a1·(1 − COR²)"};
    /// δ_u and k_w of the thesis' bumpers: ε_u·t = 0.75 × 50 mm, k_w = 1500 kN/mm (ch. 6).
    const LawParameter delta_u{"delta_u", "m", false, 0.0375, "ultimate deformation δ_u"};
    const LawParameter k_w{"k_w", "N/m", false, 1.5e9, "wall stiffness k_w beyond δ_u"};

    DashpotLawParams dashpot(const ForceLawSpec &spec)
    {
      return {spec.stiffness, spec.cor, spec.effective_mass};
    }

    template <class Law>
    std::unique_ptr<ForceLaw> make_dashpot_law(const ForceLawSpec &spec, double /*n*/)
    {
      return std::make_unique<Law>(dashpot(spec));
    }

    std::unique_ptr<ForceLaw> make_linear(const ForceLawSpec &spec, double /*n*/)
    {
      return std::make_unique<LinearElasticLaw>(LinearElasticLaw::Params{spec.stiffness});
    }

    std::unique_ptr<ForceLaw> make_hertzdamp(const ForceLawSpec &spec, double n)
    {
      return std::make_unique<HertzdampLaw>(
        HertzdampLaw::Params{spec.stiffness, n, spec.cor, spec.hertzdamp_ye});
    }

    std::unique_ptr<ForceLaw> make_hysteretic(const ForceLawSpec &spec, double n)
    {
      return std::make_unique<HystereticLaw>(
        HystereticLaw::Params{spec.stiffness, n, spec.cor, spec.effective_mass, spec.impact_a1});
    }

    std::unique_ptr<ForceLaw> make_bumper(const ForceLawSpec &spec, double n)
    {
      return std::make_unique<BumperLaw>(BumperLaw::Params{spec.stiffness,
                                                           n,
                                                           spec.bumper_ultimate_deformation,
                                                           spec.bumper_wall_stiffness,
                                                           spec.cor,
                                                           spec.effective_mass,
                                                           spec.impact_a1});
    }
  } // namespace

  const std::vector<LawTraits> &law_traits()
  {
    static const std::vector<LawTraits> traits = {
      {LinearElasticLaw::law_name,
       1,
       "Linear",
       "Law 1, linear spring: F = kδ (k in N/m).",
       1.0,
       true,
       false,
       {k},
       make_linear},
      {KelvinVoigtLaw::law_name,
       2,
       "KelvinVoigt",
       "Law 2, Kelvin-Voigt: F = kδ + cδ̇, c = 2ξ√(k·m_eff), ξ = −ln e/√(π² + ln² e) (k in N/m).",
       1.0,
       true,
       false,
       {k, cor, m_eff},
       make_dashpot_law<KelvinVoigtLaw>},
      {ModifiedKelvinVoigtLaw::law_name,
       3,
       "ModifiedKelvinVoigt",
       "Law 3, Kelvin-Voigt without tension (ends the contact, keeps a permanent set; k in N/m).",
       1.0,
       true,
       false,
       {k, cor, m_eff},
       make_dashpot_law<ModifiedKelvinVoigtLaw>},
      {JankowskiLaw::law_name,
       4,
       "Jankowski",
       "Law 4, Jankowski's non-linear viscoelastic law: k in N/m^1.5, damping only on approach.",
       1.5,
       true,
       false,
       {k, cor, m_eff},
       make_dashpot_law<JankowskiLaw>},
      {HertzdampLaw::law_name,
       5,
       "Hertzdamp",
       "Law 5, Hertzdamp (Muthukumar & DesRoches): F = kδ^n·(1 + β·δ̇/v_imp), k in N/m^n, n = 1.5 "
       "by default, β = 3(1 − e²)/4 (ye: Ye et al.'s β = 8(1 − e)/(5e)); no m_eff.",
       1.5,
       true,
       false,
       {k, cor, exponent, ye},
       make_hertzdamp},
      {HystereticLaw::law_name,
       6,
       "Hysteretic",
       "Law 6, hysteretic (C_imp of eq. 2.23, or a1·(1 − e²)): k in N/m^n, n = 1.5 by default.",
       1.5,
       true,
       false,
       {k, cor, m_eff, exponent, a1},
       make_hysteretic},
      {BumperLaw::law_name,
       7,
       "Bumper",
       "Law 7, rubber bumper: hysteretic with n = 2.65 up to δ_u (m), then the wall k_w (N/m).",
       2.65,
       false,
       true,
       {k, cor, m_eff, delta_u, k_w, exponent, a1},
       make_bumper},
    };
    return traits;
  }

  bool LawTraits::has_parameter(std::string_view parameter) const
  {
    return std::any_of(parameters.begin(),
                       parameters.end(),
                       [&](const LawParameter &p) { return p.name == parameter; });
  }

  const LawTraits *find_law_traits(std::string_view name)
  {
    for (const LawTraits &t : law_traits())
      if (t.name == name)
        return &t;
    return nullptr;
  }

  const LawTraits &law_traits(std::string_view name, std::string_view what)
  {
    if (const LawTraits *t = find_law_traits(name))
      return *t;
    std::ostringstream msg;
    msg << what << ": law = '" << name << "' (must be one of " << law_name_list(true) << ")";
    throw std::invalid_argument(msg.str());
  }

  std::string law_name_list(bool quoted)
  {
    std::string list;
    for (const LawTraits &t : law_traits())
    {
      if (!list.empty())
        list += quoted ? " " : ", ";
      list += quoted ? "'" + std::string(t.name) + "'" : std::string(t.name);
    }
    return list;
  }
} // namespace kimp::lumped
