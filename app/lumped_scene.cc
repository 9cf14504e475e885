// `kimp lumped` scene: validation rules and the construction of the lumped model (docs/physics.md
// §2-3; bumper stiffness k_b = 2.25·N·A·K_r/t^n, thesis eqs. 6.2-6.3).
#include "app/lumped_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <set>
#include <stdexcept>

#include "app/k_table.h"
#include "fit/fitter.h"
#include "io/units.h"
#include "lumped/excitation/ground_motion.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/bouc_wen_isolator.h"
#include "lumped/isolators/friction_pendulum_isolator.h"
#include "lumped/isolators/linear_isolator.h"
#include "lumped/laws/bumper_law.h"

namespace kimp::app
{
  using namespace kimp::io;
  // The engines and io each name g (lumped includes nothing of kimp): one value.
  static_assert(io::standard_gravity == lumped::standard_gravity,
                "io and lumped must use the same standard gravity");
  namespace
  {
    bool law_has_fixed_exponent(const std::string &law)
    {
      return law == "linear" || law == "kelvin_voigt" || law == "modified_kelvin_voigt" ||
             law == "jankowski";
    }

    bool law_uses_cor(const std::string &law)
    {
      return law != "linear";
    }

    /// Dimension of N/m^n: kg·m^(1−n)·s^−2.
    Dimension stiffness_dimension(const double exponent)
    {
      return Dimension{1.0, 1.0 - exponent, -2.0};
    }

    std::string percent(const double value)
    {
      return format_quantity(value, "%");
    }

