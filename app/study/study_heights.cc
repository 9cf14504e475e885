// Compute stage of `kimp study` per wall height: the FEM case (fixed level or the fidelity
// ladder of study_ladder.h) and the fits of laws 2 and 4 (docs/physics.md §4), on one or all ranks.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <string>

#include "app/study/study_fem.h"
#include "app/study/study_internal.h"
#include "app/study/study_velocity.h"
#include "base/format.h"
#include "base/logging.h"

namespace kimp::app::study_internal
{
  namespace
  {
    /// The ladder's engineer's quantities of a record (LevelOutcome::quantities).
    std::map<std::string, double> record_quantities(const io::FemCase &fem_case)
    {
      std::map<std::string, double>       quantities;
      const std::map<std::string, double> entries = fem_case.summary.entries();
      for (const LadderQuantity &q : ladder_quantities())
        if (const auto it = entries.find(q.key); it != entries.end())
          quantities[q.key] = it->second;
      return quantities;
    }

    void log_quantity_errors(const std::string                &name,
                             const char                       *what,
                             const std::vector<QuantityError> &errors)
    {
      for (const QuantityError &e : errors)
        logger().info("{}: {} of {}: {:.3g} % ({:.4g} -> {:.4g} {}): {}",
                      name,
                      what,
                      e.key,
                      100.0 * e.relative,
                      e.coarse,
                      e.fine,
                      e.unit,
                      e.verdict);
    }

    /**
     * fem.fidelity_far_side_spread: the reported level once more with the other far side
     * (rollers <-> absorbing), and the change of the engineer's quantities from the scene's
     * far side to it (h.ladder.far_side_spread, "coarse" = the other far side).
     */
    void add_far_side_spread(const FemScene    &material,
                             double             wall_height,
                             const OutputDir   &output,
                             const std::string &prefix,
                             StudyHeight       &h)
    {
      const FidelityLevel &level = h.ladder.used_level();
      FemScene             other = fem_level_scene(material, level.h_contact, level.penalty_factor);
      // The rollered block against the unbounded backfill the scene chose (absorbing when it
      // chose rollers).
      const bool absorbing    = other.boundary.far != FemBoundary::Far::rollers;
      other.boundary.far      = absorbing ? FemBoundary::Far::rollers : FemBoundary::Far::absorbing;
      h.ladder.other_far_side = far_boundary_name(other.boundary.far);
      StudyFemCase fem =
        study_fem_case(other,
                       wall_height,
                       output,
                       prefix + "_" + level.label() + "_far_" + h.ladder.other_far_side);
      h.fem_seconds += fem.wall_seconds;
      LevelOutcome scene_side, other_side;
      scene_side.quantities    = h.ladder.used_outcome().quantities;
      other_side.quantities    = record_quantities(fem.fem_case);
      h.ladder.far_side_spread = quantity_errors(other_side, scene_side);
      log_quantity_errors(h.name,
                          ("spread to the " + h.ladder.other_far_side + " far side").c_str(),
                          h.ladder.far_side_spread);
    }

    /// The ladder's numerical error of the engineer's quantities to the log; the far-side
    /// spread if the scene asks for it.
    void quantities_on_the_ladder(const StudyFemScene &scene,
                                  const FemScene      &material,
                                  double               wall_height,
                                  const OutputDir     &output,
                                  const std::string   &prefix,
                                  StudyHeight         &h)
    {
      log_quantity_errors(h.name, "numerical error", h.ladder.quantity_errors);
      if (scene.fidelity_far_side_spread)
        add_far_side_spread(material, wall_height, output, prefix, h);
    }
  } // namespace

