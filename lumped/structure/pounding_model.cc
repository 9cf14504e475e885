// Assembly of pounding configurations: buildings as tridiagonal blocks, walls, basement wall,
// floor-to-floor contacts with neighbours, bumpers (thesis ch. 4-6, docs/physics.md §2).
#include "lumped/structure/pounding_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace kimp::lumped
{
  namespace
  {
    double effective_mass(const double m1, const double m2)
    {
      return m1 * m2 / (m1 + m2);
    }

    std::shared_ptr<const ForceLaw>
    make_law(const ForceLawFactory &factory, const double m_eff, const std::string &where)
    {
      if (!factory)
        throw std::invalid_argument(where + ".law is not set (need an impact law)");
      std::unique_ptr<ForceLaw> law = factory(m_eff);
      if (!law)
        throw std::invalid_argument(where + ".law: the factory returned no law");
      return std::shared_ptr<const ForceLaw>(std::move(law));
    }

    void check_wall(const MoatWall &wall, const std::string &where)
    {
      if (!(std::isfinite(wall.gap) && wall.gap > 0.0))
      {
        std::ostringstream msg;
        msg << where << ".gap = " << wall.gap << " m (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
      if (!(std::isfinite(wall.mass) && wall.mass > 0.0))
      {
        std::ostringstream msg;
        msg << where << ".mass = " << wall.mass << " kg (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
      if (wall.sdof_mass && !(std::isfinite(*wall.sdof_mass) && *wall.sdof_mass > 0.0))
      {
        std::ostringstream msg;
        msg << where << ".sdof_mass = " << *wall.sdof_mass << " kg (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
      if (wall.flexible && !(std::isfinite(wall.stiffness) && wall.stiffness > 0.0))
      {
        std::ostringstream msg;
        msg << where << ".stiffness = " << wall.stiffness << " N/m (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
      if (wall.flexible && !(wall.damping_ratio >= 0.0 && wall.damping_ratio < 1.0))
      {
        std::ostringstream msg;
        msg << where << ".damping_ratio = " << wall.damping_ratio << " (must be in [0, 1))";
        throw std::invalid_argument(msg.str());
      }
      if (wall.flexible && wall.yielding)
        throw std::invalid_argument(where + ": flexible and yielding exclude each other");
      if (!(wall.bumper_thickness >= 0.0 && wall.bumper_thickness < wall.gap))
      {
        std::ostringstream msg;
        msg << where << ".bumper_thickness = " << wall.bumper_thickness
            << " m (must be in [0, gap = " << wall.gap << " m))";
        throw std::invalid_argument(msg.str());
      }
    }

    void append_block(const ShearBuilding        &building,
                      std::vector<double>        &masses,
                      TridiagonalMatrix          &k,
                      TridiagonalMatrix          &c,
                      std::vector<Storey>        &storeys,
                      std::vector<BuildingBlock> &blocks,
                      const bool                  with_storeys = true)
    {
      const TridiagonalMatrix kb    = stiffness_matrix(building, false);
      BuildingBlock           block = {building.name,
                                       static_cast<int>(masses.size()),
                                       static_cast<int>(building.n_dofs()),
                                       building_damping(building)};
      const std::size_t       first = masses.size();
      for (std::size_t i = 0; i < building.n_dofs(); ++i)
      {
        masses.push_back(building.floor_masses[i]);
        k.diag.push_back(kb.diag[i]);
        c.diag.push_back(block.damping.matrix.diag[i]);
        // The entry coupling this block's last DOF to the next block stays 0.
        if (first + i > 0)
        {
          k.upper.push_back(i > 0 ? kb.upper[i - 1] : 0.0);
          c.upper.push_back(i > 0 ? block.damping.matrix.upper[i - 1] : 0.0);
        }
      }
      const int first_storey = building.is_isolated() ? 1 : 0;
      for (int i = first_storey; with_storeys && i < block.n_dofs; ++i)
        storeys.push_back(
          {i == 0 ? -1 : block.first_dof + i - 1, block.first_dof + i, building.name});
      blocks.push_back(std::move(block));
    }
  } // namespace

  ForceLawFactory force_law_factory(ForceLawSpec spec)
  {
    return [spec](const double effective_mass)
    {
      ForceLawSpec s   = spec;
      s.effective_mass = effective_mass;
      return make_force_law(s);
    };
  }

  PoundingModel::PoundingModel(const PoundingScene &scene)
  {
    validate(scene.building);
    append_block(scene.building, masses_, stiffness_, damping_, storeys_, buildings_);
    isolator_ = scene.building.isolator;

    // Contacts with a flexible wall, patched to the wall's DOF once it exists (after the
    // neighbours, so that their DOFs do not move): (contact index, wall, right side).
    std::vector<std::tuple<std::size_t, const MoatWall *, bool>> flexible_contacts;
    const auto add_wall = [&](const MoatWall &wall, const bool right, const std::string &where)
    {
      check_wall(wall, where);
      const int n_levels = scene.basement ? 2 : 1;
      if (n_levels > static_cast<int>(scene.building.n_dofs()))
        throw std::invalid_argument("basement = true needs a building with at least 2 floors");
      for (int level = 0; level < n_levels; ++level)
      {
        ContactPair c;
        c.name            = where + (level == 0 ? "" : "_floor1");
        c.left_dof        = right ? level : -1;
        c.right_dof       = right ? -1 : level;
        c.gap             = wall.clear_gap();
        const double mass = masses_[static_cast<std::size_t>(level)];
        // The law is the one calibrated against the wall mass `mass`, whatever the SDOF's mass:
        // a flexible wall then differs from the rigid one by its compliance and inertia only,
        // not by the law's dashpot constant (docs/physics.md §2 "Flexible moat wall"). The
        // stable step needs the bodies' own masses.
        c.effective_mass =
          effective_mass(mass, wall.has_dof() ? wall.oscillator_mass() : wall.mass);
        c.law = make_law(wall.law, effective_mass(mass, wall.mass), where);
        if (wall.has_dof())
          flexible_contacts.emplace_back(contacts_.size(), &wall, right);
        contacts_.push_back(std::move(c));
      }
    };
    if (scene.left_wall)
      add_wall(*scene.left_wall, false, "left_wall");
    if (scene.right_wall)
      add_wall(*scene.right_wall, true, "right_wall");

    const auto add_neighbour =
      [&](const AdjacentBuilding &nb, const bool right, const std::string &where)
    {
      validate(nb.building);
      if (nb.building.is_isolated())
        throw std::invalid_argument(where + ".building: adjacent buildings must be fixed-base");
      if (!(std::isfinite(nb.separation) && nb.separation > 0.0))
      {
        std::ostringstream msg;
        msg << where << ".separation = " << nb.separation << " m (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
      const int first = static_cast<int>(masses_.size());
      append_block(nb.building, masses_, stiffness_, damping_, storeys_, buildings_);
      // Isolated main building: its floor j (DOF j, j >= 1) faces the neighbour's floor j (local
      // DOF j − 1). Fixed-base main building: floor j is DOF j − 1 in both.
      const int main_offset = scene.building.is_isolated() ? 0 : -1;
      const int n_main      = static_cast<int>(scene.building.n_dofs());
      for (int j = 1; j + main_offset < n_main && j <= static_cast<int>(nb.building.n_dofs()); ++j)
      {
        ContactPair c;
        const int   main_dof = j + main_offset;
        const int   nb_dof   = first + j - 1;
        c.name               = where + "_floor" + std::to_string(j);
        c.left_dof           = right ? main_dof : nb_dof;
        c.right_dof          = right ? nb_dof : main_dof;
        c.gap                = nb.separation;
        c.effective_mass     = effective_mass(masses_[static_cast<std::size_t>(main_dof)],
                                          masses_[static_cast<std::size_t>(nb_dof)]);
        c.law                = make_law(nb.law, c.effective_mass, where);
        contacts_.push_back(std::move(c));
      }
    };
    if (scene.left_neighbour)
      add_neighbour(*scene.left_neighbour, false, "left_neighbour");
    if (scene.right_neighbour)
      add_neighbour(*scene.right_neighbour, true, "right_neighbour");

    // Flexible walls: one fixed-base single-storey block each (stiffness-proportional damping
    // gives exactly ζ for one mode), no storey (its deflection is not an interstorey drift).
    // Yielding walls: a block of one DOF without stiffness or damping, held by the permanent
    // pair of its wall-and-backfill part.
    for (const auto &[wall, where] :
         {std::pair<const std::optional<MoatWall> *, const char *>{&scene.left_wall, "left_wall"},
          {&scene.right_wall, "right_wall"}})
    {
      if (!*wall || !(*wall)->has_dof())
        continue;
      if ((*wall)->yielding)
      {
        const int dof = append_yielding_wall(**wall, where, where == std::string("right_wall"));
        for (const auto &[index, w, right] : flexible_contacts)
          if (w == &**wall)
            (right ? contacts_[index].right_dof : contacts_[index].left_dof) = dof;
        continue;
      }
      ShearBuilding sdof;
      sdof.name                    = where;
      sdof.floor_masses            = {(*wall)->oscillator_mass()};
      sdof.storey_stiffnesses      = {(*wall)->stiffness};
      sdof.damping_ratio           = (*wall)->damping_ratio;
      sdof.isolation_damping_ratio = (*wall)->damping_ratio;
      const int dof                = static_cast<int>(masses_.size());
      append_block(sdof, masses_, stiffness_, damping_, storeys_, buildings_, false);
      for (const auto &[index, w, right] : flexible_contacts)
        if (w == &**wall)
          (right ? contacts_[index].right_dof : contacts_[index].left_dof) = dof;
    }
    check();
  }

  int PoundingModel::append_yielding_wall(const MoatWall    &wall,
                                          const std::string &where,
                                          bool               right)
  {
    const int dof = static_cast<int>(masses_.size());
    masses_.push_back(wall.oscillator_mass());
    stiffness_.diag.push_back(0.0);
    damping_.diag.push_back(0.0);
    stiffness_.upper.push_back(0.0);
    damping_.upper.push_back(0.0);
    BuildingBlock block;
    block.name      = where;
    block.first_dof = dof;
    block.n_dofs    = 1;
    buildings_.push_back(std::move(block));

    WallBackfillParams params = *wall.yielding;
    params.mass               = wall.oscillator_mass();
    ContactPair c;
    c.name = where + "_backfill";
    // w = the wall's displacement into its backfill: −u_wall on the left, u_wall on the right.
    c.left_dof            = right ? dof : -1;
    c.right_dof           = right ? -1 : dof;
    c.gap                 = 0.0;
    c.effective_mass      = params.mass;
    c.law                 = std::make_shared<const WallBackfillLaw>(params);
    c.permanent           = true;
    c.failure_deformation = params.failure_displacement;
    contacts_.push_back(std::move(c));
    return dof;
  }

  PoundingModel::PoundingModel(std::vector<double>             masses,
                               TridiagonalMatrix               stiffness,
                               TridiagonalMatrix               damping,
                               std::shared_ptr<const Isolator> isolator,
                               std::vector<ContactPair>        contacts,
                               std::vector<Storey>             storeys)
    : masses_(std::move(masses))
    , stiffness_(std::move(stiffness))
    , damping_(std::move(damping))
    , isolator_(std::move(isolator))
    , contacts_(std::move(contacts))
    , storeys_(std::move(storeys))
  {
    check();
  }

  void PoundingModel::check() const
  {
    const std::size_t n = masses_.size();
    if (n == 0)
      throw std::invalid_argument("pounding model: no degrees of freedom");
    if (stiffness_.size() != n || damping_.size() != n || stiffness_.upper.size() + 1 != n ||
        damping_.upper.size() + 1 != n)
      throw std::invalid_argument("pounding model: K and C must be tridiagonal of the size of M");
    for (std::size_t i = 0; i < n; ++i)
      if (!(masses_[i] > 0.0))
      {
        std::ostringstream msg;
        msg << "pounding model: mass[" << i << "] = " << masses_[i] << " kg (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
    for (const ContactPair &c : contacts_)
    {
      const int nn = static_cast<int>(n);
      if (c.left_dof < -1 || c.left_dof >= nn || c.right_dof < -1 || c.right_dof >= nn ||
          c.left_dof == c.right_dof)
        throw std::invalid_argument("contact '" + c.name + "': DOF indices out of range");
      if (!c.law)
        throw std::invalid_argument("contact '" + c.name + "': no impact law");
      if (!(c.gap >= 0.0 && c.effective_mass > 0.0))
      {
        std::ostringstream msg;
        msg << "contact '" << c.name << "': gap = " << c.gap
            << " m, effective_mass = " << c.effective_mass
            << " kg (need gap >= 0, effective_mass > 0)";
        throw std::invalid_argument(msg.str());
      }
    }
  }

  Eigen::MatrixXd PoundingModel::initial_stiffness_matrix() const
  {
    Eigen::MatrixXd k = stiffness_.to_dense();
    if (isolator_)
      k(0, 0) += isolator_->initial_stiffness();
    return k;
  }

  ModalProperties PoundingModel::modes() const
  {
    return modal_analysis(Eigen::Map<const Eigen::VectorXd>(masses_.data(),
                                                            static_cast<Eigen::Index>(n_dofs())),
                          initial_stiffness_matrix());
  }

  PoundingModel PoundingModel::without_contacts() const
  {
    PoundingModel copy = *this;
    copy.contacts_.erase(std::remove_if(copy.contacts_.begin(),
                                        copy.contacts_.end(),
                                        [](const ContactPair &c) { return !c.permanent; }),
                         copy.contacts_.end());
    return copy;
  }
} // namespace kimp::lumped
