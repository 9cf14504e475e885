// `kimp lumped`: one pounding analysis per case (central difference or Newmark) and the loop over
// a scene's cases; failed cases are recorded, not fatal. The cost estimate of a case is in
// lumped_estimate.cc, the files (lumped.h5, summary.json, peaks.csv) in lumped_files.cc.
#include "app/lumped/lumped_run.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "app/lumped/lumped_run_internal.h"
#include "base/errors.h"
#include "base/format.h"
#include "base/logging.h"
#include "io/units.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/newmark_integrator.h"
#include "lumped/structure/pounding_model.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace lumped_internal;
  namespace
  {
    /// AdaptiveStepReport::text() with a few significant figures.
    std::string variable_step_text(const lumped::AdaptiveStepReport &r)
    {
      return fmt::format("variable step: {} s, {} s approaching, {} s at contacts ({} windows, "
                         "{} steps of which {} below the large step, +{} for the estimate); "
                         "estimated errors: peak force {} %, peak acceleration {} %, peak "
                         "displacement {} %",
                         base::sig(r.dt_large, 3),
                         base::sig(r.dt_approach, 3),
                         base::sig(r.dt_contact, 3),
                         r.windows,
                         r.steps,
                         r.contact_steps_taken,
                         r.estimate_steps,
                         base::sig(100.0 * r.force_error, 2),
                         base::sig(100.0 * r.acceleration_error, 2),
                         base::sig(100.0 * r.displacement_error, 2));
    }

    /// "<building> isolation level" for DOF 0 of an isolated main building, the wall's name for
    /// a flexible moat wall, else "<building> floor j" (floors above the ground numbered from 1).
    std::vector<std::string> dof_labels(const lumped::PoundingModel &model)
    {
      std::vector<std::string> labels(model.n_dofs());
      for (std::size_t b = 0; b < model.buildings().size(); ++b)
      {
        const lumped::BuildingBlock &block    = model.buildings()[b];
        const bool                   isolated = b == 0 && model.isolator() != nullptr;
        // A flexible moat wall is a block of one DOF named after the wall ("left_wall").
        const bool wall =
          block.name.size() > 5 && block.name.compare(block.name.size() - 5, 5, "_wall") == 0;
        if (wall && block.n_dofs == 1)
        {
          labels[static_cast<std::size_t>(block.first_dof)] = block.name;
          continue;
        }
        for (int i = 0; i < block.n_dofs; ++i)
          labels[static_cast<std::size_t>(block.first_dof + i)] =
            block.name + (isolated && i == 0 ? std::string(" isolation level") :
                                               " floor " + std::to_string(isolated ? i : i + 1));
      }
      return labels;
    }

    /// The storey below a floor takes its number: "building floor 2" -> "building storey 2".
    std::string storey_label(const std::string &upper_dof_label)
    {
      const std::size_t at = upper_dof_label.rfind(" floor ");
      return at == std::string::npos ?
               upper_dof_label + " storey" :
               upper_dof_label.substr(0, at) + " storey " + upper_dof_label.substr(at + 7);
    }
    /// `dt: auto` warns when its estimated error of the peak impact force exceeds this (the
    /// estimate is pessimistic: 0.09-0.87 % on Table 4.3 for true errors of 0.001-0.23 %).
    constexpr double variable_step_warning = 0.01;

    /// Cases may scale the record further: an absurd peak is worth a warning before the run.
    constexpr double warning_pga = 5.0 * standard_gravity;
  } // namespace

  namespace
  {
    /// One line per yielding wall: its peak force against its capacity, its displacements and,
    /// for a failed wall, a warning with the time.
    void log_yielding_walls(const LumpedCaseResult &r)
    {
      for (const YieldingWallLimits &w : r.yielding_walls)
      {
        const lumped::ContactResult &c = r.response.contacts[w.contact];
        logger().info("case {}: {}: peak resistance {} MN = {} of its capacity {} MN (with the "
                      "dashpot {} MN), peak displacement {} cm, residual {} cm",
                      r.name,
                      w.wall,
                      base::sig(c.peak_resistance / 1e6),
                      base::sig(c.peak_resistance / w.capacity),
                      base::sig(w.capacity / 1e6),
                      base::sig(c.peak_force / 1e6),
                      base::sig(100.0 * c.peak_deformation),
                      base::sig(100.0 * c.permanent_indentation));
        if (c.failure_time)
          logger().warn("case {}: {} failed at t = {} s: pushed back beyond {} cm",
                        r.name,
                        w.wall,
                        base::sig(*c.failure_time),
                        base::sig(100.0 * w.failure_displacement));
      }
    }

    /// The model's buildings (periods, damping), contacts, storeys, DOF labels and isolator, as
    /// the case's files name them.
    void describe_model(const lumped::PoundingModel &model, LumpedCaseResult &result)
    {
      for (const lumped::BuildingBlock &block : model.buildings())
      {
        BuildingModes b;
        b.name = block.name;
        for (Eigen::Index i = 0; i < block.damping.modes.period.size(); ++i)
          b.periods.push_back(block.damping.modes.period[i]);
        b.rayleigh_a = block.damping.rayleigh.a;
        b.rayleigh_b = block.damping.rayleigh.b;
        b.c_iso      = block.damping.c_iso;
        result.buildings.push_back(std::move(b));
      }
      for (const lumped::ContactPair &c : model.contacts())
      {
        if (const auto *wall = dynamic_cast<const lumped::WallBackfillLaw *>(c.law.get()))
          result.yielding_walls.push_back({c.name.substr(0, c.name.rfind("_backfill")),
                                           result.contact_names.size(),
                                           wall->parameters().capacity,
                                           wall->parameters().failure_displacement});
        result.contact_names.push_back(c.name);
      }
      for (const lumped::Storey &s : model.storeys())
        result.storey_upper_dofs.push_back(s.upper_dof);
      result.dof_labels = dof_labels(model);
      for (const lumped::Storey &s : model.storeys())
        result.storey_labels.push_back(
          storey_label(result.dof_labels[static_cast<std::size_t>(s.upper_dof)]));
      if (model.isolator())
        result.isolator = model.isolator()->name();
    }

    /// One case's run: its model, scene, motion and result; check_budget(step) estimates the
    /// run at the step the integrator takes and refuses it above the budget.
    struct CaseRun
    {
      const std::string           &name;
      const lumped::PoundingModel &model;
      const IntegrationScene      &in;
      const lumped::GroundMotion  &used;
      LumpedCaseResult            &result;

      void check_budget(const double step) const
      {
        const RunEstimate estimate = make_estimate(step, in, used, model.n_dofs());
        result.estimated_steps     = estimate.n_steps;
        if (logger().should_log(spdlog::level::debug))
          logger().debug("case {}: {}", name, estimate.text());
        check_run_budget(name, estimate, in);
      }
    };

    /// A variable-step run in which no contact closed is its companion run (its steps differ
    /// only where a gap approached), so that amplification factors are then exactly 1.
    void take_companion_if_untouched(LumpedCaseResult &result)
    {
      bool touched = result.response.n_impacts() > 0;
      for (const lumped::ContactResult &c : result.response.contacts)
        touched = touched || c.peak_force != 0.0;
      if (touched)
        return;
      lumped::Response same      = *result.companion;
      same.contacts              = result.response.contacts;
      same.history.contact_force = result.response.history.contact_force;
      result.response            = std::move(same);
    }

    /// The variable step's report of a case at -v, and a warning when its force error is large.
    void report_variable_step(const std::string &name, const lumped::AdaptiveStepReport &report)
    {
      // Per case at -v; the study and the summary.json give the largest errors.
      logger().debug("case {}: {}", name, variable_step_text(report));
      if (report.force_error > variable_step_warning)
        logger().warn("case {}: dt auto estimates the peak impact force within {:.2g} %, "
                      "above {:.2g} %: raise integration.contact_steps or use a fixed dt",
                      name,
                      100.0 * report.force_error,
                      100.0 * variable_step_warning);
    }

    /// A fixed central-difference step from a shared free run's prefix when `free_runs` gives
    /// one (and histories are not recorded): the response, and the prefix's companion run.
    bool run_from_free_prefix(const CaseRun       &run,
                              const Integration   &integration,
                              const FreeRunSource &free_runs)
    {
      if (!free_runs || integration.method != IntegrationMethod::cdm || integration.variable ||
          integration.cdm.output_interval > 0.0)
        return false;
      lumped::CentralDifferenceOptions free_options = integration.cdm;
      const lumped::CentralDifference  integrator(run.model, integration.cdm);
      free_options.dt = integrator.time_step(run.used.dt);
      const std::shared_ptr<const lumped::FreeRunPrefix> prefix =
        free_runs(lumped::CentralDifference(run.model.without_contacts(), free_options),
                  free_options.dt,
                  run.used);
      if (!prefix)
        return false;
      run.result.response = prefix->run(integrator, run.used);
      if (run.in.companion)
        run.result.companion = prefix->response();
      return true;
    }

    /// The main run of integration.method and its companion run without contacts, both through
    /// integrate().
    void integrate_case(const CaseRun               &run,
                        const std::optional<double> &dt,
                        const FreeRunSource         &free_runs)
    {
      const IntegrationScene &in          = run.in;
      LumpedCaseResult       &result      = run.result;
      const Integration       integration = integration_of(in, dt);
      if (in.method == IntegrationMethod::cdm)
      {
        const lumped::CentralDifference integrator(run.model, integration.cdm);
        result.dt_critical = integrator.stability().dt_critical;
        result.governing   = integrator.stability().governing;
        result.dt_policy   = dt ? "fixed" : integration.variable ? "variable" : "stable";
        logger().debug("case {}: dt_cr = {} s ({})",
                       run.name,
                       result.dt_critical,
                       result.governing);
      }
      else
        result.dt_policy = dt ? "fixed" : "record";
      run.check_budget(planned_step(run.model, integration, run.used.dt));
      if (run_from_free_prefix(run, integration, free_runs))
        return;
      Integrated main = integrate(run.model, integration, run.used);
      result.response = std::move(main.response);
      result.adaptive = main.adaptive;
      if (in.companion)
        // The companion chooses its own variable steps (independent of the walls); a fixed step
        // is the main run's.
        result.companion = integrate(run.model.without_contacts(),
                                     companion_integration(integration, result.response),
                                     run.used)
                             .response;
      if (integration.variable)
      {
        if (result.companion)
          take_companion_if_untouched(result);
        report_variable_step(run.name, *result.adaptive);
      }
    }
  } // namespace

  LumpedCaseResult run_lumped_case(const std::string          &name,
                                   const LumpedScene          &scene,
                                   const lumped::GroundMotion &motion,
                                   const double                base_scale)
  {
    return run_lumped_case(name, scene, motion, base_scale, FreeRunSource());
  }

  LumpedCaseResult run_lumped_case(const std::string          &name,
                                   const LumpedScene          &scene,
                                   const lumped::GroundMotion &motion,
                                   const double                base_scale,
                                   const FreeRunSource        &free_runs)
  {
    LumpedCaseResult        result;
    const Clock::time_point start = Clock::now();
    result.name                   = name;
    try
    {
      const lumped::PoundingModel model(make_pounding_scene(scene));
      describe_model(model, result);

      const double         factor = scene.ground_motion.scale / base_scale;
      lumped::GroundMotion used   = factor != 1.0 ? lumped::scaled(motion, factor) : motion;
      result.pga                  = used.pga();
      if (factor != 1.0 && result.pga > warning_pga)
        logger().warn("case {}: ground motion scaled by {:.4g} to a PGA of {:.4g} g, above {} g "
                      "(beyond any recorded motion): is the scale intended?",
                      name,
                      factor,
                      result.pga / standard_gravity,
                      warning_pga / standard_gravity);

      const IntegrationScene &in = scene.integration;
      integrate_case(CaseRun{name, model, in, used, result}, requested_time_step(in), free_runs);
      if (const std::string why = implausibility(result.response, in); !why.empty())
        throw std::runtime_error("implausible result: " + why);
    }
    catch (const std::exception &error)
    {
      result.status   = "failed: " + base::error_text(error);
      result.response = lumped::Response{};
      result.companion.reset();
    }
    result.wall_time = seconds_since(start);
    return result;
  }

  LumpedCasesRun run_lumped_cases(const LumpedScene                          &scene,
                                  const std::string                          &file_name,
                                  const std::string                          &scene_text,
                                  const std::optional<std::filesystem::path> &records_dir_override,
                                  const std::optional<std::string>           &only_case,
                                  const SyntheticMotionSource                &synthetic)
  {
    const auto load = [&](const GroundMotionScene &section, const std::string &key_path)
    {
      if (!section.is_record() && synthetic)
        return synthetic(section);
      return std::make_shared<const lumped::GroundMotion>(
        load_ground_motion_at(section, records_dir_override, file_name, scene_text, key_path));
    };

    // The cases to run, with their index in `cases` (which names their keys in messages).
    const auto               cases = resolve_cases(scene);
    std::vector<std::size_t> chosen;
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (!only_case || cases[i].first == *only_case)
        chosen.push_back(i);
    if (chosen.empty())
    {
      std::string known;
      for (const auto &c : cases)
        known += (known.empty() ? "" : ", ") + c.first;
      throw std::invalid_argument("no case '" + only_case.value_or("") + "' in " + file_name +
                                  " (cases: " + known + ")");
    }

    LumpedCasesRun run;
    run.motion                         = load(scene.ground_motion, "ground_motion");
    const lumped::GroundMotion &motion = *run.motion;
    logger().info("ground motion {}: {} samples at {:.4g} s, PGA {:.4g} g",
                  motion.name,
                  motion.acceleration.size(),
                  motion.dt,
                  motion.pga() / lumped::standard_gravity);

    // Which k each case takes from a study's k table (summary.json "impact_k" too).
    for (const std::size_t i : chosen)
      if (const std::optional<nlohmann::json> k = k_from_table(cases[i].second.impact))
        logger().info("case {}: impact k = {} {} from the k table {} at wall height {} m",
                      cases[i].first,
                      base::sig(k->at("k_display").get<double>()),
                      k->at("display_unit").get<std::string>(),
                      k->at("k_table").get<std::string>(),
                      base::sig(k->at("wall_height").get<double>()));
    // The cases' own records (cases[i].record) before any run, so that a missing one is an error
    // at its key rather than a run stopped half-way.
    std::vector<std::shared_ptr<const lumped::GroundMotion>> own_motions(cases.size());
    for (const std::size_t i : chosen)
      if (cases[i].second.ground_motion.record != scene.ground_motion.record)
        own_motions[i] = load(cases[i].second.ground_motion, "cases[" + std::to_string(i) + "]");
    // Every case's cost first, so that a run over budget is refused before anything is computed
    // (an invalid case is left to run_lumped_case(), which records why it fails).
    for (const std::size_t i : chosen)
    {
      const auto &[name, case_scene] = cases[i];
      RunEstimate estimate;
      try
      {
        const double factor = case_scene.ground_motion.scale / scene.ground_motion.scale;
        estimate            = own_motions[i] ?
                                estimate_lumped_case(case_scene, *own_motions[i]) :
                                estimate_lumped_case(case_scene,
                                          factor != 1.0 ? lumped::scaled(motion, factor) : motion);
      }
      catch (const std::exception &)
      {
        continue;
      }
      if (logger().should_log(spdlog::level::info))
        logger().info("case {}: estimated {}", name, estimate.text());
      check_run_budget(name, estimate, case_scene.integration);
    }

    Progress progress(chosen.size(), static_cast<double>(chosen.size()));
    for (std::size_t done = 0; done < chosen.size(); ++done)
    {
      const std::size_t i = chosen[done];
      logger().info("case {}/{}: {}", i + 1, cases.size(), cases[i].first);
      if (!own_motions[i])
        run.results.push_back(
          run_lumped_case(cases[i].first, cases[i].second, motion, scene.ground_motion.scale));
      else
      {
        // A case with its own record (cases[i].record), loaded above.
        logger().info("case {}: ground motion {}", cases[i].first, own_motions[i]->name);
        run.results.push_back(run_lumped_case(cases[i].first,
                                              cases[i].second,
                                              *own_motions[i],
                                              cases[i].second.ground_motion.scale));
        own_motions[i].reset();
      }
      const LumpedCaseResult &r = run.results.back();
      if (r.ok() && logger().should_log(spdlog::level::info))
        logger().info("case {}: {} steps of {:.4g} s, {} impacts, peak base {} m, wall time {} s",
                      r.name,
                      r.response.n_steps,
                      r.response.dt,
                      r.response.n_impacts(),
                      base::sig(r.response.peak_displacement.empty() ?
                                  0.0 :
                                  r.response.peak_displacement[0]),
                      base::sig(r.wall_time, 3));
      else if (!r.ok())
        logger().error("case {}: {}", r.name, r.status);
      if (r.ok())
        log_yielding_walls(r);
      progress.update(done + 1, static_cast<double>(done + 1));
    }
    progress.finish();
    return run;
  }
  std::vector<LumpedCaseResult>
  run_lumped(const LoadedScene<LumpedScene>             &loaded,
             const OutputDir                            &output,
             const std::optional<std::filesystem::path> &records_dir_override)
  {
    const Clock::time_point start = Clock::now();
    LumpedCasesRun          run =
      run_lumped_cases(loaded.scene, loaded.file_name, loaded.text, records_dir_override);
    write_lumped_files(loaded, output, run, start);
    // Failed cases are recorded in these files: the command's failure for them keeps the files.
    output.keep_written();
    return std::move(run.results);
  }

} // namespace kimp::app