    bool is_valid_case_name(const std::string &name)
    {
      if (name.empty())
        return false;
      for (const char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
          return false;
      return true;
    }

    /// Checks of one impact law; key paths relative to the current section.
    void validate_law(const ImpactLawScene &law, ValidationContext &ctx, const bool bumper_allowed)
    {
      const auto &names = lumped::force_law_names();
      if (!ctx.check(std::find(names.begin(), names.end(), law.law) != names.end(),
                     "law",
                     law.law,
                     "must be one of linear, kelvin_voigt, modified_kelvin_voigt, jankowski, "
                     "hertzdamp, hysteretic, bumper"))
        return;
      if (!bumper_allowed)
        ctx.check(law.law != "bumper",
                  "law",
                  law.law,
                  "bumper acts only at the moat walls (use another law for floor contacts)");
      if (law.exponent)
      {
        if (law_has_fixed_exponent(law.law))
          ctx.fail("exponent",
                   format_quantity(*law.exponent, ""),
                   "must be null: law " + law.law + " has a fixed exponent");
        else
          ctx.check(std::isfinite(*law.exponent) && *law.exponent >= 1.0,
                    "exponent",
                    format_quantity(*law.exponent, ""),
                    "must be >= 1");
      }
      if (law_uses_cor(law.law))
      {
        ctx.check(std::isfinite(law.cor) && law.cor > 0.0 && law.cor <= 1.0,
                  "cor",
                  format_quantity(law.cor, ""),
                  "must be in (0, 1]");
      }
      if (law.a1)
        ctx.check(std::isfinite(*law.a1) && *law.a1 >= 0.0,
                  "a1",
                  format_quantity(*law.a1, "s/m"),
                  "must be >= 0");
      if (law.law != "bumper" && law.k_si)
        ctx.check(std::isfinite(*law.k_si) && *law.k_si > 0.0,
                  "k",
                  format_quantity(*law.k_si, "") + " N/m^n",
                  "must be > 0");
      else if (law.law != "bumper")
      {
        const double n = impact_exponent(law);
        try
        {
          const Quantity k = parse_quantity(law.k);
          if (!ctx.check(k.dimension == stiffness_dimension(n),
                         "k",
                         law.k,
                         "law " + law.law + " (n = " + format_quantity(n, "") +
                           ") needs a stiffness in N/m^n, e.g. \"" +
                           (n == 1.0 ? std::string("2500 ") : std::string("750 ")) +
                           fit::stiffness_display_unit(n) + "\""))
            return;
          ctx.check(std::isfinite(k.value) && k.value > 0.0, "k", law.k, "must be > 0");
        }
        catch (const UnitError &error)
        {
          ctx.fail("k", law.k, error.what());
        }
      }
    }

    /**
     * `impact` with k_si set from its k_table (if any), so that validate_law() checks the table's
     * k; the table's problems are reported at k_table / wall_height. With `required` false a
     * missing wall_height is not an error (the cases give it).
     */
    ImpactScene
    with_table_stiffness(const ImpactScene &impact, ValidationContext &ctx, bool required)
    {
      ImpactScene out = impact;
      if (impact.k_table.empty() || impact.k_si || impact.law == "bumper")
        return out;
      out.k_si = 1.0; // a placeholder when the table cannot give k: reported below instead
      if (!impact.wall_height)
      {
        if (required)
          ctx.fail("wall_height", "null", "must be given with k_table = " + impact.k_table);
        return out;
      }
      const double n = impact_exponent(impact);
      KTable       table;
      try
      {
        table = read_k_table(ctx.resolve_path(impact.k_table));
      }
      catch (const std::invalid_argument &error)
      {
        ctx.fail("k_table", impact.k_table, error.what());
        return out;
      }
      if (n != 1.0 && n != 1.5)
      {
        ctx.fail("k_table",
                 impact.k_table,
                 "holds k for n = 1 and n = 1.5 only (law " + impact.law +
                   " has n = " + format_quantity(n, "") + ")");
        return out;
      }
      try
      {
        out.k_si = table.stiffness(*impact.wall_height, n);
      }
      catch (const std::invalid_argument &error)
      {
        ctx.fail("wall_height", format_quantity(*impact.wall_height, "m"), error.what());
      }
      return out;
    }

    void validate_bumper(const ImpactScene &impact, ValidationContext &ctx)
    {
      const auto         scope = ctx.section("bumper");
      const BumperScene &b     = impact.bumper;
      ctx.check(b.thickness > 0.0, "thickness", format_quantity(b.thickness, "mm"), "must be > 0");
      ctx.check(b.width > 0.0, "width", format_quantity(b.width, "mm"), "must be > 0");
      ctx.check(b.height > 0.0, "height", format_quantity(b.height, "mm"), "must be > 0");
      ctx.check(b.ultimate_strain > 0.0 && b.ultimate_strain <= 1.0,
                "ultimate_strain",
                format_quantity(b.ultimate_strain, ""),
                "must be in (0, 1]");
      ctx.check(b.modulus > 0.0, "modulus", format_quantity(b.modulus, "kN/m^2"), "must be > 0");
      ctx.check(b.wall_stiffness > 0.0,
                "wall_stiffness",
                format_quantity(b.wall_stiffness, "kN/mm"),
                "must be > 0");
      if (!b.k_b.empty())
      {
        const double n = impact_exponent(impact);
        try
        {
          const Quantity k = parse_quantity(b.k_b);
          if (ctx.check(k.dimension == stiffness_dimension(n),
                        "k_b",
                        b.k_b,
                        "needs a stiffness in N/m^n with n = " + format_quantity(n, "") +
                          ", e.g. \"0.36 " + fit::stiffness_display_unit(n) + "\""))
            ctx.check(k.value > 0.0, "k_b", b.k_b, "must be > 0");
        }
        catch (const UnitError &error)
        {
          ctx.fail("k_b", b.k_b, error.what());
        }
      }
    }

    /// Walls and bumpers of an (already case-applied) scene; `gap_key` names the key to blame.
    void validate_walls(const LumpedScene &scene,
                        ValidationContext &ctx,
                        const std::string &left_gap_key,
                        const std::string &right_gap_key)
    {
      const bool bumper = scene.impact.law == "bumper";
      const auto one    = [&](const WallScene &w, const std::string &gap_key)
      {
        if (!w.present)
          return;
        if (!ctx.check(std::isfinite(w.gap) && w.gap > 0.0,
                       gap_key,
                       format_quantity(w.gap, "cm"),
                       "must be > 0"))
          return;
        if (bumper && !scene.impact.bumper.recessed)
          ctx.check(w.gap > scene.impact.bumper.thickness,
                    gap_key,
                    format_quantity(w.gap, "cm"),
                    "must be > impact.bumper.thickness = " +
                      format_quantity(scene.impact.bumper.thickness, "mm") +
                      " (the bumpers would touch the building at rest)");
      };
      one(scene.walls.left, left_gap_key);
      one(scene.walls.right, right_gap_key);
    }
  } // namespace

