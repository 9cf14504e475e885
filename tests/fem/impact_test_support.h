// Shared helpers of the kimp::fem tests: scratch files, the two-bar and scene meshes, summaries.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <mpi.h>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>

#include "fem/impact.h"
#include "geometry/scene_geometry.h"
#include "geometry/scene_ids.h"
#include "geometry/scene_mesh.h"
#include "tests/fem/test_meshes.h"
#include "tests/support/mpi_temp_dir.h"

namespace kimp::fem::testing
{
  namespace ids = kimp::geometry;

  inline const Material concrete{30e9, 0.2, 2400};
  inline const Material soil{50e6, 0.3, 1900};
  /** Poisson ratio 0: plane strain is then exactly 1D for a bar, c = sqrt(E / rho). */
  inline const Material bar_material{30e9, 0.0, 2400};

  inline int rank()
  {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
  }

  /** A per-process scratch directory (same on all ranks of one mpirun). */
  inline std::filesystem::path scratch(const std::string &name)
  {
    return kimp::testing::shared_temp_dir("fem_test", MPI_COMM_WORLD) / name;
  }

  /**
   * Two equal bars of length L and thickness t, the left one (slab, material 1) moving at v
   * towards the right one (material 2) at rest, gap g, n_t cells across the thickness.
   */
  inline std::filesystem::path
  write_two_bars(double L, double t, double gap, unsigned int n_t, const std::string &name)
  {
    const auto file = scratch(name);
    if (rank() == 0)
    {
      const unsigned int n_l = static_cast<unsigned int>(std::lround(n_t * L / t));
      kimp::fem::testing::write_blocks_msh(
        {{-gap - L, -gap, 0, t, n_l, n_t, ids::slab_material, 0, ids::slab_contact, 0, 0},
         {0, L, 0, t, n_l, n_t, ids::wall_material, ids::wall_contact, 0, 0, 0}},
        file);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    return file;
  }

  inline ImpactParameters bar_parameters(const std::filesystem::path &mesh)
  {
    ImpactParameters p;
    p.mesh_file                     = mesh;
    p.materials[ids::slab_material] = bar_material;
    p.materials[ids::wall_material] = bar_material;
    p.end_time                      = 2e-3;
    p.separation_hold_time          = 0.1e-3;
    p.output_interval               = 0;
    return p;
  }

  /** Mean of the smoothed force over the middle part [a, b] of the contact (fractions). */
  inline double plateau(const ImpactResult &r, double a, double b)
  {
    const auto  &h  = r.history;
    const double t0 = r.summary.contact_start, T = r.summary.contact_duration;
    double       sum = 0;
    int          n   = 0;
    for (std::size_t i = 0; i < h.time.size(); ++i)
      if (h.time[i] >= t0 + a * T && h.time[i] <= t0 + b * T)
      {
        sum += h.smoothed_contact_force[i];
        ++n;
      }
    return n > 0 ? sum / n : 0;
  }

  inline std::string summary_line(const ImpactResult &r)
  {
    std::ostringstream s;
    const auto        &m = r.summary;
    s << "peak " << m.peak_force << " N/m (raw " << m.peak_force_raw << "), duration "
      << m.contact_duration << " s, impulse " << m.impulse << " N s/m, COR " << m.apparent_cor
      << ", |dE/E0| " << m.energy_error << ", penetration max " << m.max_penetration << " m, mean "
      << m.mean_penetration << " m, " << m.n_dofs << " DoFs, " << m.n_steps << " steps, dt " << m.dt
      << " s, " << m.wall_seconds << " s";
    return s.str();
  }


  /** The docs/physics.md §4 scene (H = 1.25 m) meshed by geometry/ with contact size h. */
  inline ImpactParameters
  scene_parameters(double h_contact, bool rigid, const std::string &name, double h_max = 0.2)
  {
    kimp::geometry::SceneGeometry g;
    g.h_contact     = h_contact;
    g.h_max         = std::max(h_max, h_contact);
    g.mesh_slab     = !rigid;
    const auto file = scratch(name);
    if (rank() == 0)
      kimp::geometry::build_scene_mesh(g, file);
    MPI_Barrier(MPI_COMM_WORLD);
    ImpactParameters p;
    p.mesh_file                     = file;
    p.materials[ids::slab_material] = concrete;
    p.materials[ids::wall_material] = concrete;
    p.materials[ids::soil_material] = soil;
    p.rigid_slab                    = rigid;
    p.slab_mass                     = concrete.density * g.slab_length * g.slab_thickness;
    p.slab_face_y0                  = g.slab_bottom();
    p.slab_face_y1                  = g.resolved_slab_top();
    p.slab_front_x                  = g.slab_front_x();
    p.end_time                      = 0.05;
    p.output_interval               = 1e-5;
    return p;
  }

  /**
   * Compare the contact-force histories of two runs sampled alike (e.g. on 1-2 ranks and on
   * MPI_COMM_SELF): {largest force of `reference`, largest |force(run) - force(reference)|}, N/m.
   */
  inline std::pair<double, double> force_history_difference(const ImpactResult &run,
                                                            const ImpactResult &reference)
  {
    double max_force = 0, max_difference = 0;
    for (std::size_t i = 0; i < reference.history.time.size(); ++i)
    {
      max_force = std::max(max_force, reference.history.contact_force[i]);
      max_difference =
        std::max(max_difference,
                 std::abs(run.history.contact_force[i] - reference.history.contact_force[i]));
    }
    return {max_force, max_difference};
  }
} // namespace kimp::fem::testing
