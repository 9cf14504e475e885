// A `kimp lumped` scene in plan: validation, the engine's building and moat, the motion.
#include "app/lumped/plan_scene.h"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "app/lumped/lumped_run_internal.h"
#include "lumped/isolators/isolator.h"
#include "lumped/plan/plan_geometry.h"
#include "lumped/plan/plan_isolators.h"
#include "lumped/plan/plan_moat.h"

namespace kimp::app
{
  using io::ValidationContext;
  namespace plan = lumped::plan;

  namespace
  {
    plan::Polygon to_polygon(const std::vector<PlanPointScene> &points)
    {
      plan::Polygon out;
      for (const PlanPointScene &p : points)
        out.emplace_back(p.x, p.y);
      return out;
    }

    std::string polygon_text(const std::vector<PlanPointScene> &points)
    {
      std::string out = "[";
      for (const PlanPointScene &p : points)
        out += fmt::format("{}({:.4g}, {:.4g}) m", out.size() > 1 ? ", " : "", p.x, p.y);
      return out + "]";
    }

    /// The moat polygon: the wall as given, or the outline's edges moved out by the gaps.
    plan::Polygon moat_wall(const PlanSection &p, const plan::PlanBuilding &building)
    {
      if (!p.moat.wall.empty())
        return to_polygon(p.moat.wall);
      return plan::moat_around(building,
                               p.moat.gaps.empty() ? std::vector<double>{p.moat.gap} : p.moat.gaps);
    }

    plan::PlanBuilding make_plan_building(const LumpedScene &base, const PlanSection &p)
    {
      const BuildingScene &b        = base.building;
      const bool           isolated = b.kind == BuildingKind::isolated;
      const plan::Polygon  outline  = plan_outline(p);
      const plan::Point    centre   = plan::centroid(outline);

      plan::PlanBuilding building;
      building.damping = p.damping;
      std::vector<double> masses;
      if (isolated)
        masses.push_back(b.isolation_mass);
      for (const double m : b.floor_masses())
        masses.push_back(m);
      for (const double m : masses)
      {
        plan::PlanLevel level;
        level.mass              = m;
        level.outline           = outline;
        level.mass_eccentricity = plan::Point(p.eccentricity_x, p.eccentricity_y);
        building.levels.push_back(level);
      }

      plan::PlanStorey storey;
      if (p.elements.empty())
      {
        const double k_x  = p.k_x.value_or(b.storey_stiffness);
        const double k_y  = p.k_y.value_or(b.storey_stiffness);
        const double area = std::abs(plan::signed_area(outline));
        const double k_theta =
          p.k_theta.value_or(0.5 * (k_x + k_y) * plan::polar_moment(outline, centre) / area);
        storey = plan::storey(k_x, k_y, k_theta, centre);
      }
      else
        for (const PlanElementScene &e : p.elements)
          storey.elements.push_back({plan::Point(e.x, e.y), e.k_x, e.k_y});
      building.storeys.assign(b.n_storeys, storey);

      if (isolated)
      {
        building.damping_ratio           = b.damping_ratio;
        building.isolation_damping_ratio = base.isolator.damping_ratio;
        double total_mass                = 0.0;
        for (const double m : masses)
          total_mass += m;
        const IsolatorScene &iso       = base.isolator;
        const double         g         = lumped::standard_gravity;
        const double         Q         = iso.Q ? *iso.Q : iso.Q_ratio * g * total_mass;
        const plan::Polygon  positions = p.isolators.empty() ? outline : to_polygon(p.isolators);
        const double         n         = static_cast<double>(positions.size());
        std::shared_ptr<const plan::PlanIsolator> law;
        switch (iso.kind)
        {
          case IsolatorKind::bilinear:
            law = std::make_shared<plan::PlanBilinearIsolator>(
              lumped::BilinearParameters{iso.K1 / n, iso.K2 / n, Q / n});
            break;
          case IsolatorKind::bouc_wen:
            law = std::make_shared<plan::PlanBoucWenIsolator>(bouc_wen_parameters(iso, Q, n));
            break;
          case IsolatorKind::friction_pendulum:
            law = std::make_shared<plan::PlanFrictionPendulumIsolator>(
              friction_pendulum_parameters(iso, g * total_mass, n));
            break;
          case IsolatorKind::linear:
            throw std::invalid_argument(
              "isolator.kind = linear: has no model in plan (use bilinear or bouc_wen)");
        }
        for (const plan::Point &position : positions)
          building.isolators.push_back({position, law});
      }
      else
      {
        building.damping_ratio           = b.fixed_base_damping_ratio;
        building.isolation_damping_ratio = b.fixed_base_damping_ratio;
      }
      return building;
    }

    /// Rethrow what `f` throws as a failure at `key` of `ctx`; false when it threw.
    template <class F>
    bool
    engine_check(ValidationContext &ctx, const std::string &key, const std::string &value, F &&f)
    {
      try
      {
        f();
        return true;
      }
      catch (const std::exception &error)
      {
        ctx.fail(key, value, error.what());
        return false;
      }
    }

