// `kimp export-opensees`: the fitted impact laws as OpenSees uniaxial materials (Tcl and
// OpenSeesPy), from a study's k table or explicit k (docs/physics.md §4 "OpenSees export").
#pragma once

#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "app/laws/cor_key.h"
#include "app/laws/impact_scene.h"
#include "app/lumped/building_keys.h"
#include "io/scene_io.h"
#include "lumped/laws/law_traits.h"

namespace kimp::app
{
  /// What is exported, SI (N, m, s, kg); k for the whole contact (k_per_metre · W).
  struct OpenSeesLawInput
  {
    std::optional<double> k_kelvin_voigt; ///< N/m: ViscoelasticGap, ElasticPPGap
    std::optional<double> k_hertz;        ///< N/m^1.5: JankowskiImpact, Hertzdamp, ImpactMaterial
    double                cor = lumped::thesis_cor; ///< coefficient of restitution, (0, 1]
    /// m_eff = m1·m2/(m1 + m2) of the contact, kg (> 0; NaN: not known, refused).
    double      effective_mass  = std::numeric_limits<double>::quiet_NaN();
    double      impact_velocity = 1.0;  ///< v_imp, m/s: δ_m of ImpactMaterial
    double      gap             = 0.15; ///< clear gap, m (written negative: compression only)
    double      yield_ratio     = 0.1;  ///< a = δ_y/δ_m of ImpactMaterial (Muthukumar: 0.1)
    int         first_tag       = 1;    ///< tag of the first material
    std::string source;                 ///< where k comes from, for the header comment
    /// Where each other parameter comes from, for the header comment ("given", "the study's
    /// building (summary.json)", ...).
    std::string cor_source             = "given";
    std::string effective_mass_source  = "given";
    std::string impact_velocity_source = "given";
    std::string gap_source             = "given";
  };

  /// The material parameters, SI, from the formulas of docs/physics.md §1 and §4.
  struct OpenSeesParameters
  {
    double kv_xi                = 0.0; ///< −ln e/sqrt(π² + ln² e)
    double kv_c                 = 0.0; ///< 2ξ·sqrt(k·m_eff), N·s/m
    double kv_delta_max         = 0.0; ///< v·sqrt(m_eff/k), m (undamped peak indentation)
    double pp_yield_force       = 0.0; ///< ElasticPPGap Fy = k·10·kv_delta_max, N (stays elastic)
    double jankowski_xi         = 0.0; ///< (9√5/2)(1 − e²)/(e(e(9π − 16) + 16))
    double hertzdamp_xi_norm    = 0.0; ///< ξ̄ = 3(1 − e²)/4 (kimp's hertzdamp, Muthukumar)
    double hertzdamp_xi_norm_ye = 0.0; ///< ξ̄ = 8(1 − e)/(5e) (Ye et al., OpenSees' suggestion)
    double delta_m              = 0.0; ///< (5·m_eff·v²/(4·k_h))^(2/5), m (Hertz peak, n = 1.5)
    double energy               = 0.0; ///< ΔE = k_h·δ_m^2.5·(1 − e²)/2.5, J
    double k_eff                = 0.0; ///< k_h·sqrt(δ_m), N/m
    double delta_y              = 0.0; ///< a·δ_m, m
    double k1                   = 0.0; ///< K_eff + ΔE/(a·δ_m²), N/m
    double k2                   = 0.0; ///< K_eff − ΔE/((1 − a)·δ_m²), N/m
  };

  /// @throws std::invalid_argument for k <= 0, COR outside (0, 1], m_eff, v or gap <= 0, a
  ///         outside (0, 1), or K2 <= 0 (a too large for the COR).
  OpenSeesParameters opensees_parameters(const OpenSeesLawInput &input);

  /// Tcl commands (`uniaxialMaterial ViscoelasticGap 1 ...`) with a header stating units and
  /// source.
  std::string opensees_tcl(const OpenSeesLawInput &input);
  /// The same as OpenSeesPy calls (`ops.uniaxialMaterial('ViscoelasticGap', 1, ...)`).
  std::string opensees_python(const OpenSeesLawInput &input);

