// Plane-strain linear elasticity sigma = lambda tr(eps) I + 2 mu eps in Voigt form, and the
// quadrature-point history storage (see material_law.h).
#include "fem/material_law.h"

#include <algorithm>

#include "fem/material.h"

namespace kimp::fem
{
  void MaterialLaw::initial_history(double *history) const
  {
    std::fill(history, history + n_history(), 0.0);
  }

  void MaterialLaw::initialize_point(double *history, double) const
  {
    initial_history(history);
  }

  void MaterialLaw::initialize_anchored_point(double *history, double h, double) const
  {
    initialize_point(history, h);
  }

  void MaterialLaw::begin_step(double *, double) const {}

  bool MaterialLaw::set_initial_stress(double *, const InitialStress &) const
  {
    return false;
  }

  PointOutput MaterialLaw::output(const VoigtStrain &e, const double *history) const
  {
    std::vector<double> scratch(n_history());
    std::copy(history, history + n_history(), scratch.begin());
    const VoigtStress s = stress(e, history, scratch.data());
    PointOutput       o;
    o.stored_energy = 0.5 * (s[0] * e[0] + s[1] * e[1] + s[2] * e[2]);
    return o;
  }

  void MaterialLaw::update_points(unsigned int           n,
                                  const VoigtStrain     *strain,
                                  const double          *committed,
                                  double                *trial,
                                  unsigned int           stride,
                                  VoigtStress           *stress,
                                  std::array<double, 3> *energy) const
  {
    update_points_of(*this, n, strain, committed, trial, stride, stress, energy);
  }

  PointOutput LinearElasticLaw::output(const VoigtStrain &e, const double *) const
  {
    const VoigtStress s = stress(e, nullptr, nullptr);
    PointOutput       o;
    o.sigma_zz      = tangent_[1] * (e[0] + e[1]); // lambda tr(eps)
    o.stored_energy = 0.5 * (s[0] * e[0] + s[1] * e[1] + s[2] * e[2]);
    return o;
  }

  LinearElasticLaw::LinearElasticLaw(const Material &m)
  {
    const auto [lambda, mu] = lame(m.youngs_modulus, m.poisson_ratio);
    tangent_                = {{lambda + 2 * mu, lambda, 0, lambda, lambda + 2 * mu, 0, 0, 0, mu}};
  }

  VoigtStress LinearElasticLaw::stress(const VoigtStrain &e, const double *, double *) const
  {
    const auto &d = tangent_;
    return {{d[0] * e[0] + d[1] * e[1], d[3] * e[0] + d[4] * e[1], d[8] * e[2]}};
  }

  void QuadraturePointHistory::reinit(unsigned int n_cells,
                                      unsigned int n_points_per_cell,
                                      unsigned int n_values)
  {
    n_points_per_cell_ = n_points_per_cell;
    n_values_          = n_values;
    committed_.assign(static_cast<std::size_t>(n_cells) * n_points_per_cell * n_values, 0.0);
    trial_ = committed_;
  }

  void QuadraturePointHistory::initialize_cell(unsigned int cell, const MaterialLaw &law)
  {
    initialize_cell(cell, law, 0.0);
  }

  void QuadraturePointHistory::initialize_cell(unsigned int cell, const MaterialLaw &law, double h)
  {
    initialize_cell(cell, law, h, 0.0);
  }

  void QuadraturePointHistory::initialize_cell(unsigned int       cell,
                                               const MaterialLaw &law,
                                               double             h,
                                               double             height)
  {
    if (law.n_history() == 0)
      return;
    for (unsigned int q = 0; q < n_points_per_cell_; ++q)
    {
      if (height > 0)
        law.initialize_anchored_point(trial(cell, q), h, height);
      else
        law.initialize_point(trial(cell, q), h);
      std::copy(trial(cell, q),
                trial(cell, q) + law.n_history(),
                committed_.data() + offset(cell, q));
    }
  }
} // namespace kimp::fem
