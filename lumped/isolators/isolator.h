// Interface of base-isolation devices: restoring force f_iso(u, u̇) between the ground and the
// isolation level (DOF 0), with trial/commit state like the impact laws (docs/architecture.md
// "Force laws").
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <string_view>

#include "lumped/parameter_check.h"
#include "lumped/trial_commit.h"

namespace kimp::lumped
{
  /// Result of one trial evaluation of an isolator.
  struct IsolatorResponse
  {
    double force     = 0.0; ///< restoring force, N (positive for positive displacement)
    double stiffness = 0.0; ///< tangent df/du at the trial state, N/m (exact derivative)
    double damping   = 0.0; ///< df/du̇ at the trial state, N·s/m (0 for rate-independent laws)
  };

  /**
   * Isolator law with trial/commit state; admits hysteretic laws (bilinear, later Bouc-Wen and the
   * friction pendulum). The linear viscous part of the isolation system is not evaluated here: it
   * enters the damping matrix at C[0,0] (docs/physics.md §2), see viscous_coefficient().
   *
   * Contract (as ForceLaw): `set_trial(u, u̇)` starts from the committed state every time, so it is
   * idempotent; `commit()` accepts the last trial; `revert_to_last_commit()` discards it;
   * `revert_to_start()` returns to the virgin state; `clone()` copies committed and trial state.
   */
  class Isolator : public TrialCommit
  {
  public:
    /// Evaluate at the trial displacement u (m, isolation level relative to the ground) and
    /// velocity u̇ (m/s).
    virtual IsolatorResponse set_trial(double displacement, double velocity) = 0;

    /// Initial (elastic) stiffness, N/m: used in K for modal analysis, the Rayleigh damping and
    /// c_iso of docs/physics.md §2, and the stability limit of the explicit integrator.
    virtual double initial_stiffness() const = 0;
    /// Linear viscous coefficient of the device itself, N·s/m, added to C[0,0] (default 0).
    virtual double viscous_coefficient() const { return 0.0; }
    /// Recoverable (elastic) energy stored at the committed state, J.
    virtual double stored_energy() const = 0;
    /// Hysteretic energy dissipated up to the last commit, J (>= 0).
    virtual double dissipated_energy() const = 0;
    /// Restoring force at the committed state, N (the force of the last committed trial).
    virtual double committed_force() const = 0;
    /**
     * Whether the law sticks and slips (a friction bearing: a stiff elastic branch while it
     * sticks, a kink of the force where its velocity reverses). The variable-step integrator
     * (`dt: auto`) then ends a step where the isolator's velocity reverses and limits the step
     * while sticking() (AdaptiveStepOptions::stick_step). Default false.
     */
    virtual bool stick_slip() const { return false; }
    /// The committed state is on the stick (elastic) branch of a stick-slip law.
    virtual bool sticking() const { return false; }

    virtual std::string               name() const  = 0;
    virtual std::unique_ptr<Isolator> clone() const = 0;
  };

  /// require_parameter() of the isolators: "isolator.<key> = <value> <unit> (<rule>)".
  inline void require_isolator(const bool             ok,
                               const std::string_view key,
                               const double           value,
                               const std::string_view unit,
                               const std::string_view rule)
  {
    require_parameter(ok, "isolator.", key, value, unit, rule);
  }

  /// require_isolator() of a parameter that must lie in [low, high) (NaN and infinity fail).
  inline void require_isolator_in(const std::string_view key,
                                  const double           value,
                                  const double           low,
                                  const double           high,
                                  const std::string_view unit,
                                  const std::string_view rule)
  {
    require_isolator(std::isfinite(value) && value >= low && value < high, key, value, unit, rule);
  }

  /// require_isolator() of a parameter that must be > 0 and finite (NaN fails).
  inline void require_positive_isolator(const std::string_view key,
                                        const double           value,
                                        const std::string_view unit)
  {
    require_isolator(std::isfinite(value) && value > 0.0,
                     key,
                     value,
                     unit,
                     "must be > 0 and finite");
  }

  /// require_isolator() of a parameter that must be >= 0 and finite (NaN fails).
  inline void require_non_negative_isolator(const std::string_view key,
                                            const double           value,
                                            const std::string_view unit)
  {
    require_isolator_in(key,
                        value,
                        0.0,
                        std::numeric_limits<double>::infinity(),
                        unit,
                        "must be >= 0 and finite");
  }

  /**
   * CRTP base of the hysteretic isolators (bilinear, Bouc-Wen, friction pendulum), planar
   * (`Base` = Isolator, HystereticIsolator) and in plan (`Base` = plan::PlanIsolator): the history
   * is one struct `State` (value-initialised = virgin, with the hysteretic energy `dissipated`,
   * J) held as committed and trial copies, and the device dashpot c; the trial/commit verbs, the
   * dissipated energy and clone() follow from that. `Derived` provides set_trial() (from
   * committed_, writing trial_), the stiffness and energy queries and name().
   */
  template <class Base, class Derived, class State>
  class HystereticIsolatorLaw : public Base
  {
  public:
    void   commit() final { committed_ = trial_; }
    void   revert_to_last_commit() final { trial_ = committed_; }
    void   revert_to_start() final { committed_ = trial_ = State{}; }
    double viscous_coefficient() const final { return c_; }
    double dissipated_energy() const final { return committed_.dissipated; }

    std::unique_ptr<Base> clone() const final
    {
      return std::make_unique<Derived>(static_cast<const Derived &>(*this));
    }

  protected:
    /// @throws std::invalid_argument unless c (N·s/m) is >= 0 and finite.
    explicit HystereticIsolatorLaw(const double c)
      : c_(c)
    {
      require_non_negative_isolator("c", c, "N*s/m");
    }

    State committed_;
    State trial_;

  private:
    double c_;
  };

  /// The planar hysteretic isolators' base.
  template <class Derived, class State>
  using HystereticIsolator = HystereticIsolatorLaw<Isolator, Derived, State>;
} // namespace kimp::lumped
