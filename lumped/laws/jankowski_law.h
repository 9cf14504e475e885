// Impact law 4, non-linear viscoelastic (Jankowski 2005, 2006): F = k·δ^1.5 + c(t)·δ̇ while
// approaching (δ̇ > 0), F = k·δ^1.5 while restoring; c = 2ξ·sqrt(k·sqrt(δ)·m_eff),
// ξ = (9√5/2)·(1 − COR²)/(COR·(COR·(9π − 16) + 16)) (thesis eqs. 2.9-2.12).
#pragma once

#include <string>

#include "lumped/laws/contact_law.h"

namespace kimp::lumped
{
  /// ξ of (2.12), Jankowski's approximate relation to the COR.
  /// @throws std::invalid_argument unless 0 < COR <= 1 (ξ → ∞ as COR → 0).
  double jankowski_damping_ratio(double cor);

  /**
   * Hertz spring with a dashpot active only during approach (no tension).
   *
   * | parameter | meaning                            | unit     | range  |
   * |-----------|------------------------------------|----------|--------|
   * | k         | Hertz stiffness                    | N/m^1.5  | > 0    |
   * | cor       | nominal coefficient of restitution | -        | (0, 1] |
   * | m_eff     | m1·m2/(m1 + m2) of the pair        | kg       | > 0    |
   *
   * Tangent: dF/dδ = 1.5k·δ^0.5 + ¼·2ξ·sqrt(k·m_eff)·δ^−0.75·δ̇ while approaching (unbounded as
   * δ → 0 with δ̇ > 0). dF/dδ̇ jumps from c to 0 at δ̇ = 0 (kink, F continuous).
   * Limitation: (2.12) is approximate, the effective COR deviates from the nominal one by a few
   * per cent (measured in tests/lumped/two_body_test.cc).
   */
  class JankowskiLaw final : public ContactLaw<JankowskiLaw, DashpotLawParams>
  {
  public:
    static constexpr const char *law_name = "jankowski";

    /// @throws std::invalid_argument naming the bad parameter.
    explicit JankowskiLaw(const Params &params);

    /// 1.5k·sqrt(δ_max)/(sqrt(1+ξ'²) − ξ')², N/m, with ξ' = ξ/sqrt(1.5) the damping ratio
    /// relative to the tangent stiffness; the δ^−0.75 rate term of the tangent is left out.
    /// @throws std::invalid_argument if max_deformation <= 0.
    double stability_stiffness(double max_deformation) const override;

    /// The law itself, called by ContactLaw::set_trial (see there for the contract).
    void evaluate(const ContactState &committed, ContactState &trial) const;

  private:
    double damping_ratio_;
    double damping_scale_; ///< 2ξ·sqrt(k·m_eff), c = damping_scale_·δ^0.25
  };
} // namespace kimp::lumped