    /// The moat of a valid plan section: the wall polygon simple and enclosing the slab, or
    /// the gaps one per edge, and the engine's own checks.
    void validate_moat(const LumpedScene        &base,
                       const PlanSection        &p,
                       const plan::PlanBuilding &building,
                       ValidationContext        &ctx)
    {
      const plan::Polygon slab = plan_outline(p);
      if (!p.moat.wall.empty())
      {
        if (!engine_check(ctx,
                          "moat.wall",
                          polygon_text(p.moat.wall),
                          [&]
                          { plan::validate_polygon(to_polygon(p.moat.wall), "a simple polygon"); }))
          return;
        const plan::Polygon wall = to_polygon(p.moat.wall);
        for (const plan::Point &corner : slab)
          if (!plan::strictly_inside(wall, corner, 1e-9))
          {
            ctx.fail("moat.wall",
                     polygon_text(p.moat.wall),
                     fmt::format("must enclose the slab outline with a clear gap (slab corner "
                                 "({:.4g}, {:.4g}) m is not inside)",
                                 corner.x(),
                                 corner.y()));
            return;
          }
      }
      else
      {
        const std::string key = p.moat.gaps.empty() ? "moat.gap" : "moat.gaps";
        const std::size_t n   = slab.size();
        if (!p.moat.gaps.empty() &&
            !ctx.check(p.moat.gaps.size() == n,
                       key,
                       fmt::format("[{} gaps]", p.moat.gaps.size()),
                       fmt::format("must hold one gap per slab edge ({})", n)))
          return;
        if (!engine_check(ctx, key, "", [&] { moat_wall(p, building); }))
          return;
      }
      engine_check(ctx,
                   p.moat.wall.empty() ? "moat" : "moat.wall",
                   "",
                   [&] { make_plan_scene(base, p); });
    }
  } // namespace

  namespace
  {
    /// The yielding faces: per metre × the face's length (the wall counter-clockwise), the DOF
    /// mass (null: moat.mass). Faces outside the wall are left to the engine's check.
    std::vector<plan::PlanYieldingWall> yielding_faces(const PlanMoatScene &m,
                                                       const plan::Polygon &wall_polygon)
    {
      const plan::Polygon                 wall = plan::counter_clockwise(wall_polygon);
      std::vector<plan::PlanYieldingWall> out;
      for (std::size_t i = 0; i < m.yielding.size(); ++i)
      {
        const PlanYieldingFaceScene &f = m.yielding[i];
        if (f.wall.width != YieldingWallScene{}.width)
          throw std::invalid_argument("moat.yielding[" + std::to_string(i) +
                                      "].width does not apply in plan (each face takes its "
                                      "own length)");
        YieldingWallScene w = f.wall;
        if (f.face < wall.size())
          w.width = (wall[(f.face + 1) % wall.size()] - wall[f.face]).norm();
        plan::PlanYieldingWall y;
        y.segment     = f.face;
        y.params      = w.resolved();
        y.params.mass = f.mass.value_or(m.mass);
        out.push_back(y);
      }
      return out;
    }
  } // namespace

  plan::Polygon plan_outline(const PlanSection &p)
  {
    if (!p.outline.empty())
      return to_polygon(p.outline);
    return plan::rectangle(p.width, p.depth);
  }

