// The largest circular frequency of a lumped model, ω_max of (K, M) with M diagonal, and the
// other steps of the stability limit Δt_cr = 2/ω_max of the central difference method that the
// planar model and the model in plan share (stability_limit(), plan::PlanCentralDifference).
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "lumped/integrators/central_difference.h"

namespace kimp::lumped
{
  /// √λ_max of K·φ = λ·M·φ for the lumped masses `m` (kg) and the stiffness `k` (N/m), rad/s;
  /// 0 when k has no positive eigenvalue.
  inline double largest_omega(const Eigen::Ref<const Eigen::VectorXd> &m, const Eigen::MatrixXd &k)
  {
    const Eigen::VectorXd inv_sqrt_m = m.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd a          = inv_sqrt_m.asDiagonal() * k * inv_sqrt_m.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(solver.eigenvalues().maxCoeff(), 0.0));
  }

  /// Refuses a penetration δ_max (m) of the contact tangents that is not > 0.
  /// @throws std::invalid_argument naming expected_max_penetration.
  inline void require_expected_penetration(const double expected_max_penetration)
  {
    if (!(expected_max_penetration > 0.0))
    {
      std::ostringstream msg;
      msg << "expected_max_penetration = " << expected_max_penetration << " m (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
  }

  /// One impact bound ω = √(k_t/m) (k_t in N/m, m in kg): kept in s.omega_impact, and `name` in
  /// `impact_name`, when it is the largest so far.
  inline void note_impact(StabilityLimit    &s,
                          std::string       &impact_name,
                          const double       kt,
                          const double       mass,
                          const std::string &name)
  {
    const double w = std::sqrt(kt / mass);
    if (w > s.omega_impact)
    {
      s.omega_impact = w;
      impact_name    = name;
    }
  }

  /// Δt_cr = 2/ω_max of the three bounds of `s` (∞ when all are 0) and s.governing, the text of
  /// the bound that governs: the contact `impact_name` (at the penetration δ_max, m), the
  /// structure, or `closed_text` for the structure with its contacts closed.
  inline void set_critical_step(StabilityLimit    &s,
                                const std::string &impact_name,
                                const double       expected_max_penetration,
                                const std::string &closed_text)
  {
    const double w_max = std::max({s.omega_structure, s.omega_closed, s.omega_impact});
    s.dt_critical      = w_max > 0.0 ? 2.0 / w_max : std::numeric_limits<double>::infinity();
    std::ostringstream g;
    if (w_max == s.omega_impact && !impact_name.empty())
      g << "contact '" << impact_name << "': omega_imp = sqrt(k_t/m_eff) = " << s.omega_impact
        << " rad/s with k_t at a penetration of " << expected_max_penetration << " m";
    else if (w_max == s.omega_structure)
      g << "structure: omega_max = " << s.omega_structure << " rad/s";
    else
      g << closed_text;
    s.governing = g.str();
  }
} // namespace kimp::lumped
