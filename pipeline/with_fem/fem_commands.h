// The FEM commands of the `kimp` CLI: `kimp mesh` (scene meshes and previews) and `kimp fem`
// (the PHYSICS.md §4 impact per wall height, also under mpirun). Built only with KIMP_WITH_FEM.
#pragma once

#include <exception>
#include <filesystem>
#include <string>

#include "fem/impact.h"
#include "pipeline/fem_results.h"
#include "pipeline/with_fem/fem_scene.h"

namespace CLI
{
  class App;
}

namespace kimp::pipeline
{
  /**
   * `kimp mesh SCENE.yaml -o DIR`: per wall height H, DIR/mesh/H<H>.msh (ASCII MSH 4.1),
   * DIR/mesh/H<H>.vtu (deal.II's reading of it, material id per cell), DIR/mesh/H<H>.png (if
   * /usr/bin/python3 with matplotlib is available, else a warning) and DIR/summary.json with the
   * mesh statistics. Runs on rank 0 only.
   */
  void register_mesh_command(CLI::App &app);

  /**
   * `kimp fem SCENE.yaml -o DIR` (MPI collective; needs MPI initialised, see fem::MpiSession):
   * per wall height the mesh DIR/mesh/H<H>.msh and fem::run_impact(); rank 0 writes DIR/fem.h5
   * (/fem/<case> as in pipeline/fem_results.h, plus /fem/<case>/energy/... and contact
   * diagnostics), DIR/summary.json, DIR/fem_histories.csv and, if output.vtu_interval > 0,
   * DIR/vtu/<case>/impact.pvd. A failing case aborts the command before any of the three result
   * files exists under its final name.
   */
  void register_fem_command(CLI::App &app);

  /** The user-facing part of an exception message: the "Additional information" of a deal.II
   *  exception, whitespace collapsed; other messages unchanged. */
  std::string error_message(const std::exception &error);

  /**
   * The FemCase of one `kimp fem` run (pipeline/fem_results.h contract): histories, the
   * ImpactSummary as summary entries, and labels (integrator, slab, mesh level, penalty factor,
   * what stopped the run). Shared by `kimp fem` and `kimp study`.
   */
  FemCase to_fem_case(const std::string       &name,
                      double                   wall_height,
                      const FemScene          &scene,
                      const fem::ImpactResult &result);
} // namespace kimp::pipeline
