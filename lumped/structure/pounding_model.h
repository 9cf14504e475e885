// Assembled pounding system (thesis ch. 3-5, docs/physics.md §2): the isolated (or fixed-base)
// building, adjacent fixed-base buildings stacked as independent tridiagonal blocks, the isolator
// at DOF 0 and unilateral contacts (moat walls, basement wall, floor-to-floor) coupling them:
//   M·ü + C·u̇ + K·u + f_iso(u_0) + Σ_c e_c·F_c(δ_c, δ̇_c) = −M·1·ü_g(t),  δ_c = u_L − u_R − gap_c.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lumped/isolators/isolator.h"
#include "lumped/laws/force_law.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/wall_backfill_law.h"
#include "lumped/structure/shear_building.h"
#include "lumped/structure/tridiagonal_matrix.h"

namespace kimp::lumped
{
  /// Creates the impact law of one contact from its effective mass m_eff = m1·m2/(m1+m2), kg
  /// (the laws use m_eff in their damping constants). Wraps make_force_law(ForceLawSpec).
  using ForceLawFactory = std::function<std::unique_ptr<ForceLaw>(double effective_mass)>;

  /// A ForceLawFactory that calls make_force_law(spec) with spec.effective_mass set per contact.
  ForceLawFactory force_law_factory(ForceLawSpec spec);

  /**
   * Moat wall on one side of the isolation level: rigid, moving with the ground, or (`flexible`)
   * a single-DOF oscillator of mass `sdof_mass` (unset: `mass`), stiffness `stiffness` and damping
   * ratio `damping_ratio` attached to the ground (docs/physics.md §2 "Flexible moat wall"); the
   * contact then acts between the isolation level and the wall's DOF. The impact law's m_eff
   * always takes `mass`, so a flexible wall with its own `sdof_mass` keeps the law (its dashpot
   * constant) of the rigid wall of mass `mass`.
   *
   * | field            | unit | admissible     | meaning                                      |
   * |------------------|------|----------------|----------------------------------------------|
   * | gap              | m    | > 0            | distance from the isolation level to the     |
   * |                  |      |                | wall face (before bumpers)                   |
   * | mass             | kg   | > 0            | wall mass for m_eff in the law (thesis 500 t)|
   * | sdof_mass        | kg   | > 0 or unset   | flexible: the SDOF's mass (unset: `mass`)    |
   * | bumper_thickness | m    | [0, gap)       | rubber bumper thickness t (law 7)            |
   * | bumper_recessed  | -    |                | true: bumpers sit in a recess, gap unchanged |
   * | flexible         | -    |                | false: rigid; true: SDOF wall                |
   * | stiffness        | N/m  | > 0            | SDOF wall: stiffness to the ground           |
   * | damping_ratio    | -    | [0, 1)         | SDOF wall: ζ (c = 2ζ·sqrt(k·m))              |
   * | yielding         | -    | set or unset   | yielding wall: its wall-and-backfill part    |
   *
   * A yielding wall (docs/physics.md §2 "Yielding moat wall") is a DOF of mass `sdof_mass`
   * (unset: `mass`) held to the ground by a WallBackfillLaw (`yielding`, its `mass` set by the
   * model) instead of a linear spring: the impact law is the local contact part in series with
   * the wall-and-backfill part. `flexible` and `yielding` exclude each other.
   */
  struct MoatWall
  {
    double          gap              = 0.15;
    double          mass             = 500e3;
    double          bumper_thickness = 0.0;
    bool            bumper_recessed  = false;
    ForceLawFactory law;
    bool            flexible      = false;
    double          stiffness     = 1.5e9;
    double          damping_ratio = 0.05;
    /// Flexible wall: the SDOF's mass, kg (unset: `mass`); not used by the law's m_eff.
    std::optional<double> sdof_mass;
    /// Yielding wall: the wall-and-backfill part (its `mass` is set to oscillator_mass()).
    std::optional<WallBackfillParams> yielding;

    /// True for a wall with a DOF of its own (flexible or yielding).
    bool has_dof() const { return flexible || yielding.has_value(); }

    /// The mass of the wall's DOF, kg: `sdof_mass` if set, else `mass`.
    double oscillator_mass() const { return sdof_mass.value_or(mass); }

    /// Clear gap before contact, m: gap − t unless recessed.
    double clear_gap() const { return bumper_recessed ? gap : gap - bumper_thickness; }
  };

  /// A fixed-base building beside the main one; its floor j meets floor j of the main building's
  /// superstructure (j >= 1 above the isolation level) across `separation` (m, > 0).
  struct AdjacentBuilding
  {
    ShearBuilding   building;
    double          separation = 0.15;
    ForceLawFactory law;
  };

