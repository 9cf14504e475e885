// Compute stage of `kimp study` after the k table: the isolated building pounding on moat walls
// with each height's k (docs/physics.md §2-3), then the accuracy, stability and sensitivity
// studies.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <set>

#include "app/lumped/lumped_run.h"
#include "app/study/study_internal.h"
#include "app/study/wall_capacity.h"
#include "base/errors.h"
#include "base/format.h"
#include "base/logging.h"
#include "lumped/collision/two_body.h"
#include "lumped/integrators/response.h"

namespace kimp::app::study_internal
{
  namespace
  {
    void fill_peaks(StudyBuildingRun       &run,
                    const LumpedCaseResult &result,
                    unsigned int            top_dof,
                    const lumped::Response *without_walls)
    {
      run.status       = result.status;
      run.wall_seconds = result.wall_time;
      run.pga          = result.pga;
      if (!result.ok())
        return;
      const lumped::Response &r = result.response;
      run.base_displacement     = r.peak_displacement.at(0);
      run.top_displacement      = r.peak_displacement.at(top_dof);
      run.base_acceleration     = r.peak_absolute_acceleration.at(0);
      run.top_acceleration      = r.peak_absolute_acceleration.at(top_dof);
      run.max_floor_acceleration =
        *std::max_element(r.peak_absolute_acceleration.begin() + 1,
                          r.peak_absolute_acceleration.begin() + top_dof + 1);
      run.max_interstorey_drift = r.max_interstorey_drift();
      run.n_impacts             = r.n_impacts();
      for (const lumped::ContactResult &c : r.contacts)
      {
        run.peak_impact_force     = std::max(run.peak_impact_force, c.peak_force);
        run.permanent_indentation = std::max(run.permanent_indentation, c.permanent_indentation);
      }
      if (without_walls)
      {
        const lumped::Amplification a = lumped::amplification_factors(r, *without_walls);
        run.amplification_base_acc    = a.absolute_acceleration.at(0);
        run.amplification_top_acc     = a.absolute_acceleration.at(top_dof);
        run.amplification_drift =
          run.max_interstorey_drift / std::max(without_walls->max_interstorey_drift(), 1e-300);
      }
    }

    /// One warning for the building runs whose peak impact force exceeds the wall's capacity
    /// estimate: how many, and the largest ratio with its run.
    void log_capacity_exceeded(const std::vector<StudyBuildingRun> &runs)
    {
      std::size_t             n = 0, n_walled = 0;
      const StudyBuildingRun *worst = nullptr;
      for (const StudyBuildingRun &r : runs)
      {
        if (!(r.wall_capacity > 0.0) || r.status != "ok" || r.yielding_wall)
          continue;
        ++n_walled;
        if (r.peak_impact_force <= r.wall_capacity)
          continue;
        ++n;
        if (!worst ||
            r.peak_impact_force / r.wall_capacity > worst->peak_impact_force / worst->wall_capacity)
          worst = &r;
      }
      if (worst)
        logger().warn("{} of {} building runs put more than the wall's capacity estimate "
                      "(M_p + P_p H/3)/h_c x W on a wall (linear walls do not yield); largest: "
                      "{} times {} MN, record {}, H = {} m, {} (building_response.csv "
                      "peak_force_over_capacity)",
                      n,
                      n_walled,
                      base::sig(worst->peak_impact_force / worst->wall_capacity),
                      base::sig(worst->wall_capacity / 1e6),
                      worst->record,
                      base::sig(worst->wall_height),
                      worst->law);
    }

    /// The height of the k table nearest to `wall_height` with a Kelvin-Voigt fit (or null).
    const StudyHeight *nearest_height(const std::vector<StudyHeight> &heights, double wall_height)
    {
      const StudyHeight *best = nullptr;
      for (const StudyHeight &h : heights)
        if (h.law("kelvin_voigt").fit && (!best || std::abs(h.wall_height - wall_height) <
                                                     std::abs(best->wall_height - wall_height)))
          best = &h;
      return best;
    }

    /// The largest estimated errors of the variable-step building runs, for one log line.
    struct VariableStepErrors
    {
      std::size_t n_runs = 0, n_variable = 0;
      double      force = 0.0, acceleration = 0.0, displacement = 0.0;
      std::string force_case;

      void add(const std::string &name, const std::optional<lumped::AdaptiveStepReport> &adaptive)
      {
        ++n_runs;
        if (!adaptive)
          return;
        ++n_variable;
        if (adaptive->force_error >= force)
        {
          force      = adaptive->force_error;
          force_case = name;
        }
        acceleration = std::max(acceleration, adaptive->acceleration_error);
        displacement = std::max(displacement, adaptive->displacement_error);
      }

      void log() const
      {
        if (n_variable == 0)
          return;
        logger().info("building runs: {} of {} with variable steps (dt: auto); largest "
                      "estimated errors: peak force {} % ({}), peak acceleration {} %, peak "
                      "displacement {} % (each run with -v)",
                      n_variable,
                      n_runs,
                      base::sig(100.0 * force, 2),
                      force_case,
                      base::sig(100.0 * acceleration, 2),
                      base::sig(100.0 * displacement, 2));
      }
    };

  } // namespace

