// Factory of the contact laws 1-7 (docs/physics.md §1).
#include "lumped/laws/force_law_factory.h"

#include <sstream>
#include <stdexcept>

#include "lumped/laws/bumper_law.h"
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
    /// Laws 1-4 have a fixed exponent: a different one given explicitly is an input error.
    void require_fixed_exponent(const ForceLawSpec &spec, double fixed)
    {
      if (spec.exponent)
        detail::require_parameter(*spec.exponent == fixed,
                                  spec.law,
                                  "exponent n",
                                  *spec.exponent,
                                  "",
                                  fixed == 1.0 ? "fixed at 1 for this law" :
                                                 "fixed at 1.5 for this law");
    }
  } // namespace

  const std::vector<std::string> &force_law_names()
  {
    static const std::vector<std::string> names = {"linear",
                                                   "kelvin_voigt",
                                                   "modified_kelvin_voigt",
                                                   "jankowski",
                                                   "hertzdamp",
                                                   "hysteretic",
                                                   "bumper"};
    return names;
  }

  std::unique_ptr<ForceLaw> make_force_law(const ForceLawSpec &spec)
  {
    const std::string &law = spec.law;
    // The parameters by their symbols; n(d): the exponent given, or the law's default d.
    const double           k = spec.stiffness, cor = spec.cor, m_eff = spec.effective_mass;
    const auto             n = [&](double d) { return spec.exponent.value_or(d); };
    const DashpotLawParams dashpot{k, cor, m_eff};
    if (law == "linear")
    {
      require_fixed_exponent(spec, 1.0);
      return std::make_unique<LinearElasticLaw>(LinearElasticLaw::Params{k});
    }
    if (law == "kelvin_voigt")
    {
      require_fixed_exponent(spec, 1.0);
      return std::make_unique<KelvinVoigtLaw>(dashpot);
    }
    if (law == "modified_kelvin_voigt")
    {
      require_fixed_exponent(spec, 1.0);
      return std::make_unique<ModifiedKelvinVoigtLaw>(dashpot);
    }
    if (law == "jankowski")
    {
      require_fixed_exponent(spec, 1.5);
      return std::make_unique<JankowskiLaw>(dashpot);
    }
    if (law == "hertzdamp")
      return std::make_unique<HertzdampLaw>(
        HertzdampLaw::Params{k, n(1.5), cor, spec.hertzdamp_ye});
    if (law == "hysteretic")
      return std::make_unique<HystereticLaw>(
        HystereticLaw::Params{k, n(1.5), cor, m_eff, spec.impact_a1});
    if (law == "bumper")
    {
      const double delta_u = spec.bumper_ultimate_deformation, k_w = spec.bumper_wall_stiffness;
      return std::make_unique<BumperLaw>(
        BumperLaw::Params{k, n(2.65), delta_u, k_w, cor, m_eff, spec.impact_a1});
    }

    std::ostringstream msg;
    msg << "force law: law = '" << law << "' (must be one of";
    for (const auto &known : force_law_names())
      msg << " '" << known << "'";
    msg << ")";
    throw std::invalid_argument(msg.str());
  }
} // namespace kimp::lumped
