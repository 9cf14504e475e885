// `kimp mesh`: the FEM scene's mesh for every wall height, with statistics and previews.
#pragma once

#include <filesystem>

#include "app/fem/fem_scene.h"
#include "geometry/scene_mesh.h"
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

  /**
   * geometry::build_scene_mesh() into `msh` for a command's output directory: a signal while
   * gmsh writes removes its temporary file, and `msh` is noted as written by the run
   * (io::note_written(): removed if the command fails).
   */
  geometry::MeshStatistics write_scene_mesh(const geometry::SceneGeometry &geometry,
                                            const std::filesystem::path   &msh);
} // namespace kimp::app
