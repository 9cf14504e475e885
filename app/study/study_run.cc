// `kimp study`: FEM per wall height -> k fitted with laws 2 and 4 at COR 0.7 (docs/physics.md §4)
// -> k_total = k_per_m·W -> isolated building pounding on moat walls (docs/physics.md §2-3).
#include "app/study/study_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>
#include <map>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <tuple>
#include <unistd.h>

#include "app/helper_programs.h"
#include "app/lumped_run.h"
#include "app/study/study_fem.h"
#include "base/logging.h"
#include "base/version.h"
#include "io/results_file.h"
#include "lumped/collision/two_body.h"
#include "lumped/integrators/response.h"

extern char **environ;

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  using namespace kimp::fit;
  namespace
  {
    using Clock = std::chrono::steady_clock;

    double seconds_since(Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }

    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    std::optional<ThesisStiffness> thesis_row(double wall_height)
    {
      for (const ThesisStiffness &row : thesis_table_2_1())
        if (std::abs(row.wall_height - wall_height) < 1e-9)
          return row;
      return std::nullopt;
    }

    /// k of a fit in kN/mm^n per metre (or NaN), and its confidence interval.
    double per_metre(const std::optional<FitResult> &fit)
    {
      return fit ? fit->stiffness_per_metre_display() : nan;
    }
    double per_metre_bound(const std::optional<FitResult> &fit, bool upper)
    {
      return fit ? stiffness_to_kn_per_mm(upper ? fit->stiffness.upper : fit->stiffness.lower,
                                          fit->exponent.value) :
                   nan;
    }

    /// Numerical error of k (fidelity ladder) in kN/mm^n per metre; NaN if not estimated.
    double numerical_error(const StudyHeight &h, double exponent)
    {
      return stiffness_to_kn_per_mm(exponent == 1.0 ? h.kelvin_voigt_numerical_error() :
                                                      h.jankowski_numerical_error(),
                                    exponent);
    }

    double used_h_contact(const StudyScene &scene, const StudyHeight &h)
    {
      return h.auto_fidelity ? h.ladder.used_level().h_contact :
                               scene.fem.mesh.h_contact / std::pow(2.0, scene.fem.mesh.level);
    }

    double used_penalty(const StudyScene &scene, const StudyHeight &h)
    {
      return h.auto_fidelity ? h.ladder.used_level().penalty_factor :
                               scene.fem.contact.penalty_factor;
    }

    std::vector<double> scale(std::vector<double> values, double factor)
    {
      for (double &v : values)
        v *= factor;
      return values;
    }

    std::string number(double value)
    {
      return std::isfinite(value) ? fmt::format("{:.6g}", value) : "";
    }

    // ---------------------------------------------------------------- stage 1: FEM and fits

    FemScene level_scene(const FemScene &base, const FidelityLevel &level)
    {
      FemScene scene               = base;
      scene.mesh.h_contact         = level.h_contact;
      scene.mesh.level             = 0;
      scene.contact.penalty_factor = level.penalty_factor;
      return scene;
    }

    StudyHeight run_height(const StudyScene &scene, double wall_height, const OutputDir &output)
    {
      StudyHeight h;
      h.wall_height = wall_height;
      h.name        = fem_case_name(wall_height);
      if (scene.fem.fidelity == Fidelity::fixed)
      {
        StudyFemCase fem      = study_fem_case(scene.fem, wall_height, output);
        h.fem_case            = std::move(fem.fem_case);
        h.fem_from_cache      = fem.from_cache;
        h.fem_seconds         = fem.wall_seconds;
        StudyFits fits        = fit_study_laws(h.fem_case, scene.fit);
        h.kelvin_voigt        = std::move(fits.kelvin_voigt);
        h.jankowski           = std::move(fits.jankowski);
        h.kelvin_voigt_status = fits.kelvin_voigt_status;
        h.jankowski_status    = fits.jankowski_status;
        h.fit_seconds         = fits.seconds;
        h.fidelity_reason     = "fidelity fixed: numerical error not estimated";
        return h;
      }

      // fidelity: auto. Every level keeps its FEM case and fits; the used one is reported.
      struct Computed
      {
        FemCase   fem_case;
        StudyFits fits;
        bool      from_cache = false;
      };
      std::vector<Computed> computed;
      h.fem_from_cache = true;
      const auto run   = [&](const FidelityLevel &level)
      {
        LevelOutcome outcome;
        Computed     c;
        try
        {
          StudyFemCase fem = study_fem_case(level_scene(scene.fem, level),
                                            wall_height,
                                            output,
                                            h.name + "_" + level.label());
          h.fem_seconds += fem.wall_seconds;
          h.fem_from_cache = h.fem_from_cache && fem.from_cache;
          c.fem_case       = std::move(fem.fem_case);
          c.from_cache     = fem.from_cache;
          c.fits           = fit_study_laws(c.fem_case, scene.fit);
          h.fit_seconds += c.fits.seconds;
          outcome.seconds    = fem.wall_seconds + c.fits.seconds;
          outcome.from_cache = fem.from_cache;
          outcome.ok         = c.fits.ok();
          outcome.status     = outcome.ok ?
                                 "ok" :
                                 "fit " + c.fits.kelvin_voigt_status + " / " + c.fits.jankowski_status;
          if (outcome.ok)
          {
            outcome.k_kelvin_voigt = c.fits.kelvin_voigt->stiffness.value;
            outcome.k_jankowski    = c.fits.jankowski->stiffness.value;
          }
        }
        catch (const std::exception &error)
        {
          outcome.status = std::string("failed: ") + error.what();
          logger().warn("{}: level {} {}", h.name, level.label(), outcome.status);
        }
        computed.push_back(std::move(c));
        logger().info("{}: level {}: k_KV {:.6g} kN/mm/m, k_Jankowski {:.6g} kN/mm^1.5/m ({})",
                      h.name,
                      level.label(),
                      stiffness_to_kn_per_mm(outcome.k_kelvin_voigt, 1.0),
                      stiffness_to_kn_per_mm(outcome.k_jankowski, 1.5),
                      outcome.status);
        return outcome;
      };
      h.ladder          = climb_fidelity_ladder(scene.fem.fidelity_h_contact,
                                       scene.fem.fidelity_penalty_factors,
                                       scene.fem.fidelity_tolerance,
                                       run);
      h.auto_fidelity   = true;
      h.fidelity_reason = h.ladder.reason;
      if (!h.ladder.has_usable_level())
        throw std::runtime_error(
          fmt::format("{}: no usable FEM level ({})", h.name, h.ladder.outcomes.front().status));
      Computed &used        = computed.at(h.ladder.used);
      h.fem_case            = std::move(used.fem_case);
      h.fem_case.name       = h.name;
      h.kelvin_voigt        = std::move(used.fits.kelvin_voigt);
      h.jankowski           = std::move(used.fits.jankowski);
      h.kelvin_voigt_status = used.fits.kelvin_voigt_status;
      h.jankowski_status    = used.fits.jankowski_status;
      logger().info("{}: fidelity auto: {} -> level {} ({}); numerical error of k: KV {:.3g} "
                    "kN/mm/m, Jankowski {:.3g} kN/mm^1.5/m",
                    h.name,
                    h.ladder.reason,
                    h.ladder.used_level().label(),
                    h.ladder.converged ? "converged" : "NOT converged",
                    stiffness_to_kn_per_mm(h.ladder.error_kelvin_voigt, 1.0),
                    stiffness_to_kn_per_mm(h.ladder.error_jankowski, 1.5));
      return h;
    }

    /**
     * Under `mpirun -np N`: rank r computes the FEM (and climbs the fidelity ladder) of heights
     * r, r + N, ... into the study's FEM cache; rank 0 then finds every height there. Errors are
     * left for rank 0's own pass to report (it recomputes what is missing).
     */
    void compute_heights_on_ranks(const StudyScene &scene,
                                  const OutputDir  &output,
                                  int               rank,
                                  int               n_ranks)
    {
      const Clock::time_point start   = Clock::now();
      const auto             &heights = scene.fem.wall_heights;
      for (std::size_t i = static_cast<std::size_t>(rank); i < heights.size();
           i += static_cast<std::size_t>(n_ranks))
      {
        try
        {
          run_height(scene, heights[i], output);
        }
        catch (const std::exception &error)
        {
          logger().warn("{}: {}", fem_case_name(heights[i]), error.what());
        }
      }
      logger().info("FEM of rank {}'s share of {} heights on {} ranks: {:.2f} s",
                    rank,
                    heights.size(),
                    n_ranks,
                    seconds_since(start));
    }

    void log_k_table(const StudyScene &scene, const std::vector<StudyHeight> &heights)
    {
      logger().info("k table (per metre of wall; total = x {} m), beside thesis Table 2.1:",
                    scene.fit.width);
      logger().info("  H [m] | KV kN/mm/m [95 % CI] ± numerical | Table 2.1 | KV total kN/mm | "
                    "Jankowski kN/mm^1.5/m [95 % CI] ± numerical | Table 2.1 | J total kN/mm^1.5");
      for (const StudyHeight &h : heights)
      {
        const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
        logger().info("  {:5.2f} | {:8.4g} [{:.4g}, {:.4g}] ± {:.2g} | {:>9} | {:14.5g} | {:8.4g} "
                      "[{:.4g}, {:.4g}] ± {:.2g} | {:>9} | {:.5g}",
                      h.wall_height,
                      per_metre(h.kelvin_voigt),
                      per_metre_bound(h.kelvin_voigt, false),
                      per_metre_bound(h.kelvin_voigt, true),
                      numerical_error(h, 1.0),
                      thesis ? number(thesis->kelvin_voigt) : "-",
                      per_metre(h.kelvin_voigt) * scene.fit.width,
                      per_metre(h.jankowski),
                      per_metre_bound(h.jankowski, false),
                      per_metre_bound(h.jankowski, true),
                      numerical_error(h, 1.5),
                      thesis ? number(thesis->jankowski) : "-",
                      per_metre(h.jankowski) * scene.fit.width);
      }
    }

    // ---------------------------------------------------------------- stage 2: building runs

    std::string k_text(double k_total_si, double exponent)
    {
      return fmt::format("{:.12g} {}",
                         stiffness_to_kn_per_mm(k_total_si, exponent),
                         stiffness_display_unit(exponent));
    }

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

    std::string record_label(const GroundMotionScene &record, std::set<std::string> &used)
    {
      std::string label = record.record;
      for (int i = 2; !used.insert(label).second; ++i)
        label = fmt::format("{}_{}", record.record, i);
      return label;
    }

    std::vector<StudyBuildingRun> run_building(const StudyScene               &scene,
                                               const std::vector<StudyHeight> &heights)
    {
      std::vector<StudyBuildingRun> runs;
      std::set<std::string>         labels;
      const unsigned int            top_dof = scene.building.n_storeys;
      for (const GroundMotionScene &record : study_records(scene))
      {
        const std::string label = record_label(record, labels);
        StudyBuildingRun  bare;
        bare.record = label;
        bare.law    = "none";
        lumped::GroundMotion motion;
        try
        {
          motion = load_ground_motion(record);
        }
        catch (const std::exception &error)
        {
          bare.status = std::string("failed: ") + error.what();
          logger().warn("record {}: {}", label, bare.status);
          runs.push_back(bare);
          continue;
        }
        const LumpedScene      base = study_lumped_scene(scene, record);
        const LumpedCaseResult none = run_lumped_case("no_walls", base, motion, record.scale);
        fill_peaks(bare, none, top_dof, nullptr);
        runs.push_back(bare);
        if (!none.ok())
        {
          logger().warn("record {}: run without walls {}", label, none.status);
          continue;
        }
        const double gap =
          scene.walls.gap.value_or((1.0 - scene.walls.gap_reduction) * bare.base_displacement);
        logger().info("record {} (PGA {:.3f} g): no walls: peak isolation displacement {:.4g} cm, "
                      "top acceleration {:.4g} m/s^2 -> wall gap {:.4g} cm",
                      label,
                      none.pga / lumped::standard_gravity,
                      bare.base_displacement * 100,
                      bare.top_acceleration,
                      gap * 100);

        for (const StudyHeight &h : heights)
        {
          const std::vector<std::pair<std::string, const std::optional<FitResult> *>> laws = {
            {"modified_kelvin_voigt", &h.kelvin_voigt},
            {"jankowski", &h.jankowski},
            {"hysteretic", &h.jankowski}};
          for (const auto &[law, fit] : laws)
          {
            StudyBuildingRun run;
            run.record      = label;
            run.wall_height = h.wall_height;
            run.law         = law;
            run.gap         = gap;
            if (!*fit)
            {
              run.status = "skipped: no fitted k for " + h.name;
              runs.push_back(run);
              continue;
            }
            run.exponent          = (*fit)->exponent.value;
            run.k_total           = (*fit)->stiffness.value * scene.fit.width;
            LumpedScene s         = base;
            s.walls.left.present  = true;
            s.walls.right.present = true;
            s.walls.left.gap      = gap;
            s.walls.right.gap     = gap;
            s.impact.law          = law;
            s.impact.k            = k_text(run.k_total, run.exponent);
            s.impact.exponent     = std::nullopt;
            s.impact.cor          = scene.fit.cor;
            const LumpedCaseResult done =
              run_lumped_case(h.name + "_" + law, s, motion, record.scale);
            fill_peaks(run, done, top_dof, &none.response);
            if (!done.ok())
              logger().warn("record {} {} {}: {}", label, h.name, law, done.status);
            runs.push_back(run);
          }
        }
      }
      return runs;
    }

    // ---------------------------------------------------------------- stage 3: extra studies

    /// The height of the k table nearest to `wall_height` with a Kelvin-Voigt fit (or null).
    const StudyHeight *nearest_height(const std::vector<StudyHeight> &heights, double wall_height)
    {
      const StudyHeight *best = nullptr;
      for (const StudyHeight &h : heights)
        if (h.kelvin_voigt && (!best || std::abs(h.wall_height - wall_height) <
                                          std::abs(best->wall_height - wall_height)))
          best = &h;
      return best;
    }

    StudyExtras
    run_extras(const StudyScene &scene, const StudyResult &result, const OutputDir &output)
    {
      StudyExtras        extras;
      const StudyHeight *h       = nearest_height(result.heights, scene.accuracy.wall_height);
      const double       k_total = h ? h->kelvin_voigt->stiffness.value * scene.fit.width : nan;
      if (scene.accuracy_study)
      {
        logger().info("accuracy study at H = {} m (FEM levels, then the building's time step)",
                      scene.accuracy.wall_height);
        extras.fem_accuracy                          = run_fem_accuracy(scene, output);
        const std::vector<GroundMotionScene> records = study_records(scene);
        const auto                           bare    = std::find_if(result.building.begin(),
                                       result.building.end(),
                                       [](const StudyBuildingRun &r)
                                       { return r.law == "none" && r.status == "ok"; });
        if (h && !records.empty() && bare != result.building.end())
        {
          extras.lumped_k_total = k_total;
          extras.lumped_gap =
            scene.walls.gap.value_or((1.0 - scene.walls.gap_reduction) * bare->base_displacement);
          extras.lumped_record = bare->record;
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

    // ---------------------------------------------------------------- stage 4: files

    std::vector<std::string> k_table_header()
    {
      return {"wall_height_m",
              "slab_mass_kg_per_m",
              "impact_velocity_m_per_s",
              "fem_peak_force_kN_per_m",
              "fem_contact_duration_ms",
              "kelvin_voigt_kN_per_mm_per_m",
              "kelvin_voigt_lower_kN_per_mm_per_m",
              "kelvin_voigt_upper_kN_per_mm_per_m",
              "kelvin_voigt_total_kN_per_mm",
              "kelvin_voigt_normalised_rms",
              "thesis_kelvin_voigt_kN_per_mm_per_m",
              "jankowski_kN_per_mm1.5_per_m",
              "jankowski_lower_kN_per_mm1.5_per_m",
              "jankowski_upper_kN_per_mm1.5_per_m",
              "jankowski_total_kN_per_mm1.5",
              "jankowski_normalised_rms",
              "thesis_jankowski_kN_per_mm1.5_per_m",
              "kelvin_voigt_numerical_error_kN_per_mm_per_m",
              "jankowski_numerical_error_kN_per_mm1.5_per_m",
              "kelvin_voigt_total_numerical_error_kN_per_mm",
              "jankowski_total_numerical_error_kN_per_mm1.5",
              "fidelity",
              "fem_h_contact_cm",
              "fem_penalty_factor",
              "fidelity_converged",
              "kelvin_voigt_status",
              "jankowski_status"};
    }

    std::vector<std::string> k_table_row(const StudyScene &scene, const StudyHeight &h)
    {
      const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
      const auto                           value  = [&](const char *key)
      {
        const auto it = h.fem_case.summary.find(key);
        return it == h.fem_case.summary.end() ? nan : it->second;
      };
      return {number(h.wall_height),
              number(h.fem_case.slab_mass),
              number(h.fem_case.impact_velocity),
              number(value("peak_force") / 1e3),
              number(value("contact_duration") * 1e3),
              number(per_metre(h.kelvin_voigt)),
              number(per_metre_bound(h.kelvin_voigt, false)),
              number(per_metre_bound(h.kelvin_voigt, true)),
              number(per_metre(h.kelvin_voigt) * scene.fit.width),
              number(h.kelvin_voigt ? h.kelvin_voigt->normalised_rms : nan),
              number(thesis ? thesis->kelvin_voigt : nan),
              number(per_metre(h.jankowski)),
              number(per_metre_bound(h.jankowski, false)),
              number(per_metre_bound(h.jankowski, true)),
              number(per_metre(h.jankowski) * scene.fit.width),
              number(h.jankowski ? h.jankowski->normalised_rms : nan),
              number(thesis ? thesis->jankowski : nan),
              number(numerical_error(h, 1.0)),
              number(numerical_error(h, 1.5)),
              number(total_stiffness_error(0.0, numerical_error(h, 1.0), scene.fit.width)),
              number(total_stiffness_error(0.0, numerical_error(h, 1.5), scene.fit.width)),
              h.auto_fidelity ? "auto" : "fixed",
              number(used_h_contact(scene, h) * 100.0),
              number(used_penalty(scene, h)),
              h.auto_fidelity ? (h.ladder.converged ? "yes" : "no") : "",
              h.kelvin_voigt_status,
              h.jankowski_status};
    }

    std::vector<std::string> building_header()
    {
      return {"record",
              "wall_height_m",
              "law",
              "k_total",
              "k_total_unit",
              "gap_cm",
              "pga_m_per_s2",
              "peak_base_displacement_cm",
              "peak_top_displacement_cm",
              "peak_base_acceleration_m_per_s2",
              "peak_top_acceleration_m_per_s2",
              "peak_floor_acceleration_m_per_s2",
              "peak_interstorey_drift_cm",
              "peak_impact_force_kN",
              "n_impacts",
              "permanent_indentation_mm",
              "amplification_base_acceleration",
              "amplification_top_acceleration",
              "amplification_interstorey_drift",
              "wall_seconds",
              "status"};
    }

    std::vector<std::string> building_row(const StudyBuildingRun &r)
    {
      const bool walls = r.law != "none";
      return {r.record,
              walls ? number(r.wall_height) : "",
              r.law,
              walls ? number(stiffness_to_kn_per_mm(r.k_total, r.exponent)) : "",
              walls ? stiffness_display_unit(r.exponent) : "",
              walls ? number(r.gap * 100) : "",
              number(r.pga),
              number(r.base_displacement * 100),
              number(r.top_displacement * 100),
              number(r.base_acceleration),
              number(r.top_acceleration),
              number(r.max_floor_acceleration),
              number(r.max_interstorey_drift * 100),
              number(r.peak_impact_force / 1e3),
              std::to_string(r.n_impacts),
              number(r.permanent_indentation * 1e3),
              number(r.amplification_base_acc),
              number(r.amplification_top_acc),
              number(r.amplification_drift),
              number(r.wall_seconds),
              r.status};
    }

    std::string si_stiffness_unit(double exponent, bool per_metre_of_wall)
    {
      const std::string n = exponent == 1.0 ? "" : fmt::format("^{}", exponent);
      return "N/m" + n + (per_metre_of_wall ? "/m" : "");
    }

    void write_study_h5(const LoadedScene<StudyScene> &loaded,
                        const StudyResult             &result,
                        const OutputDir               &output)
    {
      const StudyScene &scene = loaded.scene;
      ResultsFile       file(output.file("study.h5"), loaded.text, loaded.resolved_json);
      ResultsGroup      root     = file.root();
      ResultsGroup      fem_root = root.group("fem");
      ResultsGroup      fit_root = root.group("fit");
      for (const StudyHeight &h : result.heights)
      {
        write_fem_case(fem_root, h.fem_case);
        ResultsGroup g = fit_root.group(h.name);
        g.write_scalar("wall_height", h.wall_height, "m");
        for (const auto &[law, fit, status] :
             {std::tuple{"kelvin_voigt", &h.kelvin_voigt, &h.kelvin_voigt_status},
              std::tuple{"jankowski", &h.jankowski, &h.jankowski_status}})
        {
          ResultsGroup f = g.group(law);
          f.set_status(*status);
          if (!*fit)
            continue;
          const FitResult  &r    = **fit;
          const std::string unit = si_stiffness_unit(r.exponent.value, true);
          f.write_scalar("stiffness", r.stiffness.value, unit);
          f.write_scalar("stiffness_lower", r.stiffness.lower, unit);
          f.write_scalar("stiffness_upper", r.stiffness.upper, unit);
          f.write_scalar("stiffness_total",
                         r.stiffness.value * scene.fit.width,
                         si_stiffness_unit(r.exponent.value, false));
          f.write_scalar("cor", r.cor.value, "1");
          f.write_scalar("exponent", r.exponent.value, "1");
          f.write_scalar("normalised_rms", r.normalised_rms, "1");
          f.write_scalar("model_effective_cor", r.model_effective_cor, "1");
          f.write("time", r.time, "s");
          f.write("fem_force", r.fem_force, "N/m");
          f.write("model_force", r.model_force, "N/m");
        }
      }

      std::vector<TableColumn> k(17);
      k[0]  = {"wall_height", "m", {}};
      k[1]  = {"kelvin_voigt", "kN/mm/m", {}};
      k[2]  = {"kelvin_voigt_lower", "kN/mm/m", {}};
      k[3]  = {"kelvin_voigt_upper", "kN/mm/m", {}};
      k[4]  = {"kelvin_voigt_total", "kN/mm", {}};
      k[5]  = {"thesis_kelvin_voigt", "kN/mm/m", {}};
      k[6]  = {"jankowski", "kN/mm^1.5/m", {}};
      k[7]  = {"jankowski_lower", "kN/mm^1.5/m", {}};
      k[8]  = {"jankowski_upper", "kN/mm^1.5/m", {}};
      k[9]  = {"jankowski_total", "kN/mm^1.5", {}};
      k[10] = {"thesis_jankowski", "kN/mm^1.5/m", {}};
      k[11] = {"kelvin_voigt_numerical_error", "kN/mm/m", {}};
      k[12] = {"jankowski_numerical_error", "kN/mm^1.5/m", {}};
      k[13] = {"h_contact", "m", {}};
      k[14] = {"penalty_factor", "1", {}};
      k[15] = {"fidelity_auto", "1", {}};
      k[16] = {"fidelity_converged", "1", {}};
      for (const StudyHeight &h : result.heights)
      {
        const std::optional<ThesisStiffness> thesis   = thesis_row(h.wall_height);
        const double                         values[] = {h.wall_height,
                                                         per_metre(h.kelvin_voigt),
                                                         per_metre_bound(h.kelvin_voigt, false),
                                                         per_metre_bound(h.kelvin_voigt, true),
                                                         per_metre(h.kelvin_voigt) * scene.fit.width,
                                 thesis ? thesis->kelvin_voigt : nan,
                                                         per_metre(h.jankowski),
                                                         per_metre_bound(h.jankowski, false),
                                                         per_metre_bound(h.jankowski, true),
                                                         per_metre(h.jankowski) * scene.fit.width,
                                 thesis ? thesis->jankowski : nan,
                                                         numerical_error(h, 1.0),
                                                         numerical_error(h, 1.5),
                                                         used_h_contact(scene, h),
                                                         used_penalty(scene, h),
                                 h.auto_fidelity ? 1.0 : 0.0,
                                 h.auto_fidelity && h.ladder.converged ? 1.0 : 0.0};
        for (std::size_t i = 0; i < k.size(); ++i)
          k[i].values.push_back(values[i]);
      }
      root.write_table("k_table", k);
      root.group("k_table").set_attribute("building_width_m", scene.fit.width);
      write_study_extras(root, result.extras);

      // /fidelity/<H>: the levels climbed (fidelity: auto).
      for (const StudyHeight &h : result.heights)
      {
        if (!h.auto_fidelity)
          continue;
        std::vector<TableColumn> levels = {{"h_contact", "m", {}},
                                           {"penalty_factor", "1", {}},
                                           {"kelvin_voigt", "kN/mm/m", {}},
                                           {"jankowski", "kN/mm^1.5/m", {}},
                                           {"seconds", "s", {}},
                                           {"ok", "1", {}},
                                           {"from_cache", "1", {}},
                                           {"used", "1", {}}};
        for (std::size_t i = 0; i < h.ladder.outcomes.size(); ++i)
        {
          const LevelOutcome &o   = h.ladder.outcomes[i];
          const double        v[] = {h.ladder.levels[i].h_contact,
                                     h.ladder.levels[i].penalty_factor,
                                     stiffness_to_kn_per_mm(o.k_kelvin_voigt, 1.0),
                                     stiffness_to_kn_per_mm(o.k_jankowski, 1.5),
                                     o.seconds,
                              o.ok ? 1.0 : 0.0,
                              o.from_cache ? 1.0 : 0.0,
                              i == h.ladder.used ? 1.0 : 0.0};
          for (std::size_t j = 0; j < levels.size(); ++j)
            levels[j].values.push_back(v[j]);
        }
        ResultsGroup fidelity = root.group("fidelity");
        fidelity.write_table(h.name, levels);
        ResultsGroup table = fidelity.group(h.name);
        table.set_attribute("reason", h.fidelity_reason);
        table.set_attribute("converged", h.ladder.converged ? 1.0 : 0.0);
        table.set_attribute("tolerance", scene.fem.fidelity_tolerance);
      }

      // /building/<record>/<law>: one row per wall height (law "none": the run without walls).
      std::map<std::pair<std::string, std::string>, std::vector<const StudyBuildingRun *>> tables;
      for (const StudyBuildingRun &r : result.building)
        if (r.status == "ok")
          tables[{r.record, r.law}].push_back(&r);
      for (const auto &[key, rows] : tables)
      {
        const std::string        k_unit = si_stiffness_unit(rows.front()->exponent, false);
        std::vector<TableColumn> c      = {{"wall_height", "m", {}},
                                           {"k_total", k_unit, {}},
                                           {"gap", "m", {}},
                                           {"base_displacement", "m", {}},
                                           {"top_displacement", "m", {}},
                                           {"base_acceleration", "m/s^2", {}},
                                           {"top_acceleration", "m/s^2", {}},
                                           {"floor_acceleration", "m/s^2", {}},
                                           {"interstorey_drift", "m", {}},
                                           {"impact_force", "N", {}},
                                           {"n_impacts", "1", {}},
                                           {"permanent_indentation", "m", {}},
                                           {"amplification_base_acceleration", "1", {}},
                                           {"amplification_top_acceleration", "1", {}},
                                           {"amplification_interstorey_drift", "1", {}}};
        for (const StudyBuildingRun *r : rows)
        {
          const double v[] = {r->wall_height,
                              r->k_total,
                              r->gap,
                              r->base_displacement,
                              r->top_displacement,
                              r->base_acceleration,
                              r->top_acceleration,
                              r->max_floor_acceleration,
                              r->max_interstorey_drift,
                              r->peak_impact_force,
                              static_cast<double>(r->n_impacts),
                              r->permanent_indentation,
                              r->amplification_base_acc,
                              r->amplification_top_acc,
                              r->amplification_drift};
          for (std::size_t i = 0; i < c.size(); ++i)
            c[i].values.push_back(v[i]);
        }
        root.group("building").group(key.first).write_table(key.second, c);
      }
      file.commit();
    }

    nlohmann::ordered_json summary_json(const StudyScene &scene, const StudyResult &result)
    {
      nlohmann::ordered_json j;
      j["command"]                 = "study";
      j["kimp"]                    = version_line();
      j["units"]                   = {{"wall_height", "m"},
                                      {"k_per_metre", "kN/mm^n/m"},
                                      {"k_total", "kN/mm^n"},
                                      {"seconds", "s"}};
      j["building_width"]          = scene.fit.width;
      j["wall_seconds"]            = {{"fem", result.fem_seconds},
                                      {"fit", result.fit_seconds},
                                      {"building", result.building_seconds},
                                      {"extras", result.extras.seconds},
                                      {"charts", result.charts_seconds},
                                      {"total", result.wall_seconds}};
      nlohmann::ordered_json table = nlohmann::ordered_json::array();
      for (const StudyHeight &h : result.heights)
      {
        const std::optional<ThesisStiffness> thesis = thesis_row(h.wall_height);
        nlohmann::ordered_json               row;
        row["case"]               = h.name;
        row["wall_height"]        = h.wall_height;
        row["fem_from_cache"]     = h.fem_from_cache;
        row["fem_seconds"]        = h.fem_seconds;
        row["fit_seconds"]        = h.fit_seconds;
        row["fidelity"]           = h.auto_fidelity ? "auto" : "fixed";
        row["fem_h_contact"]      = used_h_contact(scene, h);
        row["fem_penalty_factor"] = used_penalty(scene, h);
        if (h.auto_fidelity)
        {
          row["fidelity_converged"] = h.ladder.converged;
          row["fidelity_levels"]    = h.ladder.outcomes.size();
        }
        row["fidelity_reason"] = h.fidelity_reason;
        for (const char *key : {"n_dofs", "n_steps", "dt", "peak_force", "contact_duration"})
          if (const auto it = h.fem_case.summary.find(key); it != h.fem_case.summary.end())
            row[std::string("fem_") + key] = it->second;
        for (const auto &[law, fit, status, reference] :
             {std::tuple{"kelvin_voigt",
                         &h.kelvin_voigt,
                         &h.kelvin_voigt_status,
                         thesis ? thesis->kelvin_voigt : nan},
              std::tuple{"jankowski",
                         &h.jankowski,
                         &h.jankowski_status,
                         thesis ? thesis->jankowski : nan}})
        {
          nlohmann::ordered_json f;
          f["status"] = *status;
          if (*fit)
          {
            f["k_per_metre"]    = per_metre(*fit);
            f["k_lower"]        = per_metre_bound(*fit, false);
            f["k_upper"]        = per_metre_bound(*fit, true);
            f["k_total"]        = per_metre(*fit) * scene.fit.width;
            f["unit"]           = (*fit)->per_metre_unit();
            f["normalised_rms"] = (*fit)->normalised_rms;
            const double error = numerical_error(h, std::string(law) == "kelvin_voigt" ? 1.0 : 1.5);
            if (std::isfinite(error))
              f["k_numerical_error"] = error;
          }
          if (std::isfinite(reference))
            f["thesis_table_2_1"] = reference;
          row[law] = f;
        }
        table.push_back(row);
      }
      j["k_table"]         = table;
      j["n_building_runs"] = result.building.size();
      std::size_t n_failed = 0;
      for (const StudyBuildingRun &r : result.building)
        n_failed += r.status != "ok";
      j["n_building_runs_not_ok"] = n_failed;
      return j;
    }

    std::string extras_markdown(const StudyScene &scene, const StudyExtras &e, bool charts)
    {
      std::string md;
      if (!e.fem_accuracy.empty())
      {
        md += fmt::format(
          "## Accuracy against cost: FEM (H = {} m)\n\nError of k against the finest "
          "explicit mesh level; seconds are the FEM wall time of each run.\n\n"
          "| series | h_contact (cm) | penalty | FEM s | k_KV kN/mm/m | error KV | "
          "k_J kN/mm^1.5/m | error J | status |\n|---|---|---|---|---|---|---|---|---|\n",
          scene.accuracy.wall_height);
        for (const FemAccuracyPoint &p : e.fem_accuracy)
          md += fmt::format("| {} | {:g} | {:g} | {} | {} | {} | {} | {} | {} |\n",
                            p.series,
                            p.h_contact * 100,
                            p.penalty_factor,
                            number(p.seconds),
                            number(p.ok ? stiffness_to_kn_per_mm(p.k_kelvin_voigt, 1.0) : nan),
                            p.ok ? fmt::format("{:.3g} %", 100 * p.error_kelvin_voigt) : "",
                            number(p.ok ? stiffness_to_kn_per_mm(p.k_jankowski, 1.5) : nan),
                            p.ok ? fmt::format("{:.3g} %", 100 * p.error_jankowski) : "",
                            p.status);
        md += "\nData: [accuracy_fem.csv](accuracy_fem.csv), study.h5 `/accuracy/fem`.\n\n";
        if (charts)
          md += "![FEM accuracy against cost](charts/accuracy_fem.png)\n\n";
      }
      if (!e.lumped_accuracy.empty())
      {
        md += fmt::format("## Accuracy against cost: building time step (thesis Figs 3.3-3.4)\n\n"
                          "Record {}, walls at {:.4g} cm, modified Kelvin-Voigt k = {:.5g} kN/mm; "
                          "errors against central difference at {:g} s.\n\n"
                          "| method | dt (s) | s | peak impact force (kN) | error | peak base acc. "
                          "(m/s²) | error | status |\n|---|---|---|---|---|---|---|---|\n",
                          e.lumped_record,
                          e.lumped_gap * 100,
                          stiffness_to_kn_per_mm(e.lumped_k_total, 1.0),
                          scene.accuracy.lumped_reference_dt);
        for (const LumpedAccuracyPoint &p : e.lumped_accuracy)
          md += fmt::format("| {} | {:g} | {} | {} | {} | {} | {} | {} |\n",
                            p.method,
                            p.dt,
                            number(p.seconds),
                            number(p.ok ? p.peak_impact_force / 1e3 : nan),
                            p.ok ? fmt::format("{:.3g} %", 100 * p.error_force) : "",
                            number(p.ok ? p.base_acceleration : nan),
                            p.ok ? fmt::format("{:.3g} %", 100 * p.error_acceleration) : "",
                            p.status);
        md +=
          "\nData: [accuracy_lumped.csv](accuracy_lumped.csv), study.h5 `/accuracy/lumped`.\n\n";
        if (charts)
          md += "![building time step accuracy against cost](charts/accuracy_lumped.png)\n\n";
      }
      if (!e.stability.empty())
      {
        std::size_t n_stable = 0, n_accurate = 0, stable_above = 0, unstable_below = 0;
        for (const StabilityPoint &p : e.stability)
        {
          n_stable += p.stable;
          n_accurate += p.accurate;
          stable_above += p.stable && p.dt > p.dt_limit_damped;
          unstable_below += !p.stable && p.dt < p.dt_limit_damped;
        }
        md +=
          fmt::format("## Stability map of the central difference method\n\nTwo-body "
                      "collisions (isolation level {:.0f} t against the wall {:.0f} t, m_eff = "
                      "{:.4g} t, modified Kelvin-Voigt at COR {}), no stability guard: {} runs, "
                      "{} stable (energy gain < 0.1 %), {} of them accurate (effective COR within "
                      "5 % of nominal); {} stable above the damped limit "
                      "2(sqrt(1+ξ²)−ξ)/ω_imp, {} unstable below it.\n\n"
                      "Data: [stability_lumped.csv](stability_lumped.csv), study.h5 "
                      "`/stability/lumped`.\n\n",
                      scene.building.isolation_mass / 1e3,
                      scene.walls.mass / 1e3,
                      e.stability_effective_mass / 1e3,
                      scene.fit.cor,
                      e.stability.size(),
                      n_stable,
                      n_accurate,
                      stable_above,
                      unstable_below);
        if (charts)
          md += "![stability map](charts/stability_map.png)\n\n";
      }
      if (!e.fem_stability.empty())
      {
        std::size_t stable_above = 0, unstable_below = 0, n_stable = 0;
        for (const FemStabilityPoint &p : e.fem_stability)
        {
          n_stable += p.stable;
          stable_above += p.stable && p.dt_factor > 1;
          unstable_below += !p.stable && p.dt_factor < 1;
        }
        md += fmt::format(
          "## Stability map of the explicit FEM\n\nH = {} m, contact elements {:g} cm, the "
          "first {:g} ms of the impact, Δt = factor × the computed limit 2(sqrt(1+ξ²)−ξ)/ω "
          "(ω from the mesh's CFL bound and the penalty spring, ξ its contact damping), no "
          "refusal; unstable: diverged, or energy error above 1 %: {} runs, {} stable; {} stable above the limit (the bound is conservative "
          "there), {} unstable below it.\n\n| penalty factor | Δt limit (µs) | "
          "stable at Δt / limit |\n|---|---|---|\n",
          scene.accuracy.wall_height,
          e.fem_stability_h_contact * 100,
          e.fem_stability_end_time * 1e3,
          e.fem_stability.size(),
          n_stable,
          stable_above,
          unstable_below);
        std::map<double, std::pair<double, std::string>> rows;
        for (const FemStabilityPoint &p : e.fem_stability)
        {
          auto &row = rows[p.penalty_factor];
          row.first = p.dt_limit;
          row.second += fmt::format("{}{:g}: {}",
                                    row.second.empty() ? "" : ", ",
                                    p.dt_factor,
                                    p.stable ? "yes" : "no");
        }
        for (const auto &[penalty, row] : rows)
          md += fmt::format("| {:g} | {:.4g} | {} |\n", penalty, row.first * 1e6, row.second);
        md += "\nData: [stability_fem.csv](stability_fem.csv), study.h5 `/stability/fem`.\n\n";
        if (charts)
          md += "![FEM stability map](charts/stability_map_fem.png)\n\n";
      }
      if (!e.sensitivity.empty())
      {
        md += fmt::format("## Sensitivity of k (H = {} m, ±{:g} %)\n\n| parameter | factor | k_KV "
                          "kN/mm/m | k_J kN/mm^1.5/m | status |\n|---|---|---|---|---|\n",
                          scene.sensitivity_study.wall_height,
                          scene.sensitivity_study.variation * 100);
        for (const SensitivityPoint &p : e.sensitivity)
          md += fmt::format("| {} | {:g} | {} | {} | {} |\n",
                            p.parameter,
                            p.factor,
                            number(p.ok ? stiffness_to_kn_per_mm(p.k_kelvin_voigt, 1.0) : nan),
                            number(p.ok ? stiffness_to_kn_per_mm(p.k_jankowski, 1.5) : nan),
                            p.status);
        md += "\nData: [sensitivity.csv](sensitivity.csv), study.h5 `/sensitivity`.\n\n";
        if (charts)
          md += "![sensitivity of k](charts/sensitivity.png)\n\n";
      }
      return md;
    }

    std::string report_markdown(const StudyScene &scene, const StudyResult &result, bool charts)
    {
      std::string md = "# kimp wall-height study\n\n" + version_line() + "\n\n";
      md += fmt::format("## Impact stiffness per wall height (fitted at COR {}, W = {} m)\n\n",
                        scene.fit.cor,
                        scene.fit.width);
      md += "| H (m) | KV kN/mm/m [95 % CI] ± numerical | Table 2.1 | KV total kN/mm | "
            "Jankowski kN/mm^1.5/m [95 % CI] ± numerical | Table 2.1 | J total kN/mm^1.5 | FEM "
            "level (h_contact, penalty) | FEM from cache |\n"
            "|---|---|---|---|---|---|---|---|---|\n";
      const auto plus_minus = [](double error)
      { return std::isfinite(error) ? " ± " + number(error) : std::string(); };
      for (const StudyHeight &h : result.heights)
      {
        const std::optional<ThesisStiffness> t = thesis_row(h.wall_height);
        md +=
          fmt::format("| {:.2f} | {} [{}, {}]{} | {} | {} | {} [{}, {}]{} | {} | {} | {:g} cm, "
                      "{:g}{} | {} |\n",
                      h.wall_height,
                      number(per_metre(h.kelvin_voigt)),
                      number(per_metre_bound(h.kelvin_voigt, false)),
                      number(per_metre_bound(h.kelvin_voigt, true)),
                      plus_minus(numerical_error(h, 1.0)),
                      t ? number(t->kelvin_voigt) : "-",
                      number(per_metre(h.kelvin_voigt) * scene.fit.width),
                      number(per_metre(h.jankowski)),
                      number(per_metre_bound(h.jankowski, false)),
                      number(per_metre_bound(h.jankowski, true)),
                      plus_minus(numerical_error(h, 1.5)),
                      t ? number(t->jankowski) : "-",
                      number(per_metre(h.jankowski) * scene.fit.width),
                      used_h_contact(scene, h) * 100.0,
                      used_penalty(scene, h),
                      h.auto_fidelity ? (h.ladder.converged ? "" : " (not converged)") : " (fixed)",
                      h.fem_from_cache ? "yes" : "no");
      }
      md += "\nThe intervals are the fits' own (law misfit). The ± values are the FEM's numerical "
            "error of k with `fem.fidelity: auto`: the change of k from the previous level of the "
            "mesh ladder (and of the penalty ladder, added in quadrature); the climb stops when "
            "both laws change by less than `fem.fidelity_tolerance`. ";
      for (const StudyHeight &h : result.heights)
        md += fmt::format("{}: {}. ", h.name, h.fidelity_reason);
      md += "The thesis used non-linear materials in ADINA and did not state its slab mass, so "
            "the trend with H and the order of magnitude are what should agree.\n\n"
            "Data: [k_table.csv](k_table.csv), [study.h5](study.h5) (`/k_table`, `/fit/<H>`, "
            "`/fem/<H>`, `/fidelity/<H>`).\n\n";
      if (charts)
        md += "![FEM force histories with the fitted laws](charts/force_histories.png)\n\n"
              "![k against wall height](charts/k_vs_height.png)\n\n";

      md += "## Building response\n\n"
            "Isolated building of docs/physics.md §3 with moat walls on both sides, gap "
            "from the no-wall peak isolation displacement; modified Kelvin-Voigt with k_KV, "
            "Jankowski and the hysteretic law with k_Jankowski.\n\n"
            "| record | H (m) | law | gap (cm) | base acc. (m/s²) | top acc. (m/s²) | drift (cm) | "
            "impact force (kN) | impacts | top acc. amplification | status |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|\n";
      for (const StudyBuildingRun &r : result.building)
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                          r.record,
                          r.law == "none" ? "-" : number(r.wall_height),
                          r.law,
                          r.law == "none" ? "-" : number(r.gap * 100),
                          number(r.base_acceleration),
                          number(r.top_acceleration),
                          number(r.max_interstorey_drift * 100),
                          number(r.peak_impact_force / 1e3),
                          r.n_impacts,
                          number(r.amplification_top_acc),
                          r.status);
      md += "\nData: [building_response.csv](building_response.csv), study.h5 "
            "`/building/<record>/<law>`.\n\n";
      if (charts)
        md += "![building response against wall height](charts/building_response.png)\n\n";
      md += extras_markdown(scene, result.extras, charts);
      md += fmt::format("## Cost\n\nFEM {:.2f} s, fits {:.2f} s, building runs {:.2f} s, extra "
                        "studies {:.2f} s, charts {:.2f} s, total {:.2f} s (see summary.json).\n",
                        result.fem_seconds,
                        result.fit_seconds,
                        result.building_seconds,
                        result.extras.seconds,
                        result.charts_seconds,
                        result.wall_seconds);
      return md;
    }

    // ---------------------------------------------------------------- stage 4: charts

    /// Draw the charts; false (with a warning) if they could not be drawn.
    bool draw_charts(const OutputDir &output)
    {
      const ChartScriptRun run = run_chart_script("study_charts.py", output.path());
      if (run.script.empty())
      {
        logger().warn("charts skipped: scripts/study_charts.py not found (set KIMP_DATA_DIR to "
                      "the kimp source tree)");
        return false;
      }
      if (run.status != 0)
      {
        logger().warn("charts skipped: {} exited with {} (needs /usr/bin/python3 with matplotlib "
                      "and h5py; Debian python3-matplotlib python3-h5py); see {}",
                      run.script.string(),
                      run.status,
                      run.log.string());
        return false;
      }
      logger().info("charts written to {}", output.file("charts").string());
      return true;
    }
  } // namespace

  const std::vector<ThesisStiffness> &thesis_table_2_1()
  {
    static const std::vector<ThesisStiffness> table = {{1.00, 150, 50},
                                                       {1.25, 90, 27},
                                                       {1.50, 45, 10},
                                                       {2.00, 25, 5}};
    return table;
  }

  StudyResult run_study(const LoadedScene<StudyScene> &loaded, const OutputDir &output)
  {
    const Clock::time_point start = Clock::now();
    const StudyScene       &scene = loaded.scene;
    StudyResult             result;
    if (scene.fem.fidelity == Fidelity::auto_ladder)
      logger().info("fidelity auto: contact mesh ladder {} cm, penalty factors {}, tolerance {} %; "
                    "{} slab as the scene says (the rigid-slab shortcut is not taken "
                    "automatically: for this scene it doubles the peak force, docs/validation.md)",
                    fmt::join(scale(scene.fem.fidelity_h_contact, 100.0), " / "),
                    fmt::join(scene.fem.fidelity_penalty_factors, " / "),
                    scene.fem.fidelity_tolerance * 100.0,
                    scene.fem.slab.rigid ? "rigid" : "elastic");
    for (const double height : scene.fem.wall_heights)
    {
      result.heights.push_back(run_height(scene, height, output));
      result.fem_seconds += result.heights.back().fem_seconds;
      result.fit_seconds += result.heights.back().fit_seconds;
    }
    log_k_table(scene, result.heights);

    std::vector<std::vector<std::string>> k_rows;
    for (const StudyHeight &h : result.heights)
      k_rows.push_back(k_table_row(scene, h));
    write_csv_atomic(output.file("k_table.csv"), k_table_header(), k_rows);
    std::vector<std::vector<std::string>> level_rows;
    for (const StudyHeight &h : result.heights)
      for (std::size_t i = 0; i < h.ladder.outcomes.size(); ++i)
      {
        const LevelOutcome &o = h.ladder.outcomes[i];
        level_rows.push_back({number(h.wall_height),
                              number(h.ladder.levels[i].h_contact * 100.0),
                              number(h.ladder.levels[i].penalty_factor),
                              number(stiffness_to_kn_per_mm(o.k_kelvin_voigt, 1.0)),
                              number(stiffness_to_kn_per_mm(o.k_jankowski, 1.5)),
                              number(o.seconds),
                              o.from_cache ? "yes" : "no",
                              i == h.ladder.used ? "yes" : "no",
                              o.status});
      }
    if (!level_rows.empty())
      write_csv_atomic(output.file("fidelity_levels.csv"),
                       {"wall_height_m",
                        "h_contact_cm",
                        "penalty_factor",
                        "kelvin_voigt_kN_per_mm_per_m",
                        "jankowski_kN_per_mm1.5_per_m",
                        "seconds",
                        "fem_from_cache",
                        "used",
                        "status"},
                       level_rows);

    const Clock::time_point building_start = Clock::now();
    result.building                        = run_building(scene, result.heights);
    result.building_seconds                = seconds_since(building_start);
    std::vector<std::vector<std::string>> b_rows;
    for (const StudyBuildingRun &r : result.building)
      b_rows.push_back(building_row(r));
    write_csv_atomic(output.file("building_response.csv"), building_header(), b_rows);

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
    logger().info("study done in {:.2f} s (FEM {:.2f} s, fits {:.2f} s, building {:.2f} s, "
                  "charts {:.2f} s): {}",
                  result.wall_seconds,
                  result.fem_seconds,
                  result.fit_seconds,
                  result.building_seconds,
                  result.charts_seconds,
                  output.file("report.md").string());
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
    }
    if (rank != 0)
      return;
    run_study(scene, *output);
  }
} // namespace kimp::app
