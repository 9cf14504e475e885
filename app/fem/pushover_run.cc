// `kimp fem --pushover` (see pushover_run.h): the scene's pushover parameters, the run per wall
// height and its files.
#include "app/fem/pushover_run.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/fem/fem_common.h"
#include "app/fem/fem_materials.h"
#include "app/helper_programs.h"
#include "base/logging.h"
#include "io/results_file.h"
#include "io/summary.h"
#include "io/table.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;

  namespace
  {
    /** The band path of section `pushover`: each unload_at entry then 0 (unload to zero
     *  force), then the largest displacement. */
    std::vector<double> push_path(const FemPushover &s, double wall_height)
    {
      const double        u_max = s.displacement.value_or(0.05 * wall_height);
      std::vector<double> path;
      double              previous = 0;
      for (const double u : s.unload_at)
      {
        if (!(u > previous) || !(u < u_max))
          throw std::invalid_argument(
            "pushover.unload_at: " + std::to_string(u * 1e3) +
            " mm (the entries must increase and stay below pushover.displacement = " +
            std::to_string(u_max * 1e3) + " mm)");
        path.push_back(u);
        path.push_back(0.0);
        previous = u;
      }
      path.push_back(u_max);
      return path;
    }
  } // namespace

  fem::PushoverParameters pushover_parameters(const FemScene &scene, double wall_height)
  {
    fem::PushoverParameters        p;
    const geometry::SceneGeometry &g     = scene.geometry;
    const FemConcrete             &c     = scene.materials.concrete;
    const double                   scale = std::pow(0.5, scene.mesh_level);
    p.wall_height                        = wall_height;
    p.wall_thickness                     = g.wall_thickness;
    const double top                     = std::min(g.slab_top.value_or(wall_height), wall_height);
    p.band_top                           = top;
    p.band_bottom                        = std::max(0.0, top - g.slab_thickness);
    if (c.model == FemConcrete::Model::damage_plasticity)
    {
      p.wall              = fem::PushoverParameters::Wall::reinforced;
      p.concrete          = concrete_parameters(c);
      p.bars              = c.wall_reinforcement;
      p.bars.hinge_length = scene.pushover.hinge_length.value_or(0.0);
      p.cover             = scene.pushover.cover;
      // The concrete's crack frame and crush band are the impact model's (one key each).
      p.rotating_crack   = c.crack_frame == FemConcrete::CrackFrame::rotating;
      p.compression_band = c.compression_band;
    }
    else
    {
      p.wall         = fem::PushoverParameters::Wall::elastic;
      p.wall_elastic = {c.youngs_modulus, c.poisson_ratio, c.density};
    }
    p.wall_density      = c.density;
    p.with_backfill     = g.with_backfill;
    p.backfill_width    = g.backfill_width;
    p.backfill_height   = std::min(g.backfill_height.value_or(wall_height), wall_height);
    p.soil              = soil_parameters(scene.materials.soil);
    p.geostatic         = true;
    p.k0                = scene.materials.soil.K0.value_or(1 - std::sin(p.soil.friction_angle));
    p.interface_contact = scene.interface.model == FemInterface::Model::contact;
    p.friction = scene.interface.friction.value_or(std::tan(2.0 / 3.0 * p.soil.friction_angle));
    p.interface_penalty = scene.solver.wall_soil_interface.penalty_factor;
    p.element_size      = g.h_contact * scale;
    p.max_element_size  = g.h_max * scale;
    p.grading           = g.grading;
    p.path              = push_path(scene.pushover, wall_height);
    p.increment         = scene.pushover.increment;
    p.first_increment   = std::min(2e-5, 0.1 * p.increment);
    return p;
  }

  ScenePushover run_scene_pushover(const FemScene &scene, double wall_height, std::ostream *log)
  {
    ScenePushover out;
    out.result  = fem::run_pushover(pushover_parameters(scene, wall_height), log);
    out.summary = fem::summarise_pushover(out.result.curve);
    return out;
  }

  namespace
  {
    /** The leading columns of every pushover table: the case and its wall height. */
    Table case_table()
    {
      Table t;
      t.text("case").number("wall_height", "m");
      return t;
    }

    /** The columns of pushover_summary.csv and /pushover/summary. */
    Table summary_table()
    {
      Table t = case_table();
      t.number("capacity", "N/m")
        .number("displacement_at_capacity", "m")
        .number("initial_stiffness", "N/m/m")
        .number("cracked_stiffness", "N/m/m")
        .number("force_at_1cm", "N/m")
        .number("unloading_stiffness", "N/m/m")
        .number("permanent_set", "m")
        .number("unloaded_from", "m")
        .integer("n_cells")
        .integer("n_dofs")
        .integer("n_loose_steps")
        .number("wall_time", "s");
      return t;
    }

    /** The columns of a case's /pushover/<case>/curve and of pushover.csv (all cases). */
    Table curve_table()
    {
      Table t = case_table();
      t.number("displacement", "m").number("force", "N/m").integer("segment").integer("unloading");
      return t;
    }

  } // namespace

  void run_fem_pushover(const LoadedScene<FemScene> &loaded, const OutputDir &output)
  {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0)
      return;
    const FemScene &scene = loaded.scene;
    if (scene.boundary.far != FemBoundary::Far::rollers)
      logger().warn("pushover: the backfill's far side and base are held as the rollered block "
                    "(boundary.far: {} is the impact's: dashpots have no static part, and the "
                    "static solver has no springs of the viscous-spring boundary)",
                    far_boundary_name(scene.boundary.far));
    ResultsFile  results(output.file("pushover.h5"), loaded.text, loaded.resolved_json);
    ResultsGroup root    = results.root().group("pushover");
    Table        summary = summary_table(), curves = curve_table();
    for (const double height : scene.wall_heights)
    {
      const std::string name  = fem_case_name(height);
      const auto        start = std::chrono::steady_clock::now();
      logger().info("pushover {}: wall height {} m", name, height);
      // The static solver's lines (one per step) to the kimp logger at debug level (`-v`).
      LogLines            log_buffer([&name](const std::string &line)
                          { logger().debug("pushover {}: {}", name, line); });
      std::ostream        log(&log_buffer);
      const ScenePushover run =
        run_scene_pushover(scene,
                           height,
                           logger().should_log(spdlog::level::debug) ? &log : nullptr);
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      Table curve = curve_table();
      for (const fem::PushoverPoint &point : run.result.curve)
      {
        const std::vector<Cell> row{name,
                                    height,
                                    point.displacement,
                                    point.force,
                                    std::int64_t(point.segment),
                                    std::int64_t(point.unloading ? 1 : 0)};
        curve.add_row(row);
        curves.add_row(row);
      }
      ResultsGroup group = root.case_group(name);
      curve.write_hdf5(group, "curve");
      group.set_attribute("wall_height", height);
      group.set_attribute("geostatic_force", run.result.geostatic_force);
      group.set_attribute("units", "wall_height: m, geostatic_force: N/m");
      group.set_status("ok");
      const fem::PushoverSummary &s = run.summary;
      summary.add_row({name,
                       height,
                       s.capacity,
                       s.displacement_at_capacity,
                       s.initial_stiffness,
                       s.cracked_stiffness,
                       s.force_at_1cm,
                       s.unloading_stiffness,
                       s.permanent_set,
                       s.unloaded_from,
                       std::int64_t(run.result.n_cells),
                       std::int64_t(run.result.n_dofs),
                       std::int64_t(run.result.step_control.n_loose_steps),
                       seconds});
      logger().info("pushover {}: capacity {:.4g} kN/m at {:.4g} mm, initial stiffness {:.4g} "
                    "kN/mm/m, {} steps, {} Newton iterations, {} steps halved for Newton "
                    "(smallest step {:.3g} mm), {:.3g} s",
                    name,
                    s.capacity / 1e3,
                    s.displacement_at_capacity * 1e3,
                    s.initial_stiffness / 1e6,
                    run.result.curve.size() - 1,
                    run.result.step_control.n_newton_iterations,
                    run.result.step_control.n_newton_cuts,
                    run.result.smallest_increment * 1e3,
                    seconds);
    }
    summary.write_hdf5(root, "summary");
    results.commit();
    curves.write_csv(output.file("pushover.csv"));
    summary.write_csv(output.file("pushover_summary.csv"));
    nlohmann::ordered_json json = summary_preamble("fem --pushover");
    json["files"]               = {"pushover.h5", "pushover.csv", "pushover_summary.csv"};
    write_text_atomic(output.file("summary.json"), json.dump(2) + "\n");
    output.keep_written();
    // The charts of scripts/pushover_charts.py: a failure is a warning.
    draw_optional_charts("pushover_charts.py", output.path(), "pushover chart");
  }
} // namespace kimp::app
