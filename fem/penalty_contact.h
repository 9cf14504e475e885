// Frictionless node-to-segment penalty contact in the current geometry: slave point s, master
// segment [a, b] with outward normal n, gap g = (x_s - x_a(xi)) . n, p = -g, force on the slave
// lambda n with lambda = max(0, k p + c dp/dt), -lambda n (1 - xi, xi) on the master ends
// (Wriggers, Computational Contact Mechanics, 2006, ch. 4 and 9). No deal.II.
#pragma once

#include <array>
#include <vector>

namespace kimp::fem
{
  /**
   * Penalty contact between slave nodes and a master surface, either a chain of straight
   * segments between master nodes or a rigid plane x = plane_x + u_r with normal +x (the slaves
   * lie on its +x side). Nodes are numbered compactly: node i has displacement components
   * u[2 i], u[2 i + 1]; for a rigid plane u[2 n_nodes] is the plane's displacement u_r.
   */
  class PenaltyContact
  {
  public:
    struct Node
    {
      double x = 0, y = 0; ///< reference position, m
    };
    struct Slave
    {
      unsigned int node      = 0;
      double       stiffness = 0; ///< k, N/m per metre of depth
      double       damping   = 0; ///< c, N s/m per metre of depth
    };
    struct Segment
    {
      unsigned int a = 0, b = 0;
      /** +1 or -1: outward normal n = sign * (t_y, -t_x), t = (x_b - x_a) / |x_b - x_a|. */
      double normal_sign = 1;
    };
    /** One active slave: its gap derivative dg/du over up to 6 compact DoFs. */
    struct ActivePair
    {
      unsigned int                slave = 0;
      std::array<unsigned int, 6> dofs{};
      std::array<double, 6>       dg_du{};
      unsigned int                n_dofs      = 0;
      double                      penetration = 0; ///< -g, m (> 0)
      double                      force       = 0; ///< lambda, N/m
      double dforce_dpenetration = 0; ///< d lambda / dp, N/m^2 (k, or 0 when clamped at 0)
      double dforce_drate        = 0; ///< d lambda / d(dp/dt), N s/m^2 (c or 0)
    };
    struct Evaluation
    {
      std::vector<double>     force; ///< compact, N/m, on the nodes (and the plane)
      std::vector<ActivePair> active;
      double                  total_force     = 0; ///< sum of lambda, N/m
      double                  penalty_energy  = 0; ///< sum of k p^2 / 2, J/m
      double                  max_penetration = 0; ///< m
      /** Stiffness-weighted mean penetration of all slaves, sum k_i p_i / sum k_i (m). */
      double mean_penetration = 0;
    };

    /** Node-to-segment contact against a deformable master. */
    PenaltyContact(std::vector<Node>    nodes,
                   std::vector<Slave>   slaves,
                   std::vector<Segment> segments);
    /** Node-to-plane contact against a rigid master x = plane_x + u_r. */
    PenaltyContact(std::vector<Node> nodes, std::vector<Slave> slaves, double plane_x);

    /**
     * Limit the damping force to +k p, so lambda is continuous at first touch (lambda -> 0 as
     * p -> 0). Needed by Newton in implicit time stepping, where the dashpot jump c v at p = 0
     * is a discontinuity of the residual; the explicit path keeps the unlimited dashpot.
     */
    void set_continuous_damping(bool on) { continuous_damping_ = on; }

    /** Size of the compact displacement vector: 2 n_nodes (+1 with a rigid plane). */
    unsigned int              n_compact_dofs() const;
    bool                      rigid_master() const { return rigid_; }
    const std::vector<Node>  &nodes() const { return nodes_; }
    const std::vector<Slave> &slaves() const { return slaves_; }

    /** Gap g (m, negative = penetration) of every slave in the reference configuration. */
    std::vector<double> reference_gaps() const;

    /**
     * Contact forces for compact displacements u and velocities v (the damping uses the
     * penetration rate -dg/du . v). The force never pulls (lambda >= 0). At first touch the
     * dashpot gives a spike c v of duration ~ 1/omega, i.e. an impulse ~ 2 xi m v independent
     * of k: a moving average over a fixed window therefore converges as k grows. Pure: no state.
     */
    Evaluation evaluate(const std::vector<double> &u, const std::vector<double> &v) const;

  private:
    /** Closest master point of slave s at displacement u: fills pair dofs, dg_du, returns g. */
    bool project(unsigned int s, const std::vector<double> &u, ActivePair &pair, double &gap) const;

    std::vector<Node>    nodes_;
    std::vector<Slave>   slaves_;
    std::vector<Segment> segments_;
    bool                 rigid_              = false;
    bool                 continuous_damping_ = false;
    double               plane_x_            = 0;
  };
} // namespace kimp::fem
