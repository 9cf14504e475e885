// Shared helpers of the kimp::fem tests: scratch files, the two-bar and scene meshes, summaries.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <iostream>
#include <mpi.h>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

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

  /** The blocks written to scratch(name) by rank 0, every rank waiting for the file; its path. */
  inline std::filesystem::path write_blocks(const std::vector<Block> &blocks,
                                            const std::string        &name)
  {
    const auto file = scratch(name);
    if (rank() == 0)
      write_blocks_msh(blocks, file);
    MPI_Barrier(MPI_COMM_WORLD);
    return file;
  }

  /**
   * Two equal bars of length L and thickness t, the left one (slab, material 1) moving at v
   * towards the right one (material 2) at rest, gap g, n_t cells across the thickness.
   */
  inline std::filesystem::path
  write_two_bars(double L, double t, double gap, unsigned int n_t, const std::string &name)
  {
    const unsigned int n_l = static_cast<unsigned int>(std::lround(n_t * L / t));
    return write_blocks(
      {{-gap - L, -gap, 0, t, n_l, n_t, ids::slab_material, 0, ids::slab_contact, 0, 0},
       {0, L, 0, t, n_l, n_t, ids::wall_material, ids::wall_contact, 0, 0, 0}},
      name);
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


  /** The docs/physics.md §4 scene (H = 1.25 m) meshed by geometry/ with contact size h; with
   *  `interface_contact`, separate wall and soil nodes along the wall's back. */
  inline ImpactParameters scene_parameters(double             h_contact,
                                           bool               rigid,
                                           const std::string &name,
                                           double             h_max             = 0.2,
                                           bool               interface_contact = false)
  {
    kimp::geometry::SceneGeometry g;
    g.h_contact         = h_contact;
    g.h_max             = std::max(h_max, h_contact);
    g.mesh_slab         = !rigid;
    g.interface_contact = interface_contact;
    const auto file     = scratch(name);
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
   * Compare two histories sampled alike: {largest value of `reference`, largest
   * |run - reference|} over the samples of `reference`.
   */
  inline std::pair<double, double> history_difference(const std::vector<double> &run,
                                                      const std::vector<double> &reference)
  {
    double max_value = 0, max_difference = 0;
    for (std::size_t i = 0; i < reference.size(); ++i)
    {
      max_value      = std::max(max_value, reference[i]);
      max_difference = std::max(max_difference, std::abs(run[i] - reference[i]));
    }
    return {max_value, max_difference};
  }

  /**
   * Compare the contact-force histories of two runs sampled alike (e.g. on 1-2 ranks and on
   * MPI_COMM_SELF): {largest force of `reference`, largest |force(run) - force(reference)|}, N/m.
   */
  inline std::pair<double, double> force_history_difference(const ImpactResult &run,
                                                            const ImpactResult &reference)
  {
    return history_difference(run.history.contact_force, reference.history.contact_force);
  }

  /** One problem run on MPI_COMM_WORLD (1 or 2 ranks under ctest) and on MPI_COMM_SELF. */
  struct WorldAndSelf
  {
    ImpactResult world, self;
  };

  inline WorldAndSelf run_on_world_and_self(const ImpactParameters &p)
  {
    return {run_impact(p, MPI_COMM_WORLD, nullptr), run_impact(p, MPI_COMM_SELF, nullptr)};
  }

  /**
   * The world run has as many samples as the self run (fatal otherwise), the self run a
   * contact force (fatal otherwise), and the contact forces agree within `tolerance` of the
   * largest; rank 0 prints `label` with the relative difference. Call it inside
   * ASSERT_NO_FATAL_FAILURE() so that a fatal failure ends the test.
   */
  inline void
  expect_same_force_history(const WorldAndSelf &runs, double tolerance, const std::string &label)
  {
    ASSERT_EQ(runs.world.history.time.size(), runs.self.history.time.size());
    const auto [max_force, max_difference] = force_history_difference(runs.world, runs.self);
    ASSERT_GT(max_force, 0);
    EXPECT_LT(max_difference, tolerance * max_force);
    if (rank() == 0)
      std::cout << label << ": " << runs.world.summary.n_ranks
                << " ranks vs 1, max |dF| / max F = " << max_difference / max_force << '\n';
  }

  /**
   * A run of @p p with absorbing boundaries on MPI_COMM_WORLD and on MPI_COMM_SELF: the same
   * force history (expect_same_force_history()) and radiated energy, within @p tolerance (of
   * the largest force and of E_0).
   */
  inline void
  expect_same_absorbing_run(const ImpactParameters &p, double tolerance, const std::string &label)
  {
    const auto runs = run_on_world_and_self(p);
    ASSERT_NO_FATAL_FAILURE(expect_same_force_history(runs, tolerance, label));
    EXPECT_NEAR(runs.world.summary.radiated_energy,
                runs.self.summary.radiated_energy,
                tolerance * runs.self.history.kinetic.front());
    EXPECT_NEAR(runs.world.summary.boundary_spring_energy,
                runs.self.summary.boundary_spring_energy,
                tolerance * runs.self.history.kinetic.front());
  }
} // namespace kimp::fem::testing