  void resolve_paths(LumpedScene &scene, const std::filesystem::path &directory)
  {
    scene.impact.k_table = resolve_scene_path(scene.impact.k_table, directory);
    resolve_paths(scene.ground_motion, directory);
    for (CaseScene &c : scene.cases)
      c.record = resolve_record_path(c.record, directory);
  }

  double impact_exponent(const ImpactLawScene &law)
  {
    if (law.exponent)
      return *law.exponent;
    if (law.law == "linear" || law.law == "kelvin_voigt" || law.law == "modified_kelvin_voigt")
      return 1.0;
    if (law.law == "bumper")
      return 2.65;
    return 1.5;
  }

  double impact_stiffness(const ImpactLawScene &law)
  {
    if (law.k_si)
      return *law.k_si;
    const Quantity k = parse_quantity(law.k);
    if (k.dimension != stiffness_dimension(impact_exponent(law)))
      throw UnitError("impact.k = " + law.k + " (law " + law.law + " needs N/m^" +
                      format_quantity(impact_exponent(law), "") + ")");
    return k.value;
  }

  double impact_stiffness(const ImpactScene &impact)
  {
    if (impact.k_si || impact.k_table.empty())
      return impact_stiffness(static_cast<const ImpactLawScene &>(impact));
    if (!impact.wall_height)
      throw std::invalid_argument("impact.k_table = " + impact.k_table +
                                  ": impact.wall_height (or the case's wall_height) must be given");
    try
    {
      return read_k_table(impact.k_table).stiffness(*impact.wall_height, impact_exponent(impact));
    }
    catch (const std::invalid_argument &error)
    {
      throw std::invalid_argument("impact.k_table = " + impact.k_table + ", impact.wall_height = " +
                                  format_quantity(*impact.wall_height, "m") + ": " + error.what());
    }
  }

  double bumper_stiffness(const ImpactScene &impact)
  {
    const BumperScene &b = impact.bumper;
    const double       n = impact_exponent(impact);
    if (!b.k_b.empty())
    {
      const Quantity k = parse_quantity(b.k_b);
      if (k.dimension != stiffness_dimension(n))
        throw UnitError("impact.bumper.k_b = " + b.k_b + " (needs N/m^" + format_quantity(n, "") +
                        ")");
      return k.value;
    }
    return lumped::bumper_stiffness(b.width * b.height,
                                    b.modulus,
                                    b.thickness,
                                    n,
                                    static_cast<int>(b.count));
  }

  lumped::ForceLawSpec force_law_spec(const ImpactScene &impact)
  {
    lumped::ForceLawSpec spec;
    spec.law = impact.law;
    if (!law_has_fixed_exponent(impact.law))
      spec.exponent = impact_exponent(impact);
    spec.cor          = impact.cor;
    spec.hertzdamp_ye = impact.hertzdamp_ye;
    spec.impact_a1    = impact.a1;
    if (impact.law == "bumper")
    {
      spec.stiffness                   = bumper_stiffness(impact);
      spec.bumper_ultimate_deformation = impact.bumper.ultimate_strain * impact.bumper.thickness;
      spec.bumper_wall_stiffness       = impact.bumper.wall_stiffness;
    }
    else
      spec.stiffness = impact_stiffness(impact);
    return spec;
  }

  std::optional<double> requested_time_step(const IntegrationScene &integration)
  {
    if (integration.dt == "auto" || integration.dt == "stable")
      return std::nullopt;
    return parse_quantity_as(integration.dt, "s");
  }