  /// The settings of `kimp export-opensees` (its flags). A value not given comes from the k
  /// source where it holds one (OpenSeesLawInput's *_source says which), else its default.
  struct ExportOpenSeesSettings
  {
    std::optional<double> wall_height; ///< m, where the k table is interpolated
    /// With a study directory: export the consistent k of this record (consistent_k.csv)
    /// instead of the k table's k at the reference velocity ("" = the k table).
    std::string           record;
    std::optional<double> k_kelvin_voigt; ///< N/m (wins over the source)
    std::optional<double> k_hertz;        ///< N/m^1.5 (wins over the source)
    std::optional<double> cor;            ///< default: the source's fitting COR, else thesis_cor

    std::optional<double> effective_mass;  ///< kg; default: the study's building (required
                                           ///< without one)
    std::optional<double> impact_velocity; ///< m/s; default: the record's or the study's
                                           ///< reference velocity, else 1 m/s
    double gap         = 0.15;
    double yield_ratio = 0.1;
    int    first_tag   = 1;
  };

  template <class Io>
  void visit(Io &io, ExportOpenSeesSettings &s)
  {
    visit_k_source_height(io,
                          s.wall_height,
                          "wall height at which the k source is interpolated (needed when it "
                          "holds several heights)");
    io.text("record",
            s.record,
            "with a study directory: export the consistent k of this record at wall_height "
            "(consistent_k.csv: the k of its own impact velocity) instead of the k table's");
    io.quantity("k_kv",
                s.k_kelvin_voigt,
                "kN/mm",
                "Kelvin-Voigt k for the whole contact (wins over the k source)",
                io::Range::positive());
    visit_hertz_stiffness(
      io,
      "k_hertz",
      s.k_hertz,
      "Jankowski/Hertz k (n = 1.5) for the whole contact (wins over the k source)");
    visit_cor(io,
              s.cor,
              "coefficient of restitution e (default: the COR the source's k was fitted at, "
              "else the thesis' COR)");
    visit_mass(io,
               "effective_mass",
               s.effective_mass,
               "m_eff = m1 m2/(m1 + m2) of the contact (default: the study's isolation level "
               "against its wall; required when the source has no building)");
    io.quantity("impact_velocity",
                s.impact_velocity,
                "m/s",
                "design impact velocity v_imp, ImpactMaterial's delta_m (default: the record's "
                "with --record, else the study's reference velocity, else 1 m/s)",
                io::Range::positive());
    visit_moat_gap(io, "gap", s.gap, "clear gap to the wall");
    io.quantity("yield_ratio",
                s.yield_ratio,
                "",
                "ImpactMaterial a = delta_y/delta_m (Muthukumar: 0.1)",
                io::Range::greater(0.0).and_less(1.0));
    io.integer("first_tag", s.first_tag, "tag of the first material", 1, 1000000000);
  }

  /// Options of `kimp export-opensees`.
  struct ExportOpenSeesOptions
  {
    /// k_table.csv or a study directory, fit_table.csv or a `kimp fit` directory ("" = explicit k)
    std::filesystem::path  source;
    std::filesystem::path  output;   ///< directory of opensees_impact.tcl / .py
    ExportOpenSeesSettings settings; ///< the flags
    /// A `kimp lumped` scene whose yielding walls are written too
    /// (app/export/opensees_wall_export.h);
    /// "" = none.
    std::filesystem::path lumped_scene;
  };

  /**
   * Resolve the input (k from the source at wall_height, or the record's consistent k, where not
   * given; COR, m_eff and v_imp from the source's summary.json where not given), then write
   * DIR/opensees_impact.tcl, DIR/opensees_impact.py and DIR/summary.json.
   * @throws std::invalid_argument for a missing k or m_eff, an unreadable source or a height
   *         outside it.
   */
  void run_export_opensees(ExportOpenSeesOptions options);

  /**
   * The input run_export_opensees() exports: the flags given, the rest from the source (k
   * table or record's consistent k at wall_height; COR, m_eff and v_imp from its summary.json),
   * each with where it came from.
   * @throws std::invalid_argument as run_export_opensees().
   */
  OpenSeesLawInput resolve_export_input(const ExportOpenSeesOptions &options);
} // namespace kimp::app
