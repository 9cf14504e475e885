// Impact law 6, non-linear hysteretic (thesis eqs. 2.17-2.23): approach F = k·δ^n, restitution
// (δ̇ < 0) F = k·δ^n·(1 + C_imp·δ̇) clipped at 0, with
// C_imp = 1.55·(1 − COR²)/(COR^0.7076·m_eff^0.0025·v_imp^0.9755) (2.23, m_eff in kg, v in m/s).
#pragma once

#include <optional>
#include <string>

#include "lumped/laws/contact_law.h"

namespace kimp::lumped
{
  /// C_imp of (2.23), s/m, from COR, m_eff (kg) and v_imp (m/s).
  /// @throws std::invalid_argument unless 0 < COR <= 1, m_eff > 0, v_imp > 0.
  double impact_damping_coefficient(double cor, double effective_mass, double impact_velocity);

  /// The checks of the C_imp parameters of laws 6 and 7: 0 < COR <= 1, m_eff > 0, a1 > 0 if set.
  void require_impact_coefficient(const std::string    &law,
                                  double                cor,
                                  double                effective_mass,
                                  std::optional<double> a1);

  /**
   * The opening and the first trial of a contact of laws 6 and 7 (hysteretic, bumper): false
   * (open) for δ <= 0; else in contact, and the first trial of a contact records v_imp and fixes
   * C_imp for the whole contact, a1·(1 − COR²) when `a1` is given, else (2.23).
   * @throws std::invalid_argument (naming `law`) for a contact entered without approach speed.
   */
  bool enter_impact_contact(const char           *law,
                            double                cor,
                            std::optional<double> a1,
                            double                effective_mass,
                            const ContactState   &committed,
                            ContactState         &trial);

  /// enter_impact_contact() with the COR, a1 and m_eff of a law's parameters.
  template <class Params>
  bool enter_impact_contact(const char         *law,
                            const Params       &params,
                            const ContactState &committed,
                            ContactState       &trial)
  {
    return enter_impact_contact(law,
                                params.cor,
                                params.a1,
                                params.effective_mass,
                                committed,
                                trial);
  }

  /**
   * The force of laws 6 and 7 in contact from the approach force F_a(δ) (`spring`, the elastic
   * force) and its tangent: F_a while approaching (δ̇ >= 0), F_a·(1 + C_imp·δ̇) on restitution,
   * clipped at 0 (no tension: the bodies separate while δ > 0).
   */
  inline void restitution_force(const double spring, const double tangent, ContactState &trial)
  {
    trial.elastic_force = spring;
    if (trial.rate >= 0.0)
    {
      trial.force     = spring;
      trial.stiffness = tangent;
      return;
    }
    const double g = 1.0 + trial.impact_coefficient * trial.rate;
    if (g <= 0.0)
      return; // clipped
    trial.force     = spring * g;
    trial.stiffness = tangent * g;
    trial.damping   = spring * trial.impact_coefficient;
  }

  /// Parameters of the HystereticLaw.
  struct HystereticParams
  {
    double                stiffness      = 0.0; ///< k, N/m^n
    double                exponent       = 1.5; ///< n
    double                cor            = 1.0; ///< nominal COR
    double                effective_mass = 0.0; ///< m_eff, kg
    std::optional<double> a1;                   ///< if set, C_imp = a1·(1 − COR²), s/m
  };

  /**
   * Hertz-type spring on approach, a rate-proportional reduction of the force on restitution
   * (the hysteresis loop), never tensile: the thesis' proposal. v_imp is the rate δ̇ at the first
   * trial that enters contact; C_imp is fixed there for the whole contact.
   *
   * | parameter | meaning                                      | unit   | range  |
   * |-----------|----------------------------------------------|--------|--------|
   * | k         | Hertz stiffness                              | N/m^n  | > 0    |
   * | n         | exponent (1.5)                               | -      | >= 1   |
   * | cor       | nominal coefficient of restitution           | -      | (0, 1] |
   * | m_eff     | m1·m2/(m1 + m2) of the pair                  | kg     | > 0    |
   * | a1        | optional: C_imp = a1·(1 − COR²) instead of (2.23) | s/m | > 0   |
   *
   * Tangent: dF/dδ̇ jumps from 0 to k·δ^n·C_imp at δ̇ = 0 and from k·δ^n·C_imp to 0 where the
   * clipping starts (1 + C_imp·δ̇ = 0): kinks with continuous F.
   * Limitation: (2.23) is a fit; the effective COR deviates by up to a few per cent
   * (lumped/collision/cimp_calibration.h redoes the fit).
   */
  class HystereticLaw final : public ContactLaw<HystereticLaw, HystereticParams>
  {
  public:
    static constexpr const char *law_name = "hysteretic";

    /// @throws std::invalid_argument naming the bad parameter.
    explicit HystereticLaw(const Params &params);

    /// n·k·δ_max^(n−1), N/m (the approach tangent bounds the restitution one).
    /// @throws std::invalid_argument if max_deformation <= 0 and n > 1.
    double stability_stiffness(double max_deformation) const override;

    /// The law itself, called by ContactLaw::set_trial (see there for the contract).
    void evaluate(const ContactState &committed, ContactState &trial) const;
  };
} // namespace kimp::lumped