  bool variable_time_step(const IntegrationScene &integration)
  {
    return integration.dt == "auto" && integration.method == IntegrationMethod::cdm;
  }

  void validate(const LumpedScene &scene, ValidationContext &ctx)
  {
    const bool isolated = scene.building.kind == BuildingKind::isolated;
    // building: single-key ranges are declared in visit() and enforced by the reader; masses
    // below 1 kg (a slip of the unit, or a denormal that passes "> 0") are no storey, and the
    // modal analysis cannot take them.
    {
      const auto           scope = ctx.section("building");
      const BuildingScene &b     = scene.building;
      for (const auto &[key, mass] : {std::pair{"floor_mass", b.floor_mass},
                                      std::pair{"top_mass", b.top_mass},
                                      std::pair{"isolation_mass", b.isolation_mass}})
        ctx.check(!(mass < 1.0),
                  key,
                  fmt::format("{:.4g} t", mass / 1e3), // a denormal has no 15 true digits
                  "must be >= 1 kg (a storey)");
    }
    if (isolated)
    {
      const auto           scope = ctx.section("isolator");
      const IsolatorScene &iso   = scene.isolator;
      if (iso.kind == IsolatorKind::bilinear || iso.kind == IsolatorKind::bouc_wen)
      {
        if (ctx.check(iso.K1 > 0.0, "K1", format_quantity(iso.K1, "MN/m"), "must be > 0"))
          ctx.check(iso.K2 >= 0.0 && iso.K2 < iso.K1,
                    "K2",
                    format_quantity(iso.K2, "MN/m"),
                    "must be >= 0 and < K1 = " + format_quantity(iso.K1, "MN/m"));
        if (iso.Q)
          ctx.check(*iso.Q > 0.0, "Q", format_quantity(*iso.Q, "kN"), "must be > 0");
        else
          ctx.check(iso.Q_ratio > 0.0 && iso.Q_ratio < 1.0,
                    "Q_ratio",
                    percent(iso.Q_ratio),
                    "must be in (0 %, 100 %)");
      }
      if (iso.kind == IsolatorKind::bouc_wen)
      {
        ctx.check(iso.bw_beta >= std::abs(iso.bw_gamma),
                  "beta",
                  format_quantity(iso.bw_beta, ""),
                  "must be >= |gamma| = " + format_quantity(std::abs(iso.bw_gamma), "") +
                    " (non-negative dissipation)");
        ctx.check(iso.bw_beta + iso.bw_gamma > 0.0,
                  "gamma",
                  format_quantity(iso.bw_gamma, ""),
                  "must give beta + gamma > 0");
      }
      if (iso.kind == IsolatorKind::friction_pendulum)
        ctx.check(iso.mu_fast >= iso.mu_slow,
                  "mu_fast",
                  format_quantity(iso.mu_fast, ""),
                  "must be >= mu_slow = " + format_quantity(iso.mu_slow, ""));
      if (iso.kind == IsolatorKind::linear)
        ctx.check(iso.k > 0.0, "k", format_quantity(iso.k, "MN/m"), "must be > 0");
      ctx.check(iso.damping_ratio >= scene.building.damping_ratio && iso.damping_ratio < 1.0,
                "damping_ratio",
                percent(iso.damping_ratio),
                "must be >= building.damping_ratio = " + percent(scene.building.damping_ratio) +
                  " and < 100 %");
    }
    {
      const auto scope = ctx.section("walls");
      if (!isolated)
      {
        ctx.check(!scene.walls.left.present,
                  "left.present",
                  "true",
                  "must be false for a fixed-base building (moat walls act at an isolation level)");
        ctx.check(!scene.walls.right.present,
                  "right.present",
                  "true",
                  "must be false for a fixed-base building (moat walls act at an isolation level)");
      }
      for (const auto &[key, wall] :
           {std::pair<const char *, const WallScene *>{"left", &scene.walls.left},
            {"right", &scene.walls.right}})
        if (wall->present)
          ctx.check(wall->mass > 0.0,
                    std::string(key) + ".mass",
                    format_quantity(wall->mass, "t"),
                    "must be > 0");
      if (scene.walls.basement)
        ctx.check(isolated && scene.building.n_storeys >= 1,
                  "basement",
                  "true",
                  "needs an isolated building with a floor above the isolation level");
    }
    validate_walls(scene, ctx, "walls.left.gap", "walls.right.gap");
    {
      const auto scope = ctx.section("impact");
      validate_law(with_table_stiffness(scene.impact, ctx, scene.cases.empty()), ctx, true);
      if (scene.impact.law == "bumper")
        validate_bumper(scene.impact, ctx);
    }
    {
      const auto scope = ctx.section("neighbours");
      for (const auto &[key, nb] :
           {std::pair<const char *, const NeighbourScene *>{"left", &scene.neighbours.left},
            {"right", &scene.neighbours.right}})
      {
        if (!nb->present)
          continue;
        const auto side = ctx.section(key);
        ctx.check(nb->separation > 0.0,
                  "separation",
                  format_quantity(nb->separation, "cm"),
                  "must be > 0");
        ctx.check(nb->floor_mass > 0.0,
                  "floor_mass",
                  format_quantity(nb->floor_mass, "t"),
                  "must be > 0");
        ctx.check(nb->top_mass > 0.0,
                  "top_mass",
                  format_quantity(nb->top_mass, "t"),
                  "must be > 0");
        ctx.check(nb->storey_stiffness > 0.0,
                  "storey_stiffness",
                  format_quantity(nb->storey_stiffness, "MN/m"),
                  "must be > 0");
        ctx.check(nb->damping_ratio >= 0.0 && nb->damping_ratio < 1.0,
                  "damping_ratio",
                  percent(nb->damping_ratio),
                  "must be in [0 %, 100 %)");
        if (nb->impact)
        {
          const auto law_scope = ctx.section("impact");
          validate_law(*nb->impact, ctx, false);
        }
        else if (scene.impact.law == "bumper")
          ctx.fail("impact", "null", "must be given: impact.law = bumper acts only at the walls");
      }
    }
    {
      const auto scope = ctx.section("ground_motion");
      validate(scene.ground_motion, ctx);
    }
    {
      const auto              scope = ctx.section("integration");
      const IntegrationScene &in    = scene.integration;
      try
      {
        const std::optional<double> dt = requested_time_step(in);
        if (dt)
          ctx.check(std::isfinite(*dt) && *dt > 0.0,
                    "dt",
                    in.dt,
                    "must be \"auto\", \"stable\" or > 0 s");
      }
      catch (const UnitError &error)
      {
        ctx.fail("dt",
                 in.dt,
                 std::string("must be \"auto\", \"stable\" or a time (") + error.what() + ")");
      }
    }

    std::set<std::string> names;
    for (std::size_t i = 0; i < scene.cases.size(); ++i)
    {
      const CaseScene &c     = scene.cases[i];
      const auto       scope = ctx.section("cases[" + std::to_string(i) + "]");
      if (ctx.check(is_valid_case_name(c.name),
                    "name",
                    "\"" + c.name + "\"",
                    "must be non-empty letters, digits, '_', '-' or '.'"))
        ctx.check(names.insert(c.name).second, "name", c.name, "must be unique among the cases");
      if (c.ground_motion_scale)
        ctx.check(std::isfinite(*c.ground_motion_scale) && *c.ground_motion_scale != 0.0,
                  "ground_motion_scale",
                  format_quantity(*c.ground_motion_scale, ""),
                  "must be finite and != 0");
      for (const auto &[key, gap] :
           {std::pair<const char *, const std::optional<double> *>{"gap", &c.gap},
            {"left_gap", &c.left_gap},
            {"right_gap", &c.right_gap}})
        if (*gap)
          ctx.check(isolated, key, format_quantity(**gap, "cm"), "needs an isolated building");
      if (c.wall_height && scene.impact.k_table.empty())
        ctx.fail("wall_height",
                 format_quantity(*c.wall_height, "m"),
                 "needs impact.k_table (the k table it selects k from)");
      LumpedScene applied = apply_case(scene, c);
      {
        ValidationContext table_ctx;
        table_ctx.set_directory(ctx.directory());
        applied.impact = with_table_stiffness(applied.impact, table_ctx, true);
        for (const auto &failure : table_ctx.failures())
          ctx.fail(failure.key_path == "wall_height" && c.wall_height ?
                     "wall_height" :
                     "impact." + failure.key_path,
                   failure.value_text,
                   failure.expectation);
      }
      // The case's law and stiffness, reported at the case's own keys.
      ValidationContext law_ctx;
      validate_law(applied.impact, law_ctx, true);
      for (const auto &failure : law_ctx.failures())
      {
        std::string key = failure.key_path;
        if ((key == "k" && c.k.empty()) || (key == "exponent" && !c.exponent) ||
            (key == "cor" && !c.cor))
          key = c.law.empty() ? "k" : "law";
        ctx.fail(key, failure.value_text, failure.expectation);
      }
      if (!c.record.empty())
        validate(applied.ground_motion, ctx); // the case's record, reported at cases[i].record
      if (!c.law.empty() && c.law == "bumper")
        validate_bumper(applied.impact, ctx);
      validate_walls(applied,
                     ctx,
                     c.left_gap ? "left_gap" : "gap",
                     c.right_gap ? "right_gap" : "gap");
    }
  }

