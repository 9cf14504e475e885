// `kimp lumped` of a scene in plan: run the plan engine and write its files.
#include "app/lumped/plan_run.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/lumped/lumped_run_internal.h"
#include "base/format.h"
#include "base/logging.h"
#include "io/results_file.h"
#include "io/summary.h"

namespace kimp::lumped::plan
{
  // plan_energy_json(): every term under its member's name.
  NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(PlanEnergy,
                                     initial,
                                     input,
                                     kinetic,
                                     strain,
                                     viscous,
                                     hysteretic,
                                     contact_work,
                                     impact_dissipated,
                                     friction,
                                     wall_work,
                                     wall_plastic,
                                     wall_radiated,
                                     relative_error,
                                     max_relative_error)
} // namespace kimp::lumped::plan

namespace kimp::app
{
  namespace plan = lumped::plan;

  namespace
  {
    using Clock = std::chrono::steady_clock;

    const char *const direction_names[3] = {"x", "y", "theta"};

    std::string level_name(const PlanLumpedScene &scene, std::size_t level)
    {
      if (scene.base.building.kind == BuildingKind::isolated)
        return level == 0 ? "isolation level" : fmt::format("floor {}", level);
      return fmt::format("floor {}", level + 1);
    }

    std::string text(double value)
    {
      return fmt::format("{}", value);
    }

    /// A yielding wall face as the planar walls' record: the face's peak contact force and the
    /// wall-and-backfill part's capacity, peak resistance, displacements, failure and work.
    YieldingWallRecord yielding_record(const plan::PlanResponse           &r,
                                       const plan::PlanYieldingWallResult &y)
    {
      return {r.peak_wall_force[y.segment],
              y.capacity,
              y.peak_resistance,
              y.peak_displacement,
              y.permanent_set,
              y.failure_displacement,
              y.failure_time,
              y.plastic_work,
              y.radiated_work};
    }

    /// The units of yielding_walls_json()'s quantities (summary.json `units.yielding_walls`).
    nlohmann::json yielding_units()
    {
      nlohmann::json units = {{"peak_resistance_ratio", "1"},
                              {"final_displacement", "m"},
                              {"failure_time", "s"}};
      for (const YieldingWallQuantity &q : yielding_wall_quantities)
        units[q.name] = q.unit;
      return units;
    }

  } // namespace

  const char *damping_name(plan::PlanDampingModel model)
  {
    return model == plan::PlanDampingModel::modal ? "modal" : "rayleigh";
  }

  nlohmann::json plan_damping_json(const PlanRun &run)
  {
    return {{"model", damping_name(run.damping)},
            {"damping_ratio", run.damping_ratio},
            {"isolation_damping_ratio", run.isolation_damping_ratio}};
  }

  nlohmann::json plan_energy_json(const plan::PlanEnergy &e)
  {
    return e;
  }

  nlohmann::json yielding_walls_json(const plan::PlanResponse &r)
  {
    nlohmann::json out = nlohmann::json::array();
    for (const plan::PlanYieldingWallResult &y : r.yielding_walls)
    {
      nlohmann::json j        = lumped_internal::yielding_wall_json(yielding_record(r, y));
      j["face"]               = y.segment;
      j["final_displacement"] = y.final_displacement;
      if (!y.failure_time)
        j["failure_time"] = nullptr;
      out.push_back(j);
    }
    return out;
  }

  PlanPeaks plan_peaks(const plan::PlanResponse &r)
  {
    PlanPeaks peaks;
    for (const plan::PlanContactResult &c : r.contacts)
    {
      peaks.corner_force   = std::max(peaks.corner_force, c.peak_normal_force);
      peaks.friction_force = std::max(peaks.friction_force, c.peak_friction_force);
    }
    for (std::size_t i = 2; i < r.peak_displacement.size(); i += 3)
      peaks.rotation = std::max(peaks.rotation, r.peak_displacement[i]);
    for (const double d : r.peak_corner_drift)
      peaks.corner_drift = std::max(peaks.corner_drift, d);
    return peaks;
  }

