// OpenSees input of the fitted impact laws: ViscoelasticGap, ElasticPPGap, JankowskiImpact,
// Hertzdamp and ImpactMaterial (Muthukumar's bilinear approximation of the Hertz law).
#include "app/export/opensees_export.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "app/export/opensees_wall_export.h"
#include "app/laws/k_table.h"
#include "base/logging.h"
#include "io/summary.h"
#include "lumped/laws/law_traits.h"

namespace kimp::app
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// One material: OpenSees type, its arguments (numbers as text) and a comment.
    struct Material
    {
      std::string              type;
      std::vector<std::string> arguments;
      std::string              comment;
    };

    /// n of the Hertz materials (JankowskiImpact, Hertzdamp, ImpactMaterial): the Jankowski law's.
    double hertz_exponent()
    {
      return lumped::law_traits("jankowski").default_exponent;
    }

    /// n of the Kelvin-Voigt materials (ViscoelasticGap, ElasticPPGap).
    double kelvin_voigt_exponent()
    {
      return lumped::law_traits("kelvin_voigt").default_exponent;
    }

    std::vector<Material> materials(const OpenSeesLawInput &in, const OpenSeesParameters &p)
    {
      std::vector<Material> out;
      const std::string     gap = opensees_number(-in.gap);
      if (in.k_kelvin_voigt)
      {
        const double k = *in.k_kelvin_voigt;
        out.push_back({"ViscoelasticGap",
                       {opensees_number(k), opensees_number(p.kv_c), gap},
                       fmt::format("Kelvin-Voigt: K = k_KV, C = 2 xi sqrt(K m_eff), xi = -ln(e)/"
                                   "sqrt(pi^2 + ln^2 e) = {:.6g}",
                                   p.kv_xi)});
        out.push_back(
          {"ElasticPPGap",
           {opensees_number(k), opensees_number(-p.pp_yield_force), gap, "0.0"},
           fmt::format("Kelvin-Voigt spring without dashpot: E = k_KV, Fy = k_KV x 10 "
                       "x {:.4g} m (10 x the undamped peak indentation v sqrt(m_eff/k): "
                       "stays elastic), eta = 0",
                       p.kv_delta_max)});
      }
      if (in.k_hertz)
      {
        const double k = *in.k_hertz;
        out.push_back({"JankowskiImpact",
                       {opensees_number(k),
                        opensees_number(p.jankowski_xi),
                        opensees_number(in.effective_mass),
                        gap,
                        opensees_number(hertz_exponent())},
                       "Jankowski: Kh = k_J, xi = (9 sqrt(5)/2)(1 - e^2)/(e (e (9 pi - 16) + 16)), "
                       "Meff, n = 1.5"});
        out.push_back({"Hertzdamp",
                       {opensees_number(k),
                        opensees_number(p.hertzdamp_xi_norm),
                        gap,
                        opensees_number(hertz_exponent())},
                       fmt::format("Hertzdamp: Kh = k_J, xiNorm = 3 (1 - e^2)/4 (kimp's hertzdamp "
                                   "law; Ye et al.'s 8 (1 - e)/(5 e) = {:.6g})",
                                   p.hertzdamp_xi_norm_ye)});
        out.push_back(
          {"ImpactMaterial",
           {opensees_number(p.k1), opensees_number(p.k2), opensees_number(-p.delta_y), gap},
           fmt::format("Muthukumar: delta_m = (5 m_eff v^2/(4 k_J))^(2/5) = {:.6g} m, "
                       "K_eff = k_J sqrt(delta_m) = {:.6g} N/m, dE = k_J delta_m^2.5 "
                       "(1 - e^2)/2.5 = {:.6g} J, delta_y = a delta_m (a = {:.3g}), "
                       "K1 = K_eff + dE/(a delta_m^2), K2 = K_eff - dE/((1 - a) "
                       "delta_m^2)",
                       p.delta_m,
                       p.k_eff,
                       p.energy,
                       in.yield_ratio)});
      }
      return out;
    }

    std::string header(const OpenSeesLawInput &in, const char *form)
    {
      std::string h;
      const auto  line = [&](const std::string &text)
      { h += (text.empty() ? std::string("#") : "# " + text) + "\n"; };
      line(fmt::format("kimp export-opensees: fitted impact laws as OpenSees uniaxial materials "
                       "({})",
                       form));
      line("Units: N, m, s (stiffness N/m or N/m^1.5, damping N*s/m, mass kg, energy J).");
      line("Gap and yield displacement are negative: every material is a compression-only gap.");
      line("Use them in a zeroLength element between the isolation level and the moat wall.");
      line("");
      line("Parameters and where they come from:");
      const std::string k_source = in.source.empty() ? std::string("given explicitly") : in.source;
      if (in.k_kelvin_voigt)
        line(fmt::format("  k_KV = {} N/m (= {:.6g} kN/mm): {}",
                         opensees_number(*in.k_kelvin_voigt),
                         *in.k_kelvin_voigt * 1e-6,
                         k_source));
      if (in.k_hertz)
        line(fmt::format("  k_J = {} N/m^1.5 (= {:.6g} kN/mm^1.5): {}",
                         opensees_number(*in.k_hertz),
                         *in.k_hertz * 1e-3 * std::pow(1e-3, 1.5),
                         k_source));
      line(fmt::format("  e = {} (coefficient of restitution): {}",
                       opensees_number(in.cor),
                       in.cor_source));
      line(fmt::format("  m_eff = {} kg (m1 m2/(m1 + m2) of the contact): {}",
                       opensees_number(in.effective_mass),
                       in.effective_mass_source));
      line(fmt::format("  v_imp = {} m/s (impact velocity, for ImpactMaterial's delta_m): {}",
                       opensees_number(in.impact_velocity),
                       in.impact_velocity_source));
      line(fmt::format("  gap = {} m: {}", opensees_number(in.gap), in.gap_source));
      line(fmt::format("  a = {} (ImpactMaterial delta_y/delta_m, Muthukumar)",
                       opensees_number(in.yield_ratio)));
      line("");
      return h;
    }

    /// How a language writes a material command: `indent` `open` TYPE `after_type` TAG, then
    /// `separator` before each argument, then `close`.
    struct CommandSyntax
    {
      const char *indent;
      const char *open;
      const char *after_type;
      const char *separator;
      const char *close;
    };

    /// The materials of `in` as commands of `syntax`, each after its comment line, tagged from
    /// in.first_tag.
    std::string material_commands(const OpenSeesLawInput   &in,
                                  const OpenSeesParameters &p,
                                  const CommandSyntax      &syntax)
    {
      std::string out;
      int         tag = in.first_tag;
      for (const Material &material : materials(in, p))
      {
        out += std::string("\n") + syntax.indent + "# " + material.comment + "\n";
        out +=
          syntax.indent + (syntax.open + material.type) + syntax.after_type + std::to_string(tag++);
        for (const std::string &a : material.arguments)
          out += syntax.separator + a;
        out += syntax.close;
      }
      return out;
    }
  } // namespace

  OpenSeesParameters opensees_parameters(const OpenSeesLawInput &in)
  {
    const auto require = [](bool ok, const std::string &what)
    {
      if (!ok)
        throw std::invalid_argument("export-opensees: " + what);
    };
    require(!in.k_kelvin_voigt || (std::isfinite(*in.k_kelvin_voigt) && *in.k_kelvin_voigt > 0.0),
            "k_KV must be > 0");
    require(!in.k_hertz || (std::isfinite(*in.k_hertz) && *in.k_hertz > 0.0), "k_J must be > 0");
    require(in.k_kelvin_voigt || in.k_hertz, "no k given (neither a k table nor --k-kv/--k-hertz)");
    require(in.cor > 0.0 && in.cor <= 1.0, fmt::format("COR = {} must be in (0, 1]", in.cor));
    require(!std::isnan(in.effective_mass),
            "the effective mass of the contact is not known: give --effective-mass (m_eff = m1 "
            "m2/(m1 + m2) of the building's isolation level and the wall), or export from a "
            "study directory, whose building gives it");
    require(std::isfinite(in.effective_mass) && in.effective_mass > 0.0,
            "effective mass must be > 0");
    require(std::isfinite(in.impact_velocity) && in.impact_velocity > 0.0,
            "impact velocity must be > 0");
    require(std::isfinite(in.gap) && in.gap > 0.0, "gap must be > 0");
    require(in.yield_ratio > 0.0 && in.yield_ratio < 1.0, "yield ratio a must be in (0, 1)");

    OpenSeesParameters p;
    const double       e = in.cor, m = in.effective_mass, v = in.impact_velocity;
    const double       ln_e = std::log(e);
    p.kv_xi                 = -ln_e / std::sqrt(pi * pi + ln_e * ln_e);
    if (in.k_kelvin_voigt)
    {
      const double k   = *in.k_kelvin_voigt;
      p.kv_c           = 2.0 * p.kv_xi * std::sqrt(k * m);
      p.kv_delta_max   = v * std::sqrt(m / k);
      p.pp_yield_force = k * 10.0 * p.kv_delta_max;
    }
    p.jankowski_xi =
      9.0 * std::sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * pi - 16.0) + 16.0));
    p.hertzdamp_xi_norm    = 3.0 * (1.0 - e * e) / 4.0;
    p.hertzdamp_xi_norm_ye = 8.0 * (1.0 - e) / (5.0 * e);
    if (in.k_hertz)
    {
      const double k = *in.k_hertz, n = hertz_exponent(), a = in.yield_ratio;
      p.delta_m = std::pow((n + 1.0) * m * v * v / (2.0 * k), 1.0 / (n + 1.0));
      p.energy  = k * std::pow(p.delta_m, n + 1.0) * (1.0 - e * e) / (n + 1.0);
      p.k_eff   = k * std::sqrt(p.delta_m);
      p.delta_y = a * p.delta_m;
      p.k1      = p.k_eff + p.energy / (a * p.delta_m * p.delta_m);
      p.k2      = p.k_eff - p.energy / ((1.0 - a) * p.delta_m * p.delta_m);
      require(p.k2 > 0.0,
              fmt::format("ImpactMaterial K2 = {:.4g} N/m <= 0 (COR {} too low for a = {}; "
                          "raise the COR or lower a)",
                          p.k2,
                          e,
                          a));
    }
    return p;
  }

  std::string opensees_tcl(const OpenSeesLawInput &in)
  {
    const OpenSeesParameters p = opensees_parameters(in);
    return header(in, "Tcl") +
           "# Runs on its own (OpenSees opensees_impact.tcl): it starts a 1-D model. To source it "
           "into\n# a model of yours, set kimp_own_model 1 first: your model builder is then "
           "kept.\nif {![info exists kimp_own_model]} {\n    model basic -ndm 1 -ndf 1\n}\n" +
           material_commands(in, p, {"", "uniaxialMaterial ", " ", " ", "\n"});
  }

  std::string opensees_python(const OpenSeesLawInput &in)
  {
    const OpenSeesParameters p = opensees_parameters(in);
    return header(in, "OpenSeesPy") +
           "# Runs on its own (python3 opensees_impact.py): it starts a 1-D model. In a model of "
           "yours:\n# from opensees_impact import define_impact_materials, then call it after "
           "your ops.model().\nimport openseespy.opensees as ops\n\n\n"
           "def define_impact_materials():\n"
           "    \"\"\"Define the impact materials in the current OpenSees model.\"\"\"" +
           material_commands(in, p, {"    ", "ops.uniaxialMaterial('", "', ", ", ", ")\n"}) +
           "\n\nif __name__ == \"__main__\":\n    ops.wipe()\n    ops.model('basic', '-ndm', 1, "
           "'-ndf', 1)\n    define_impact_materials()\n";
  }

  namespace
  {
    /// summary.json of the source's directory (null when it has none or it is unreadable).
    nlohmann::json source_summary(const std::filesystem::path &source)
    {
      const std::filesystem::path dir =
        std::filesystem::is_directory(source) ? source : source.parent_path();
      std::ifstream in(dir / "summary.json");
      if (!in)
        return nullptr;
      nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
      return j.is_discarded() || !j.is_object() ? nlohmann::json(nullptr) : j;
    }

    /// The number at `pointer` of `j`, if there is one.
    std::optional<double> json_number(const nlohmann::json &j, const char *pointer)
    {
      const nlohmann::json::json_pointer at(pointer);
      if (j.is_object() && j.contains(at) && j.at(at).is_number())
        return j.at(at).get<double>();
      return std::nullopt;
    }

    /// The one wall height of a site's study (its k table holds one): the one to export.
    double only_wall_height(const std::filesystem::path &source)
    {
      const KTable        table = read_k_table(source);
      std::vector<double> heights;
      for (const KTableRow &r : table.rows)
        if (std::find(heights.begin(), heights.end(), r.wall_height) == heights.end())
          heights.push_back(r.wall_height);
      if (heights.size() != 1)
      {
        std::string list;
        for (const double h : heights)
          list += (list.empty() ? "" : ", ") + fmt::format("{:g} m", h);
        throw std::invalid_argument("export-opensees: --wall-height is needed: " +
                                    table.file.string() + " holds the heights " + list);
      }
      return heights.front();
    }

    /// `--record`: the k not given from the record's consistent k at `wall_height` of a study's
    /// directory; returns the record's impact velocity, if known.
    std::optional<double> take_record_k(const ExportOpenSeesOptions &options,
                                        const std::string           &command,
                                        double                       wall_height,
                                        OpenSeesLawInput            &in)
    {
      const std::string &record = options.settings.record;
      if (command != "study")
        throw std::invalid_argument("export-opensees: --record needs the output directory of "
                                    "`kimp study` (" +
                                    options.source.string() + " is not one)");
      const std::filesystem::path dir = std::filesystem::is_directory(options.source) ?
                                          options.source :
                                          options.source.parent_path();
      const RecordK               k   = read_consistent_k(dir, record, wall_height);
      if (!in.k_kelvin_voigt && std::isfinite(k.kelvin_voigt_total))
        in.k_kelvin_voigt = k.kelvin_voigt_total;
      if (!in.k_hertz && std::isfinite(k.jankowski_total))
        in.k_hertz = k.jankowski_total;
      in.source = fmt::format("the consistent k of record '{}' at wall height {} m ({}: the "
                              "k(H, v) of the building run's own impact velocity)",
                              record,
                              wall_height,
                              k.file.string());
      if (std::isfinite(k.impact_velocity))
        return k.impact_velocity;
      return std::nullopt;
    }

    /// The k neither given nor taken from a record: the k table's at `wall_height`.
    void take_table_k(const std::filesystem::path &source, double wall_height, OpenSeesLawInput &in)
    {
      if (in.k_kelvin_voigt && in.k_hertz)
        return;
      const KTable table = read_k_table(source);
      if (!in.k_kelvin_voigt)
        in.k_kelvin_voigt = table.stiffness(wall_height, kelvin_voigt_exponent());
      if (!in.k_hertz)
        in.k_hertz = table.stiffness(wall_height, hertz_exponent());
      in.source = (in.source.empty() ? std::string() : in.source + "; the rest from ") +
                  fmt::format("{} at wall height {} m (k_total = k per metre x building "
                              "width, linearly interpolated between the table's heights)",
                              table.file.string(),
                              wall_height);
    }

    /// COR, m_eff and v_imp: given, else from the source's summary.json (`command` wrote it) or
    /// the record, else the defaults.
    void take_contact(const ExportOpenSeesOptions &options,
                      const nlohmann::json        &summary,
                      const std::string           &command,
                      std::optional<double>        record_velocity,
                      OpenSeesLawInput            &in)
    {
      const ExportOpenSeesSettings &s    = options.settings;
      const std::string             file = (std::filesystem::is_directory(options.source) ?
                                              options.source / "summary.json" :
                                              options.source.parent_path() / "summary.json")
                                 .string();
      // COR: the one the source's k was fitted at.
      const std::optional<double> fitted_cor =
        command == "study" ? json_number(summary, "/contact/cor") :
        command == "fit"   ? json_number(summary, "/options/cor") :
                             std::nullopt;
      if (s.cor)
        in.cor = *s.cor;
      else if (fitted_cor)
      {
        in.cor        = *fitted_cor;
        in.cor_source = "the COR the k was fitted at (" + file + ")";
      }
      else
        in.cor_source = "default (the thesis' COR)";
      // m_eff: the study's building against its wall; never a building the user did not give.
      if (s.effective_mass)
        in.effective_mass = *s.effective_mass;
      else if (const auto m = json_number(summary, "/contact/effective_mass"))
      {
        in.effective_mass = *m;
        in.effective_mass_source =
          fmt::format("the study's isolation level {:.6g} t against its wall {:.6g} t ({})",
                      json_number(summary, "/contact/isolation_mass").value_or(std::nan("")) / 1e3,
                      json_number(summary, "/contact/wall_mass").value_or(std::nan("")) / 1e3,
                      file);
      }
      // v_imp: the record's own, else the study's reference velocity.
      if (s.impact_velocity)
        in.impact_velocity = *s.impact_velocity;
      else if (record_velocity)
      {
        in.impact_velocity = *record_velocity;
        in.impact_velocity_source =
          "the impact velocity of record '" + s.record + "' (" +
          (std::filesystem::path(file).parent_path() / "consistent_k.csv").string() + ")";
      }
      else if (const auto v =
                 command == "study" ? json_number(summary, "/reference_velocity") : std::nullopt)
      {
        in.impact_velocity        = *v;
        in.impact_velocity_source = "the study's reference velocity (" + file + ")";
      }
      else
        in.impact_velocity_source = "default";
    }
  } // namespace

  OpenSeesLawInput resolve_export_input(const ExportOpenSeesOptions &options)
  {
    const ExportOpenSeesSettings &s = options.settings;
    OpenSeesLawInput              in;
    in.k_kelvin_voigt = s.k_kelvin_voigt;
    in.k_hertz        = s.k_hertz;
    in.gap            = s.gap;
    in.yield_ratio    = s.yield_ratio;
    in.first_tag      = s.first_tag;
    in.gap_source     = "given (--gap, default 15 cm)";
    nlohmann::json        summary;
    std::string           command;
    std::optional<double> record_velocity;
    if (options.source.empty())
    {
      if (!s.record.empty())
        throw std::invalid_argument("export-opensees: --record needs a study directory");
    }
    else
    {
      const double wall_height = s.wall_height ? *s.wall_height : only_wall_height(options.source);
      summary                  = source_summary(options.source);
      command                  = summary.is_object() ? summary.value("command", "") : "";
      if (!s.record.empty())
        record_velocity = take_record_k(options, command, wall_height, in);
      take_table_k(options.source, wall_height, in);
    }
    take_contact(options, summary, command, record_velocity, in);
    return in;
  }

  void run_export_opensees(ExportOpenSeesOptions options)
  {
    const auto                   start       = std::chrono::steady_clock::now();
    const OpenSeesLawInput       laws        = resolve_export_input(options);
    const std::optional<double> &wall_height = options.settings.wall_height;
    const std::string            tcl = opensees_tcl(laws); // validates before the directory is made
    const std::string            python = opensees_python(laws);
    const io::OutputDir          output(options.output);
    io::write_text_atomic(output.file("opensees_impact.tcl"), tcl);
    io::write_text_atomic(output.file("opensees_impact.py"), python);
    if (!options.lumped_scene.empty())
      write_opensees_walls(options.lumped_scene,
                           output.file("opensees_walls.tcl"),
                           output.file("opensees_walls.py"));

    const OpenSeesParameters p = opensees_parameters(laws);
    nlohmann::ordered_json   j = io::summary_preamble("export-opensees");
    j["source"] =
      laws.source.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(laws.source);
    j["k_table"] = options.source.empty() ? nlohmann::ordered_json() :
                                            nlohmann::ordered_json(options.source.string());
    j["wall_height"] =
      wall_height ? nlohmann::ordered_json(*wall_height) : nlohmann::ordered_json();
    j["units"]          = {{"wall_height", "m"},
                           {"k_kelvin_voigt", "N/m"},
                           {"k_hertz", "N/m^1.5"},
                           {"effective_mass", "kg"},
                           {"impact_velocity", "m/s"},
                           {"gap", "m"},
                           {"kv_c", "N*s/m"},
                           {"kv_delta_max", "m"},
                           {"pp_yield_force", "N"},
                           {"delta_m", "m"},
                           {"energy", "J"},
                           {"k_eff", "N/m"},
                           {"delta_y", "m"},
                           {"k1", "N/m"},
                           {"k2", "N/m"},
                           {"wall_time", "s"}};
    const auto optional = [](const std::optional<double> &v)
    { return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(); };
    j["input"]      = {{"k_kelvin_voigt", optional(laws.k_kelvin_voigt)},
                       {"k_hertz", optional(laws.k_hertz)},
                       {"cor", laws.cor},
                       {"effective_mass", laws.effective_mass},
                       {"impact_velocity", laws.impact_velocity},
                       {"gap", laws.gap},
                       {"yield_ratio", laws.yield_ratio},
                       {"first_tag", laws.first_tag},
                       {"record", options.settings.record}};
    j["sources"]    = {{"k", laws.source.empty() ? std::string("given") : laws.source},
                       {"cor", laws.cor_source},
                       {"effective_mass", laws.effective_mass_source},
                       {"impact_velocity", laws.impact_velocity_source},
                       {"gap", laws.gap_source}};
    j["parameters"] = {{"kv_xi", p.kv_xi},
                       {"kv_c", p.kv_c},
                       {"kv_delta_max", p.kv_delta_max},
                       {"pp_yield_force", p.pp_yield_force},
                       {"jankowski_xi", p.jankowski_xi},
                       {"hertzdamp_xi_norm", p.hertzdamp_xi_norm},
                       {"hertzdamp_xi_norm_ye", p.hertzdamp_xi_norm_ye},
                       {"delta_m", p.delta_m},
                       {"energy", p.energy},
                       {"k_eff", p.k_eff},
                       {"delta_y", p.delta_y},
                       {"k1", p.k1},
                       {"k2", p.k2}};
    j["files"]      = {"opensees_impact.tcl", "opensees_impact.py"};
    if (!options.lumped_scene.empty())
      j["files"].insert(j["files"].end(), {"opensees_walls.tcl", "opensees_walls.py"});
    j["wall_time"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    io::write_text_atomic(output.file("summary.json"), j.dump(2) + "\n");
    base::logger().info("export-opensees: wrote {}, {} and {}",
                        output.file("opensees_impact.tcl").string(),
                        output.file("opensees_impact.py").string(),
                        output.file("summary.json").string());
  }
} // namespace kimp::app