  LumpedScene apply_case(const LumpedScene &scene, const CaseScene &c)
  {
    LumpedScene out = scene;
    out.cases.clear();
    if (!c.law.empty() && c.law != scene.impact.law)
    {
      out.impact.law = c.law;
      out.impact.exponent.reset();
    }
    if (!c.k.empty())
      out.impact.k = c.k;
    if (c.exponent)
      out.impact.exponent = c.exponent;
    if (c.cor)
      out.impact.cor = *c.cor;
    if (c.gap)
      out.walls.left.gap = out.walls.right.gap = *c.gap;
    if (c.left_gap)
      out.walls.left.gap = *c.left_gap;
    if (c.right_gap)
      out.walls.right.gap = *c.right_gap;
    if (c.ground_motion_scale)
      out.ground_motion.scale *= *c.ground_motion_scale;
    if (!c.k.empty())
      out.impact.k_table.clear(); // the case's own k wins over the table
    if (c.wall_height)
      out.impact.wall_height = c.wall_height;
    if (!c.record.empty())
      out.ground_motion.record = c.record;
    return out;
  }

  std::vector<std::pair<std::string, LumpedScene>> resolve_cases(const LumpedScene &scene)
  {
    std::vector<std::pair<std::string, LumpedScene>> out;
    if (scene.cases.empty())
    {
      LumpedScene single = scene;
      single.cases.clear();
      out.emplace_back("default", std::move(single));
      return out;
    }
    for (const CaseScene &c : scene.cases)
      out.emplace_back(c.name, apply_case(scene, c));
    return out;
  }