  StudyHeight run_height(const StudyScene &scene, double wall_height, const OutputDir &output)
  {
    StudyHeight h;
    h.wall_height     = wall_height;
    h.name            = fem_case_name(wall_height);
    h.impact_velocity = scene.fem.solver.initial_velocity;
    // The cheap level's inelastic fits, when the material choice ran them (reused by the ladder).
    std::optional<StudyFits> cheap_fits;
    choose_material_model(scene, wall_height, output, h, &cheap_fits);
    if (scene.fem.fidelity == Fidelity::fixed)
    {
      StudyFemCase fem = study_fem_case(scene.fem, wall_height, output);
      h.fem_case       = std::move(fem.fem_case);
      h.fem_from_cache = fem.from_cache;
      h.fem_seconds    = fem.wall_seconds;
      StudyFits fits   = fit_study_laws(h.fem_case, scene.fit);
      h.fit_seconds    = fits.seconds;
      set_fits(h, std::move(fits));
      h.fidelity_reason = "fidelity fixed: numerical error not estimated";
      if (h.inelastic)
        add_linear_counterpart(scene.fem, scene.fit, wall_height, output, h.name + "_linear", h);
      return h;
    }

    // fidelity: auto. Every level keeps its FEM case and fits; the used one is reported.
    struct Computed
    {
      io::FemCase fem_case;
      StudyFits   fits;
      bool        from_cache = false;
    };
    std::vector<Computed> computed;
    // The material model chosen above (linear for an inelastic scene: cache names "_linear").
    const FemScene    material = material_fem_scene(scene.fem, h.inelastic);
    const std::string prefix   = h.name + material_suffix(scene.fem, h.inelastic);
    h.fem_from_cache           = true;
    const auto run             = [&](const FidelityLevel &level)
    {
      LevelOutcome outcome;
      outcome.k.assign(study_laws().size(), nan);
      Computed c;
      try
      {
        StudyFemCase fem =
          study_fem_case(fem_level_scene(material, level.h_contact, level.penalty_factor),
                         wall_height,
                         output,
                         prefix + "_" + level.label());
        h.fem_seconds += fem.wall_seconds;
        h.fem_from_cache = h.fem_from_cache && fem.from_cache;
        c.fem_case       = std::move(fem.fem_case);
        c.from_cache     = fem.from_cache;
        const bool cheap = level.h_contact == scene.fem.fidelity_h_contact.front() &&
                           level.penalty_factor == scene.fem.fidelity_penalty_factors.front();
        if (cheap && cheap_fits && h.inelastic)
          c.fits = *cheap_fits; // fitted (and its warnings logged) by the material choice
        else
        {
          c.fits = fit_study_laws(c.fem_case, scene.fit);
          h.fit_seconds += c.fits.seconds;
        }
        outcome.quantities = record_quantities(c.fem_case);
        outcome.seconds    = fem.wall_seconds + c.fits.seconds;
        outcome.from_cache = fem.from_cache;
        outcome.ok         = c.fits.ok();
        outcome.status     = outcome.ok ? "ok" : "fit " + joined_status(c.fits.laws);
        if (outcome.ok)
        {
          for (std::size_t i = 0; i < c.fits.laws.size(); ++i)
            outcome.k[i] = c.fits.laws[i].fit->stiffness.value;
        }
      }
      catch (const std::exception &error)
      {
        outcome.status = std::string("failed: ") + error.what();
        logger().warn("{}: level {} {}", h.name, level.label(), outcome.status);
      }
      computed.push_back(std::move(c));
      logger().info("{}: level {}: {} ({})",
                    h.name,
                    level.label(),
                    k_text(outcome.k, "k_"),
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
    Computed &used  = computed.at(h.ladder.used);
    h.fem_case      = std::move(used.fem_case);
    h.fem_case.name = h.name;
    set_fits(h, std::move(used.fits));
    if (h.inelastic)
      add_linear_counterpart(fem_level_scene(material,
                                             h.ladder.used_level().h_contact,
                                             h.ladder.used_level().penalty_factor),
                             scene.fit,
                             wall_height,
                             output,
                             h.name + "_linear_" + h.ladder.used_level().label(),
                             h);
    logger().info("{}: fidelity auto: {} -> level {} ({}); numerical error of k: {}",
                  h.name,
                  h.ladder.reason,
                  h.ladder.used_level().label(),
                  h.ladder.converged ? "converged" : "NOT converged",
                  k_text(h.ladder.error, ""));
    quantities_on_the_ladder(scene.fem, material, wall_height, output, prefix, h);
    return h;
  }

  /**
   * Under `mpirun -np N`: rank r computes the FEM (and climbs the fidelity ladder) of heights
   * r, r + N, ... into the study's FEM cache; rank 0 then finds every height there. Errors are
   * left for rank 0's own pass to report (it recomputes what is missing).
   */
  void
  compute_heights_on_ranks(const StudyScene &scene, const OutputDir &output, int rank, int n_ranks)
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
                  base::sig(scene.fit.width));
    const std::string table = k_table_markdown(scene, heights);
    for (std::size_t begin = 0; begin < table.size();)
    {
      const std::size_t end = std::min(table.find('\n', begin), table.size());
      if (table.compare(begin, 4, "|---") != 0) // the rule line says nothing in a log
        logger().info("  {}", table.substr(begin, end - begin));
      begin = end + 1;
    }
  }
} // namespace kimp::app::study_internal
