// What `kimp fem` and `kimp study` share: the user-facing message of a deal.II exception and the
// FemCase (results-file contract of io/fem_results.h) of one FEM run. Built only with
// KIMP_WITH_FEM.
#pragma once

#include <exception>
#include <filesystem>
#include <string>

#include "app/fem/fem_scene.h"
#include "fem/impact.h"
#include "io/fem_results.h"

namespace kimp::app
{
  /** The user-facing part of an exception message: the "Additional information" of a deal.II
   *  exception, whitespace collapsed; other messages unchanged. */
  std::string error_message(const std::exception &error);

  /**
   * The FemCase of one `kimp fem` run (io/fem_results.h contract): histories, the
   * ImpactSummary as summary entries, and labels (integrator, slab, mesh level, penalty factor,
   * what stopped the run). Shared by `kimp fem` and `kimp study`.
   */
  io::FemCase to_fem_case(const std::string       &name,
                          double                   wall_height,
                          const FemScene          &scene,
                          const fem::ImpactResult &result);
} // namespace kimp::app
