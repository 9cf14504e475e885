// `kimp lumped` scene: the rules linking its keys, the cases, and the construction of the lumped
// model (docs/physics.md §2-3); the impact law section is app/laws/impact_scene.cc.
#include "app/lumped/lumped_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <set>
#include <stdexcept>

#include "app/laws/k_table.h"
#include "io/units.h"
#include "lumped/excitation/ground_motion.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/bouc_wen_isolator.h"
#include "lumped/isolators/friction_pendulum_isolator.h"
#include "lumped/isolators/linear_isolator.h"

namespace kimp::app
{
  using namespace kimp::io;
  // The engines and io each name g (lumped includes nothing of kimp): one value.
  static_assert(io::standard_gravity == lumped::standard_gravity,
                "io and lumped must use the same standard gravity");
  namespace
  {
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

    /// Walls and bumpers of an (already case-applied) scene; `gap_key` names the key to blame.
    void validate_walls(const LumpedScene &scene,
                        ValidationContext &ctx,
                        const std::string &left_gap_key,
                        const std::string &right_gap_key)
    {
      const bool bumper = scene.impact.law == "bumper";
      const auto one    = [&](const WallScene &w, const std::string &gap_key)
      {
        if (w.present && bumper && !scene.impact.bumper.recessed)
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
    /// The yielding walls' rules their ranges cannot say.
    void validate_yielding(const LumpedScene &scene, ValidationContext &ctx)
    {
      for (const auto &[w, side] :
           {std::pair<const WallScene *, const char *>{&scene.walls.left, "walls.left."},
            {&scene.walls.right, "walls.right."}})
      {
        if (!w->present || !w->yielding)
          continue;
        const std::string wall = side;
        ctx.check(!w->flexible, wall + "flexible", "true", "must be false for a yielding wall");
        const YieldingWallScene &y = *w->yielding;
        validate_yielding_wall(y, wall + "yielding.", ctx);
        if (y.ultimate_capacity && y.envelope != lumped::WallEnvelope::curve)
        {
          const double f = y.capacity.value_or(y.default_capacity());
          ctx.check(y.envelope == lumped::WallEnvelope::bilinear,
                    wall + "yielding.ultimate_capacity",
                    format_quantity(*y.ultimate_capacity, "kN/m"),
                    "is the bilinear envelope's cap (the hyperbolic one has none): leave it null");
          ctx.check(*y.ultimate_capacity >= f,
                    wall + "yielding.ultimate_capacity",
                    format_quantity(*y.ultimate_capacity, "kN/m"),
                    "must be >= capacity = " + format_quantity(f, "kN/m"));
        }
      }
    }
  } // namespace

  std::vector<double> StoreysScene::floor_masses() const
  {
    std::vector<double> masses(n_storeys, floor_mass);
    if (!masses.empty())
      masses.back() = top_mass;
    return masses;
  }

  void resolve_paths(LumpedScene &scene, const std::filesystem::path &directory)
  {
    scene.impact.k_table = resolve_scene_path(scene.impact.k_table, directory);
    resolve_paths(scene.ground_motion, directory);
    for (CaseScene &c : scene.cases)
      c.record = resolve_record_path(c.record, directory);
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

  namespace
  {
    /// building: masses below 1 kg (a slip of the unit, or a denormal that passes "> 0") are no
    /// storey, and the modal analysis cannot take them (single-key ranges are declared in
    /// visit() and enforced by the reader).
    void validate_building(const LumpedScene &scene, ValidationContext &ctx)
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

    /// isolator (of an isolated building): K2 < K1, Bouc-Wen's dissipation, μ_fast >= μ_slow,
    /// its damping >= the building's.
    void validate_isolator(const LumpedScene &scene, ValidationContext &ctx)
    {
      const auto           scope = ctx.section("isolator");
      const IsolatorScene &iso   = scene.isolator;
      // K1 <= 0 is refused by its range.
      if ((iso.kind == IsolatorKind::bilinear || iso.kind == IsolatorKind::bouc_wen) &&
          iso.K1 > 0.0)
        ctx.check(iso.K2 < iso.K1,
                  "K2",
                  format_quantity(iso.K2, "MN/m"),
                  "must be < K1 = " + format_quantity(iso.K1, "MN/m"));
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
      ctx.check(iso.damping_ratio >= scene.building.damping_ratio,
                "damping_ratio",
                percent(iso.damping_ratio),
                "must be >= building.damping_ratio = " + percent(scene.building.damping_ratio));
    }

    /// walls: none at a fixed-base building; a basement needs a floor above the isolation level.
    void validate_wall_keys(const LumpedScene &scene, const bool isolated, ValidationContext &ctx)
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
      if (scene.walls.basement)
        ctx.check(isolated && scene.building.n_storeys >= 1,
                  "basement",
                  "true",
                  "needs an isolated building with a floor above the isolation level");
    }

    /// impact: the walls' law (k from its k table if any) and bumpers; returns whether the k
    /// table (if any) can be read, so that the cases do not report it again.
    bool validate_impact(const LumpedScene &scene, ValidationContext &ctx)
    {
      // A k table that cannot be read is one error at impact.k_table, not one more per case.
      bool table_readable = true;
      if (!scene.impact.k_table.empty() && !scene.impact.k_si && scene.impact.law != "bumper")
        try
        {
          (void)read_k_table(ctx.resolve_path(scene.impact.k_table));
        }
        catch (const std::invalid_argument &error)
        {
          table_readable = false;
          if (!scene.impact.wall_height) // else with_table_stiffness() reports it below
          {
            const auto scope = ctx.section("impact");
            ctx.fail("k_table", scene.impact.k_table, error.what());
          }
        }
      {
        const auto scope = ctx.section("impact");
        validate_law(with_table_stiffness(scene.impact, ctx, scene.cases.empty()), ctx, true);
        if (scene.impact.law == "bumper")
          validate_bumper(scene.impact, ctx);
      }
      return table_readable;
    }

    /// neighbours: each present one's own law; the walls' bumper law does not act at them.
    void validate_neighbours(const LumpedScene &scene, ValidationContext &ctx)
    {
      const auto scope = ctx.section("neighbours");
      for (const auto &[key, nb] :
           {std::pair<const char *, const NeighbourScene *>{"left", &scene.neighbours.left},
            {"right", &scene.neighbours.right}})
      {
        if (!nb->present)
          continue;
        const auto side = ctx.section(key);
        if (nb->impact)
        {
          const auto law_scope = ctx.section("impact");
          validate_law(*nb->impact, ctx, false);
        }
        else if (scene.impact.law == "bumper")
          ctx.fail("impact", "null", "must be given: impact.law = bumper acts only at the walls");
      }
    }

    /// integration: dt "auto", "stable" or a time > 0.
    void validate_integration(const LumpedScene &scene, ValidationContext &ctx)
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

    /// cases[i]: a unique name, gaps only with isolation, its wall height, law, record and
    /// walls, reported at the case's own keys; `names` collects the names so far.
    void validate_case(const LumpedScene     &scene,
                       const std::size_t      i,
                       const bool             table_readable,
                       std::set<std::string> &names,
                       ValidationContext     &ctx)
    {
      const bool       isolated = scene.building.kind == BuildingKind::isolated;
      const CaseScene &c        = scene.cases[i];
      const auto       scope    = ctx.section("cases[" + std::to_string(i) + "]");
      if (ctx.check(is_valid_case_name(c.name),
                    "name",
                    "\"" + c.name + "\"",
                    "must be non-empty letters, digits, '_', '-' or '.'"))
        ctx.check(names.insert(c.name).second, "name", c.name, "must be unique among the cases");
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
          if (table_readable || failure.key_path != "k_table")
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
  } // namespace

  void validate(const LumpedScene &scene, ValidationContext &ctx)
  {
    const bool isolated = scene.building.kind == BuildingKind::isolated;
    validate_building(scene, ctx);
    if (isolated)
      validate_isolator(scene, ctx);
    validate_wall_keys(scene, isolated, ctx);
    validate_walls(scene, ctx, "walls.left.gap", "walls.right.gap");
    validate_yielding(scene, ctx);
    const bool table_readable = validate_impact(scene, ctx);
    validate_neighbours(scene, ctx);
    {
      const auto scope = ctx.section("ground_motion");
      validate(scene.ground_motion, ctx);
    }
    validate_integration(scene, ctx);
    std::set<std::string> names;
    for (std::size_t i = 0; i < scene.cases.size(); ++i)
      validate_case(scene, i, table_readable, names, ctx);
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

  lumped::BoucWenParameters
  bouc_wen_parameters(const IsolatorScene &isolator, const double Q, const double n)
  {
    const double alpha = isolator.K2 / isolator.K1;
    return {isolator.K1 / n,
            alpha,
            Q / n / (1.0 - alpha),
            isolator.bw_A,
            isolator.bw_beta,
            isolator.bw_gamma,
            isolator.bw_n};
  }

  lumped::FrictionPendulumParameters
  friction_pendulum_parameters(const IsolatorScene &isolator, const double weight, const double n)
  {
    return {isolator.weight.value_or(weight) / n,
            isolator.radius,
            isolator.mu_slow,
            isolator.mu_fast,
            isolator.rate,
            isolator.k_init / n};
  }

  lumped::ShearBuilding make_building(const LumpedScene &scene)
  {
    const BuildingScene  &b = scene.building;
    lumped::ShearBuilding building;
    building.name = "building";
    if (b.kind == BuildingKind::isolated)
    {
      building.floor_masses = {b.isolation_mass};
      for (const double m : b.floor_masses())
        building.floor_masses.push_back(m);
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
          building.isolator = std::make_shared<lumped::FrictionPendulumIsolator>(
            friction_pendulum_parameters(iso, weight));
          break;
        case IsolatorKind::bouc_wen:
          building.isolator =
            std::make_shared<lumped::BoucWenIsolator>(bouc_wen_parameters(iso, Q));
          break;
      }
    }
    else
    {
      building.floor_masses = b.floor_masses();
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
        if (w.yielding)
          wall.yielding = w.yielding->resolved();
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
      adjacent.building.name         = name;
      adjacent.building.floor_masses = nb.floor_masses();
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
