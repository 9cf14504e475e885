// Impact law 2, Kelvin-Voigt spring-dashpot (Anagnostopoulos 1988): F = k·δ + c·δ̇ for δ > 0,
// c = 2ξ·sqrt(k·m_eff), ξ = −ln(COR)/sqrt(π² + ln²COR) (thesis eqs. 2.5-2.7).
#pragma once

#include <string>

#include "lumped/laws/contact_law.h"

namespace kimp::lumped
{
  /// ξ = −ln(COR)/sqrt(π² + ln²COR) (2.7): the damping ratio whose free linear oscillator returns
  /// to δ = 0 with velocity ratio COR. @throws std::invalid_argument unless 0 < COR <= 1.
  double kelvin_voigt_damping_ratio(double cor);

  /// Factor by which a viscous damping ratio ξ lowers the central-difference stability limit,
  /// Δt_cr = (2/ω)·(sqrt(1 + ξ²) − ξ) (same for the backward-difference velocity); the laws
  /// divide their stiffness by its square so that 2/sqrt(k_t/m) gives the damped limit.
  double cdm_damping_factor(double damping_ratio);

  /// Dashpot coefficient c = 2·ξ(COR)·sqrt(k·m_eff), N·s/m, of laws 2 and 3.
  double kelvin_voigt_dashpot(double stiffness, double cor, double effective_mass);

  /// Stability stiffness k/(sqrt(1 + ξ²) − ξ)², N/m, of laws 2 and 3 (damped CDM limit).
  double kelvin_voigt_stability_stiffness(double stiffness, double cor);

  /**
   * Laws 2 and 3: a linear spring k and the dashpot c = 2ξ(COR)·sqrt(k·m_eff) of (2.7), with the
   * damped central-difference limit as stability stiffness; `Derived` provides law_name and
   * evaluate() (see ContactLaw).
   */
  template <typename Derived>
  class SpringDashpotLaw : public ContactLaw<Derived, DashpotLawParams>
  {
  public:
    /// k/(sqrt(1+ξ²) − ξ)², N/m: k raised so that 2/sqrt(k_t/m_eff) is the damped CDM limit.
    double stability_stiffness(double /*max_deformation*/) const override
    {
      return kelvin_voigt_stability_stiffness(this->params_.stiffness, this->params_.cor);
    }
    /// c = 2ξ·sqrt(k·m_eff), N·s/m.
    double damping_coefficient() const { return damping_; }

    /// @throws std::invalid_argument naming the bad parameter.
    explicit SpringDashpotLaw(const DashpotLawParams &params)
      : ContactLaw<Derived, DashpotLawParams>(params)
    {
      detail::require_dashpot_law(Derived::law_name, params, "N/m");
      damping_ = kelvin_voigt_dashpot(params.stiffness, params.cor, params.effective_mass);
    }

  protected:
    double damping_ = 0.0; ///< c, N·s/m
  };

  /**
   * Linear spring with a linear dashpot, active while δ > 0.
   *
   * | parameter | meaning                            | unit | range  |
   * |-----------|------------------------------------|------|--------|
   * | k         | contact stiffness                  | N/m  | > 0    |
   * | cor       | nominal coefficient of restitution | -    | (0, 1] |
   * | m_eff     | m1·m2/(m1 + m2) of the pair        | kg   | > 0    |
   *
   * Limitation (reproduced on purpose): the dashpot makes F tensile just before separation,
   * pulling the bodies together; law 3 is the thesis' fix.
   */
  class KelvinVoigtLaw final : public SpringDashpotLaw<KelvinVoigtLaw>
  {
  public:
    static constexpr const char *law_name = "kelvin_voigt";
    using SpringDashpotLaw::SpringDashpotLaw;

    /// The law itself, called by ContactLaw::set_trial (see there for the contract).
    void evaluate(const ContactState &committed, ContactState &trial) const;
  };
} // namespace kimp::lumped
