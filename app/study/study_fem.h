// One wall height of `kimp study`: mesh (geometry::build_scene_mesh) and FEM impact
// (fem::run_impact on MPI_COMM_SELF) -> FemCase, cached in DIR/fem/H<H>.h5 under a scene hash.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/fem/fem_common.h"
#include "app/fem/fem_estimate.h"
#include "app/fem/fem_scene.h"
#include "app/study/study_laws.h"
#include "app/study/study_scene.h"
#include "io/fem_results.h"
#include "io/summary.h"

namespace kimp::app
{
  /** The FEM case of one height and where it came from. */
  struct StudyFemCase
  {
    io::FemCase fem_case;
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
   * The cost of the FEM cases `kimp study` may run on `scene`, before any: per wall height every
   * level of the fidelity ladder (auto) or the scene's mesh (fixed), the other impact velocities
   * at the finest level, and the accuracy and sensitivity studies when on. An upper bound: the
   * ladder may stop early, a run stops at separation, the cache is not counted.
   */
  FemCost estimate_study_fem(const StudyScene &scene);

  /** `base` on the FEM level (h_contact, m; penalty factor) without mesh refinement levels. */
  FemScene fem_level_scene(const FemScene &base, double h_contact, double penalty_factor);

  /**
   * The case `case_name` ("": fem_case_name(wall_height)) of `scene` at `wall_height`, resolved
   * once, its mesh in `output`/mesh/<case>.msh.
   * @throws the resolution errors, prefixed with the case name.
   */
  FemCaseSpec study_fem_case_spec(const FemScene      &scene,
                                  double               wall_height,
                                  const io::OutputDir &output,
                                  const std::string   &case_name = "");

  /**
   * The FemCase of `spec` (see the overload below): its cache key is the stable hash of
   * spec.scene and the kimp version, equal to study_fem_cache_key(scene, wall_height).
   */
  StudyFemCase study_fem_case(const FemCaseSpec &spec, const io::OutputDir &output);

  /**
   * The FemCase of height `wall_height`: read from `output`/fem/<case>.h5 when
   * `output`/fem/<case>.key holds study_fem_cache_key(), else mesh (`output`/mesh/<case>.msh),
   * run fem::run_impact() on MPI_COMM_SELF and store the .h5 and then the .key file (a run
   * interrupted before the key exists is recomputed). Must be called on one rank only; MPI must
   * be initialised. Heights are run one after the other by the caller: gmsh's API is global.
   * @param[in] case_name name of the case and its files ("": fem_case_name(wall_height)); the
   *            fidelity levels of one height use "H1.25_h2.5cm_p1" etc.
   * @throws the meshing and FEM errors, prefixed with the case name.
   */
  StudyFemCase study_fem_case(const FemScene      &scene,
                              double               wall_height,
                              const io::OutputDir &output,
                              const std::string   &case_name = "");

  /** The study's fits of one FEM case (study_laws() at the study COR). */
  struct StudyFits
  {
    /// Per study law: "ok", "warning: ..." (fit kept) or "failed: ..." (no fit), see
    /// fit::fit_verdict()
    std::vector<StudyLawFit> laws    = unfitted_study_laws();
    double                   seconds = 0.0; ///< s

    bool ok() const { return all_fitted(laws); }
    /// The entry of the study law named `law` ("kelvin_voigt").
    const StudyLawFit &law(std::string_view name) const { return law_fit(laws, name); }
  };

  /**
   * Fit each of study_laws() at settings.cor to `fem_case` through fit_fem_case(), the
   * path `kimp fit` takes. A failed fit is logged and reported in its status, not thrown.
   */
  StudyFits fit_study_laws(const io::FemCase &fem_case, const StudyFitScene &settings);
} // namespace kimp::app
