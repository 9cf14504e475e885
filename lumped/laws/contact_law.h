// Trial/commit machinery shared by the contact laws 1-7 (docs/physics.md §1, docs/architecture.md
// "Force laws"): one state struct held twice; dissipated work D += ½(F_nc,trial +
// F_nc,committed)·Δs at commit, F_nc = F − F_el the non-conservative part of the force, s = max(δ,
// δ_p) the contact travel.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "lumped/laws/force_law.h"
#include "lumped/parameter_check.h"

namespace kimp::lumped
{
  /// History and trial variables of a contact law (all laws use the same struct).
  struct ContactState
  {
    double deformation   = 0.0; ///< geometric interpenetration δ, m (<= 0: gap open)
    double rate          = 0.0; ///< δ̇, m/s (> 0 approaching)
    double force         = 0.0; ///< F, N (compressive positive)
    double stiffness     = 0.0; ///< dF/dδ, N/m
    double damping       = 0.0; ///< dF/dδ̇, N·s/m
    double elastic_force = 0.0; ///< conservative part F_el(δ − δ_p), N; the rest is dissipative
    double stored_energy = 0.0; ///< potential of F_el at δ − δ_p, J
    double released_energy       = 0.0; ///< elastic energy lost at this step (permanent set), J
    double impact_velocity       = 0.0; ///< δ̇ at the first trial of the current contact, m/s
    double impact_coefficient    = 0.0; ///< law coefficient fixed at first contact (see each law)
    double permanent_indentation = 0.0; ///< δ_p, m; contact exists only for δ > δ_p
    double dissipated            = 0.0; ///< dissipated work since the virgin state, J
    bool   in_contact            = false;
  };

  /**
   * CRTP base implementing the ForceLaw state machine for a law `Derived` with parameters `P`
   * (held as params_, returned by parameters()) that provides, public, its name as
   * `static constexpr const char *law_name` and the law itself as
   * `void evaluate(const ContactState& committed, ContactState& trial) const` (const: it only
   * fills the trial state it is given).
   * `evaluate` receives `trial` = committed state with the new δ, δ̇ and zeroed force, tangent,
   * elastic force, stored and released energy, and fills them (and any history it changes).
   *
   * Dissipation: the trapezoid rule on F_nc over the contact travel s = max(δ, δ_p), so opening
   * travel before contact does no work, plus any elastic energy released by a permanent set.
   * With rates that are consistent with the δ increments (e.g. backward differences) every
   * increment is >= 0 except at a turning point δ̇ = 0 that falls between two samples, where an
   * increment of order (ω·Δt)² of the step's work may be negative (quadrature error).
   */
  template <typename Derived, typename P>
  class ContactLaw : public ForceLaw
  {
  public:
    using Params = P;

    ForceResponse set_trial(double deformation, double rate) final
    {
      trial_                 = committed_;
      trial_.deformation     = deformation;
      trial_.rate            = rate;
      trial_.force           = 0.0;
      trial_.stiffness       = 0.0;
      trial_.damping         = 0.0;
      trial_.elastic_force   = 0.0;
      trial_.stored_energy   = 0.0;
      trial_.released_energy = 0.0;
      static_cast<const Derived &>(*this).evaluate(committed_, trial_);

      const double s_c  = std::max(committed_.deformation, committed_.permanent_indentation);
      const double s_t  = std::max(trial_.deformation, trial_.permanent_indentation);
      const double nc_c = committed_.force - committed_.elastic_force;
      const double nc_t = trial_.force - trial_.elastic_force;
      trial_.dissipated =
        committed_.dissipated + 0.5 * (nc_t + nc_c) * (s_t - s_c) + trial_.released_energy;
      return {trial_.force, trial_.stiffness, trial_.damping};
    }

    void commit() final { committed_ = trial_; }
    void revert_to_last_commit() final { trial_ = committed_; }
    void revert_to_start() final
    {
      committed_ = ContactState{};
      trial_     = ContactState{};
    }

    double dissipated_energy() const final { return committed_.dissipated; }
    double permanent_indentation() const final { return committed_.permanent_indentation; }
    bool   in_contact() const final { return committed_.in_contact; }
    double stored_energy() const final { return committed_.stored_energy; }
    double impact_velocity() const final { return committed_.impact_velocity; }

