// What `kimp fem` and `kimp study` share: the user-facing message of a deal.II exception and the
// FemCase (results-file contract of io/fem_results.h) of one FEM run. Built only with
// KIMP_WITH_FEM.
#pragma once

#include <exception>
#include <filesystem>
#include <functional>
#include <streambuf>
#include <string>

#include "app/fem/fem_scene.h"
#include "fem/impact.h"
#include "io/fem_results.h"

namespace kimp::app
{
  /** The user-facing part of an exception message: the "Additional information" of a deal.II
   *  exception, whitespace collapsed; other messages as base::error_text() (one line). */
  std::string error_message(const std::exception &error);

  /**
   * A log stream for an engine (fem::run_impact(), the pushover's static solver): each
   * complete line written to it goes to `sink` without its newline (the caller prefixes the
   * case and picks the level).
   */
  class LogLines : public std::streambuf
  {
  public:
    explicit LogLines(std::function<void(const std::string &)> sink)
      : sink_(std::move(sink))
    {
    }

  protected:
    int_type overflow(int_type c) override;

  private:
    std::function<void(const std::string &)> sink_;
    std::string                              line_;
  };

  /** The scene restricted to one wall height (wall_heights = {wall_height}). */
  FemScene single_height_scene(const FemScene &scene, double wall_height);

  /**
   * One FEM case resolved once from its scene: the scene restricted to the case's height and
   * what the mesher and the solver take. Every stage of a case (cache key, mesh, run, FemCase,
   * results file) reads this instead of resolving the scene again.
   */
  struct FemCaseSpec
  {
    std::string             name;              ///< case and file name, "H1.25" or "H1.25_h2.5cm_p1"
    double                  wall_height = 0.0; ///< m
    FemScene                scene;             ///< single_height_scene(scene, wall_height)
    geometry::SceneGeometry geometry;          ///< scene_geometry(): the meshing parameters
    std::filesystem::path   mesh_file;         ///< where the mesh is written and read
    fem::ImpactParameters   parameters;        ///< impact_parameters() on mesh_file
  };

  /**
   * Resolve the case `name` of `scene` at `wall_height` whose mesh is `mesh_file`.
   * @param[in] vtu_dir field output directory, used only if scene.output.vtu_interval > 0
   */
  FemCaseSpec resolve_fem_case(const FemScene              &scene,
                               double                       wall_height,
                               const std::string           &name,
                               const std::filesystem::path &mesh_file,
                               const std::filesystem::path &vtu_dir = {});

  /**
   * The FemCase of one FEM run of `spec` (io/fem_results.h contract): histories, the
   * ImpactSummary as the FemSummary, and labels (integrator, slab, mesh level, penalty factor,
   * what stopped the run). Shared by `kimp fem` and `kimp study`.
   */
  io::FemCase to_fem_case(const FemCaseSpec &spec, const fem::ImpactResult &result);
} // namespace kimp::app
