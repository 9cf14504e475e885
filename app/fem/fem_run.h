// `kimp fem`: the slab-wall impact of the FEM scene for every wall height (fem::run_impact, MPI
// collective), written to fem.h5, summary.json and fem_histories.csv.
#pragma once

#include "app/fem/fem_scene.h"
#include "io/scene_io.h"
#include "io/summary.h"

namespace kimp::app
{
  /**
   * Per wall height the mesh DIR/mesh/H<H>.msh and fem::run_impact() (MPI collective; needs MPI
   * initialised, see fem::MpiSession); rank 0 writes DIR/fem.h5 (/fem/<case> as in
   * io/fem_results.h, plus /fem/<case>/energy/... and contact diagnostics), DIR/summary.json,
   * DIR/fem_histories.csv and, if output.vtu_interval > 0, DIR/vtu/<case>/impact.pvd. A failing
   * case aborts before any of the three result files exists under its final name.
   */
  void run_fem(const io::LoadedScene<FemScene> &scene, const io::OutputDir &output);
} // namespace kimp::app
