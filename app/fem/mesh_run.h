// `kimp mesh`: the FEM scene's mesh for every wall height, with statistics and previews.
#pragma once

#include "app/fem/fem_scene.h"
#include "io/scene_io.h"
#include "io/summary.h"

namespace kimp::app
{
  /**
   * Per wall height H: DIR/mesh/H<H>.msh (ASCII MSH 4.1), DIR/mesh/H<H>.vtu (deal.II's reading of
   * it, material id per cell), DIR/mesh/H<H>.png (if /usr/bin/python3 with matplotlib is
   * available, else a warning) and DIR/summary.json with the mesh statistics. Rank 0 only.
   */
  void run_mesh(const io::LoadedScene<FemScene> &scene, const io::OutputDir &output);
} // namespace kimp::app
