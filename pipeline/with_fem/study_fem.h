// One wall height of `kimp study`: mesh (geometry::build_scene_mesh) and FEM impact
// (fem::run_impact on MPI_COMM_SELF) -> FemCase, cached in DIR/fem/H<H>.h5 under a scene hash.
#pragma once

#include <string>

#include "pipeline/fem_results.h"
#include "pipeline/summary.h"
#include "pipeline/with_fem/fem_scene.h"

namespace kimp::pipeline
{
  /** The FEM case of one height and where it came from. */
  struct StudyFemCase
  {
    FemCase     fem_case;
    bool        from_cache = false; ///< read from DIR/fem/H<H>.h5 instead of computed
    std::string cache_key;          ///< hex hash of the resolved single-height scene
    double      wall_seconds = 0.0; ///< s spent here (meshing + FEM, or reading the cache)
  };

  /**
   * Cache key of the case `wall_height` of `scene`: stable 64-bit hash (hex) of the resolved
   * scene restricted to that height and of the kimp version. Any parameter change changes it.
   */
  std::string study_fem_cache_key(const FemScene &scene, double wall_height);

  /**
   * The FemCase of height `wall_height`: read from `output`/fem/<case>.h5 when
   * `output`/fem/<case>.key holds study_fem_cache_key(), else mesh (`output`/mesh/<case>.msh),
   * run fem::run_impact() on MPI_COMM_SELF and store the .h5 and then the .key file (a run
   * interrupted before the key exists is recomputed). Must be called on one rank only; MPI must
   * be initialised. Heights are run one after the other by the caller: gmsh's API is global.
   * @throws the meshing and FEM errors, prefixed with the case name.
   */
  StudyFemCase study_fem_case(const FemScene &scene, double wall_height, const OutputDir &output);
} // namespace kimp::pipeline
