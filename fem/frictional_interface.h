// Unilateral frictional penalty interface between two conforming faces whose nodes coincide in
// pairs (wall back face and backfill front face): normal penalty without tension, Coulomb
// friction by a return mapping of the tangential penalty force (Wriggers, Computational Contact
// Mechanics, 2006, §5.2 and §10.3), history committed once per accepted step. No deal.II.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace kimp::fem
{
  /**
   * Node-to-node interface: pair i joins node a (master, e.g. the wall) and node b (slave, e.g.
   * the soil), which start at the same place. With d = u_b - u_a, n the unit normal pointing
   * from a's body into b's body and t = (-n_y, n_x):
   * - normal: penetration p = -d.n, force lambda = k_N max(0, p) (no tension: an opening pair
   *   carries nothing and forgets its tangential force);
   * - tangential: trial T = T_committed + k_T (s - s_committed), s = d.t; if |T| > mu lambda
   *   the pair slips and T = mu lambda sign(T) (radial return), dissipating mu lambda |ds_p|
   *   with ds_p = (|T_trial| - mu lambda) / k_T;
   * - forces: f_b = lambda n - T t, f_a = -f_b.
   * Compact numbering: node k has displacement components u[2 k], u[2 k + 1].
   */
  class FrictionalInterface
  {
  public:
    struct Pair
    {
      unsigned int a = 0, b = 0;             ///< compact node indices (master, slave)
      double       nx = 1, ny = 0;           ///< unit normal from a's body into b's body
      double       normal_stiffness     = 0; ///< k_N, N/m per metre of depth (> 0)
      double       tangential_stiffness = 0; ///< k_T, N/m per metre (> 0)
      double       friction             = 0; ///< Coulomb mu (>= 0)
    };
    /** History of one pair. */
    struct PairState
    {
      double tangential_force = 0; ///< T, N/m
      double tangential_slip  = 0; ///< s at the last update, m
      double dissipation      = 0; ///< accumulated friction work, J/m
      bool   closed           = false;
      bool   slipping         = false;
    };
    struct Evaluation
    {
      std::vector<double> force;                ///< compact nodal forces, N/m
      double              normal_force     = 0; ///< sum of lambda, N/m
      double              tangential_force = 0; ///< sum of T, N/m
      double              penalty_energy   = 0; ///< sum k_N p^2 / 2 + T^2 / (2 k_T), J/m (stored)
      double              dissipation = 0; ///< friction work accumulated to this trial state, J/m
      unsigned int        n_closed = 0, n_slipping = 0;
    };

    /** @throws std::invalid_argument for a non-unit normal or a bad stiffness or friction. */
    FrictionalInterface(std::vector<Pair> pairs, unsigned int n_nodes);

    /** Forces at compact displacements @p u from the committed history; writes the trial one.
     *  Pure in the committed state: repeated calls with the same u give the same result. */
    Evaluation evaluate(const std::vector<double> &u);
    /** The consistent tangent of pair @p i at compact displacements @p u from the committed
     *  history: the 2 x 2 block A (row-major, x then y) of d(-f_b)/d(u_b), so that the pair's
     *  stiffness over (u_a, u_b) is [[A, -A], [-A, A]]. Open (p < 0): 0; stick (and p = 0, the
     *  closed side of the kink): k_N n n^T + k_T t t^T; slip: k_N n n^T - mu k_N sign(T) t n^T
     *  (unsymmetric: the friction force follows the normal force, not the slip). With @p stick
     *  the stick springs whatever the state (the virgin operator). */
    std::array<double, 4> tangent(std::size_t i, const std::vector<double> &u, bool stick) const;
    /** The last trial history becomes the committed one (an accepted step). */
    void commit() { committed_ = trial_; }
    /** The trial history is discarded. */
    void revert() { trial_ = committed_; }

    const std::vector<Pair>      &pairs() const { return pairs_; }
    const std::vector<PairState> &committed() const { return committed_; }
    unsigned int                  n_nodes() const { return n_nodes_; }

  private:
    std::vector<Pair>      pairs_;
    unsigned int           n_nodes_ = 0;
    std::vector<PairState> committed_, trial_;
  };
} // namespace kimp::fem