  /**
   * A pounding configuration (plain data). The main building is usually isolated; walls act at
   * its DOF 0 (and at DOF 1 too with `basement`, the wall reaching floor 1, same gap). DOFs:
   * the main building, then the neighbours, then one DOF per flexible or yielding wall (left
   * first), each a block of its own named after the wall ("left_wall") without a storey. A
   * yielding wall adds the permanent pair "<wall>_backfill" between its DOF and the ground.
   */
  struct PoundingScene
  {
    ShearBuilding                   building;
    std::optional<MoatWall>         left_wall;
    std::optional<MoatWall>         right_wall;
    bool                            basement = false;
    std::optional<AdjacentBuilding> left_neighbour;
    std::optional<AdjacentBuilding> right_neighbour;
  };

  /**
   * One unilateral contact between a "left" and a "right" body (index −1 = the ground, i.e. a
   * rigid wall moving with it): δ = u_L − u_R − gap. The compressive force F pushes L towards −x
   * and R towards +x.
   */
  struct ContactPair
  {
    std::string name;
    int         left_dof  = -1;
    int         right_dof = -1;
    double      gap       = 0.0; ///< clear gap, m
    /// The two bodies' m1·m2/(m1 + m2), kg, for ω_imp = √(k_t/m_eff) of the stable step. The
    /// law's own m_eff may differ: at a flexible wall with `sdof_mass` the law keeps the m_eff of
    /// the wall mass `mass` (MoatWall), this one the SDOF's.
    double                          effective_mass = 0.0;
    std::shared_ptr<const ForceLaw> law; ///< prototype; integrators clone it per run
    /// A permanent connection, not an impact contact (a yielding wall's backfill part): its law
    /// is in contact from the start and evaluated at every step; no impacts or pulses are
    /// recorded for it, and without_contacts() keeps it.
    bool permanent = false;
    /// The pair has failed once δ exceeds this, m (the time is recorded; +inf: never).
    double failure_deformation = std::numeric_limits<double>::infinity();
  };

  /// A superstructure storey between `lower_dof` (−1: ground) and `upper_dof`.
  struct Storey
  {
    int         lower_dof = -1;
    int         upper_dof = 0;
    std::string building;
  };

  /// Where a building's DOFs sit in the global vector, with its modal/damping data.
  struct BuildingBlock
  {
    std::string     name;
    int             first_dof = 0;
    int             n_dofs    = 0;
    BuildingDamping damping;
  };

  /**
   * The assembled system: diagonal M, tridiagonal K (storeys only) and C (block-tridiagonal: one
   * block per building, zero coupling between blocks), the isolator at global DOF 0, the contacts.
   */
  class PoundingModel
  {
  public:
    /// Assemble a configuration. @throws std::invalid_argument naming the bad field.
    explicit PoundingModel(const PoundingScene &scene);

    /**
     * A custom system (tests, single-degree-of-freedom studies).
     * @param[in] isolator isolator at DOF 0, or nullptr
     */
    PoundingModel(std::vector<double>             masses,
                  TridiagonalMatrix               stiffness,
                  TridiagonalMatrix               damping,
                  std::shared_ptr<const Isolator> isolator,
                  std::vector<ContactPair>        contacts,
                  std::vector<Storey>             storeys);

    std::size_t                       n_dofs() const { return masses_.size(); }
    const std::vector<double>        &masses() const { return masses_; }
    const TridiagonalMatrix          &stiffness() const { return stiffness_; }
    const TridiagonalMatrix          &damping() const { return damping_; }
    const Isolator                   *isolator() const { return isolator_.get(); }
    const std::vector<ContactPair>   &contacts() const { return contacts_; }
    const std::vector<Storey>        &storeys() const { return storeys_; }
    const std::vector<BuildingBlock> &buildings() const { return buildings_; }

    /// K with the isolator's initial stiffness at [0,0] (dense), N/m.
    Eigen::MatrixXd initial_stiffness_matrix() const;
    /// Modes of (K with isolator K1, M) of the whole system, contacts open.
    ModalProperties modes() const;
    /// The same system without any impact contact (companion run for amplification factors);
    /// permanent pairs stay.
    PoundingModel without_contacts() const;

  private:
    void check() const;
    /// Appends the DOF of a yielding wall and its permanent backfill pair; returns the DOF.
    int append_yielding_wall(const MoatWall &wall, const std::string &where, bool right);

    std::vector<double>             masses_;
    TridiagonalMatrix               stiffness_;
    TridiagonalMatrix               damping_;
    std::shared_ptr<const Isolator> isolator_;
    std::vector<ContactPair>        contacts_;
    std::vector<Storey>             storeys_;
    std::vector<BuildingBlock>      buildings_;
  };
} // namespace kimp::lumped
