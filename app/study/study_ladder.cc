// The fidelity ladder of `kimp study`: k on successively finer FEM levels, stop at a relative
// change below the tolerance, error = change to the previous level.
#include "app/study/study_ladder.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <string_view>

#include "app/study/study_laws.h"

namespace kimp::app
{
  namespace
  {
    void check_levels(const std::vector<double> &values, const char *name, bool decreasing)
    {
      if (values.empty())
        throw std::invalid_argument(fmt::format("{}: empty (need at least one level)", name));
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        if (!(values[i] > 0.0 && std::isfinite(values[i])))
          throw std::invalid_argument(
            fmt::format("{}[{}] = {} (must be > 0 and finite)", name, i, values[i]));
        if (i > 0 && (decreasing ? !(values[i] < values[i - 1]) : !(values[i] > values[i - 1])))
          throw std::invalid_argument(fmt::format("{}[{}] = {} after {} (must be {})",
                                                  name,
                                                  i,
                                                  values[i],
                                                  values[i - 1],
                                                  decreasing ? "decreasing" : "increasing"));
      }
    }

    bool within(const LevelOutcome &coarse, const LevelOutcome &fine, double tolerance)
    {
      for (std::size_t i = 0; i < fine.k.size(); ++i)
        if (!(relative_change(coarse.k.at(i), fine.k[i]) <= tolerance))
          return false;
      return true;
    }

    /// Every law's k is known.
    bool all_finite(const std::vector<double> &k)
    {
      return std::all_of(k.begin(), k.end(), [](double v) { return std::isfinite(v); });
    }

    /// "4.1 % (KV) and 2.3 % (Jankowski)": the change of each law's k (named by study_laws()).
    std::string changes_text(const LevelOutcome &before, const LevelOutcome &after)
    {
      std::string text;
      for (std::size_t i = 0; i < after.k.size(); ++i)
        text += fmt::format("{}{:.3g} % ({})",
                            i ? " and " : "",
                            100.0 * relative_change(before.k.at(i), after.k[i]),
                            i < study_laws().size() ? study_laws()[i].short_name :
                                                      std::string_view("law"));
      return text;
    }

