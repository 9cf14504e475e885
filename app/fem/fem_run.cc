// `kimp fem SCENE.yaml -o DIR`: the slab-wall impact of docs/physics.md §4 for every wall height
// (fem::run_impact, MPI collective), written to fem.h5, summary.json and fem_histories.csv.
#include "app/fem/fem_run.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <map>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

#include "app/fem/fem_common.h"
#include "app/fem/fem_estimate.h"
#include "app/fem/fem_quantities.h"
#include "app/fem/fem_scene.h"
#include "app/fem/mesh_run.h"
#include "base/logging.h"
#include "fem/impact.h"
#include "geometry/scene_mesh.h"
#include "io/fem_results.h"
#include "io/output_dir.h"
#include "io/results_file.h"
#include "io/summary.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  namespace
  {
    /// A failed case: names the case; the command exits non-zero without final result files.
    class FemCaseError : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

    /// Rank 0 runs `work`; every rank then learns whether it succeeded and throws if not, so no
    /// rank waits forever for a failed one.
    template <class Work>
    void on_rank_zero(int rank, const std::string &what, Work work)
    {
      int         ok = 1;
      std::string message;
      if (rank == 0)
      {
        try
        {
          work();
        }
        catch (const std::exception &error)
        {
          ok      = 0;
          message = error_message(error);
        }
      }
      MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
      if (!ok)
        throw FemCaseError(rank == 0 ? what + ": " + message : what + " failed on rank 0");
    }

    /// Diagnostics beyond the FemCase contract: energies and contact state (docs/architecture.md
    /// "Results files").
    void write_diagnostics(ResultsGroup &case_group, const fem::ImpactHistory &h)
    {
      std::vector<std::int64_t> steps(h.time.size());
      for (std::size_t i = 0; i < steps.size(); ++i)
        steps[i] = static_cast<std::int64_t>(i);
      const auto series =
        [&](ResultsGroup &g, const char *name, const std::vector<double> &values, const char *units)
      {
        if (!values.empty())
          g.write_time_series(name, steps, h.time, values, 1, units);
      };
      ResultsGroup energy = case_group.group("energy");
      series(energy, "kinetic", h.kinetic, "J/m");
      series(energy, "strain", h.strain, "J/m");
      series(energy, "penalty", h.penalty, "J/m");
      series(energy, "contact_dissipation", h.contact_dissipation, "J/m");
      series(energy, "relative_error", h.energy_error, "1");
      // Inelastic laws only (empty, hence not written, for linear ones).
      series(energy, "internal_work", h.internal_work, "J/m");
      series(energy, "plastic_dissipation", h.plastic_dissipation, "J/m");
      series(energy, "damage_dissipation", h.damage_dissipation, "J/m");
      // Absorbing boundaries only.
      series(energy, "radiation", h.radiation, "J/m");
      // Slab damping only.
      series(energy, "slab_damping", h.slab_damping, "J/m");
      // Viscous-spring boundary only: stored in its springs.
      series(energy, "boundary_springs", h.boundary_springs, "J/m");
      ResultsGroup contact = case_group.group("contact");
      series(contact, "n_active", h.n_active, "1");
      series(contact, "max_penetration", h.max_penetration, "m");
      // Wall-soil contact interface only.
      if (!h.interface_normal_force.empty())
      {
        ResultsGroup interface = case_group.group("interface");
        series(interface, "normal_force", h.interface_normal_force, "N/m");
        series(interface, "closed_pairs", h.interface_closed, "1");
        series(energy, "friction_dissipation", h.friction_dissipation, "J/m");
      }
    }

    /// The deformed-mesh frames (fem::ImpactFrames) as group `frames`, if any were recorded.
    void write_frames(ResultsGroup &case_group, const fem::ImpactFrames &f)
    {
      if (f.time.empty())
        return;
      ResultsGroup      g        = case_group.group("frames");
      const std::size_t n_frames = f.time.size(), n_vertices = f.vertices.size() / 2,
                        n_cells = f.material.size();
      g.write_matrix("vertices", f.vertices, n_vertices, 2, "m");
      g.write_matrix("cells", f.cells, n_cells, 4, "1");
      g.write("material", f.material, "1");
      g.write("time", f.time, "s");
      g.write_matrix("displacement", f.displacement, n_frames, 2 * n_vertices, "m");
      g.write_matrix("von_mises_stress", f.von_mises_stress, n_frames, n_cells, "Pa");
      g.write_matrix("mean_stress", f.mean_stress, n_frames, n_cells, "Pa");
      if (!f.damage.empty())
      {
        g.write_matrix("damage", f.damage, n_frames, n_cells, "1");
        g.write_matrix("equivalent_plastic_strain",
                       f.equivalent_plastic_strain,
                       n_frames,
                       n_cells,
                       "1");
      }
      if (!f.contact_vertices.empty())
      {
        const std::size_t n_nodes = f.contact_vertices.size();
        g.write("contact_vertices", f.contact_vertices, "1");
        g.write("contact_length", f.contact_length, "m");
        g.write_matrix("contact_pressure", f.contact_pressure, n_frames, n_nodes, "Pa");
      }
    }

    nlohmann::ordered_json summary_json(const FemCase &c, const std::string &mesh_file)
    {
      nlohmann::ordered_json entry;
      entry["wall_height"]     = c.wall_height;
      entry["slab_mass"]       = c.slab_mass;
      entry["impact_velocity"] = c.impact_velocity;
      entry.update(c.summary.json()); // counts as integers
      for (const auto &[key, value] : c.labels)
        entry[key] = value;
      entry["mesh_file"] = mesh_file;
      return entry;
    }


    /// The log lines of a finished case: its impact, then the state and dissipation after it.
    void log_fem_case(const std::string &name, const fem::ImpactResult &result)
    {
      logger().info("{}: peak force {:.4g} kN/m (raw {:.4g}), contact {:.4g} ms, impulse "
                    "{:.4g} N s/m, COR {:.3f}, {} DoFs, {} steps of {:.3g} s, {:.2f} s",
                    name,
                    result.summary.peak_force / 1e3,
                    result.summary.peak_force_raw / 1e3,
                    result.summary.contact_duration * 1e3,
                    result.summary.impulse,
                    result.summary.apparent_cor,
                    result.summary.n_dofs,
                    result.summary.n_steps,
                    result.summary.dt,
                    result.summary.wall_seconds);
      const auto &sm = result.summary;
      logger().info("{}: after the impact: permanent indentation {:.4g} mm, wall displacement at "
                    "the end {:.4g} mm; dissipation plastic {:.4g} (soil {:.4g}, wall {:.4g}, "
                    "slab {:.4g}), damage {:.4g} (wall {:.4g}, slab {:.4g}), contact {:.4g} "
                    "J/m, left in the bodies {:.4g} J/m; COR implied by the material "
                    "dissipation {:.3f} (apparent {:.3f})",
                    name,
                    result.summary.permanent_indentation * 1e3,
                    result.summary.wall_residual_displacement * 1e3,
                    sm.plastic_dissipation,
                    sm.plastic_dissipation_by_body[2],
                    sm.plastic_dissipation_by_body[1],
                    sm.plastic_dissipation_by_body[0],
                    sm.damage_dissipation,
                    sm.damage_dissipation_by_body[1],
                    sm.damage_dissipation_by_body[0],
                    result.summary.contact_dissipation,
                    result.summary.residual_energy,
                    result.summary.dissipation_cor,
                    result.summary.apparent_cor);
    }

    /// fem_histories.csv: one row per sample of the case's force history.
    void add_history_rows(std::vector<std::vector<std::string>> &rows,
                          const std::string                     &name,
                          const FemCase                         &fem_case)
    {
      for (std::size_t i = 0; i < fem_case.time.size(); ++i)
        rows.push_back({name,
                        fmt::format("{}", fem_case.time[i]),
                        fmt::format("{}", fem_case.contact_force[i]),
                        fmt::format("{}", fem_case.smoothed_contact_force[i]),
                        fmt::format("{}", fem_case.indentation[i]),
                        fmt::format("{}", fem_case.slab_velocity[i]),
                        fmt::format("{}", fem_case.wall_displacement[i])});
    }

    /// summary.json of `kimp fem`: ranks, wall time, the units (with those of the keys only some
    /// cases have, `extra_units`) and the cases.
    nlohmann::ordered_json fem_summary(int                                          n_ranks,
                                       const std::chrono::steady_clock::time_point &start,
                                       const std::map<std::string, std::string>    &extra_units,
                                       const nlohmann::ordered_json                &cases)
    {
      nlohmann::ordered_json summary = io::summary_preamble("fem");
      summary["n_ranks"]             = n_ranks;
      summary["wall_time"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      summary["units"] = {{"wall_height", "m"},
                          {"slab_mass", "kg/m"},
                          {"impact_velocity", "m/s"},
                          {"peak_force", "N/m"},
                          {"peak_force_raw", "N/m"},
                          {"impulse", "N*s/m"},
                          {"contact_start", "s"},
                          {"contact_duration", "s"},
                          {"rebound_velocity", "m/s"},
                          {"max_penetration", "m"},
                          {"mean_penetration", "m"},
                          {"initial_gap", "m"},
                          {"penalty_stiffness", "N/m/m"},
                          {"smoothing_window", "s"},
                          {"dt", "s"},
                          {"dt_stable", "s"},
                          {"wall_time", "s"},
                          {"plastic_dissipation", "J/m"},
                          {"damage_dissipation", "J/m"},
                          {"contact_dissipation", "J/m"},
                          {"residual_energy", "J/m"},
                          {"dissipation_cor", "1"},
                          {"permanent_indentation", "m"},
                          {"wall_residual_displacement", "m"}};
      // The units of the keys only some cases have (geostatic step, interface, dissipation by
      // body).
      for (const auto &[key, unit] : extra_units)
        if (!summary["units"].contains(key))
          summary["units"][key] = unit;
      summary["cases"] = cases;
      return summary;
    }

    /** The engineer's quantities of a case (app/fem/fem_quantities.h) as a log line, and a
     *  warning if its record fails the impulse-momentum check. */
    void log_engineer_quantities(const FemCase &c)
    {
      const FemSummary &s   = c.summary;
      const auto        val = [](const std::optional<double> &x, double scale)
      { return x ? fmt::format("{:.4g}", *x * scale) : std::string("-"); };
      logger().info("{}: first peak {} kN/m at {} ms, its impulse {} N s/m; slab travel {} mm, "
                    "wall {} mm, energy-equivalent resistance {} kN/m, time to 95 % of the "
                    "travel {} ms (slab velocity zero at {} ms), wall at the end {} mm, bar strain "
                    "/ yield strain {} at {} m (at a point, mesh-dependent), over a {} m gauge {} "
                    "centred at {} m; impulse / momentum {}",
                    c.name,
                    val(s.first_peak_force, 1e-3),
                    val(s.first_peak_time, 1e3),
                    val(s.first_peak_impulse, 1.0),
                    val(s.max_slab_displacement, 1e3),
                    val(s.max_wall_displacement, 1e3),
                    val(s.energy_equivalent_resistance, 1e-3),
                    val(s.time_to_95_travel, 1e3),
                    val(s.time_to_stop, 1e3),
                    val(s.wall_residual_displacement, 1e3),
                    val(s.max_bar_strain_ratio, 1.0),
                    val(s.max_bar_strain_height, 1.0),
                    val(s.bar_gauge_length, 1.0),
                    val(s.max_bar_gauge_strain_ratio, 1.0),
                    val(s.max_bar_gauge_strain_height, 1.0),
                    val(s.impulse_momentum_ratio, 1.0));
      const std::string status = impulse_momentum_status(c);
      if (status != "ok")
        logger().warn("{}: impulse-momentum check: {}", c.name, status);
    }

    std::vector<std::string> engineer_quantity_header()
    {
      return {"case",
              "first_peak_force_N_per_m",
              "first_peak_time_s",
              "first_peak_impulse_N_s_per_m",
              "max_slab_displacement_m",
              "max_wall_displacement_m",
              "energy_equivalent_resistance_N_per_m",
              "time_to_stop_s",
              "time_to_95_travel_s",
              "wall_residual_displacement_m",
              "max_bar_strain_ratio",
              "max_bar_strain_height_m",
              "max_bar_gauge_strain_ratio",
              "max_bar_gauge_strain_height_m",
              "bar_gauge_length_m",
              "impulse_momentum_ratio",
              "impulse_momentum"};
    }

    /** One row of fem_quantities.csv (an empty cell: not shown by the record). */
    std::vector<std::string> engineer_quantity_row(const FemCase &c)
    {
      const FemSummary &s   = c.summary;
      const auto        val = [](const std::optional<double> &x)
      { return x ? fmt::format("{}", *x) : std::string(); };
      return {c.name,
              val(s.first_peak_force),
              val(s.first_peak_time),
              val(s.first_peak_impulse),
              val(s.max_slab_displacement),
              val(s.max_wall_displacement),
              val(s.energy_equivalent_resistance),
              val(s.time_to_stop),
              val(s.time_to_95_travel),
              val(s.wall_residual_displacement),
              val(s.max_bar_strain_ratio),
              val(s.max_bar_strain_height),
              val(s.max_bar_gauge_strain_ratio),
              val(s.max_bar_gauge_strain_height),
              val(s.bar_gauge_length),
              val(s.impulse_momentum_ratio),
              impulse_momentum_status(c)};
    }
  } // namespace

  void run_fem(const LoadedScene<FemScene> &loaded, const OutputDir &output)
  {
    int mpi_initialized = 0;
    MPI_Initialized(&mpi_initialized);
    if (!mpi_initialized)
      throw std::logic_error("kimp fem: MPI is not initialised (kimp::fem::MpiSession in main)");
    int rank = 0, n_ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &n_ranks);

    const auto                  start = std::chrono::steady_clock::now();
    const FemScene             &scene = loaded.scene;
    std::optional<ResultsFile>  results;
    std::optional<ResultsGroup> fem_root;
    if (rank == 0)
    {
      results.emplace(output.file("fem.h5"), loaded.text, loaded.resolved_json);
      fem_root.emplace(results->root().group("fem"));
    }

    nlohmann::ordered_json                cases = nlohmann::ordered_json::array();
    std::map<std::string, std::string>    extra_units; // of the cases' optional summary keys
    std::vector<std::vector<std::string>> rows, quantity_rows;
    for (const double height : scene.wall_heights)
    {
      const std::string           name     = fem_case_name(height);
      const std::string           mesh_rel = "mesh/" + name + ".msh";
      const std::filesystem::path mesh     = output.path() / mesh_rel;
      const std::filesystem::path vtu_dir  = output.path() / "vtu" / name;
      // Resolved once: the mesher, the solver and the FemCase read the same case.
      const FemCaseSpec spec = resolve_fem_case(scene, height, name, mesh, vtu_dir);
      // Before meshing (every rank: the same numbers), so that an absurd mesh is refused rather
      // than allocated.
      const FemEstimate estimate = estimate_fem_case(spec);
      logger().info("{}: estimate {}", name, estimate.text());
      check_fem_budget(name, estimate, spec.scene.max_steps);
      on_rank_zero(rank,
                   name + ": meshing",
                   [&]()
                   {
                     std::ostringstream statistics;
                     statistics << write_scene_mesh(spec.geometry, output.file(mesh_rel));
                     logger().info("{}: mesh {} ({})", name, mesh.string(), statistics.str());
                     if (scene.output.vtu_interval > 0)
                       std::filesystem::create_directories(vtu_dir);
                   });

      fem::ImpactResult result;
      try
      {
        // Each line to the kimp logger prefixed by the case name: "step ..." lines at debug
        // level, the others at info.
        LogLines log_buffer(
          [&name](const std::string &line)
          {
            if (line.rfind("step ", 0) == 0)
              logger().debug("{}: {}", name, line);
            else
              logger().info("{}: {}", name, line);
          });
        std::ostream          log(&log_buffer);
        Progress              progress(0, scene.solver.end_time);
        fem::ImpactParameters parameters = spec.parameters;
        parameters.progress              = [&progress](double t, double) { progress.update(0, t); };
        parameters.frame_interval        = scene.output.frame_interval;
        result                           = fem::run_impact(parameters, MPI_COMM_WORLD, &log);
      }
      catch (const std::exception &error)
      {
        throw FemCaseError(fmt::format("{}: {}", name, error_message(error)));
      }
      if (rank != 0)
        continue;
      if (scene.output.vtu_interval > 0)
        for (const auto &file : std::filesystem::directory_iterator(vtu_dir))
          note_written(file.path()); // part of the output set: removed if the command fails

      const FemCase fem_case = to_fem_case(spec, result);
      write_fem_case(*fem_root, fem_case);
      ResultsGroup case_group = fem_root->group(name);
      write_diagnostics(case_group, result.history);
      write_frames(case_group, result.frames);
      if (scene.output.vtu_interval > 0)
        case_group.set_attribute("pvd", "vtu/" + name + "/impact.pvd");
      // `cases` is a list of objects with "name" in every command's summary.json.
      nlohmann::ordered_json entry{{"name", name}, {"status", fem_case.status}};
      entry.update(summary_json(fem_case, mesh_rel));
      cases.push_back(entry);
      for (const auto &[key, value] : fem_case.summary.entries())
        extra_units.emplace(key, fem_summary_units(fem_case, key));
      add_history_rows(rows, name, fem_case);
      log_fem_case(name, result);
      log_engineer_quantities(fem_case);
      quantity_rows.push_back(engineer_quantity_row(fem_case));
    }
    if (rank != 0)
      return;

    results->commit();
    write_csv_atomic(output.file("fem_histories.csv"),
                     {"case",
                      "time_s",
                      "contact_force_N_per_m",
                      "smoothed_contact_force_N_per_m",
                      "indentation_m",
                      "slab_velocity_m_per_s",
                      "wall_displacement_m"},
                     rows);
    write_csv_atomic(output.file("fem_quantities.csv"), engineer_quantity_header(), quantity_rows);
    const nlohmann::ordered_json summary = fem_summary(n_ranks, start, extra_units, cases);
    write_text_atomic(output.file("summary.json"), summary.dump(2) + "\n");
    logger().info("wrote {}, {}, {}",
                  results->final_path().string(),
                  output.file("summary.json").string(),
                  output.file("fem_histories.csv").string());
  }

} // namespace kimp::app
