// YAML scene texts that several suites run: plain strings, no kimp library needed.
#pragma once

#include <string>

namespace kimp::testing
{
  /**
   * A small lumped scene: walls at 4 cm on both sides, 6 s of the synthetic motion at
   * dt = 1e-4 s with histories every `output_interval`, and two cases, mkv and hysteretic
   * (k = 750 kN/mm^1.5). `integration_extra` is added to the integration section as it stands
   * (YAML lines, e.g. "  companion: true\n").
   */
  inline std::string two_case_walled_scene(const std::string &output_interval,
                                           const std::string &integration_extra = "")
  {
    return "walls:\n"
           "  left:\n"
           "    gap: \"4 cm\"\n"
           "  right:\n"
           "    gap: \"4 cm\"\n"
           "ground_motion:\n"
           "  record: synthetic\n"
           "  duration: \"6 s\"\n"
           "integration:\n"
           "  dt: \"1e-4 s\"\n"
           "  output_interval: \"" +
           output_interval + "\"\n" + integration_extra +
           "cases:\n"
           "  - name: mkv\n"
           "  - name: hysteretic\n"
           "    law: hysteretic\n"
           "    k: \"750 kN/mm^1.5\"\n";
  }
} // namespace kimp::testing
