// One wall height of `kimp study`: mesh + FEM impact (docs/physics.md §4) with a per-height cache.
#include "app/study/study_fem.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <fstream>
#include <mpi.h>
#include <sstream>
#include <stdexcept>

#include "app/fem/fem_common.h"
#include "app/fem/fem_estimate.h"
#include "app/fem/mesh_run.h"
#include "app/laws/fit_run.h"
#include "app/study/study_velocity.h"
#include "base/errors.h"
#include "base/hash.h"
#include "base/logging.h"
#include "base/stopwatch.h"
#include "base/version.h"
#include "fem/impact.h"
#include "geometry/scene_mesh.h"
#include "io/output_dir.h"
#include "io/results_file.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::fit;
  namespace
  {
    using base::seconds_since;

    std::string read_key(const std::filesystem::path &file)
    {
      std::ifstream in(file);
      std::string   key;
      in >> key;
      return key;
    }

  } // namespace

  StudyFits fit_study_laws(const FemCase &fem_case, const StudyFitScene &settings)
  {
    const auto start = std::chrono::steady_clock::now();
    StudyFits  fits;
    for (const FitVariant &variant : fit_variants(settings))
    {
      const auto law =
        std::find_if(fits.laws.begin(),
                     fits.laws.end(),
                     [&](const StudyLawFit &l) { return l.law->fit_variant() == variant.name; });
      if (law == fits.laws.end())
        continue;
      std::optional<FitResult> &fit    = law->fit;
      std::string              &status = law->status;
      try
      {
        // The same path as `kimp fit` (fit_fem_case), so both give the same k.
        fit    = fit_fem_case(fem_case, variant, settings);
        status = fem_fit_verdict(fem_case, *fit, settings.peak_tolerance);
        if (status.rfind("failed", 0) == 0)
          fit.reset();
        if (status != "ok")
          logger().warn("{} {}: fit {}", fem_case.name, variant.name, status);
      }
      catch (const std::exception &error)
      {
        status = "failed: " + base::error_text(error);
        logger().warn("{} {}: fit {}", fem_case.name, variant.name, status);
      }
    }
    fits.seconds = seconds_since(start);
    return fits;
  }

  std::string study_fem_cache_key(const FemScene &scene, double wall_height)
  {
    return fmt::format("{:016x}",
                       base::stable_hash(base::version_line() + "\n" +
                                         to_json_text(single_height_scene(scene, wall_height), 0)));
  }

  FemScene fem_level_scene(const FemScene &base, double h_contact, double penalty_factor)
  {
    FemScene scene              = base;
    scene.geometry.h_contact    = h_contact;
    scene.mesh_level            = 0;
    scene.solver.penalty_factor = penalty_factor;
    return scene;
  }

  FemCost estimate_study_fem(const StudyScene &scene)
  {
    FemCost              cost;
    const StudyFemScene &fem = scene.fem;
    const auto add = [&cost](const FemScene &level, double height, const std::string &what)
    {
      const std::string name = fem_case_name(height) + what;
      cost.add(name, estimate_fem_case(resolve_fem_case(level, height, name, {})));
    };
    const auto level_name = [](double h_contact, double penalty)
    { return fmt::format("_h{:g}cm_p{:g}", h_contact * 100.0, penalty); };
    const bool ladder = fem.fidelity == Fidelity::auto_ladder && !fem.fidelity_h_contact.empty() &&
                        !fem.fidelity_penalty_factors.empty();
    const double penalty =
      ladder ? fem.fidelity_penalty_factors.front() : fem.solver.penalty_factor;
    const std::size_t n_velocities = study_internal::study_velocities(scene).size();
    for (const double height : fem.wall_heights)
    {
      FemScene finest = fem;
      if (ladder)
      {
        for (const double h : fem.fidelity_h_contact)
          add(fem_level_scene(fem, h, penalty), height, level_name(h, penalty));
        const double h_finest = fem.fidelity_h_contact.back();
        for (std::size_t j = 1; j < fem.fidelity_penalty_factors.size(); ++j)
          add(fem_level_scene(fem, h_finest, fem.fidelity_penalty_factors[j]),
              height,
              level_name(h_finest, fem.fidelity_penalty_factors[j]));
        finest = fem_level_scene(fem, h_finest, penalty);
      }
      else
        add(fem, height, "");
      for (std::size_t v = 1; v < n_velocities; ++v)
        add(finest, height, fmt::format("_v{}", v));
    }
    if (scene.accuracy_study)
    {
      const StudyAccuracyScene &a = scene.accuracy;
      for (const double h : a.h_contact)
        for (const double p : a.penalty_factors)
          add(fem_level_scene(fem, h, p), a.wall_height, "_accuracy" + level_name(h, p));
      if (a.implicit)
        for (const double h : a.h_contact)
        {
          FemScene implicit          = fem_level_scene(fem, h, a.penalty_factors.front());
          implicit.solver.integrator = fem::ImpactParameters::Integrator::implicit_newmark;
          add(implicit, a.wall_height, "_implicit" + level_name(h, a.penalty_factors.front()));
        }
    }
    if (scene.sensitivity) // four parameters, each one step down and one up
      for (int i = 0; i < 8; ++i)
        add(fem, scene.sensitivity_study.wall_height, fmt::format("_sensitivity{}", i));
    return cost;
  }

  FemCaseSpec study_fem_case_spec(const FemScene    &scene,
                                  double             wall_height,
                                  const OutputDir   &output,
                                  const std::string &case_name)
  {
    const std::string name = case_name.empty() ? fem_case_name(wall_height) : case_name;
    try
    {
      return resolve_fem_case(scene, wall_height, name, output.path() / "mesh" / (name + ".msh"));
    }
    catch (const std::exception &error)
    {
      throw std::runtime_error(fmt::format("{}: {}", name, error_message(error)));
    }
  }

  StudyFemCase study_fem_case(const FemScene    &scene,
                              double             wall_height,
                              const OutputDir   &output,
                              const std::string &case_name)
  {
    return study_fem_case(study_fem_case_spec(scene, wall_height, output, case_name), output);
  }

  StudyFemCase study_fem_case(const FemCaseSpec &spec, const OutputDir &output)
  {
    const auto         start = std::chrono::steady_clock::now();
    const std::string &name  = spec.name;
    StudyFemCase       result;
    result.cache_key                       = study_fem_cache_key(spec.scene, spec.wall_height);
    const std::filesystem::path cache_file = output.file("fem/" + name + ".h5");
    const std::filesystem::path key_file   = output.file("fem/" + name + ".key");

    if (std::filesystem::is_regular_file(cache_file) && read_key(key_file) == result.cache_key)
    {
      std::vector<FemCase> cases;
      try
      {
        cases = read_fem_cases(cache_file);
      }
      catch (const std::exception &error)
      {
        // A damaged cache (a truncated copy, a full disk before kimp wrote atomically) is
        // computed again, not a permanent failure of the study.
        logger().warn("{}: FEM cache {} is unreadable ({}); computing it again",
                      name,
                      cache_file.string(),
                      error_text(error));
      }
      if (cases.size() == 1 && cases.front().name == name && cases.front().status == "ok")
      {
        result.fem_case     = std::move(cases.front());
        result.from_cache   = true;
        result.wall_seconds = seconds_since(start);
        logger().info("{}: FEM result reused from {} (cache key {})",
                      name,
                      cache_file.string(),
                      result.cache_key);
        return result;
      }
    }
    std::filesystem::remove(key_file);

    const std::filesystem::path &mesh     = spec.mesh_file;
    const FemEstimate            estimate = estimate_fem_case(spec);
    logger().debug("{}: estimate {}", name, estimate.text());
    check_fem_budget(name, estimate, spec.scene.max_steps);
    fem::ImpactResult impact;
    try
    {
      std::filesystem::create_directories(mesh.parent_path());
      std::ostringstream statistics;
      statistics << write_scene_mesh(spec.geometry, mesh);
      logger().info("{}: mesh {} ({})", name, mesh.string(), statistics.str());
      std::ostringstream log;
      impact = fem::run_impact(spec.parameters, MPI_COMM_SELF, &log);
      std::istringstream lines(log.str());
      for (std::string line; std::getline(lines, line);)
        logger().debug("{}: {}", name, line);
    }
    catch (const std::exception &error)
    {
      throw std::runtime_error(fmt::format("{}: {}", name, error_message(error)));
    }
    result.fem_case = to_fem_case(spec, impact);

    const std::string resolved = to_json_text(spec.scene);
    ResultsFile       file(cache_file, resolved, resolved);
    ResultsGroup      fem_root = file.root().group("fem");
    write_fem_case(fem_root, result.fem_case);
    file.commit();
    write_text_atomic(key_file, result.cache_key + "\n");
    // The cache outlives a failed study: a rerun reuses it.
    keep_on_failure(cache_file);
    keep_on_failure(key_file);
    result.wall_seconds = seconds_since(start);
    logger().info("{}: FEM {} DoFs, {} steps of {:.3g} s, peak force {:.4g} kN/m, contact "
                  "{:.4g} ms, COR {:.3f}, {:.2f} s",
                  name,
                  impact.summary.n_dofs,
                  impact.summary.n_steps,
                  impact.summary.dt,
                  impact.summary.peak_force / 1e3,
                  impact.summary.contact_duration * 1e3,
                  impact.summary.apparent_cor,
                  result.wall_seconds);
    return result;
  }
} // namespace kimp::app