  void validate(const PlanLumpedScene &scene, ValidationContext &ctx)
  {
    validate(scene.base, ctx);
    if (!scene.plan)
      return;
    const LumpedScene &base     = scene.base;
    const PlanSection &p        = *scene.plan;
    const bool         isolated = base.building.kind == BuildingKind::isolated;
    ctx.check(base.cases.empty(),
              "cases",
              fmt::format("[{} cases]", base.cases.size()),
              "must be empty in a plan scene (one run; vary plan.angle with one scene per angle "
              "or kimp sweep)");
    ctx.check(base.integration.method == IntegrationMethod::cdm,
              "integration.method",
              "newmark",
              "must be cdm in a plan scene (the plan engine is explicit)");
    ctx.check(!base.integration.companion,
              "integration.companion",
              "true",
              "must be false in a plan scene");
    ctx.check(!base.neighbours.left.present && !base.neighbours.right.present,
              "neighbours",
              "present",
              "must be absent in a plan scene (neighbours in plan are not modelled)");
    if (isolated)
      ctx.check(base.isolator.kind != IsolatorKind::linear,
                "isolator.kind",
                "linear",
                "must be bilinear, bouc_wen or friction_pendulum in a plan scene");
    ctx.check(base.impact.law != "bumper",
              "impact.law",
              "bumper",
              "must be one of the laws 1-7 in a plan scene (bumpers in plan are not modelled)");
    ctx.check(base.impact.k_table.empty(),
              "impact.k_table",
              base.impact.k_table,
              "must be empty in a plan scene (give impact.k)");

    const auto scope = ctx.section("plan");
    if (!p.outline.empty() &&
        !engine_check(ctx,
                      "outline",
                      polygon_text(p.outline),
                      [&] { plan::validate_polygon(to_polygon(p.outline), "a simple polygon"); }))
      return;
    for (std::size_t i = 0; i < p.moat.yielding.size(); ++i)
      validate_yielding_wall(p.moat.yielding[i].wall,
                             "moat.yielding[" + std::to_string(i) + "].",
                             ctx);
    if (!isolated)
      ctx.check(!p.moat.present,
                "moat.present",
                "true",
                "must be false for a fixed-base building (the moat acts at an isolation level)");
    if (isolated && !p.isolators.empty())
      ctx.check(p.isolators.size() >= 2,
                "isolators",
                fmt::format("[{} positions]", p.isolators.size()),
                "must hold at least 2 positions (one isolator has no torsional stiffness)");
    switch (p.second_component)
    {
      case SecondComponent::record:
        ctx.check(!p.second_record.empty(),
                  "second_record",
                  "\"\"",
                  "must name the second component's record (second_component = record)");
        break;
      case SecondComponent::synthetic:
        ctx.check(!base.ground_motion.is_record(),
                  "second_component",
                  "synthetic",
                  "needs ground_motion.record = synthetic");
        break;
      case SecondComponent::none:
        ctx.check(p.second_record.empty(),
                  "second_record",
                  p.second_record,
                  "must be empty with second_component = none (set second_component: record)");
        break;
    }
    if (!ctx.failures().empty())
      return;

    plan::PlanBuilding building;
    if (!engine_check(ctx,
                      p.elements.empty() ? "k_theta" : "elements",
                      "",
                      [&]
                      {
                        building = make_plan_building(base, p);
                        plan::validate(building);
                      }))
      return;
    if (!isolated || !p.moat.present)
      return;
    validate_moat(base, p, building, ctx);
  }

  void resolve_paths(PlanLumpedScene &scene, const std::filesystem::path &directory)
  {
    resolve_paths(scene.base, directory);
    if (scene.plan && !scene.plan->second_record.empty())
      scene.plan->second_record = resolve_record_path(scene.plan->second_record, directory);
  }

  plan::PlanScene make_plan_scene(const LumpedScene &base, const PlanSection &p)
  {
    plan::PlanScene scene;
    scene.building = make_plan_building(base, p);
    if (base.building.kind == BuildingKind::isolated && p.moat.present)
    {
      plan::PlanMoat moat;
      moat.wall                 = moat_wall(p, scene.building);
      lumped::ForceLawSpec spec = force_law_spec(base.impact);
      // impact.k is the planar wall's k_total against a slab edge of length k_length.
      const plan::Polygon outline = plan_outline(p);
      double              y_min = outline.front().y(), y_max = y_min;
      for (const plan::Point &c : outline)
      {
        y_min = std::min(y_min, c.y());
        y_max = std::max(y_max, c.y());
      }
      const double length = p.moat.k_length.value_or(y_max - y_min);
      spec.stiffness /= length;
      moat.law             = spec;
      moat.mass            = p.moat.mass;
      moat.friction        = p.moat.friction;
      moat.stick_velocity  = p.moat.stick_velocity;
      moat.points_per_edge = static_cast<int>(p.moat.points_per_edge);
      moat.yielding        = yielding_faces(p.moat, moat.wall);
      plan::validate(moat, scene.building);
      scene.moat = moat;
    }
    return scene;
  }

  plan::PlanOptions plan_options(const IntegrationScene &in)
  {
    // The stepping options of a planar run of the same integration section.
    return lumped_internal::cdm_options(in, requested_time_step(in));
  }

  plan::PlanGroundMotion load_plan_motion(const LumpedScene                          &base,
                                          const PlanSection                          &p,
                                          const std::optional<std::filesystem::path> &records_dir,
                                          const std::string                          &file_name,
                                          const std::string                          &scene_text)
  {
    const lumped::GroundMotion first = load_ground_motion_at(base.ground_motion,
                                                             records_dir,
                                                             file_name,
                                                             scene_text,
                                                             "ground_motion");
    const double               angle = p.angle * (3.14159265358979323846 / 180.0);
    if (p.second_component == SecondComponent::none)
      return plan::along_angle(first, angle);
    GroundMotionScene second_scene = base.ground_motion;
    if (p.second_component == SecondComponent::record)
      second_scene.record = p.second_record;
    else
      second_scene.synthetic.seed += 1;
    lumped::GroundMotion second;
    try
    {
      second = load_ground_motion(second_scene, records_dir);
    }
    catch (const std::exception &error)
    {
      const int line = io::key_line(scene_text, "plan.second_record");
      throw io::SceneError(fmt::format("{}{}: plan.second_record = '{}': {}",
                                       file_name,
                                       line > 0 ? ":" + std::to_string(line) : std::string(),
                                       p.second_record,
                                       error.what()));
    }
    for (double &a : second.acceleration)
      a *= p.second_scale;
    return plan::two_components(first, second, angle);
  }
} // namespace kimp::app
