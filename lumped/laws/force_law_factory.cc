// Factory of the contact laws 1-7 (docs/physics.md §1): each law is made by its entry of
// law_traits() (lumped/laws/law_traits.cc).
#include "lumped/laws/force_law_factory.h"

#include <sstream>

#include "lumped/laws/contact_law.h"
#include "lumped/laws/law_traits.h"

namespace kimp::lumped
{
  const std::vector<std::string> &force_law_names()
  {
    static const std::vector<std::string> names = []
    {
      std::vector<std::string> out;
      for (const LawTraits &t : law_traits())
        out.emplace_back(t.name);
      return out;
    }();
    return names;
  }

  std::unique_ptr<ForceLaw> make_force_law(const ForceLawSpec &spec)
  {
    const LawTraits &traits = law_traits(spec.law);
    // A law with a fixed exponent given another one explicitly: an input error.
    if (spec.exponent && traits.fixed_exponent())
    {
      std::ostringstream fixed;
      fixed << "fixed at " << traits.default_exponent << " for this law";
      detail::require_parameter(*spec.exponent == traits.default_exponent,
                                spec.law,
                                "exponent n",
                                *spec.exponent,
                                "",
                                fixed.str());
    }
    return traits.make(spec, traits.exponent(spec.exponent));
  }
} // namespace kimp::lumped
