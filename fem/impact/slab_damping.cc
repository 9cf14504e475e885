// ImpactProblem slab damping: mass-proportional damping of the elastic slab's x velocity relative
// to its plane sections' motion, tuned to the slab's first free-free axial mode
// (ImpactParameters::slab_damping_ratio, docs/physics.md §4).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <deal.II/base/mpi.h>

#include "fem/impact/impact_problem.h"
#include "geometry/scene_ids.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  void ImpactProblem::setup_slab_damping()
  {
    slab_damped_index.clear();
    slab_damped_m.clear();
    slab_damped_y.clear();
    slab_damping_local = 0;
    slab_alpha         = 0;
    if (prm.slab_damping_ratio == 0)
      return;

    // The owned, free x DoFs of the slab's vertices, with their heights.
    std::vector<char>   seen(locally_owned.n_elements(), 0);
    std::vector<double> y;
    double              x_min = std::numeric_limits<double>::max(), x_max = -x_min;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() == geometry::slab_material)
        for (unsigned int v = 0; v < cell->n_vertices(); ++v)
        {
          x_min                           = std::min(x_min, cell->vertex(v)[0]);
          x_max                           = std::max(x_max, cell->vertex(v)[0]);
          const types::global_dof_index i = cell->vertex_dof_index(v, 0);
          if (!locally_owned.is_element(i) || constraints.is_constrained(i))
            continue;
          const auto k = locally_owned.index_within_set(i);
          if (seen[k] != 0)
            continue;
          seen[k] = 1;
          slab_damped_index.push_back(static_cast<unsigned int>(k));
          slab_damped_m.push_back(mass(i));
          y.push_back(cell->vertex(v)[1]);
        }
    const double length = Utilities::MPI::max(x_max, comm) + Utilities::MPI::max(-x_min, comm);
    require(length > 0 && length < std::numeric_limits<double>::max(),
            "slab_damping_ratio: mesh '" + prm.mesh_file.string() + "' has no slab cells");

    // The slab's centre height and its mass moment about it, over every rank's DoFs.
    std::array<double, 2> local{}, global{};
    for (std::size_t k = 0; k < y.size(); ++k)
    {
      local[0] += slab_damped_m[k];
      local[1] += slab_damped_m[k] * y[k];
    }
    reduce_over_ranks(local.data(), global.data(), 2, MPI_SUM, comm);
    slab_damped_mass = global[0];
    const double y_c = global[1] / global[0];
    slab_damped_y.resize(y.size());
    double inertia_local = 0;
    for (std::size_t k = 0; k < y.size(); ++k)
    {
      slab_damped_y[k] = y[k] - y_c;
      inertia_local += slab_damped_m[k] * slab_damped_y[k] * slab_damped_y[k];
    }
    slab_damped_inertia = Utilities::MPI::sum(inertia_local, comm);

    // First free-free axial mode of a plane-strain bar: omega_1 = pi / L sqrt(E / (rho (1 -
    // nu^2))).
    const Material &m = prm.materials.at(geometry::slab_material);
    const double    c =
      std::sqrt(m.youngs_modulus / (m.density * (1 - m.poisson_ratio * m.poisson_ratio)));
    const double omega_1 = numbers::PI * c / length;
    slab_alpha           = 2 * prm.slab_damping_ratio * omega_1;
    log_line("slab damping: " + fmt_sig(prm.slab_damping_ratio) +
             " of critical at omega_1 = " + fmt_sig(omega_1) + " rad/s (L = " + fmt_sig(length) +
             " m), alpha = " + fmt_sig(slab_alpha) + " 1/s");
  }

  void ImpactProblem::apply_slab_damping(const bool first_step, const Vec &v_half, Vec &a)
  {
    // The plane sections' motion: the mass-weighted least-squares fit V + w y of the slab's x
    // velocities (V from the momentum, w from the first moment about the centre).
    const double         *vp = v_half.begin();
    double               *ap = a.begin();
    std::array<double, 2> local{}, global{};
    for (std::size_t k = 0; k < slab_damped_index.size(); ++k)
    {
      const double mv = slab_damped_m[k] * vp[slab_damped_index[k]];
      local[0] += mv;
      local[1] += mv * slab_damped_y[k];
    }
    reduce_over_ranks(local.data(), global.data(), 2, MPI_SUM, comm);
    const double V = global[0] / slab_damped_mass;
    const double w = slab_damped_inertia > 0 ? global[1] / slab_damped_inertia : 0.0;
    // The step's work: the force times v_n = v_{n-1/2} + dt/2 a_n, over the leap-frog step dt
    // (half of it at the start), the dissipation alpha m |v - v_plane|^2 dt.
    const double h = first_step ? 0.5 * dt : dt;
    for (std::size_t k = 0; k < slab_damped_index.size(); ++k)
    {
      const unsigned int j   = slab_damped_index[k];
      const double       d   = vp[j] - V - w * slab_damped_y[k];
      const double       v_n = first_step ? vp[j] : vp[j] + 0.5 * dt * ap[j];
      ap[j] -= slab_alpha * d;
      slab_damping_local +=
        slab_alpha * slab_damped_m[k] * d * (v_n - 0.5 * dt * slab_alpha * d) * h;
    }
  }
} // namespace kimp::fem::internal