  PlanRun run_plan(const PlanLumpedScene                      &scene,
                   const std::string                          &file_name,
                   const std::string                          &scene_text,
                   const std::optional<std::filesystem::path> &records_dir_override)
  {
    const PlanSection &p     = scene.plan.value();
    const auto         start = Clock::now();
    PlanRun            out;
    out.motion = load_plan_motion(scene.base, p, records_dir_override, file_name, scene_text);
    plan::PlanModel model(make_plan_scene(scene.base, p));
    for (const plan::PlanContact &c : model.contacts())
    {
      out.contact_names.push_back(c.name);
      out.contact_positions.push_back(c.position);
    }
    out.damping                 = model.building().damping;
    out.damping_ratio           = model.building().damping_ratio;
    out.isolation_damping_ratio = model.building().isolation_damping_ratio;
    const plan::PlanLevel &slab = model.building().levels.front();
    out.n_corners               = slab.outline.size();
    out.slab_outline            = slab.outline;
    out.slab_reference          = slab.centre_of_mass();
    if (model.moat())
      out.wall = model.moat()->wall;
    const plan::PlanCentralDifference integrator(std::move(model),
                                                 plan_options(scene.base.integration));
    out.dt_critical            = integrator.stability().dt_critical;
    const double      dt       = integrator.time_step(out.motion.dt);
    const double      duration = scene.base.integration.duration.value_or(out.motion.duration());
    const double      n_steps  = duration / dt;
    const std::size_t n_dofs   = integrator.model().n_dofs();
    base::logger().info("plan: {:.3g} steps of {:.3g} s over {:.4g} s x {} DoFs (dt_cr {:.3g} s, "
                        "{})",
                        n_steps,
                        dt,
                        duration,
                        n_dofs,
                        out.dt_critical,
                        integrator.stability().governing);
    if (n_steps > scene.base.integration.max_steps)
      throw std::runtime_error(
        fmt::format("plan run: {:.3g} steps of {:.3g} s exceed the step budget "
                    "integration.max_steps = {:.3g} (raise it or shorten integration.duration)",
                    n_steps,
                    dt,
                    scene.base.integration.max_steps));
    out.response  = integrator.run(out.motion);
    out.wall_time = std::chrono::duration<double>(Clock::now() - start).count();
    return out;
  }

  RunEstimate estimate_plan_case(const PlanLumpedScene                &scene,
                                 const lumped::plan::PlanGroundMotion &motion)
  {
    const plan::PlanCentralDifference integrator(plan::PlanModel(
                                                   make_plan_scene(scene.base, scene.plan.value())),
                                                 plan_options(scene.base.integration));
    lumped::GroundMotion              length; // make_estimate() reads the record's dt and length
    length.dt = motion.dt;
    length.acceleration.assign(motion.x.size(), 0.0);
    return lumped_internal::make_estimate(integrator.time_step(motion.dt),
                                          scene.base.integration,
                                          length,
                                          integrator.model().n_dofs());
  }

  namespace
  {
    /// Points as an n × 2 matrix (x, y per row), row-major.
    std::vector<double> xy_rows(const std::vector<plan::Point> &points)
    {
      std::vector<double> rows;
      for (const plan::Point &p : points)
      {
        rows.push_back(p.x());
        rows.push_back(p.y());
      }
      return rows;
    }

    /// /lumped/default/plan: the geometry at rest that the plan view draws (PlanRun).
    void write_plan_geometry(io::ResultsGroup &g, const PlanRun &run)
    {
      io::ResultsGroup geometry = g.group("plan");
      geometry.write_matrix("slab_outline",
                            xy_rows(run.slab_outline),
                            run.slab_outline.size(),
                            2,
                            "m");
      geometry.write("slab_reference",
                     std::vector<double>{run.slab_reference.x(), run.slab_reference.y()},
                     "m");
      if (!run.wall.empty())
        geometry.write_matrix("wall", xy_rows(run.wall), run.wall.size(), 2, "m");
      if (!run.contact_positions.empty())
        geometry.write_matrix("contact_position",
                              xy_rows(run.contact_positions),
                              run.contact_positions.size(),
                              2,
                              "m");
    }

    /// `walls/face_<k>` per yielding wall face (as the planar `walls/<wall>`, with the face and
    /// its final displacement).
    void write_plan_yielding(io::ResultsGroup &g, const plan::PlanResponse &r)
    {
      for (const plan::PlanYieldingWallResult &y : r.yielding_walls)
      {
        io::ResultsGroup wg = g.group(fmt::format("walls/face_{}", y.segment));
        wg.set_attribute("face", static_cast<std::int64_t>(y.segment));
        lumped_internal::write_yielding_wall(wg, yielding_record(r, y));
        wg.write_scalar("final_displacement", y.final_displacement, "m");
      }
    }

