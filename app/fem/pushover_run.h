// `kimp fem --pushover`: the static pushover of wall and backfill (fem::run_pushover) for every
// wall height of the FEM scene, written to pushover.h5, pushover.csv, pushover_summary.csv and a
// chart; and the scene's pushover of one height for app-level callers (the lumped wall-and-
// backfill element is fitted to its summary).
#pragma once

#include <ostream>

#include "app/fem/fem_scene.h"
#include "fem/pushover.h"
#include "io/output_dir.h"
#include "io/scene_io.h"

namespace kimp::app
{
  /**
   * The engine's parameters of the scene's pushover at wall height @p wall_height (m): wall,
   * bars (damage_plasticity; else the elastic wall), the backfill with the soil's Mohr-Coulomb
   * strength (also when materials.soil.model is elastic), the geostatic state (K0), the
   * interface (contact or bonded), the slab's band, the mesh sizes of section `mesh` at its
   * level and the path of section `pushover`.
   * @throws std::invalid_argument for a path it cannot honour (unload_at not increasing or
   * not below displacement)
   */
  fem::PushoverParameters pushover_parameters(const FemScene &scene, double wall_height);

  /** The scene's pushover at one wall height and its summary (capacity, cracked and unloading
   *  stiffness, permanent set): what the lumped wall-and-backfill element is fitted to. */
  struct ScenePushover
  {
    fem::PushoverResult  result;
    fem::PushoverSummary summary;
  };
  /** With @p log: the static solver's line per step (and per halved step) to it. */
  ScenePushover
  run_scene_pushover(const FemScene &scene, double wall_height, std::ostream *log = nullptr);

  /**
   * Every wall height on rank 0 (serial; the other ranks return): DIR/pushover.h5
   * (/pushover/<case>/curve and /pushover/summary, units per dataset), DIR/pushover.csv,
   * DIR/pushover_summary.csv (units in the headers), DIR/summary.json and
   * DIR/charts/pushover.{png,svg} (scripts/pushover_charts.py; a failed chart is a warning).
   * Every file is written under a temporary name and renamed.
   */
  void run_fem_pushover(const io::LoadedScene<FemScene> &scene, const io::OutputDir &output);
} // namespace kimp::app
