// The step budget of a run: a run whose estimate exceeds it is refused before it starts. Its
// scene key, max_steps, is declared here once for the FEM and the building scenes.
#pragma once

#include <fmt/format.h>
#include <stdexcept>
#include <string>
#include <string_view>

#include "io/scene_io.h"

namespace kimp::app
{
  /**
   * Refuses a run over its step budget: unless `steps` <= `max_steps` (NaN steps are refused),
   * throws std::invalid_argument "<name>: the estimate (<estimate>) exceeds the step budget
   * <budget>", `budget` saying which budget it is (max_steps formatted into it) and how to stay
   * within it.
   */
  inline void check_step_budget(const std::string         &name,
                                const std::string         &estimate,
                                double                     steps,
                                double                     max_steps,
                                fmt::format_string<double> budget)
  {
    if (!(steps <= max_steps))
      throw std::invalid_argument(fmt::format("{}: the estimate ({}) exceeds the step budget {}",
                                              name,
                                              estimate,
                                              fmt::format(budget, max_steps)));
  }

  /// The key `max_steps`: the largest number of time steps of a case (no unit, >= 1); `doc` says
  /// how the steps are counted and what the refusal reports.
  template <class Io>
  void visit_max_steps(Io &io, double &max_steps, std::string_view doc)
  {
    io.quantity("max_steps", max_steps, "", doc, io::Range::at_least(1.0));
  }
} // namespace kimp::app