    double quadrature(double a, double b)
    {
      if (std::isnan(a))
        return std::isnan(b) ? b : std::abs(b);
      if (std::isnan(b))
        return std::abs(a);
      return std::hypot(a, b);
    }
  } // namespace

  const std::vector<LadderQuantity> &ladder_quantities()
  {
    // Floors: 0.01 mm of displacement, 0.1 ms of time (ten samples of the default output
    // interval), 0.01 of the bar strain ratio, 5 cm of the height where the bar strain peaks
    // (two elements of the finest default level; a height near the ground has no relative
    // error); forces, impulses and resistances have none.
    static const std::vector<LadderQuantity> quantities = {
      {"first_peak_force", "N/m", 0.0},
      {"first_peak_impulse", "N*s/m", 0.0},
      {"energy_equivalent_resistance", "N/m", 0.0},
      {"max_slab_displacement", "m", 1e-5},
      {"max_wall_displacement", "m", 1e-5},
      {"time_to_stop", "s", 1e-4},
      {"time_to_95_travel", "s", 1e-4},
      {"wall_residual_displacement", "m", 1e-5},
      {"max_bar_strain_ratio", "1", 0.01},
      {"max_bar_strain_height", "m", 0.05},
      {"max_bar_gauge_strain_ratio", "1", 0.01},
      {"max_bar_gauge_strain_height", "m", 0.05}};
    return quantities;
  }

  std::vector<QuantityError> quantity_errors(const LevelOutcome &coarse, const LevelOutcome &fine)
  {
    std::vector<QuantityError> errors;
    for (const LadderQuantity &q : ladder_quantities())
    {
      QuantityError e;
      e.key        = q.key;
      e.unit       = q.unit;
      const auto a = coarse.quantities.find(q.key), b = fine.quantities.find(q.key);
      if (a == coarse.quantities.end() || b == fine.quantities.end())
      {
        // Shown by neither level (no bars, a slab that never stops): nothing to converge.
        if (a == coarse.quantities.end() && b == fine.quantities.end())
          continue;
        e.verdict = "not shown";
        errors.push_back(e);
        continue;
      }
      e.coarse   = a->second;
      e.fine     = b->second;
      e.relative = relative_change(e.coarse, e.fine);
      e.pass    = e.relative <= ladder_quantity_tolerance || std::abs(e.coarse - e.fine) <= q.floor;
      e.verdict = e.pass ? "pass" : "fail";
      errors.push_back(e);
    }
    return errors;
  }

  std::string FidelityLevel::label() const
  {
    return fmt::format("h{:g}cm_p{:g}", h_contact * 100.0, penalty_factor);
  }

  double relative_change(double coarse, double fine)
  {
    if (coarse == fine)
      return 0.0;
    if (fine == 0.0)
      return std::numeric_limits<double>::infinity();
    return std::abs(coarse - fine) / std::abs(fine);
  }

  double total_stiffness_error(double k_per_metre, double k_error, double width, double width_error)
  {
    return std::hypot(width * k_error, k_per_metre * width_error);
  }

  namespace
  {
    /** The engineer's quantities' change between the two finest usable levels of `result` (the
     *  reported one and the usable level before it), and whether all of them pass. */
    void add_quantity_errors(LadderResult &result)
    {
      if (result.used > 0)
      {
        // The two finest levels: the reported one and the usable level before it.
        std::size_t before = result.used - 1;
        while (before > 0 && !result.outcomes[before].ok)
          --before;
        if (result.outcomes[before].ok)
          result.quantity_errors =
            quantity_errors(result.outcomes[before], result.outcomes[result.used]);
      }
      result.quantities_converged = !result.quantity_errors.empty() &&
                                    std::all_of(result.quantity_errors.begin(),
                                                result.quantity_errors.end(),
                                                [](const QuantityError &e) { return e.pass; });
    }
  } // namespace

  LadderResult climb_fidelity_ladder(const std::vector<double> &h_contact_levels,
                                     const std::vector<double> &penalty_levels,
                                     double                     tolerance,
                                     const std::function<LevelOutcome(const FidelityLevel &)> &run)
  {
    check_levels(h_contact_levels, "fidelity_h_contact", true);
    check_levels(penalty_levels, "fidelity_penalty_factors", false);
    if (!(tolerance > 0.0 && std::isfinite(tolerance)))
      throw std::invalid_argument(
        fmt::format("fidelity_tolerance = {} (must be > 0 and finite)", tolerance));

    LadderResult result;
    // One phase: run `levels` in order from the current state; returns true if it converged.
    // `first_known`: index of an already computed level that starts the phase (npos: none).
    const auto phase = [&](const std::vector<FidelityLevel> &levels,
                           std::size_t                       first_known,
                           std::vector<double>              &errors,
                           const char                       *what)
    {
      std::size_t previous = first_known;
      for (const FidelityLevel &level : levels)
      {
        result.levels.push_back(level);
        result.outcomes.push_back(run(level));
        const std::size_t   i       = result.outcomes.size() - 1;
        const LevelOutcome &outcome = result.outcomes[i];
        if (!outcome.ok || outcome.k.empty() || !all_finite(outcome.k))
        {
          result.reason = fmt::format("{} level {} unusable ({}): reporting the previous level",
                                      what,
                                      level.label(),
                                      outcome.status);
          return false;
        }
        result.used = i;
        if (previous < i)
        {
          const LevelOutcome &before = result.outcomes[previous];
          errors.assign(outcome.k.size(), 0.0);
          for (std::size_t law = 0; law < outcome.k.size(); ++law)
            errors[law] = std::abs(outcome.k[law] - before.k.at(law));
          if (within(before, outcome, tolerance))
          {
            result.reason = fmt::format("{} converged at {}: k changed by {} from {} (tolerance "
                                        "{:.3g} %)",
                                        what,
                                        level.label(),
                                        changes_text(before, outcome),
                                        result.levels[previous].label(),
                                        100.0 * tolerance);
            return true;
          }
        }
        previous = i;
      }
      result.reason = result.outcomes.size() == 1 ?
                        fmt::format("{}: one level ({}), numerical error not estimated",
                                    what,
                                    result.levels.back().label()) :
                        fmt::format("{} ladder exhausted at {} without meeting the tolerance "
                                    "{:.3g} %",
                                    what,
                                    result.levels.back().label(),
                                    100.0 * tolerance);
      return false;
    };

    std::vector<FidelityLevel> mesh;
    for (const double h : h_contact_levels)
      mesh.push_back({h, penalty_levels.front()});
    const bool mesh_converged =
      phase(mesh, std::numeric_limits<std::size_t>::max(), result.mesh_error, "mesh");
    if (!result.has_usable_level())
      return result;
    // A level that failed after a usable one ends the climb.
    const bool        mesh_failed = result.used + 1 != result.outcomes.size();
    const std::string mesh_reason = result.reason;

    bool penalty_converged = penalty_levels.size() == 1;
    if (penalty_levels.size() > 1 && !mesh_failed)
    {
      std::vector<FidelityLevel> penalty;
      const double               h = result.used_level().h_contact;
      for (std::size_t j = 1; j < penalty_levels.size(); ++j)
        penalty.push_back({h, penalty_levels[j]});
      penalty_converged = phase(penalty, result.used, result.penalty_error, "penalty");
      result.reason     = mesh_reason + "; " + result.reason;
    }
    result.converged = mesh_converged && penalty_converged && !mesh_failed &&
                       result.used + 1 == result.outcomes.size();
    // Per law, NaN where a phase did not estimate its error.
    const std::size_t n_laws = result.used_outcome().k.size();
    result.mesh_error.resize(n_laws, std::numeric_limits<double>::quiet_NaN());
    result.penalty_error.resize(n_laws, std::numeric_limits<double>::quiet_NaN());
    result.error.resize(n_laws);
    for (std::size_t law = 0; law < n_laws; ++law)
      result.error[law] = quadrature(result.mesh_error[law], result.penalty_error[law]);
    add_quantity_errors(result);
    return result;
  }
} // namespace kimp::app
