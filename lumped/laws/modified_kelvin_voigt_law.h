// Impact law 3, modified Kelvin-Voigt (thesis eq. 2.16): F = k·(δ − δ_p) + c·δ̇ while that is
// >= 0; when it would turn tensile the contact ends and δ becomes the permanent indentation δ_p.
#pragma once

#include "lumped/laws/kelvin_voigt_law.h"

namespace kimp::lumped
{
  /**
   * Kelvin-Voigt without tension: the thesis' proposal. c = 2ξ·sqrt(k·m_eff) with ξ of (2.7).
   * The deformation left when the force would become tensile is kept as permanent indentation
   * δ_p, which widens the gap of this contact from then on (contact only for δ > δ_p); its
   * elastic energy ½k(δ − δ_p,old)² counts as dissipated at that step.
   *
   * | parameter | meaning                            | unit | range  |
   * |-----------|------------------------------------|------|--------|
   * | k         | contact stiffness                  | N/m  | > 0    |
   * | cor       | nominal coefficient of restitution | -    | (0, 1] |
   * | m_eff     | m1·m2/(m1 + m2) of the pair        | kg   | > 0    |
   *
   * Limitations: the effective COR exceeds the nominal one (the tensile phase is cut off);
   * δ_p depends on the time step through the sample at which the force changes sign.
   */
  class ModifiedKelvinVoigtLaw final : public SpringDashpotLaw<ModifiedKelvinVoigtLaw>
  {
  public:
    static constexpr const char *law_name = "modified_kelvin_voigt";
    using SpringDashpotLaw::SpringDashpotLaw;

    /// The law itself, called by ContactLaw::set_trial (see there for the contract).
    void evaluate(const ContactState &committed, ContactState &trial) const;
  };
} // namespace kimp::lumped
