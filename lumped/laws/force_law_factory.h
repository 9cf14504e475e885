// Creation of the contact laws 1-7 of docs/physics.md §1 from a plain parameter struct (SI units),
// keyed by the law's name; per-contact instances then come from ForceLaw::clone().
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lumped/laws/force_law.h"
#include "lumped/laws/law_traits.h"

namespace kimp::lumped
{
  /**
   * Parameters of any contact law; a law reads only the fields of its LawTraits::parameters
   * (lumped/laws/law_traits.h: k = stiffness, cor, m_eff = effective_mass, exponent,
   * ye = hertzdamp_ye, a1 = impact_a1, delta_u = bumper_ultimate_deformation,
   * k_w = bumper_wall_stiffness); k's unit is N/m^n with the law's exponent n.
   */
  struct ForceLawSpec
  {
    std::string           law       = "linear";        ///< one of force_law_names()
    double                stiffness = 0.0;             ///< k (bumper: k_b of all bumpers), N/m^n
    std::optional<double> exponent;                    ///< n; unset: the law's default
    double                cor            = thesis_cor; ///< nominal COR, (0, 1]
    double                effective_mass = 0.0;        ///< m_eff = m1·m2/(m1 + m2), kg
    bool                  hertzdamp_ye   = false;      ///< Hertzdamp with Ye et al.'s damping
    std::optional<double> impact_a1; ///< laws 6-7: C_imp = a1·(1 − COR²) (s/m) instead of 2.23
    double                bumper_ultimate_deformation = 0.0; ///< δ_u = ε_u·t, m
    double                bumper_wall_stiffness       = 0.0; ///< k_w, N/m
  };

  /// The names make_force_law() accepts (the names of law_traits()), in the order of
  /// docs/physics.md §1.
  const std::vector<std::string> &force_law_names();

  /**
   * Create the law named `spec.law`.
   * @throws std::invalid_argument for an unknown name (the message lists the known ones), an
   *         exponent given for a law whose exponent is fixed, or any invalid parameter.
   */
  std::unique_ptr<ForceLaw> make_force_law(const ForceLawSpec &spec);
} // namespace kimp::lumped
