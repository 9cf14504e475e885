// The one home of what kimp knows about each impact law 1-7 of docs/physics.md §1 besides its
// physics: scene name, number, default exponent, the parameters it reads (and so whether it uses
// the COR or the effective mass), and how to make it. Read by the factory, the scene reader, the
// fitter, the OpenSees export and (through the bindings) the Python package.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lumped/laws/force_law.h"

namespace kimp::lumped
{
  struct ForceLawSpec;

  /// The thesis' nominal coefficient of restitution of concrete on concrete (docs/physics.md §4),
  /// the default COR of every law, scene and fit.
  inline constexpr double thesis_cor = 0.7;

  /// One parameter a law reads from its ForceLawSpec, as scene files and Python name it.
  struct LawParameter
  {
    std::string_view
      name; ///< keyword: "k", "cor", "m_eff", "exponent", "ye", "a1", "delta_u", "k_w"
    std::string_view unit; ///< SI unit; "N/m^n": k for the law's exponent n; "" dimensionless;
                           ///< "flag": a yes/no option
    bool required = false; ///< no default: must be given (k)
    /// Default in `unit` (flag: 0 or 1); unset and not required: absent by default (a1).
    /// The exponent's default is the law's default_exponent, the COR's thesis_cor.
    std::optional<double> default_value;
    std::string_view      meaning;
  };

  /// Traits of one impact law; a new law is its header and source, one entry of law_traits() and
  /// its contract test (docs/architecture.md "Force laws").
  struct LawTraits
  {
    std::string_view name;       ///< scene name, e.g. "kelvin_voigt" (= the law's law_name)
    int              number = 0; ///< law number of docs/physics.md §1 (1-7)
    std::string_view class_name; ///< Python class of kimp.laws, e.g. "KelvinVoigt"
    std::string_view summary;    ///< one paragraph: the force and k's unit
    double           default_exponent = 1.0;   ///< n of k's unit N/m^n unless the spec gives one
    bool             fittable         = true;  ///< the FEM fitter can fit it (fit/fitter.h)
    bool             moat_wall_only   = false; ///< acts only at the moat walls (the bumpers)
    std::vector<LawParameter> parameters;      ///< in the order of Python's keyword arguments
    /// The law made from `spec` (its exponent resolved to the default when unset).
    std::unique_ptr<ForceLaw> (*make)(const ForceLawSpec &spec, double exponent) = nullptr;

    /// Whether the law reads the named parameter.
    bool has_parameter(std::string_view parameter) const;
    /// n is fixed at default_exponent: a spec may not give another one.
    bool fixed_exponent() const { return !has_parameter("exponent"); }
    bool uses_cor() const { return has_parameter("cor"); }
    bool uses_effective_mass() const { return has_parameter("m_eff"); }
    /// n for an exponent given (or not) by a scene or spec.
    double exponent(const std::optional<double> &given) const
    {
      return given.value_or(default_exponent);
    }
  };

  /// Every law, in the order of docs/physics.md §1.
  const std::vector<LawTraits> &law_traits();

  /// The law named `name`, nullptr if there is none.
  const LawTraits *find_law_traits(std::string_view name);

  /**
   * The law named `name`.
   * @throws std::invalid_argument "<what>: law = 'NAME' (must be one of 'linear' ...)" for an
   *         unknown name.
   */
  const LawTraits &law_traits(std::string_view name, std::string_view what = "force law");

  /// "linear, kelvin_voigt, ..." (or quoted: "'linear' 'kelvin_voigt' ..."), the laws' names.
  std::string law_name_list(bool quoted = false);
} // namespace kimp::lumped
