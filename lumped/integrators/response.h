// Responses of a pounding analysis (docs/physics.md §2, §5): decimated histories, peaks per floor
// and storey, impacts per contact, permanent indentation and the energy balance
//   E_0 + W_in = E_kin + E_strain + E_viscous + E_hysteretic + W_contact  (relative error
//   reported).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace kimp::lumped
{
  /// First-contact event of one impact.
  struct ImpactEvent
  {
    double time     = 0.0; ///< s
    double velocity = 0.0; ///< closing rate δ̇ passed to the law at the first contact step, m/s
  };

  struct ContactResult
  {
    std::string              name;
    double                   peak_force = 0.0; ///< N
    std::vector<ImpactEvent> impacts;
    double                   permanent_indentation = 0.0; ///< m, at the end (law's value)
    double                   dissipated_energy     = 0.0; ///< J, the law's own bookkeeping
    /// A permanent pair (a yielding wall's backfill part, ContactPair::permanent): no impacts or
    /// pulses; its permanent_indentation is the wall's permanent set.
    bool   permanent        = false;
    double peak_deformation = 0.0; ///< max δ over the run, m (a wall part: peak w)
    /// The time δ first exceeded the pair's failure_deformation, s (unset: never).
    std::optional<double> failure_time;
    double                plastic_work = 0.0; ///< a wall part: W_p, J (0 otherwise)
    /// A wall part: the largest resistance R without its dashpot, N (0 otherwise); peak_force
    /// is R + c_r·ẇ.
    double peak_resistance = 0.0;
    double radiated_work   = 0.0; ///< a wall part: ∫c_r·ẇ dw, J (0 otherwise)
    /// The contact force at full rate: every step at which it is non-zero (the impact pulses,
    /// unlike the decimated history which can miss their peaks), s and N.
    std::vector<double> pulse_time;
    std::vector<double> pulse_force;
    /// The deformation δ (interpenetration beyond the gap, m) at the same steps: an impact's
    /// indentation is its largest value.
    std::vector<double> pulse_deformation;

    /// The impact velocity of the contact: the largest closing rate at first contact over its
    /// impacts, m/s (0 without impacts).
    double largest_impact_velocity() const;
    /// One column of `impacts`, in order: `&ImpactEvent::time` (s) or `&ImpactEvent::velocity`
    /// (m/s).
    std::vector<double> impact_column(double ImpactEvent::*column) const;
  };

  /**
   * Energy terms, J, relative formulation (u relative to the ground): W_in = −∫ u̇ᵀ·M·1·ü_g dt.
   * Works are trapezoid sums over the integer time levels; E_kin uses v_n = (u_{n+1}−u_{n−1})/(2Δt)
   * in the central difference method, E_strain = ½uᵀKu + the isolator's stored energy.
   * W_contact = Σ ∫F dδ over all contacts (stored while in contact, dissipated after separation).
   */
  struct EnergyBalance
  {
    double initial           = 0.0; ///< E_kin + E_strain at t = 0
    double input             = 0.0; ///< W_in
    double kinetic           = 0.0;
    double strain            = 0.0;
    double viscous           = 0.0; ///< ∫ u̇ᵀ·C·u̇ dt
    double hysteretic        = 0.0; ///< isolator
    double contact_work      = 0.0; ///< W_contact
    double impact_dissipated = 0.0; ///< Σ impact laws' dissipated_energy()
    /// Σ over yielding walls' backfill parts of the plastic and the radiated work, J (both are
    /// in contact_work; with impact_dissipated and the stored energies they make it up).
    double wall_plastic   = 0.0;
    double wall_radiated  = 0.0;
    double relative_error = 0.0; ///< at the end, see residual_relative_error()
    /// max over time of the absolute residual divided by the largest energy supplied during the
    /// run, max_t (E_0 + W_in) (checked at the output samples, every 512 steps and the end)
    double max_relative_error = 0.0;

    /// |E_0 + W_in − (E_kin + E_strain + E_viscous + E_hyst + W_contact)| divided by the larger
    /// of E_0 + |W_in| and the sum of the magnitudes of the right-hand terms.
    double residual_relative_error() const;
  };

  /// Decimated histories; row-major [sample][index].
  struct ResponseHistory
  {
    double              interval = 0.0;        ///< s between samples
    std::vector<double> time;                  ///< s
    std::vector<double> displacement;          ///< relative to the ground, m, [sample][dof]
    std::vector<double> absolute_acceleration; ///< ü + ü_g, m/s², [sample][dof]
    std::vector<double> interstorey_drift;     ///< u_upper − u_lower, m, [sample][storey]
    std::vector<double> contact_force;         ///< N, [sample][contact]
    std::vector<double> isolator_force;        ///< f_iso at the sample, N, [sample] (0: none)
    std::vector<double> hysteretic_energy;     ///< isolator's E_hysteretic, J, [sample]
    std::vector<double> energy_input;          ///< E_0 + W_in, J, [sample]
    std::vector<double> energy_error;          ///< residual / max energy supplied so far, [sample]
  };

  struct Response
  {
    double      dt        = 0.0; ///< s
    long        n_steps   = 0;   ///< steps taken (t_end = n_steps·dt for fixed-step methods)
    double      duration  = 0.0; ///< s
    std::size_t n_dofs    = 0;
    std::size_t n_storeys = 0;

    std::vector<double>        peak_displacement;          ///< max |u_i|, m, per DOF
    std::vector<double>        peak_absolute_acceleration; ///< max |ü_i + ü_g|, m/s², per DOF
    std::vector<double>        peak_interstorey_drift;     ///< m, per storey
    double                     peak_isolator_force = 0.0;  ///< max |f_iso|, N (0: no isolator)
    std::vector<ContactResult> contacts;
    EnergyBalance              energy;
    ResponseHistory            history;

    /// max over storeys of peak_interstorey_drift, m (0 without storeys).
    double      max_interstorey_drift() const;
    std::size_t n_impacts() const;
  };

  /// Peak with pounding divided by peak without (ratio 0/0 := 1), per DOF and per storey.
  struct Amplification
  {
    std::vector<double> displacement;
    std::vector<double> absolute_acceleration;
    std::vector<double> interstorey_drift;
  };

  /// @throws std::invalid_argument when the two responses have different sizes.
  Amplification amplification_factors(const Response &with_pounding,
                                      const Response &without_pounding);
} // namespace kimp::lumped