  lumped::ShearBuilding make_building(const LumpedScene &scene)
  {
    const BuildingScene  &b = scene.building;
    lumped::ShearBuilding building;
    building.name = "building";
    if (b.kind == BuildingKind::isolated)
    {
      building.floor_masses.push_back(b.isolation_mass);
      for (unsigned int j = 1; j <= b.n_storeys; ++j)
        building.floor_masses.push_back(j == b.n_storeys ? b.top_mass : b.floor_mass);
      building.storey_stiffnesses.assign(b.n_storeys, b.storey_stiffness);
      building.damping_ratio           = b.damping_ratio;
      building.isolation_damping_ratio = scene.isolator.damping_ratio;
      const IsolatorScene &iso         = scene.isolator;
      const double         weight      = lumped::standard_gravity * building.total_mass();
      // (Q_ratio·g)·m, the association of reference_isolated_building(): bitwise the same Q.
      const double Q =
        iso.Q ? *iso.Q : iso.Q_ratio * lumped::standard_gravity * building.total_mass();
      switch (iso.kind)
      {
        case IsolatorKind::bilinear:
          building.isolator = std::make_shared<lumped::BilinearIsolator>(iso.K1, iso.K2, Q);
          break;
        case IsolatorKind::linear:
          building.isolator = std::make_shared<lumped::LinearIsolator>(iso.k);
          break;
        case IsolatorKind::friction_pendulum:
          building.isolator =
            std::make_shared<lumped::FrictionPendulumIsolator>(iso.weight.value_or(weight),
                                                               iso.radius,
                                                               iso.mu_slow,
                                                               iso.mu_fast,
                                                               iso.rate,
                                                               iso.k_init);
          break;
        case IsolatorKind::bouc_wen:
        {
          const double alpha = iso.K2 / iso.K1;
          building.isolator  = std::make_shared<lumped::BoucWenIsolator>(iso.K1,
                                                                        alpha,
                                                                        Q / (1.0 - alpha),
                                                                        iso.bw_A,
                                                                        iso.bw_beta,
                                                                        iso.bw_gamma,
                                                                        iso.bw_n);
          break;
        }
      }
    }
    else
    {
      for (unsigned int j = 1; j <= b.n_storeys; ++j)
        building.floor_masses.push_back(j == b.n_storeys ? b.top_mass : b.floor_mass);
      building.storey_stiffnesses.assign(b.n_storeys, b.storey_stiffness);
      building.damping_ratio           = b.fixed_base_damping_ratio;
      building.isolation_damping_ratio = b.fixed_base_damping_ratio;
    }
    return building;
  }

