// Accuracy against cost, stability map (Δt_cr = 2/ω_imp, thesis eq. 3.12-3.13) and sensitivity
// studies of `kimp study`; each run is one FEM case (study cache), building run or collision.
#include "app/study/study_extras.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <limits>

#include "app/fem/mesh_run.h"
#include "app/lumped/lumped_run.h"
#include "app/study/study_fem.h"
#include "app/study/study_ladder.h"
#include "base/errors.h"
#include "base/logging.h"
#include "fem/impact.h"
#include "geometry/scene_mesh.h"
#include "lumped/collision/two_body.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/kelvin_voigt_law.h"

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::fit;
  namespace
  {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    /// One FEM case through the study cache, fitted; failures become the point's status.
    template <class Point>
    void run_fem_point(Point             &point,
                       const FemScene    &fem,
                       double             wall_height,
                       const std::string &name,
                       const StudyScene  &scene,
                       const OutputDir   &output,
                       double            *seconds,
                       double            *n_dofs,
                       double            *n_steps,
                       bool              *from_cache)
    {
      try
      {
        const StudyFemCase c    = study_fem_case(fem, wall_height, output, name);
        const StudyFits    fits = fit_study_laws(c.fem_case, scene.fit);
        if (seconds)
          *seconds = c.fem_case.summary.wall_time.value_or(nan);
        if (n_dofs)
          *n_dofs =
            c.fem_case.summary.n_dofs ? static_cast<double>(*c.fem_case.summary.n_dofs) : nan;
        if (n_steps)
          *n_steps =
            c.fem_case.summary.n_steps ? static_cast<double>(*c.fem_case.summary.n_steps) : nan;
        if (from_cache)
          *from_cache = c.from_cache;
        point.ok     = fits.ok();
        point.status = point.ok ? "ok" : joined_status(fits.laws);
        if (point.ok)
        {
          for (const StudyLawFit &law : fits.laws)
            point.k.push_back(law.fit->stiffness.value);
        }
      }
      catch (const std::exception &error)
      {
        point.ok     = false;
        point.status = "failed: " + base::error_text(error);
        logger().warn("{}: {}", name, point.status);
      }
    }

  } // namespace

  std::vector<FemAccuracyPoint> run_fem_accuracy(const StudyScene &scene, const OutputDir &output)
  {
    const StudyAccuracyScene     &a = scene.accuracy;
    const double                  H = a.wall_height;
    std::vector<FemAccuracyPoint> points;
    const auto                    add = [&](const std::string                &series,
                         double                            h,
                         double                            penalty,
                         fem::ImpactParameters::Integrator integrator)
    {
      FemAccuracyPoint p;
      p.series              = series;
      p.h_contact           = h;
      p.penalty_factor      = penalty;
      FemScene fem          = fem_level_scene(scene.fem, h, penalty);
      fem.solver.integrator = integrator;
      const bool implicit   = integrator == fem::ImpactParameters::Integrator::implicit_newmark;
      const std::string name =
        fem_case_name(H) + "_" + FidelityLevel{h, penalty}.label() + (implicit ? "_implicit" : "");
      run_fem_point(p,
                    fem,
                    H,
                    name,
                    scene,
                    output,
                    &p.seconds,
                    &p.n_dofs,
                    &p.n_steps,
                    &p.from_cache);
      logger().info("accuracy {} {}: {}, {:.3g} s ({})",
                    series,
                    name,
                    k_text(p.k, "k_"),
                    p.seconds,
                    p.status);
      points.push_back(p);
    };
    const auto explicit_cd = fem::ImpactParameters::Integrator::explicit_central_difference;
    for (const double h : a.h_contact)
      add("mesh", h, a.penalty_factors.front(), explicit_cd);
    // Penalty levels on the finest mesh below the reference (the reference's own level if only
    // one).
    const double h_penalty =
      a.h_contact.size() > 1 ? a.h_contact[a.h_contact.size() - 2] : a.h_contact.front();
    for (std::size_t j = 0; j < a.penalty_factors.size(); ++j)
      add("penalty", h_penalty, a.penalty_factors[j], explicit_cd);
    // Implicit Newmark on every mesh level but the reference (its finest level costs minutes).
    if (a.implicit)
      for (const double h :
           std::vector<double>(a.h_contact.begin(), a.h_contact.end() - (a.h_contact.size() > 1)))
        add("implicit",
            h,
            a.penalty_factors.front(),
            fem::ImpactParameters::Integrator::implicit_newmark);

    // Reference: the finest explicit mesh level.
    const FemAccuracyPoint &reference = points.at(a.h_contact.size() - 1);
    for (FemAccuracyPoint &p : points)
    {
      const bool usable = p.ok && reference.ok;
      p.error.assign(study_laws().size(), nan);
      for (std::size_t i = 0; usable && i < p.error.size(); ++i)
        p.error[i] = std::abs(p.k.at(i) / reference.k.at(i) - 1.0);
    }
    return points;
  }

  std::vector<LumpedAccuracyPoint> run_lumped_accuracy(const StudyScene        &scene,
                                                       const GroundMotionScene &record,
                                                       double                   k_total,
                                                       double                   gap)
  {
    const lumped::GroundMotion motion = load_ground_motion(record);
    LumpedScene                base   = study_lumped_scene(scene, record);
    base.walls.left.present = base.walls.right.present = true;
    base.walls.left.gap = base.walls.right.gap = gap;
    base.impact.law                            = "modified_kelvin_voigt";
    base.impact.k.clear();
    base.impact.k_si                 = k_total;
    base.impact.cor                  = scene.fit.cor;
    base.integration.output_interval = 0.0;

    const auto run = [&](IntegrationMethod method, double dt)
    {
      LumpedAccuracyPoint p;
      p.method             = method == IntegrationMethod::cdm ? "cdm" : "newmark";
      p.dt                 = dt;
      LumpedScene s        = base;
      s.integration.method = method;
      s.integration.dt     = fmt::format("{:.12g} s", dt);
      const LumpedCaseResult r =
        run_lumped_case(fmt::format("{}_dt{:g}", p.method, dt), s, motion, record.scale);
      p.ok      = r.ok();
      p.status  = r.status;
      p.seconds = r.wall_time;
      if (p.ok)
      {
        for (const lumped::ContactResult &c : r.response.contacts)
          p.peak_impact_force = std::max(p.peak_impact_force, c.peak_force);
        p.base_acceleration = r.response.peak_absolute_acceleration.at(0);
      }
      return p;
    };
    const LumpedAccuracyPoint reference =
      run(IntegrationMethod::cdm, scene.accuracy.lumped_reference_dt);
    if (!reference.ok)
      throw std::runtime_error("lumped accuracy: the reference run failed: " + reference.status);
    std::vector<LumpedAccuracyPoint> points;
    for (const IntegrationMethod method : {IntegrationMethod::cdm, IntegrationMethod::newmark})
      for (const double dt : scene.accuracy.lumped_dt)
      {
        LumpedAccuracyPoint p = run(method, dt);
        p.error_force =
          p.ok ? std::abs(p.peak_impact_force / reference.peak_impact_force - 1.0) : nan;
        p.error_acceleration =
          p.ok ? std::abs(p.base_acceleration / reference.base_acceleration - 1.0) : nan;
        points.push_back(p);
      }
    LumpedAccuracyPoint ref = reference;
    ref.method              = "cdm_reference";
    points.push_back(ref);
    return points;
  }

  std::vector<StabilityPoint>
  lumped_stability_map(double mass_1, double mass_2, double cor, double k_study)
  {
    std::vector<StabilityPoint> points;
    lumped::TwoBodySetup        setup;
    setup.mass_1         = mass_1;
    setup.mass_2         = mass_2;
    setup.velocity_1     = 1.0;
    setup.record_history = false;
    setup.max_steps      = 200000;
    const double m_eff   = setup.effective_mass();
    const double xi      = lumped::kelvin_voigt_damping_ratio(cor);
    for (const double k_factor : {0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0})
      for (int i = 0; i <= 28; ++i)
      {
        StabilityPoint p;
        p.stiffness        = k_factor * k_study;
        p.dt               = 1e-4 * std::pow(10.0, i * 3.5 / 14.0); // 1e-4 ... 0.316 s
        const double omega = std::sqrt(p.stiffness / m_eff);
        p.dt_limit         = 2.0 / omega;
        p.dt_limit_damped  = 2.0 * (std::sqrt(1.0 + xi * xi) - xi) / omega;
        lumped::ForceLawSpec spec;
        spec.law            = "modified_kelvin_voigt";
        spec.stiffness      = p.stiffness;
        spec.cor            = cor;
        spec.effective_mass = m_eff;
        setup.time_step     = p.dt;
        try
        {
          const lumped::TwoBodyResult r =
            lumped::simulate_two_body(*lumped::make_force_law(spec), setup);
          p.effective_cor = r.effective_cor;
          p.peak_force    = r.peak_force;
          // Unstable: energy gained (the dashpot can only dissipate). A gain below 0.1 % is the
          // discrete contact of 2-3 steps near ω·Δt ≈ 1 returning COR ≈ 1: inaccurate, bounded.
          p.stable   = std::isfinite(r.effective_cor) && r.effective_cor <= 1.0 + 1e-3;
          p.accurate = p.stable && std::abs(r.effective_cor / cor - 1.0) <= 0.05;
        }
        catch (const lumped::CollisionError &)
        {
          p.effective_cor = nan;
          p.peak_force    = nan;
          p.stable        = false;
        }
        points.push_back(p);
      }
    return points;
  }

  std::vector<FemStabilityPoint>
  fem_stability_map(const StudyScene &scene, const OutputDir &output, double &h_contact)
  {
    const double H = scene.accuracy.wall_height;
    h_contact = *std::max_element(scene.accuracy.h_contact.begin(), scene.accuracy.h_contact.end());
    const std::string           name = fem_case_name(H) + "_stability";
    const std::filesystem::path mesh = output.file("mesh/" + name + ".msh");
    std::filesystem::create_directories(mesh.parent_path());
    write_scene_mesh(
      resolve_fem_case(fem_level_scene(scene.fem, h_contact, 1.0), H, name, mesh).geometry,
      mesh);
    std::vector<FemStabilityPoint> points;
    for (const double penalty_factor : fem_stability_penalty_factors)
    {
      fem::ImpactParameters p =
        resolve_fem_case(fem_level_scene(scene.fem, h_contact, penalty_factor), H, name, mesh)
          .parameters;
      p.integrator    = fem::ImpactParameters::Integrator::explicit_central_difference;
      p.end_time      = fem_stability_end_time;
      p.log_interval  = 0;
      p.vtu_interval  = 0;
      p.dt            = 0;
      double dt_limit = nan; // from the first (stable) run of this penalty
      for (const double dt_factor : fem_stability_dt_factors)
      {
        FemStabilityPoint point;
        point.penalty_factor             = penalty_factor;
        point.dt_factor                  = dt_factor;
        p.explicit_options.dt_over_limit = dt_factor;
        try
        {
          const fem::ImpactResult r = fem::run_impact(p, MPI_COMM_SELF, nullptr);
          dt_limit                  = r.summary.dt_stable;
          point.energy_error        = r.summary.energy_error;
          point.stable              = point.energy_error < fem_stability_energy_tolerance;
          if (!point.stable)
            point.status = fmt::format("energy error {:.3g} > {:g}",
                                       point.energy_error,
                                       fem_stability_energy_tolerance);
        }
        catch (const fem::NumericalError &error)
        {
          point.stable = false;
          point.status = std::string("diverged: ") + error.what();
        }
        point.dt_limit = dt_limit;
        point.dt       = dt_factor * dt_limit;
        logger().debug("FEM stability: penalty x{}, dt = {} x limit: {}",
                       penalty_factor,
                       dt_factor,
                       point.stable ? "stable" : point.status);
        points.push_back(point);
      }
    }
    return points;
  }

  std::vector<SensitivityPoint> run_sensitivity(const StudyScene &scene, const OutputDir &output)
  {
    const double                  H    = scene.sensitivity_study.wall_height;
    const double                  v    = scene.sensitivity_study.variation;
    const FemScene               &base = scene.fem;
    const FidelityLevel           level{base.geometry.h_contact / std::pow(2.0, base.mesh_level),
                              base.solver.penalty_factor};
    std::vector<SensitivityPoint> points;
    const auto run = [&](const std::string &parameter, double factor, const FemScene &fem)
    {
      SensitivityPoint p;
      p.parameter = parameter;
      p.factor    = factor;
      const std::string name =
        fem_case_name(H) + "_" + level.label() +
        (parameter == "base" ? "" : fmt::format("_{}_x{:g}", parameter, factor));
      run_fem_point(p,
                    fem_level_scene(fem, level.h_contact, level.penalty_factor),
                    H,
                    name,
                    scene,
                    output,
                    nullptr,
                    nullptr,
                    nullptr,
                    nullptr);
      points.push_back(p);
    };
    run("base", 1.0, base);
    for (const double factor : {1.0 - v, 1.0 + v})
    {
      FemScene s       = base;
      s.materials.soil = without_preset(s.materials.soil); // a preset's E is scaled too
      s.materials.soil.youngs_modulus *= factor;
      run("soil_modulus", factor, s);
      s = base;
      s.geometry.slab_length *= factor;
      if (s.rigid_slab_mass)
        *s.rigid_slab_mass *= factor;
      run("slab_mass", factor, s);
      s = base;
      s.solver.initial_velocity *= factor;
      run("impact_velocity", factor, s);
      s = base;
      s.geometry.wall_thickness *= factor;
      run("wall_thickness", factor, s);
    }
    return points;
  }
} // namespace kimp::app