  std::vector<std::pair<std::string, GroundMotionScene>> labelled_records(const StudyScene &scene)
  {
    std::vector<std::pair<std::string, GroundMotionScene>> records;
    std::set<std::string>                                  used;
    for (const GroundMotionScene &record : study_records(scene))
    {
      std::string label = record.record;
      for (int i = 2; !used.insert(label).second; ++i)
        label = fmt::format("{}_{}", record.record, i);
      records.emplace_back(label, record);
    }
    return records;
  }

  double wall_gap(const StudyScene &scene, double base_displacement)
  {
    return scene.walls.gap.value_or((1.0 - scene.walls.gap_reduction) * base_displacement);
  }

  std::vector<std::pair<std::string, const std::optional<FitResult> *>>
  building_laws(const StudyHeight &h)
  {
    std::vector<std::pair<std::string, const std::optional<FitResult> *>> laws;
    for (const StudyLawFit &law : h.laws)
      for (const std::string_view building_law : law.law->building_laws)
        laws.emplace_back(std::string(building_law), &law.fit);
    return laws;
  }

  LumpedScene walled_scene(const LumpedScene &base,
                           double             gap,
                           const std::string &law,
                           double             k_total,
                           double             cor)
  {
    LumpedScene s         = base;
    s.walls.left.present  = true;
    s.walls.right.present = true;
    s.walls.left.gap      = gap;
    s.walls.right.gap     = gap;
    s.impact.law          = law;
    s.impact.k.clear();
    s.impact.k_si     = k_total;
    s.impact.exponent = std::nullopt;
    s.impact.cor      = cor;
    return s;
  }

  namespace
  {
    /// The run without walls of `record` labelled `label`: its row; when it is ok, its context
    /// is appended to `records`.
    StudyBuildingRun run_without_walls(const StudyScene           &scene,
                                       const std::string          &label,
                                       const GroundMotionScene    &record,
                                       std::vector<RecordContext> &records,
                                       VariableStepErrors         &errors)
    {
      StudyBuildingRun bare;
      bare.record = label;
      bare.law    = "none";
      RecordContext context;
      try
      {
        context.motion = load_ground_motion(record);
      }
      catch (const std::exception &error)
      {
        bare.status = "failed: " + base::error_text(error);
        logger().warn("record {}: {}", label, bare.status);
        return bare;
      }
      context.base = study_lumped_scene(scene, record);
      const LumpedCaseResult none =
        run_lumped_case("no_walls", context.base, context.motion, record.scale);
      errors.add(label + " no_walls", none.adaptive);
      fill_peaks(bare, none, scene.building.n_storeys, nullptr);
      if (!none.ok())
      {
        logger().warn("record {}: run without walls {}", label, none.status);
        return bare;
      }
      context.label         = label;
      context.scale         = record.scale;
      context.gap           = wall_gap(scene, bare.base_displacement);
      context.without_walls = none.response;
      logger().info("record {} (PGA {:.3f} g): no walls: peak isolation displacement {:.4g} cm, "
                    "top acceleration {:.4g} m/s^2 -> wall gap {:.4g} cm",
                    label,
                    none.pga / lumped::standard_gravity,
                    bare.base_displacement * 100,
                    bare.top_acceleration,
                    context.gap * 100);
      records.push_back(std::move(context));
      return bare;
    }

    /// The runs of every law of `h` against `record`'s walls (a linear study).
    std::vector<StudyBuildingRun> run_law_walls(const StudyScene    &scene,
                                                const RecordContext &record,
                                                const StudyHeight   &h,
                                                VariableStepErrors  &errors)
    {
      std::vector<StudyBuildingRun> runs;
      for (const auto &[law, fit] : building_laws(h))
      {
        StudyBuildingRun run;
        run.record      = record.label;
        run.wall_height = h.wall_height;
        run.law         = law;
        run.gap         = record.gap;
        if (!*fit)
        {
          run.status = "skipped: no fitted k for " + h.name;
          runs.push_back(run);
          continue;
        }
        run.exponent = (*fit)->exponent.value;
        run.k_total  = (*fit)->stiffness.value * scene.fit.width;
        run.wall_capacity =
          wall_capacity_estimate(scene.fem, h.wall_height).per_metre * scene.fit.width;
        const LumpedCaseResult done =
          run_lumped_case(h.name + "_" + law,
                          walled_scene(record.base, record.gap, law, run.k_total, scene.fit.cor),
                          record.motion,
                          record.scale);
        errors.add(record.label + " " + h.name + " " + law, done.adaptive);
        fill_peaks(run, done, scene.building.n_storeys, &record.without_walls);
        if (!done.ok())
          logger().warn("record {} {} {}: {}", record.label, h.name, law, done.status);
        runs.push_back(run);
      }
      return runs;
    }
  } // namespace