  lumped::PoundingScene make_pounding_scene(const LumpedScene &scene)
  {
    lumped::PoundingScene out;
    out.building = make_building(scene);
    if (scene.building.kind == BuildingKind::isolated)
    {
      const lumped::ForceLawFactory law = lumped::force_law_factory(force_law_spec(scene.impact));
      const bool                    bumper  = scene.impact.law == "bumper";
      const auto                    to_wall = [&](const WallScene &w)
      {
        lumped::MoatWall wall;
        wall.gap              = w.gap;
        wall.mass             = w.mass;
        wall.bumper_thickness = bumper ? scene.impact.bumper.thickness : 0.0;
        wall.bumper_recessed  = bumper && scene.impact.bumper.recessed;
        wall.law              = law;
        wall.flexible         = w.flexible;
        wall.stiffness        = w.stiffness;
        wall.damping_ratio    = w.damping_ratio;
        wall.sdof_mass        = w.sdof_mass;
        return wall;
      };
      if (scene.walls.left.present)
        out.left_wall = to_wall(scene.walls.left);
      if (scene.walls.right.present)
        out.right_wall = to_wall(scene.walls.right);
      out.basement = scene.walls.basement;
    }
    const auto to_neighbour = [&](const NeighbourScene &nb, const std::string &name)
    {
      lumped::AdjacentBuilding adjacent;
      adjacent.building.name = name;
      for (unsigned int j = 1; j <= nb.n_storeys; ++j)
        adjacent.building.floor_masses.push_back(j == nb.n_storeys ? nb.top_mass : nb.floor_mass);
      adjacent.building.storey_stiffnesses.assign(nb.n_storeys, nb.storey_stiffness);
      adjacent.building.damping_ratio           = nb.damping_ratio;
      adjacent.building.isolation_damping_ratio = nb.damping_ratio;
      adjacent.separation                       = nb.separation;
      ImpactScene law                           = scene.impact;
      if (nb.impact)
      {
        static_cast<ImpactLawScene &>(law) = *nb.impact;
        law.k_table.clear(); // the neighbour's own k, not the walls' table
      }
      adjacent.law = lumped::force_law_factory(force_law_spec(law));
      return adjacent;
    };
    if (scene.neighbours.left.present)
      out.left_neighbour = to_neighbour(scene.neighbours.left, "left_neighbour");
    if (scene.neighbours.right.present)
      out.right_neighbour = to_neighbour(scene.neighbours.right, "right_neighbour");
    return out;
  }
} // namespace kimp::app