    /// DIR/lumped.h5 of a plan run: /lumped/default with peaks, energy and histories.
    void write_plan_h5(const io::LoadedScene<PlanLumpedScene> &loaded,
                       const io::OutputDir                    &output,
                       const PlanRun                          &run)
    {
      const plan::PlanResponse &r        = run.response;
      const std::size_t         n_levels = r.n_levels;
      std::vector<std::string>  dof_labels;
      for (std::size_t l = 0; l < n_levels; ++l)
        for (const char *d : direction_names)
          dof_labels.push_back(level_name(loaded.scene, l) + " " + d);
      io::ResultsFile  file(output.file("lumped.h5"), loaded.text, loaded.resolved_json);
      io::ResultsGroup root = file.root();
      root.group("input").set_attribute("ground_motion", run.motion.name);
      io::ResultsGroup g = root.group("lumped").case_group("default");
      g.set_attribute("plan", static_cast<std::int64_t>(1));
      g.write_scalar("wall_time", run.wall_time, "s");
      g.write_scalar("dt", r.dt, "s");
      g.write_scalar("dt_critical", run.dt_critical, "s");
      g.set_attribute("n_steps", static_cast<std::int64_t>(r.n_steps));
      g.write_scalar("duration", r.duration, "s");
      g.write("dof_labels", dof_labels);
      g.write("contact_names", run.contact_names);
      g.set_attribute("damping", damping_name(run.damping));
      g.write_scalar("damping_ratio", run.damping_ratio, "1");
      g.write_scalar("isolation_damping_ratio", run.isolation_damping_ratio, "1");
      write_plan_geometry(g, run);
      write_plan_yielding(g, r);
      {
        io::ResultsGroup peaks = g.group("peaks");
        peaks.write("displacement", r.peak_displacement, "m|rad");
        peaks.write("absolute_acceleration", r.peak_absolute_acceleration, "m/s^2|rad/s^2");
        peaks.write("corner_displacement", r.peak_corner_displacement, "m");
        peaks.write("horizontal_acceleration", r.peak_horizontal_acceleration, "m/s^2");
        peaks.write("drift_x", r.peak_drift_x, "m");
        peaks.write("drift_y", r.peak_drift_y, "m");
        peaks.write("corner_drift", r.peak_corner_drift, "m");
        peaks.write("wall_force", r.peak_wall_force, "N");
        peaks.write_scalar("isolator_force", r.peak_isolator_force, "N");
        std::vector<double> normal, friction;
        for (const plan::PlanContactResult &c : r.contacts)
        {
          normal.push_back(c.peak_normal_force);
          friction.push_back(c.peak_friction_force);
        }
        peaks.write("contact_normal_force", normal, "N");
        peaks.write("contact_friction_force", friction, "N");
      }
      {
        io::ResultsGroup        e     = g.group("energy");
        const plan::PlanEnergy &en    = r.energy;
        const nlohmann::json    terms = plan_energy_json(en);
        for (const auto &[key, value] : terms.items())
          e.write_scalar(key,
                         value.get<double>(),
                         key.find("relative") != std::string::npos ? "1" : "J");
      }
      const plan::PlanHistory &h = r.history;
      if (!h.time.empty())
      {
        io::ResultsGroup          hist = g.group("history");
        std::vector<std::int64_t> steps;
        for (const double t : h.time)
          steps.push_back(static_cast<std::int64_t>(std::llround(t / r.dt)));
        const std::size_t n_dofs    = 3 * n_levels;
        const std::size_t n_contact = run.contact_names.size();
        hist.write_time_series("displacement", steps, h.time, h.displacement, n_dofs, "m|rad");
        hist.write_time_series("absolute_acceleration",
                               steps,
                               h.time,
                               h.absolute_acceleration,
                               n_dofs,
                               "m/s^2|rad/s^2");
        hist.write_time_series("corner_displacement",
                               steps,
                               h.time,
                               h.corner_displacement,
                               2 * run.n_corners,
                               "m");
        if (n_contact > 0)
        {
          hist.write_time_series("contact_force", steps, h.time, h.contact_force, n_contact, "N");
          hist.write_time_series("friction_force", steps, h.time, h.friction_force, n_contact, "N");
        }
        hist.write_time_series("energy_error", steps, h.time, h.energy_error, 1, "1");
      }
      g.set_status("ok");
      file.commit();
    }

