// The soil presets of inelastic_laws.h: five sands and clays by name (E, nu, rho, c, phi, psi;
// docs/physics.md "inelastic materials" gives the sources).
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/inelastic_laws.h"

namespace kimp::fem
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;
    double           deg(double d)
    {
      return d * pi / 180;
    }
  } // namespace

  const std::vector<SoilPreset> &soil_presets()
  {
    // E, nu, rho, c, phi, psi: docs/physics.md (inelastic materials) gives the sources.
    static const std::vector<SoilPreset> presets = {
      {"loose_sand", {20e6, 0.3, 1700, 0, deg(30), deg(0), 0}},
      {"medium_dense_sand", {40e6, 0.3, 1850, 0, deg(34), deg(4), 0}},
      {"dense_sand", {70e6, 0.3, 2000, 0, deg(38), deg(8), 0}},
      {"soft_clay", {5e6, 0.45, 1700, 20e3, deg(0), deg(0), 0}},
      {"stiff_clay", {40e6, 0.45, 2000, 100e3, deg(0), deg(0), 0}},
    };
    return presets;
  }

  const SoilParameters &soil_preset(const std::string &name)
  {
    std::string names;
    for (const auto &p : soil_presets())
    {
      if (p.name == name)
        return p.parameters;
      names += (names.empty() ? "" : ", ") + p.name;
    }
    throw std::invalid_argument("unknown soil preset '" + name + "' (expected one of: " + names +
                                ")");
  }
} // namespace kimp::fem
