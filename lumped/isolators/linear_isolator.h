// Linear isolator: f = k·u (restoring) plus an optional device dashpot c that is added to the
// damping matrix at C[0,0] (thesis §3.1, docs/physics.md §2).
#pragma once

#include "lumped/isolators/isolator.h"

namespace kimp::lumped
{
  /**
   * Linear elastic isolator.
   *
   * | parameter | unit   | admissible | meaning                                      |
   * |-----------|--------|------------|----------------------------------------------|
   * | k         | N/m    | > 0        | horizontal stiffness of the isolation system |
   * | c         | N·s/m  | >= 0       | device dashpot added to C[0,0] (default 0)   |
   *
   * The isolation system's excess damping of docs/physics.md §2 (c_iso from ζ_iso) is added by the
   * building's damping model on top of c.
   */
  class LinearIsolator final : public Isolator
  {
  public:
    /// @throws std::invalid_argument for k <= 0, c < 0 or non-finite values.
    explicit LinearIsolator(double k, double c = 0.0);

    IsolatorResponse set_trial(double displacement, double velocity) override
    {
      (void)velocity;
      trial_u_ = displacement;
      return {k_ * displacement, k_, 0.0};
    }
    void commit() override { committed_u_ = trial_u_; }
    void revert_to_last_commit() override { trial_u_ = committed_u_; }
    void revert_to_start() override { trial_u_ = committed_u_ = 0.0; }

    double initial_stiffness() const override { return k_; }
    double viscous_coefficient() const override { return c_; }
    double stored_energy() const override { return 0.5 * k_ * committed_u_ * committed_u_; }
    double dissipated_energy() const override { return 0.0; }
    double committed_force() const override { return k_ * committed_u_; }

    std::string               name() const override { return "linear"; }
    std::unique_ptr<Isolator> clone() const override
    {
      return std::make_unique<LinearIsolator>(*this);
    }

  private:
    double k_;
    double c_;
    double committed_u_ = 0.0;
    double trial_u_     = 0.0;
  };
} // namespace kimp::lumped
