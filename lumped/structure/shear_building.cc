// Shear buildings: validation, storey stiffness matrix, non-classical damping (thesis eq. 3.1-3.3),
// reference buildings of thesis Table 4.2.
#include "lumped/structure/shear_building.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "lumped/excitation/ground_motion.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/linear_isolator.h"

namespace kimp::lumped
{
  double ShearBuilding::total_mass() const
  {
    double m = 0.0;
    for (const double mi : floor_masses)
      m += mi;
    return m;
  }

  void validate(const ShearBuilding &building)
  {
    const std::size_t n = building.n_dofs();
    if (n == 0)
      throw std::invalid_argument(building.name + ".floor_masses is empty (need >= 1 floor)");
    for (std::size_t i = 0; i < n; ++i)
      if (!(std::isfinite(building.floor_masses[i]) && building.floor_masses[i] > 0.0))
      {
        std::ostringstream msg;
        msg << building.name << ".floor_masses[" << i << "] = " << building.floor_masses[i]
            << " kg (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
    const std::size_t n_storeys = building.is_isolated() ? n - 1 : n;
    if (building.storey_stiffnesses.size() != n_storeys)
    {
      std::ostringstream msg;
      msg << building.name << ".storey_stiffnesses has " << building.storey_stiffnesses.size()
          << " entries (expected " << n_storeys << " for " << n << " floor masses, "
          << (building.is_isolated() ? "isolated" : "fixed base") << ')';
      throw std::invalid_argument(msg.str());
    }
    for (std::size_t i = 0; i < n_storeys; ++i)
      if (!(std::isfinite(building.storey_stiffnesses[i]) && building.storey_stiffnesses[i] > 0.0))
      {
        std::ostringstream msg;
        msg << building.name << ".storey_stiffnesses[" << i
            << "] = " << building.storey_stiffnesses[i] << " N/m (must be > 0)";
        throw std::invalid_argument(msg.str());
      }
    if (!(building.damping_ratio >= 0.0 && building.damping_ratio < 1.0))
    {
      std::ostringstream msg;
      msg << building.name << ".damping_ratio = " << building.damping_ratio
          << " (must be in [0, 1))";
      throw std::invalid_argument(msg.str());
    }
    if (building.is_isolated() && !(building.isolation_damping_ratio >= building.damping_ratio &&
                                    building.isolation_damping_ratio < 1.0))
    {
      std::ostringstream msg;
      msg << building.name << ".isolation_damping_ratio = " << building.isolation_damping_ratio
          << " (must be in [damping_ratio = " << building.damping_ratio << ", 1))";
      throw std::invalid_argument(msg.str());
    }
  }

  TridiagonalMatrix stiffness_matrix(const ShearBuilding &building, const bool include_isolator)
  {
    validate(building);
    const std::size_t n = building.n_dofs();
    TridiagonalMatrix k(n);
    if (building.is_isolated())
    {
      for (std::size_t s = 0; s + 1 < n; ++s)
      {
        const double ks = building.storey_stiffnesses[s];
        k.diag[s] += ks;
        k.diag[s + 1] += ks;
        k.upper[s] -= ks;
      }
      if (include_isolator)
        k.diag[0] += building.isolator->initial_stiffness();
    }
    else
    {
      for (std::size_t s = 0; s < n; ++s)
      {
        const double ks = building.storey_stiffnesses[s];
        k.diag[s] += ks;
        if (s > 0)
        {
          k.diag[s - 1] += ks;
          k.upper[s - 1] -= ks;
        }
      }
    }
    return k;
  }

  BuildingDamping building_damping(const ShearBuilding &building)
  {
    validate(building);
    const std::size_t       n = building.n_dofs();
    const TridiagonalMatrix k = stiffness_matrix(building, true);
    Eigen::VectorXd         m(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i)
      m(static_cast<Eigen::Index>(i)) = building.floor_masses[i];

    BuildingDamping d;
    d.modes           = modal_analysis(m, k.to_dense());
    const double zeta = building.damping_ratio;
    d.rayleigh =
      rayleigh_coefficients(d.modes.omega(0), d.modes.omega(d.modes.omega.size() - 1), zeta, zeta);
    d.matrix = TridiagonalMatrix(n);
    for (std::size_t i = 0; i < n; ++i)
      d.matrix.diag[i] = d.rayleigh.a * building.floor_masses[i] + d.rayleigh.b * k.diag[i];
    for (std::size_t i = 0; i + 1 < n; ++i)
      d.matrix.upper[i] = d.rayleigh.b * k.upper[i];
    if (building.is_isolated())
    {
      const double k_iso = building.isolator->initial_stiffness();
      d.c_iso =
        2.0 * (building.isolation_damping_ratio - zeta) * std::sqrt(building.total_mass() * k_iso);
      d.matrix.diag[0] += d.c_iso + building.isolator->viscous_coefficient();
    }
    return d;
  }

  namespace
  {
    ShearBuilding reference_floors(const unsigned int n_floors, const bool isolated)
    {
      if (n_floors < 1)
        throw std::invalid_argument("reference building: n_storeys = 0 (must be >= 1)");
      ShearBuilding b;
      if (isolated)
        b.floor_masses.push_back(320e3);
      for (unsigned int i = 0; i + 1 < n_floors; ++i)
        b.floor_masses.push_back(320e3);
      b.floor_masses.push_back(250e3);
      b.storey_stiffnesses.assign(n_floors, 600e6);
      return b;
    }
  } // namespace

  ShearBuilding reference_isolated_building(const unsigned int n_storeys)
  {
    ShearBuilding b           = reference_floors(n_storeys, true);
    b.name                    = "isolated";
    b.damping_ratio           = 0.02;
    b.isolation_damping_ratio = 0.05;
    // W_tot with kimp's one gravity value, as the scene path (docs/physics.md §3 "Gravity"):
    // Q = 1500.42 kN for the 4-storey building (the thesis' 9.81 gives 1500.9 kN).
    const double q = 0.1 * standard_gravity * b.total_mass();
    b.isolator     = std::make_shared<BilinearIsolator>(200e6, 25e6, q);
    return b;
  }

  ShearBuilding reference_isolated_building_linear(const unsigned int n_storeys, const double k_iso)
  {
    ShearBuilding b = reference_isolated_building(n_storeys);
    b.isolator      = std::make_shared<LinearIsolator>(k_iso);
    return b;
  }

  ShearBuilding reference_fixed_base_building(const unsigned int n_storeys)
  {
    ShearBuilding b = reference_floors(n_storeys, false);
    b.name          = "fixed_base";
    b.damping_ratio = 0.05;
    return b;
  }
} // namespace kimp::lumped
