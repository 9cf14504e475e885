// Section `impact` of a scene: an impact law of docs/physics.md §1 (laws 1-7) with its stiffness k
// (as text with a unit, from a study's k table, or handed over in SI) and the rubber bumpers of
// law 7 (thesis ch. 6). Shared by `kimp lumped` (walls and neighbours) and `kimp collide`.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "app/laws/cor_key.h"
#include "app/laws/wall_keys.h"
#include "io/scene_io.h"
#include "lumped/laws/force_law_factory.h"

namespace kimp::app
{
  /**
   * An impact law: name, stiffness k as text with a unit matching the law's exponent n
   * (N/m^n: "2500 kN/mm" for n = 1, "750 kN/mm^1.5" for n = 1.5), COR and options.
   */
  struct ImpactLawScene
  {
    std::string law = "modified_kelvin_voigt";
    std::string k   = "2500 kN/mm";
    /// k in SI (N/m^n) handed over by a program (the study's fitted k); when set it is used
    /// instead of the text `k`, so the number is not rounded through text. Not a scene key.
    std::optional<double> k_si;
    std::optional<double> exponent;
    double                cor          = lumped::thesis_cor;
    bool                  hertzdamp_ye = false;
    std::optional<double> a1;
  };

  /// An impact stiffness key: a text with a unit of N/m^n, n the law's exponent (the unit is
  /// checked by validate_law() and validate_bumper()), > 0; "" where the key admits it (`doc`).
  template <class Io>
  void visit_impact_stiffness(Io &io, std::string_view key, std::string &k, std::string_view doc)
  {
    io.quantity_text(key, k, "N/m^n", doc, io::Range::positive());
  }

  /// An impact stiffness of a Hertz law (exponent n = 1.5: hysteretic, Jankowski, Hertzdamp)
  /// given as a number (shown in kN/mm^1.5, > 0); `doc` says of which law.
  template <class Io, class Q>
  void visit_hertz_stiffness(Io &io, std::string_view key, Q &k, std::string_view doc)
  {
    io.quantity(key, k, "kN/mm^1.5", doc, io::Range::positive());
  }

  /// The key `exponent`: the impact exponent n (no unit, >= 1); `doc` says whose.
  template <class Io>
  void visit_exponent(Io &io, std::optional<double> &exponent, std::string_view doc)
  {
    io.quantity("exponent", exponent, "", doc, io::Range::at_least(1.0));
  }

  /// The key `wall_height`: the height of the moat wall (visit_wall_height()) at which a k source
  /// (app/laws/k_table.h) is interpolated; `doc` says which source and what a null means.
  template <class Io>
  void visit_k_source_height(Io &io, std::optional<double> &wall_height, std::string_view doc)
  {
    visit_wall_height(io, "wall_height", wall_height, doc);
  }

  template <class Io>
  void visit_law(Io &io, ImpactLawScene &s)
  {
    io.choice("law",
              s.law,
              lumped::force_law_names(),
              "impact law of docs/physics.md §1 (laws 1-7)");
    visit_impact_stiffness(io,
                           "k",
                           s.k,
                           "impact stiffness with a unit of N/m^n for the law's exponent n, e.g. "
                           "\"2500 kN/mm\" (n = 1) or \"750 kN/mm^1.5\" (n = 1.5); unused by "
                           "law bumper (see bumper.k_b)");
    visit_exponent(io,
                   s.exponent,
                   "n for hertzdamp/hysteretic (1.5) and bumper (2.65); fixed for the others");
    visit_cor(io, s.cor, "nominal coefficient of restitution");
    io.flag("hertzdamp_ye", s.hertzdamp_ye, "hertzdamp: Ye et al. (2009) damping instead");
    io.quantity("a1",
                s.a1,
                "s/m",
                "hysteretic/bumper: C_imp = a1 (1 - COR^2) instead of eq. 2.23",
                io::Range::non_negative());
  }

  template <class Io>
  void visit(Io &io, ImpactLawScene &s)
  {
    visit_law(io, s);
  }

  /// Rubber bumpers on the walls (law 7, thesis ch. 6): k_b from the material or given.
  struct BumperScene
  {
    double       thickness       = 0.05;
    double       width           = 0.15;
    double       height          = 0.15;
    unsigned int count           = 4;
    double       ultimate_strain = 0.75;
    double       modulus         = 55835e3; ///< K_r, N/m²
    std::string  k_b             = "";      ///< all bumpers, N/m^n; "" = from the material
    double       wall_stiffness  = 1500e6;  ///< k_w, N/m
    bool         recessed        = false;
  };

