// The k(H, v) axis of `kimp study`: per wall height the FEM cases at the other impact velocities
// (at the reference velocity's FEM level and material model), the material-model choice of
// fidelity: auto (linear or inelastic) and the linear k beside an inelastic one.
#include "app/study/study_velocity.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "app/study/study_fem.h"
#include "app/study/study_internal.h"
#include "base/format.h"
#include "base/logging.h"

namespace kimp::app::study_internal
{
  namespace
  {
    bool same_speed(double a, double b)
    {
      return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b));
    }

    /// relative error of the reference case's k times `k` (NaN if either is unknown).
    double scaled_error(double                          error,
                        const std::optional<FitResult> &reference,
                        const std::optional<FitResult> &fit)
    {
      if (!reference || !fit || !(reference->stiffness.value > 0.0))
        return nan;
      return error / reference->stiffness.value * fit->stiffness.value;
    }

    /// One velocity case of `reference` at `velocity`.
    StudyHeight run_velocity_case(const StudyScene  &scene,
                                  const StudyHeight &reference,
                                  double             velocity,
                                  const OutputDir   &output)
    {
      StudyHeight c;
      c.wall_height               = reference.wall_height;
      c.name                      = velocity_case_name(reference.wall_height, velocity);
      c.impact_velocity           = velocity;
      c.reference_velocity        = false;
      c.inelastic                 = reference.inelastic;
      c.material_reason           = reference.material_reason;
      c.auto_fidelity             = reference.auto_fidelity;
      c.ladder                    = reference.ladder;
      c.fidelity_reason           = fmt::format("FEM level and material model of {} (the reference "
                                                "velocity {} m/s)",
                                      reference.name,
                                      reference.impact_velocity);
      FemScene fem                = material_fem_scene(scene.fem, reference.inelastic);
      fem.solver.initial_velocity = velocity;
      if (reference.auto_fidelity)
        fem = fem_level_scene(fem,
                              reference.ladder.used_level().h_contact,
                              reference.ladder.used_level().penalty_factor);
      try
      {
        StudyFemCase result =
          study_fem_case(fem,
                         c.wall_height,
                         output,
                         c.name + material_suffix(scene.fem, reference.inelastic));
        c.fem_case       = std::move(result.fem_case);
        c.fem_case.name  = c.name;
        c.fem_from_cache = result.from_cache;
        c.fem_seconds    = result.wall_seconds;
      }
      catch (const std::exception &error)
      {
        // A velocity case that fails is a row with its status; the reference k stays usable.
        for (StudyLawFit &law : c.laws)
          law.status = std::string("failed: FEM: ") + error.what();
        logger().warn("{}: failed: FEM: {}", c.name, error.what());
        return c;
      }
      StudyFits fits = fit_study_laws(c.fem_case, scene.fit);
      c.fit_seconds  = fits.seconds;
      set_fits(c, std::move(fits));
      // The ladder ran at the reference velocity only: its relative error is carried over.
      for (const auto &[errors, of_reference] :
           {std::pair{&c.ladder.error, &reference.ladder.error},
            std::pair{&c.ladder.mesh_error, &reference.ladder.mesh_error},
            std::pair{&c.ladder.penalty_error, &reference.ladder.penalty_error}})
      {
        errors->assign(c.laws.size(), nan);
        for (std::size_t i = 0; i < c.laws.size() && i < of_reference->size(); ++i)
          (*errors)[i] = scaled_error((*of_reference)[i], reference.laws[i].fit, c.laws[i].fit);
      }
      if (c.inelastic)
        add_linear_counterpart(fem, scene.fit, c.wall_height, output, c.name + "_linear", c);
      std::vector<double> k;
      for (const StudyLawFit &law : c.laws)
        k.push_back(law.fit ? law.fit->stiffness.value : nan);
      logger().info("{}: {} at {} m/s", c.name, k_text(k, "k_"), velocity);
      return c;
    }
  } // namespace

  std::vector<double> study_velocities(const StudyScene &scene)
  {
    std::vector<double> v = scene.fem.velocities;
    if (std::none_of(v.begin(),
                     v.end(),
                     [&](double x) { return same_speed(x, scene.fem.solver.initial_velocity); }))
      v.push_back(scene.fem.solver.initial_velocity);
    std::sort(v.begin(), v.end());
    return v;
  }

  std::string velocity_case_name(double wall_height, double velocity)
  {
    return fmt::format("{}_v{:g}", fem_case_name(wall_height), velocity);
  }

  FemScene linear_fem_scene(const FemScene &scene)
  {
    FemScene linear = scene;
    if (scene.materials.concrete.model != FemConcrete::Model::elastic)
    {
      // The damage law's initial stiffness: E_ci from f_cm (fib MC2010), as the inelastic run.
      linear.materials.concrete.youngs_modulus =
        concrete_parameters(scene.materials.concrete).youngs_modulus;
      linear.materials.concrete.model = FemConcrete::Model::elastic;
      // The linear reference is the plain concrete's: bars, b_c, the crack frame and the crush
      // band act in the damage law only.
      linear.materials.concrete.wall_reinforcement = fem::ReinforcementParameters{};
      linear.materials.concrete.slab_reinforcement = fem::ReinforcementParameters{};
      linear.materials.concrete.plastic_fraction   = 0;
      linear.materials.concrete.compression_band   = FemConcrete{}.compression_band;
      linear.materials.concrete.crack_frame        = FemConcrete{}.crack_frame;
    }
    // An elastic soil keeps its preset's E, nu and rho (soil_parameters()).
    linear.materials.soil.model = FemSoil::Model::elastic;
    return linear;
  }

  FemScene material_fem_scene(const FemScene &scene, bool inelastic)
  {
    return inelastic ? scene : linear_fem_scene(scene);
  }

  std::string material_suffix(const FemScene &scene, bool inelastic)
  {
    return !inelastic && has_inelastic_materials(scene) ? "_linear" : "";
  }

  void choose_material_model(const StudyScene         &scene,
                             double                    wall_height,
                             const OutputDir          &output,
                             StudyHeight              &h,
                             std::optional<StudyFits> *inelastic_cheap_fits)
  {
    if (!has_inelastic_materials(scene.fem))
    {
      h.inelastic       = false;
      h.material_reason = "linear elastic materials (the scene's)";
      return;
    }
    h.inelastic = true;
    if (scene.fem.fidelity == Fidelity::fixed)
    {
      h.material_reason = "fidelity fixed: the scene's inelastic materials as given";
      return;
    }
    const FidelityLevel cheap{scene.fem.fidelity_h_contact.front(),
                              scene.fem.fidelity_penalty_factors.front()};
    StudyFits           fits[2];
    for (const bool inelastic : {false, true})
    {
      StudyFemCase fem =
        study_fem_case(fem_level_scene(material_fem_scene(scene.fem, inelastic),
                                       cheap.h_contact,
                                       cheap.penalty_factor),
                       wall_height,
                       output,
                       h.name + material_suffix(scene.fem, inelastic) + "_" + cheap.label());
      h.fem_seconds += fem.wall_seconds;
      fits[inelastic] = fit_study_laws(fem.fem_case, scene.fit);
      h.fit_seconds += fits[inelastic].seconds;
    }
    if (inelastic_cheap_fits != nullptr)
      *inelastic_cheap_fits = fits[1];
    if (!fits[0].ok() || !fits[1].ok())
    {
      h.material_reason = fmt::format("at {} a fit failed (linear: {}; inelastic: {}): "
                                      "the ladder climbs with the inelastic materials",
                                      cheap.label(),
                                      joined_status(fits[0].laws),
                                      joined_status(fits[1].laws));
      return;
    }
    // The change of each law's k, "4.1 % (KV) and 2.3 % (Jankowski)".
    bool        within = true;
    std::string changes;
    for (std::size_t i = 0; i < fits[0].laws.size(); ++i)
    {
      const StudyLaw &law = *fits[0].laws[i].law;
      const double    change =
        relative_change(fits[0].laws[i].fit->stiffness.value, fits[1].laws[i].fit->stiffness.value);
      within = within && change <= scene.fem.fidelity_tolerance;
      changes += fmt::format("{}{:.3g} % ({})",
                             changes.empty() ? "" : " and ",
                             100.0 * change,
                             law.short_name);
    }
    h.inelastic = !within;
    h.material_reason =
      fmt::format("at {} the linear k differs from the inelastic one by {}, {} the tolerance "
                  "{:.3g} %: {}",
                  cheap.label(),
                  changes,
                  h.inelastic ? "above" : "within",
                  100.0 * scene.fem.fidelity_tolerance,
                  h.inelastic ? "the ladder climbs with the inelastic materials" :
                                "linear materials kept (inelasticity does not change k here)");
    logger().info("{}: material model: {}", h.name, h.material_reason);
  }

  void add_linear_counterpart(const FemScene      &level_scene,
                              const StudyFitScene &fit,
                              double               wall_height,
                              const OutputDir     &output,
                              const std::string   &case_name,
                              StudyHeight         &h)
  {
    try
    {
      StudyFemCase fem =
        study_fem_case(linear_fem_scene(level_scene), wall_height, output, case_name);
      h.fem_seconds += fem.wall_seconds;
      StudyFits fits = fit_study_laws(fem.fem_case, fit);
      h.fit_seconds += fits.seconds;
      for (std::size_t i = 0; i < h.laws.size(); ++i)
        h.laws[i].linear = std::move(fits.laws[i].fit);
    }
    catch (const std::exception &error)
    {
      logger().warn("{}: linear counterpart failed: {}", case_name, error.what());
    }
  }

  std::vector<StudyHeight>
  run_velocity_cases(const StudyScene &scene, const StudyHeight &reference, const OutputDir &output)
  {
    std::vector<StudyHeight> cases;
    for (const double v : study_velocities(scene))
      if (!same_speed(v, scene.fem.solver.initial_velocity))
        cases.push_back(run_velocity_case(scene, reference, v, output));
    return cases;
  }

  void compute_velocity_cases_on_ranks(const StudyScene &scene,
                                       const OutputDir  &output,
                                       int               rank,
                                       int               n_ranks)
  {
    std::vector<std::pair<double, double>> jobs;
    for (const double height : scene.fem.wall_heights)
      for (const double v : study_velocities(scene))
        if (!same_speed(v, scene.fem.solver.initial_velocity))
          jobs.emplace_back(height, v);
    for (std::size_t i = static_cast<std::size_t>(rank); i < jobs.size();
         i += static_cast<std::size_t>(n_ranks))
    {
      try
      {
        // The reference height is in the FEM cache: this only re-reads and re-fits it.
        const StudyHeight reference = run_height(scene, jobs[i].first, output);
        run_velocity_case(scene, reference, jobs[i].second, output);
      }
      catch (const std::exception &error)
      {
        logger().warn("{}: {}", velocity_case_name(jobs[i].first, jobs[i].second), error.what());
      }
    }
  }

  std::vector<const StudyHeight *> k_table_cases(const StudyResult &result)
  {
    std::vector<const StudyHeight *> cases;
    for (const StudyHeight &h : result.heights)
      cases.push_back(&h);
    for (const StudyHeight &h : result.velocity_cases)
      cases.push_back(&h);
    std::stable_sort(cases.begin(),
                     cases.end(),
                     [](const StudyHeight *a, const StudyHeight *b)
                     {
                       return a->wall_height < b->wall_height ||
                              (a->wall_height == b->wall_height &&
                               a->impact_velocity < b->impact_velocity);
                     });
    return cases;
  }

  KTable study_k_table(const StudyScene &scene, const StudyResult &result)
  {
    KTable table;
    table.file = "the study's k table";
    for (const StudyHeight *h : k_table_cases(result))
      if (const auto &kv = h->law("kelvin_voigt").fit, &j = h->law("jankowski").fit; kv && j)
        table.rows.push_back({h->wall_height,
                              kv->stiffness.value * scene.fit.width,
                              j->stiffness.value * scene.fit.width,
                              h->impact_velocity,
                              h->reference_velocity});
    return table;
  }

  void log_velocity_table(const StudyResult &result)
  {
    if (result.velocity_cases.empty() &&
        std::none_of(result.heights.begin(),
                     result.heights.end(),
                     [](const StudyHeight &h) { return h.inelastic; }))
      return;
    logger().info("k(H, v) per metre of wall (linear k beside an inelastic one):");
    logger().info("  H [m] | v [m/s] | model | KV kN/mm/m | linear KV | Jankowski kN/mm^1.5/m | "
                  "linear J");
    // A k that was not computed (no linear run beside a linear FEM case) is "-", not "nan".
    const auto k = [](double value)
    { return std::isfinite(value) ? base::sig(value) : std::string("-"); };
    for (const StudyHeight *h : k_table_cases(result))
      logger().info("  {:5.2f} | {:>7} | {:9} | {:>10} | {:>9} | {:>21} | {}",
                    h->wall_height,
                    base::sig(h->impact_velocity, 3),
                    h->inelastic ? "inelastic" : "linear",
                    k(per_metre(h->law("kelvin_voigt").fit)),
                    k(per_metre(h->law("kelvin_voigt").linear)),
                    k(per_metre(h->law("jankowski").fit)),
                    k(per_metre(h->law("jankowski").linear)));
  }
} // namespace kimp::app::study_internal