    /// DIR/summary.json of a plan run (its wall_time counted from `start`).
    void write_plan_summary(const io::LoadedScene<PlanLumpedScene> &loaded,
                            const io::OutputDir                    &output,
                            const PlanRun                          &run,
                            Clock::time_point                       start)
    {
      const plan::PlanResponse &r       = run.response;
      nlohmann::json            summary = io::summary_preamble("lumped");
      summary["scene"]                  = loaded.file_name;
      summary["plan"]                   = true;
      summary["wall_time"]     = std::chrono::duration<double>(Clock::now() - start).count();
      summary["ground_motion"] = {{"name", run.motion.name},
                                  {"dt", run.motion.dt},
                                  {"duration", run.motion.duration()},
                                  {"angle_deg", loaded.scene.plan->angle}};
      summary["units"]         = {{"displacement", "m"},
                                  {"rotation", "rad"},
                                  {"absolute_acceleration", "m/s^2"},
                                  {"force", "N"},
                                  {"time", "s"},
                                  {"energy", "J"},
                                  {"wall_time", "s"}};
      const PlanPeaks peaks    = plan_peaks(r);
      nlohmann::json  c;
      c["name"]        = "default";
      c["status"]      = "ok";
      c["dt"]          = r.dt;
      c["dt_critical"] = run.dt_critical;
      c["n_steps"]     = r.n_steps;
      c["n_impacts"]   = r.n_impacts();
      c["peaks"]       = {{"base_corner_displacement", r.peak_corner_displacement.front()},
                          {"corner_impact_force", peaks.corner_force},
                          {"friction_force", peaks.friction_force},
                          {"top_acceleration", r.peak_horizontal_acceleration.back()},
                          {"corner_drift", peaks.corner_drift},
                          {"rotation", peaks.rotation},
                          {"isolator_force", r.peak_isolator_force},
                          {"displacement", r.peak_displacement},
                          {"absolute_acceleration", r.peak_absolute_acceleration},
                          {"corner_displacement", r.peak_corner_displacement},
                          {"drift_x", r.peak_drift_x},
                          {"drift_y", r.peak_drift_y},
                          {"wall_force", r.peak_wall_force}};
      c["energy"]      = plan_energy_json(r.energy);
      c["damping"]     = plan_damping_json(run);
      if (!r.yielding_walls.empty())
      {
        c["yielding_walls"]                = yielding_walls_json(r);
        summary["units"]["yielding_walls"] = yielding_units();
      }
      summary["cases"] = nlohmann::json::array({c});
      io::write_json_atomic(output.file("summary.json"), summary);
    }

    /// DIR/peaks.csv of a plan run: one row per level and direction.
    void write_plan_peaks(const io::LoadedScene<PlanLumpedScene> &loaded,
                          const io::OutputDir                    &output,
                          const PlanRun                          &run)
    {
      const plan::PlanResponse             &r        = run.response;
      const std::size_t                     n_levels = r.n_levels;
      std::vector<std::vector<std::string>> rows;
      for (std::size_t l = 0; l < n_levels; ++l)
        for (std::size_t d = 0; d < 3; ++d)
        {
          const std::size_t dof = 3 * l + d;
          const std::size_t s =
            l - (loaded.scene.base.building.kind == BuildingKind::isolated ? 1 : 0);
          const bool storey =
            (l > 0 || loaded.scene.base.building.kind != BuildingKind::isolated) &&
            s < r.peak_corner_drift.size();
          rows.push_back({"default",
                          std::to_string(dof),
                          level_name(loaded.scene, l),
                          direction_names[d],
                          text(r.peak_displacement[dof]),
                          text(r.peak_absolute_acceleration[dof]),
                          d == 0 ? text(r.peak_corner_displacement[l]) : "",
                          storey && d == 0 ? text(r.peak_drift_x[s]) :
                          storey && d == 1 ? text(r.peak_drift_y[s]) :
                          storey           ? text(r.peak_corner_drift[s]) :
                                             ""});
        }
      io::write_csv_atomic(output.file("peaks.csv"),
                           {"case",
                            "dof",
                            "level",
                            "direction",
                            "peak_displacement_m_or_rad",
                            "peak_absolute_acceleration_m_per_s2_or_rad_per_s2",
                            "peak_corner_displacement_m",
                            "peak_interstorey_drift_m"},
                           rows);
    }

    /// One line per yielding wall face: its peak resistance against its capacity, its
    /// displacements and, for a failed face, a warning with the time.
    void log_yielding_faces(const plan::PlanResponse &r)
    {
      for (const plan::PlanYieldingWallResult &y : r.yielding_walls)
      {
        base::logger().info("plan: yielding wall face {}: peak resistance {} MN = {} of its "
                            "capacity {} MN (face force {} MN), peak displacement {} cm, "
                            "residual {} cm",
                            y.segment,
                            base::sig(y.peak_resistance / 1e6),
                            base::sig(y.peak_resistance / y.capacity),
                            base::sig(y.capacity / 1e6),
                            base::sig(r.peak_wall_force[y.segment] / 1e6),
                            base::sig(100.0 * y.peak_displacement),
                            base::sig(100.0 * y.permanent_set));
        if (y.failure_time)
          base::logger().warn("plan: yielding wall face {} failed at t = {} s: pushed back "
                              "beyond {} cm",
                              y.segment,
                              base::sig(*y.failure_time),
                              base::sig(100.0 * y.failure_displacement));
      }
    }
  } // namespace

  PlanRun run_plan_lumped(const io::LoadedScene<PlanLumpedScene>     &loaded,
                          const io::OutputDir                        &output,
                          const std::optional<std::filesystem::path> &records_dir_override)
  {
    const auto    start = Clock::now();
    const PlanRun run = run_plan(loaded.scene, loaded.file_name, loaded.text, records_dir_override);
    write_plan_h5(loaded, output, run);
    write_plan_summary(loaded, output, run, start);
    write_plan_peaks(loaded, output, run);
    log_yielding_faces(run.response);
    return run;
  }
} // namespace kimp::app
