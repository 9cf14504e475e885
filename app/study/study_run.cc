// `kimp study`: FEM per wall height -> k fitted with laws 2 and 4 at the thesis COR
// (lumped::thesis_cor; docs/physics.md §4)
// -> k_total = k_per_m·W -> isolated building pounding on moat walls (docs/physics.md §2-3).
#include "app/study/study_run.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <mpi.h>
#include <optional>

#include "app/study/study_internal.h"
#include "app/study/study_velocity.h"
#include "base/format.h"
#include "base/logging.h"
#include "io/results_file.h"

#include "report/report.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::fit;
  using namespace study_internal;

  StudyResult run_study(const LoadedScene<StudyScene> &loaded, const OutputDir &output)
  {
    const Clock::time_point start = Clock::now();
    const StudyScene       &scene = loaded.scene;
    StudyResult             result;
    result.warnings = missing_study_records(scene);
    for (const std::string &warning : result.warnings)
      logger().warn("{}", warning);
    if (scene.fem.fidelity == Fidelity::auto_ladder)
      logger().info("fidelity auto: contact mesh ladder {} cm, penalty factors {}, tolerance {} %; "
                    "{} slab as the scene says (the rigid-slab shortcut is not taken "
                    "automatically: for this scene it doubles the peak force, docs/validation.md)",
                    fmt::join(scale(scene.fem.fidelity_h_contact, 100.0), " / "),
                    fmt::join(scene.fem.fidelity_penalty_factors, " / "),
                    scene.fem.fidelity_tolerance * 100.0,
                    scene.fem.solver.rigid_slab ? "rigid" : "elastic");
    for (const double height : scene.fem.wall_heights)
    {
      result.heights.push_back(run_height(scene, height, output));
      result.fem_seconds += result.heights.back().fem_seconds;
      result.fit_seconds += result.heights.back().fit_seconds;
    }
    for (const StudyHeight &h : result.heights)
      for (StudyHeight &c : run_velocity_cases(scene, h, output))
      {
        result.fem_seconds += c.fem_seconds;
        result.fit_seconds += c.fit_seconds;
        result.velocity_cases.push_back(std::move(c));
      }
    log_k_table(scene, result.heights);
    log_velocity_table(result);
    write_k_table_csv(output, scene, result.heights, result.velocity_cases);

    const Clock::time_point building_start = Clock::now();
    // Inelastic materials: the walls of every building run; linear: the estimate element, run
    // beside the laws so that the report reads each wall's capacity and permanent set.
    result.yielding_walls = derive_study_yielding_walls(scene, result.heights);
    result.building       = run_building(scene, result.heights, result.yielding_walls);
    result.consistent_k   = run_consistent_k(scene, result);
    write_consistent_k_csv(output, result);
    result.building_seconds = seconds_since(building_start);
    write_building_csv(output, result.building);
    write_yielding_wall_csv(output, result);
    if (scene.walls.flexible && has_inelastic_materials(scene.fem))
      logger().info("walls.flexible skipped: with inelastic materials the walls are the yielding "
                    "wall elements (yielding_wall.csv)");
    else if (scene.walls.flexible)
    {
      const Clock::time_point flexible_start = Clock::now();
      result.wall_sdofs                      = compute_wall_sdofs(scene, result.heights, output);
      result.flexible_building =
        run_flexible_wall_building(scene, result.heights, result.wall_sdofs, result.building);
      result.flexible_wall_seconds = seconds_since(flexible_start);
      write_flexible_wall_csv(output, result);
    }

    const Clock::time_point extras_start = Clock::now();
    result.extras                        = run_extras(scene, result, output);
    result.extras.seconds                = seconds_since(extras_start);
    write_study_extras_csv(output, result.extras);
    write_study_h5(loaded, result, output);

    bool charts = false;
    if (scene.charts)
    {
      const Clock::time_point charts_start = Clock::now();
      charts                               = draw_charts(output);
      result.charts_seconds                = seconds_since(charts_start);
    }
    result.wall_seconds = seconds_since(start);
    write_text_atomic(output.file("report.md"), report_markdown(scene, result, charts));
    write_text_atomic(output.file("summary.json"), summary_json(scene, result).dump(2) + "\n");
    try
    {
      kimp::report::write_report(output.path());
    }
    catch (const std::exception &error)
    {
      // The results are complete by now: a report that cannot be written is only a warning.
      logger().warn("no HTML report: {}", error.what());
    }
    logger().info("study done: {}: {}", cost_text(result), output.file("report.md").string());
    logger().info("HTML report: {}", output.file("report.html").string());
    return result;
  }

  void run_study_job(const io::LoadedScene<StudyScene> &scene,
                     const std::filesystem::path       &output_dir)
  {
    int mpi_initialized = 0, rank = 0, n_ranks = 1;
    MPI_Initialized(&mpi_initialized);
    if (!mpi_initialized)
      throw std::logic_error("kimp study: MPI is not initialised (fem::MpiSession in main)");
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &n_ranks);
    // A missing record is an input error: said before any output or FEM run.
    check_study_records(scene);
    // Rank 0 creates the output directory before the others use it.
    std::optional<OutputDir> output;
    if (rank == 0)
      output.emplace(output_dir);
    if (n_ranks > 1)
    {
      MPI_Barrier(MPI_COMM_WORLD);
      if (rank != 0)
        output.emplace(output_dir);
      compute_heights_on_ranks(scene.scene, *output, rank, n_ranks);
      MPI_Barrier(MPI_COMM_WORLD);
      // The velocity cases need their height's FEM level, chosen by the ladder above.
      compute_velocity_cases_on_ranks(scene.scene, *output, rank, n_ranks);
      MPI_Barrier(MPI_COMM_WORLD);
    }
    if (rank != 0)
      return;
    run_study(scene, *output);
  }
} // namespace kimp::app
