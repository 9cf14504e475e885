// Impact law 7, rubber bumper against a wall (thesis ch. 6, eq. 6.4): approach F = k_b·δ^n for
// δ < δ_u, F = k_b·δ_u^n + k_w·(δ − δ_u) beyond (bumper crushed, wall takes over); restitution
// as law 6, F = F_approach(δ)·(1 + C_imp·δ̇) clipped at 0; δ_u = ε_u·t.
#pragma once

#include <optional>
#include <string>

#include "lumped/laws/contact_law.h"

namespace kimp::lumped
{
  /**
   * Bumper stiffness from the material (thesis 6.2-6.3): k_b = count·2.25·A·K_r/t^n, N/m^n.
   * @param[in] area        loaded face A of one bumper, m²
   * @param[in] modulus     rubber constant K_r, N/m²
   * @param[in] thickness   bumper thickness t, m
   * @param[in] exponent    n (2.65 for the thesis' rubber)
   * @param[in] count       number of bumpers in parallel (>= 1)
   * @throws std::invalid_argument naming the bad parameter.
   */
  double
  bumper_stiffness(double area, double modulus, double thickness, double exponent, int count);

  /// Parameters of the BumperLaw.
  struct BumperParams
  {
    double                stiffness            = 0.0;  ///< k_b, N/m^n
    double                exponent             = 2.65; ///< n
    double                ultimate_deformation = 0.0;  ///< δ_u, m
    double                wall_stiffness       = 0.0;  ///< k_w, N/m
    double                cor                  = 1.0;  ///< nominal COR
    double                effective_mass       = 0.0;  ///< m_eff, kg
    std::optional<double> a1;                          ///< C_imp = a1·(1 − COR²), s/m
  };

  /**
   * Rubber bumper(s) in series with a stiff wall; no permanent indentation.
   *
   * | parameter | meaning                                        | unit  | range  |
   * |-----------|------------------------------------------------|-------|--------|
   * | k_b       | bumper stiffness of all bumpers together       | N/m^n | > 0    |
   * | n         | exponent (2.65)                                | -     | >= 1   |
   * | delta_u   | deformation at which the bumper is crushed, ε_u·t | m  | > 0    |
   * | k_w       | wall stiffness beyond delta_u                  | N/m   | > 0    |
   * | cor       | nominal coefficient of restitution             | -     | (0, 1] |
   * | m_eff     | m1·m2/(m1 + m2) of the pair                    | kg    | > 0    |
   * | a1        | optional: C_imp = a1·(1 − COR²) instead of (2.23) | s/m | > 0    |
   *
   * Tangent: kinks at δ = δ_u (n·k_b·δ_u^(n−1) against k_w), at δ̇ = 0 and at the start of the
   * clipping, as in law 6. Limitation: the thesis calibrated C_imp for Hertz contact (2.23); it
   * is reused here unchanged.
   */
  class BumperLaw final : public ContactLaw<BumperLaw, BumperParams>
  {
  public:
    static constexpr const char *law_name = "bumper";

    /// @throws std::invalid_argument naming the bad parameter.
    explicit BumperLaw(const Params &params);

    /// Largest approach tangent up to max_deformation, N/m.
    /// @throws std::invalid_argument if max_deformation <= 0.
    double stability_stiffness(double max_deformation) const override;

    /// The law itself, called by ContactLaw::set_trial (see there for the contract).
    void evaluate(const ContactState &committed, ContactState &trial) const;

  private:
    double force_u_;  ///< k_b·δ_u^n, N
    double energy_u_; ///< k_b·δ_u^(n+1)/(n+1), J
  };
} // namespace kimp::lumped