  /// A dimension of one bumper (shown in mm, > 0); `doc` says which.
  template <class Io>
  void visit_bumper_size(Io &io, std::string_view key, double &size, std::string_view doc)
  {
    io.quantity(key, size, "mm", doc, io::Range::positive());
  }

  template <class Io>
  void visit(Io &io, BumperScene &s)
  {
    visit_bumper_size(io, "thickness", s.thickness, "bumper thickness t");
    visit_bumper_size(io, "width", s.width, "bumper width (contact area = width x height)");
    visit_bumper_size(io, "height", s.height, "bumper height");
    io.integer("count", s.count, "bumpers in parallel on each wall", 1, 1000);
    io.quantity("ultimate_strain",
                s.ultimate_strain,
                "",
                "epsilon_u: crushed at delta_u = eps_u t",
                io::Range::greater(0.0).and_at_most(1.0));
    io.quantity("modulus",
                s.modulus,
                "kN/m^2",
                "rubber constant K_r of k_st = A K_r / t^n (6.2)",
                io::Range::positive());
    visit_impact_stiffness(io,
                           "k_b",
                           s.k_b,
                           "stiffness of all bumpers, N/m^n (e.g. \"0.36 kN/mm^2.65\"); \"\" = "
                           "2.25 k_st count");
    io.quantity("wall_stiffness",
                s.wall_stiffness,
                "kN/mm",
                "k_w beyond delta_u",
                io::Range::positive());
    io.flag("recessed", s.recessed, "bumpers sit in a recess: the clear gap is not reduced");
  }

  /// Impact law of the walls (and default of the neighbours), with the bumper data of law 7.
  struct ImpactScene : ImpactLawScene
  {
    BumperScene bumper;
    /// A study's k_table.csv (or its output directory): k from the table at `wall_height`
    /// instead of the text `k` (app/laws/k_table.h); "" = use `k`.
    std::string           k_table;
    std::optional<double> wall_height; ///< m, where k_table is interpolated
  };

  template <class Io>
  void visit(Io &io, ImpactScene &s)
  {
    visit_law(io, s);
    io.section("bumper", s.bumper, "rubber bumpers (used when law = bumper)");
    io.text("k_table",
            s.k_table,
            "a study's k_table.csv (or its output directory), path relative to the scene file's "
            "directory: k = k_total of the law's column (n = 1: Kelvin-Voigt, n = 1.5: Jankowski) "
            "interpolated at wall_height, instead of k (\"\" = use k)");
    visit_k_source_height(io,
                          s.wall_height,
                          "with k_table: wall height at which k is interpolated (linearly; "
                          "refused outside the table's heights)");
  }

  /// Exponent n the law will use: the given one or the law's default (1, 1.5 or 2.65).
  double impact_exponent(const ImpactLawScene &law);

  /**
   * k of the walls' law in SI (N/m^n): `k_si` if set, else from `k_table` at `wall_height` if
   * given, else parsed from the text `k`.
   * @throws std::invalid_argument naming impact.k_table's file and impact.wall_height when the
   *         table cannot be read or the height is outside it.
   */
  double impact_stiffness(const ImpactScene &impact);
  /**
   * k of `law` in SI (N/m^n): `law.k_si` if set, else parsed from its text.
   * @throws UnitError when the text is not a quantity of dimension N/m^n.
   */
  double impact_stiffness(const ImpactLawScene &law);

  /// k_b of all bumpers (N/m^n): given, or 2.25·count·A·K_r/t^n (thesis eqs. 6.2-6.3).
  double bumper_stiffness(const ImpactScene &impact);

  /// The lumped::ForceLawSpec of the walls' law (m_eff is set per contact by the model).
  lumped::ForceLawSpec force_law_spec(const ImpactScene &impact);

  /**
   * The rules of one impact law that link its keys (a law with a fixed exponent given one, k's
   * unit against the law's exponent, k > 0); key paths relative to the current section.
   * `bumper_allowed` false refuses law bumper (it acts at the moat walls only).
   */
  void validate_law(const ImpactLawScene &law, io::ValidationContext &ctx, bool bumper_allowed);

  /// The bumpers' k_b against the law's exponent; key paths relative to the impact section.
  void validate_bumper(const ImpactScene &impact, io::ValidationContext &ctx);

  /**
   * `impact` with k_si set from its k_table (if any), so that validate_law() checks the table's
   * k; the table's problems are reported at k_table / wall_height. With `required` false a
   * missing wall_height is not an error (the cases give it).
   */
  ImpactScene
  with_table_stiffness(const ImpactScene &impact, io::ValidationContext &ctx, bool required);
} // namespace kimp::app
