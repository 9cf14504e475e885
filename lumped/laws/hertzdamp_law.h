// Impact law 5, Hertzdamp (Muthukumar & DesRoches 2006): F = k·δ^n + c·δ̇,
// c = 3k(1 − COR²)·δ^n/(4·v_imp) (thesis eqs. 2.13-2.14); option (Ye, Li & Zhu 2009):
// c = ξ·δ^n with ξ = 8k(1 − COR)/(5·COR·v_imp). Both read F = k·δ^n·(1 + β·δ̇/v_imp).
#pragma once

#include <string>

#include "lumped/laws/contact_law.h"

namespace kimp::lumped
{
  /// Parameters of the HertzdampLaw.
  struct HertzdampParams
  {
    double stiffness = 0.0;   ///< k, N/m^n
    double exponent  = 1.5;   ///< n
    double cor       = 1.0;   ///< nominal COR
    bool   ye        = false; ///< Ye et al. (2009) damping instead of (2.14)
  };

  /**
   * Hertz spring with a deformation-dependent dashpot; v_imp is the rate δ̇ at the first trial
   * that enters contact (the caller's backward difference in the MDOF solver), kept until the
   * contact opens again. β = 3(1 − COR²)/4 (Muthukumar-DesRoches) or 8(1 − COR)/(5·COR) (Ye).
   *
   * | parameter | meaning                            | unit    | range  |
   * |-----------|------------------------------------|---------|--------|
   * | k         | Hertz stiffness                    | N/m^n   | > 0    |
   * | n         | exponent (1.5 for Hertz)           | -       | >= 1   |
   * | cor       | nominal coefficient of restitution | -       | (0, 1] |
   * | ye        | use Ye et al.'s ξ instead          | bool    |        |
   *
   * Tangent: at the first contact trial v_imp = δ̇, so F = k·δ^n·(1 + β) and dF/dδ̇ = 0 there.
   * Limitations: the Muthukumar-DesRoches coefficient assumes high COR and misses low target
   * CORs badly (a known flaw, kept); F may turn tensile for δ̇ < −v_imp/β (not clipped).
   */
  class HertzdampLaw final : public ContactLaw<HertzdampLaw, HertzdampParams>
  {
  public:
    static constexpr const char *law_name = "hertzdamp";

    /// @throws std::invalid_argument naming the bad parameter.
    explicit HertzdampLaw(const Params &params);

    /// n·k·δ_max^(n−1)·(1 + β), N/m: the largest dF/dδ for |δ̇| <= v_imp.
    /// @throws std::invalid_argument if max_deformation <= 0 and n > 1.
    double stability_stiffness(double max_deformation) const override;
    /// β of the header formula.
    double damping_factor() const { return beta_; }

    /// The law itself, called by ContactLaw::set_trial (see there for the contract).
    void evaluate(const ContactState &committed, ContactState &trial) const;

  private:
    double beta_;
  };
} // namespace kimp::lumped