  std::vector<StudyBuildingRun> run_building(const StudyScene                     &scene,
                                             const std::vector<StudyHeight>       &heights,
                                             const std::vector<StudyYieldingWall> &yielding)
  {
    VariableStepErrors errors;
    // Per record its run without walls (a failed one ends its record's rows).
    std::vector<std::vector<StudyBuildingRun>> rows;
    std::vector<RecordContext>                 records;
    for (const auto &[label, record] : labelled_records(scene))
    {
      rows.push_back({run_without_walls(scene, label, record, records, errors)});
    }
    // The laws' runs (a linear study) beside the yielding walls' runs, which run on a pool.
    const bool instead = has_inelastic_materials(scene.fem);
    std::vector<std::vector<std::vector<StudyBuildingRun>>> laws(records.size());
    const auto                                              run_laws = [&]()
    {
      if (instead)
        return;
      for (std::size_t i = 0; i < records.size(); ++i)
        for (const StudyHeight &h : heights)
          laws[i].push_back(run_law_walls(scene, records[i], h, errors));
    };
    std::vector<YieldingWallCase> cases;
    if (yielding.empty())
      run_laws();
    else
      cases = run_yielding_wall_cases(scene, records, heights, yielding, run_laws);
    // The rows record by record: without walls, then per height its laws and its yielding wall.
    std::vector<StudyBuildingRun> runs;
    std::size_t                   i = 0;
    for (const std::vector<StudyBuildingRun> &record : rows)
    {
      runs.insert(runs.end(), record.begin(), record.end());
      if (record.front().status != "ok")
        continue;
      for (std::size_t j = 0; j < heights.size(); ++j)
      {
        if (!instead)
          runs.insert(runs.end(), laws[i][j].begin(), laws[i][j].end());
        if (cases.empty())
          continue;
        const YieldingWallCase &y = cases[i * heights.size() + j];
        if (y.ran)
          errors.add(records[i].label + " " + heights[j].name + " yielding_wall", y.adaptive);
        runs.push_back(y.run);
      }
      ++i;
    }
    errors.log();
    log_capacity_exceeded(runs);
    log_yielding_walls(runs,
                       instead ? "yielding walls" :
                                 "estimate element beside the linear springs (capacity "
                                 "(M_p + P_p H/3)/h_c, cracked cantilever, rho c dashpot)");
    return runs;
  }

  StudyExtras
  run_extras(const StudyScene &scene, const StudyResult &result, const OutputDir &output)
  {
    StudyExtras        extras;
    const StudyHeight *h = nearest_height(result.heights, scene.accuracy.wall_height);
    const double k_total = h ? h->law("kelvin_voigt").fit->stiffness.value * scene.fit.width : nan;
    if (scene.accuracy_study)
    {
      logger().info("accuracy study at H = {} m (FEM levels, then the building's time step)",
                    scene.accuracy.wall_height);
      extras.fem_accuracy                          = run_fem_accuracy(scene, output);
      const std::vector<GroundMotionScene> records = study_records(scene);
      const auto                           bare =
        std::find_if(result.building.begin(),
                     result.building.end(),
                     [](const StudyBuildingRun &r) { return r.law == "none" && r.status == "ok"; });
      if (h && !records.empty() && bare != result.building.end())
      {
        extras.lumped_k_total = k_total;
        extras.lumped_gap     = wall_gap(scene, bare->base_displacement);
        extras.lumped_record  = bare->record;
        try
        {
          extras.lumped_accuracy =
            run_lumped_accuracy(scene, records.front(), k_total, extras.lumped_gap);
        }
        catch (const std::exception &error)
        {
          logger().warn("lumped accuracy study skipped: {}", error.what());
        }
      }
    }
    if (scene.stability_map && h)
    {
      extras.stability_study_k = k_total;
      extras.stability         = lumped_stability_map(scene.building.isolation_mass,
                                              scene.walls.mass,
                                              scene.fit.cor,
                                              k_total);
      const lumped::TwoBodySetup setup{scene.building.isolation_mass, scene.walls.mass};
      extras.stability_effective_mass = setup.effective_mass();
      try
      {
        extras.fem_stability_end_time = fem_stability_end_time;
        extras.fem_stability = fem_stability_map(scene, output, extras.fem_stability_h_contact);
      }
      catch (const std::exception &error)
      {
        logger().warn("FEM stability map skipped: {}", error.what());
      }
    }
    if (scene.sensitivity)
    {
      logger().info("sensitivity study at H = {} m (+-{} %)",
                    scene.sensitivity_study.wall_height,
                    scene.sensitivity_study.variation * 100);
      extras.sensitivity = run_sensitivity(scene, output);
    }
    return extras;
  }

  void fill_building_peaks(StudyBuildingRun       &run,
                           const LumpedCaseResult &result,
                           unsigned int            top_dof,
                           const lumped::Response *without_walls)
  {
    fill_peaks(run, result, top_dof, without_walls);
  }
} // namespace kimp::app::study_internal
