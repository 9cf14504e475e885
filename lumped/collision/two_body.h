// Two-body collision lab: two free masses (or one mass and a rigid wall) meeting through a contact
// law, integrated by the central difference method (docs/physics.md §2, eqs. 3.9-3.11) until they
// separate; the reference is the stereomechanical impact (2.2-2.3).
#pragma once

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "lumped/laws/force_law.h"
#include "lumped/laws/force_law_factory.h"

namespace kimp::lumped
{
  /// Rate δ̇_n handed to the law inside a central-difference step (u_{n+1} is not known yet).
  enum class VelocityEstimate
  {
    /// (δ_n − δ_{n−1})/Δt: first order; it is the half-step velocity v_{n−½} that the CDM
    /// carries, so it lags the true δ̇(t_n) by Δt/2. The MDOF solver uses the same.
    backward_difference,
    /// (3δ_n − 4δ_{n−1} + δ_{n−2})/(2Δt) = v_{n−½} + ½Δt·a_{n−1}: second order at t_n.
    second_order
  };

  /// Collision set-up, SI. Body 1 moves towards body 2 (δ = u1 − u2 grows while they approach).
  struct TwoBodySetup
  {
    double           mass_1     = 280.0e3; ///< m1, kg (thesis: 280 t)
    double           mass_2     = 300.0e3; ///< m2, kg (thesis: 300 t); infinity: a fixed rigid wall
    double           velocity_1 = 1.0;     ///< v1 before impact, m/s
    double           velocity_2 = 0.0;     ///< v2 before impact, m/s (0 for a wall); v1 > v2
    double           time_step  = 2.0e-4;  ///< Δt, s (thesis: 2e-4 s)
    VelocityEstimate velocity_estimate = VelocityEstimate::backward_difference;
    bool             record_history    = true;       ///< keep the contact history
    std::size_t      max_steps         = 50'000'000; ///< give up (CollisionError) beyond this

    /// m1·m2/(m1 + m2), kg; m1 against a rigid wall.
    double effective_mass() const;
    /// @throws std::invalid_argument naming the bad field.
    void validate() const;
  };

  /// Samples of the contact phase (first in-contact step to the first open one), for the loop.
  struct TwoBodyHistory
  {
    std::vector<double> time;        ///< s (t = 0: the bodies touch)
    std::vector<double> deformation; ///< δ, m
    std::vector<double> rate;        ///< δ̇ given to the law, m/s
    std::vector<double> force;       ///< F, N
  };

  struct TwoBodyResult
  {
    double         velocity_1_after      = 0.0; ///< v1', m/s
    double         velocity_2_after      = 0.0; ///< v2', m/s
    double         effective_cor         = 0.0; ///< (v2' − v1')/(v1 − v2)
    double         peak_force            = 0.0; ///< max F, N
    double         min_force             = 0.0; ///< min F, N (< 0: tension, Kelvin-Voigt)
    double         contact_duration      = 0.0; ///< steps in contact · Δt, s
    double         max_penetration       = 0.0; ///< max δ, m
    double         impact_velocity       = 0.0; ///< v_imp the law recorded, m/s
    double         kinetic_energy_before = 0.0; ///< KE before the impact, J
    double         kinetic_energy_loss   = 0.0; ///< KE before − KE after, J
    double         dissipated_energy     = 0.0; ///< law's dissipated work (loop area), J
    double         permanent_indentation = 0.0; ///< m
    double         momentum_error = 0.0; ///< |p_after − p_before|/|p_before| (0 for a wall)
    std::size_t    n_steps        = 0;
    TwoBodyHistory history;
  };

  /// The bodies did not separate within TwoBodySetup::max_steps, or the state became non-finite.
  class CollisionError : public std::runtime_error
  {
  public:
    CollisionError(const std::string &what, double time, std::size_t step);
    double      time() const { return time_; }
    std::size_t step() const { return step_; }

  private:
    double      time_;
    std::size_t step_;
  };

  /**
   * Simulate one collision with a fresh copy of `law` (cloned, reverted to start).
   * The bodies touch at t = 0 (δ_0 = 0), so the first contact step sees δ_1 = (v1 − v2)·Δt and
   * the law's v_imp is exactly v1 − v2. Stops at the first step after contact with the law out of
   * contact; the velocities after that step are final (no more force).
   * @throws std::invalid_argument for a bad set-up, CollisionError on failure.
   */
  TwoBodyResult simulate_two_body(const ForceLaw &law, const TwoBodySetup &setup);

  /// One line of the effective-COR table of `kimp collide`.
  struct CorTableRow
  {
    std::string law;
    double      nominal_cor      = 0.0;
    double      effective_cor    = 0.0;
    double      relative_error   = 0.0; ///< (effective − nominal)/nominal
    double      peak_force       = 0.0; ///< N
    double      contact_duration = 0.0; ///< s
    double      max_penetration  = 0.0; ///< m
    double      energy_error     = 0.0; ///< |ΔKE − dissipated|/KE before impact
  };

  /**
   * Effective COR of each law over a COR grid (thesis test: 280 t and 300 t at 1 m/s, Δt 2e-4 s).
   * Each spec is used with `cor` from the grid and `effective_mass` = setup.effective_mass().
   */
  std::vector<CorTableRow> effective_cor_table(const std::vector<ForceLawSpec> &laws,
                                               const std::vector<double>       &cor_grid,
                                               const TwoBodySetup              &setup);
} // namespace kimp::lumped
