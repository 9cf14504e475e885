// The step budget of a run: a run whose estimate exceeds it is refused before it starts.
#pragma once

#include <fmt/format.h>
#include <stdexcept>
#include <string>

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
} // namespace kimp::app
