// YAML scene texts that several suites run: plain strings, no kimp library needed.
#pragma once

#include <stdexcept>
#include <string>

namespace kimp::testing
{
  /// `text` with its first `from` replaced by `to`, to derive a scene from another.
  /// @throws std::invalid_argument if `text` has no `from` (the base scene changed).
  inline std::string replaced(std::string text, const std::string &from, const std::string &to)
  {
    const std::size_t at = text.find(from);
    if (at == std::string::npos)
      throw std::invalid_argument("replaced(): '" + from + "' not in the text:\n" + text);
    return text.replace(at, from.size(), to);
  }

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
