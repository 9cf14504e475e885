// Node-to-node unilateral Coulomb penalty interface; see frictional_interface.h.
#include "fem/frictional_interface.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace kimp::fem
{
  FrictionalInterface::FrictionalInterface(std::vector<Pair> pairs, unsigned int n_nodes)
    : pairs_(std::move(pairs))
    , n_nodes_(n_nodes)
    , committed_(pairs_.size())
    , trial_(pairs_.size())
  {
    for (std::size_t i = 0; i < pairs_.size(); ++i)
    {
      const Pair &p = pairs_[i];
      if (p.a >= n_nodes || p.b >= n_nodes || p.a == p.b ||
          std::abs(std::hypot(p.nx, p.ny) - 1) > 1e-12 || !(p.normal_stiffness > 0) ||
          !(p.tangential_stiffness > 0) || !(p.friction >= 0))
        throw std::invalid_argument(
          "FrictionalInterface: pair " + std::to_string(i) +
          " needs two distinct nodes < n_nodes, a unit normal, k_N > 0, k_T > 0 and mu >= 0");
    }
  }

  FrictionalInterface::Evaluation FrictionalInterface::evaluate(const std::vector<double> &u)
  {
    Evaluation ev;
    ev.force.assign(2 * static_cast<std::size_t>(n_nodes_), 0.0);
    for (std::size_t i = 0; i < pairs_.size(); ++i)
    {
      const Pair      &p  = pairs_[i];
      const PairState &c  = committed_[i];
      PairState       &tr = trial_[i];
      tr                  = c;
      const double dx = u[2 * p.b] - u[2 * p.a], dy = u[2 * p.b + 1] - u[2 * p.a + 1];
      const double tx = -p.ny, ty = p.nx;
      const double pen   = -(dx * p.nx + dy * p.ny);
      const double s     = dx * tx + dy * ty;
      tr.tangential_slip = s;
      if (pen <= 0)
      {
        // Open: no force. The tangential spring restarts from zero at the next closure; the
        // little elastic energy it held (|T| <= mu k_N p before opening) is lost, as friction.
        if (c.closed)
          tr.dissipation += 0.5 * c.tangential_force * c.tangential_force / p.tangential_stiffness;
        tr.tangential_force = 0;
        tr.closed           = false;
        tr.slipping         = false;
        ev.dissipation += tr.dissipation;
        continue;
      }
      const double lambda = p.normal_stiffness * pen;
      const double t_trial =
        (c.closed ? c.tangential_force : 0.0) + p.tangential_stiffness * (s - c.tangential_slip);
      const double limit = p.friction * lambda;
      double       t     = t_trial;
      tr.slipping        = std::abs(t_trial) > limit;
      if (tr.slipping)
      {
        t = std::copysign(limit, t_trial);
        tr.dissipation += limit * (std::abs(t_trial) - limit) / p.tangential_stiffness;
      }
      tr.tangential_force = t;
      tr.closed           = true;
      const double fx = lambda * p.nx - t * tx, fy = lambda * p.ny - t * ty;
      ev.force[2 * p.b] += fx;
      ev.force[2 * p.b + 1] += fy;
      ev.force[2 * p.a] -= fx;
      ev.force[2 * p.a + 1] -= fy;
      ev.normal_force += lambda;
      ev.tangential_force += t;
      ev.penalty_energy += 0.5 * lambda * pen + 0.5 * t * t / p.tangential_stiffness;
      ev.dissipation += tr.dissipation;
      ++ev.n_closed;
      ev.n_slipping += tr.slipping ? 1 : 0;
    }
    return ev;
  }

  std::array<double, 4>
  FrictionalInterface::tangent(std::size_t i, const std::vector<double> &u, bool stick) const
  {
    const Pair      &p  = pairs_.at(i);
    const PairState &c  = committed_.at(i);
    const double     tx = -p.ny, ty = p.nx;
    const double     kn = p.normal_stiffness, kt = p.tangential_stiffness;
    // k_N n n^T + k_T t t^T: the stick springs.
    std::array<double, 4> a{{kn * p.nx * p.nx + kt * tx * tx,
                             kn * p.nx * p.ny + kt * tx * ty,
                             kn * p.ny * p.nx + kt * ty * tx,
                             kn * p.ny * p.ny + kt * ty * ty}};
    if (stick)
      return a;
    const double dx = u[2 * p.b] - u[2 * p.a], dy = u[2 * p.b + 1] - u[2 * p.a + 1];
    const double pen = -(dx * p.nx + dy * p.ny);
    if (pen < 0)
      return {{0, 0, 0, 0}}; // open: no force, whatever the move (at p = 0 the closed side)
    const double s       = dx * tx + dy * ty;
    const double t_trial = (c.closed ? c.tangential_force : 0.0) + kt * (s - c.tangential_slip);
    if (std::abs(t_trial) <= p.friction * kn * pen)
      return a;
    // Slip: T = mu k_N p sign(T*), dT/dd = -mu k_N sign(T*) n; -df_b/dd = k_N n n^T - t dT/dd^T.
    const double m = p.friction * kn * std::copysign(1.0, t_trial);
    return {{kn * p.nx * p.nx - m * tx * p.nx,
             kn * p.nx * p.ny - m * tx * p.ny,
             kn * p.ny * p.nx - m * ty * p.nx,
             kn * p.ny * p.ny - m * ty * p.ny}};
  }
} // namespace kimp::fem