    std::string               name() const final { return Derived::law_name; }
    std::unique_ptr<ForceLaw> clone() const final
    {
      return std::make_unique<Derived>(static_cast<const Derived &>(*this));
    }

    const Params &parameters() const { return params_; }

    /// Last committed state (read-only, for diagnostics and tests).
    const ContactState &committed_state() const { return committed_; }
    /// Current trial state (read-only, for diagnostics and tests).
    const ContactState &trial_state() const { return trial_; }

  protected:
    explicit ContactLaw(const Params &params)
      : params_(params)
    {
    }

    const Params params_;

  private:
    ContactState committed_;
    ContactState trial_;
  };

  /// Parameters of the laws whose dashpot follows from the COR and the pair's mass (2-4).
  struct DashpotLawParams
  {
    double stiffness      = 0.0; ///< k, N/m (laws 2, 3) or N/m^1.5 (law 4)
    double cor            = 1.0; ///< nominal COR
    double effective_mass = 0.0; ///< m_eff, kg
  };

  namespace detail
  {
    /// Throw std::invalid_argument "<law> law: <name> = <value> <unit> (<expected>)" unless ok.
    inline void require_parameter(bool               ok,
                                  const std::string &law,
                                  const std::string &name,
                                  double             value,
                                  const std::string &unit,
                                  const std::string &expected)
    {
      if (!ok)
        lumped::require_parameter(false, law + " law: ", name, value, unit, expected);
    }

    /**
     * The opening of every law: at deformation x <= 0 the trial state is open (returns false);
     * otherwise it is in contact, and the first step of a contact records the impact velocity.
     */
    inline bool enter_contact(double x, const ContactState &committed, ContactState &trial)
    {
      if (x <= 0.0)
      {
        trial.in_contact = false;
        return false;
      }
      if (!committed.in_contact)
        trial.impact_velocity = trial.rate;
      trial.in_contact = true;
      return true;
    }

    /// Checks shared by several laws; NaN fails every check.
    inline void require_positive(const std::string &law,
                                 const std::string &name,
                                 double             value,
                                 const std::string &unit)
    {
      require_parameter(std::isfinite(value) && value > 0.0, law, name, value, unit, "must be > 0");
    }

    inline void require_cor(const std::string &law, double cor)
    {
      require_parameter(cor > 0.0 && cor <= 1.0, law, "cor", cor, "", "must be in (0, 1]");
    }

    inline void require_exponent(const std::string &law, double n)
    {
      require_parameter(std::isfinite(n) && n >= 1.0, law, "exponent n", n, "", "must be >= 1");
    }

    /// The checks of laws 2-4: k > 0 (in `stiffness_unit`), 0 < COR <= 1, m_eff > 0.
    inline void require_dashpot_law(const std::string      &law,
                                    const DashpotLawParams &params,
                                    const std::string      &stiffness_unit)
    {
      require_positive(law, "k", params.stiffness, stiffness_unit);
      require_cor(law, params.cor);
      require_positive(law, "m_eff", params.effective_mass, "kg");
    }

    /// x^(n−1) with the common exponents 1 and 1.5 (Hertz) done without std::pow.
    inline double power_minus_one(double x, double n)
    {
      if (n == 1.5)
        return std::sqrt(x);
      if (n == 1.0)
        return 1.0;
      return std::pow(x, n - 1.0);
    }

    /// v_imp of the trial: the committed one while in contact, else the trial rate, which must
    /// be > 0 for laws whose damping scales with 1/v_imp.
    inline double
    impact_velocity_of(const char *law, const ContactState &committed, const ContactState &trial)
    {
      if (committed.in_contact)
        return committed.impact_velocity;
      if (!(trial.rate > 0.0))
      {
        std::ostringstream msg;
        msg << law << " law: contact entered at delta = " << trial.deformation
            << " m with rate = " << trial.rate
            << " m/s; the impact velocity must be > 0 (rate inconsistent with the deformation)";
        throw std::domain_error(msg.str());
      }
      return trial.rate;
    }
  } // namespace detail
} // namespace kimp::lumped
