// A `kimp lumped` scene in plan (docs/physics.md §7 "Pounding in plan"): the keys of a planar
// lumped scene (app/lumped/lumped_scene.h) plus an optional `plan` section. With `plan`, the
// building is a stack of rigid diaphragms (u_x, u_y, θ per level) on isolators at plan positions,
// in a moat wall around its base, under two ground-motion components; without it the scene is
// planar and runs exactly as before.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/laws/friction_key.h"
#include "app/lumped/building_keys.h"
#include "app/lumped/lumped_scene.h"
#include "io/scene_io.h"
#include "lumped/excitation/ground_motion.h"
#include "lumped/plan/plan_central_difference.h"
#include "lumped/plan/plan_motion.h"

namespace kimp::app
{
  /// A point in plan, m.
  struct PlanPointScene
  {
    double x = 0.0;
    double y = 0.0;
  };

  template <class Io>
  void visit(Io &io, PlanPointScene &s)
  {
    io.quantity("x", s.x, "m", "x coordinate in plan");
    io.quantity("y", s.y, "m", "y coordinate in plan");
  }

  /// A column or wall of every storey at a plan position (x, y), with its lateral stiffnesses.
  struct PlanElementScene : PlanPointScene
  {
    double k_x = 0.0;
    double k_y = 0.0;
  };

  template <class Io>
  void visit(Io &io, PlanElementScene &s)
  {
    visit(io, static_cast<PlanPointScene &>(s));
    visit_stiffness(io, "k_x", s.k_x, "lateral stiffness along x", io::Range::non_negative());
    visit_stiffness(io, "k_y", s.k_y, "lateral stiffness along y", io::Range::non_negative());
  }

  /// Which second ground-motion component a plan scene takes.
  enum class SecondComponent
  {
    none,     ///< ground_motion alone, turned to plan.angle
    record,   ///< plan.second_record along plan.angle + 90°
    synthetic ///< the synthetic motion of ground_motion.synthetic with seed + 1 along angle + 90°
  };

  /// A yielding wall face of the moat (lumped::plan::PlanYieldingWall): the `yielding` keys of a
  /// planar wall (per metre), times the face's length, on a DOF of `mass`.
  struct PlanYieldingFaceScene
  {
    unsigned int          face = 0;
    std::optional<double> mass; ///< kg (null: moat.mass)
    YieldingWallScene     wall;
  };

  template <class Io>
  void visit(Io &io, PlanYieldingFaceScene &s)
  {
    io.integer("face",
               s.face,
               "wall face k: wall corner k to k + 1 counter-clockwise (with gaps: the face of "
               "slab edge k)",
               0,
               1000);
    visit_mass(io,
               "mass",
               s.mass,
               "the face's DOF mass (null: moat.mass); the impact law keeps the m_eff of "
               "moat.mass");
    visit(io, s.wall);
  }

  /// The moat wall around the isolation level in plan (lumped::plan::PlanMoat).
  struct PlanMoatScene
  {
    bool                               present = true;
    double                             gap     = 0.15;
    std::vector<double>                gaps;
    std::vector<PlanPointScene>        wall;
    double                             mass            = 500e3;
    double                             friction        = 0.0;
    double                             stick_velocity  = 1e-3;
    unsigned int                       points_per_edge = 2;
    std::optional<double>              k_length;
    std::vector<PlanYieldingFaceScene> yielding;
  };

  template <class Io>
  void visit(Io &io, PlanMoatScene &s)
  {
    io.flag("present", s.present, "is there a moat wall around the isolation level");
    visit_moat_gap(io,
                   "gap",
                   s.gap,
                   "clear gap between every slab edge and its wall face (convex outline)");
    io.quantity_list("gaps",
                     s.gaps,
                     "cm",
                     "one gap per slab edge, edge k from outline corner k to k + 1 counter-"
                     "clockwise (empty: gap for every edge)",
                     moat_gap_range());
    io.list("wall",
            s.wall,
            "wall polygon (at least 3 corners; empty: the outline's edges moved out by the gaps); "
            "must enclose the slab with a clear gap");
    visit_mass(io, "mass", s.mass, "wall mass for m_eff in the impact law");
    visit_friction(io, s.friction, "Coulomb friction coefficient mu along the wall face");
    io.quantity("stick_velocity",
                s.stick_velocity,
                "m/s",
                "sliding velocity of the regularised stick-slip law",
                io::Range::positive());
    io.integer("points_per_edge",
               s.points_per_edge,
               "contact points per slab edge (2: the corners)",
               2,
               100);
    io.quantity("k_length",
                s.k_length,
                "m",
                "edge length over which impact.k acts (k per metre = impact.k / k_length; null: "
                "the outline's extent along y, the face of the planar model's walls)",
                io::Range::positive());
    io.list("yielding",
            s.yielding,
            "yielding wall faces: per face the planar yielding-wall keys (per metre, times the "
            "face's length; width does not apply) on a DOF of its own (convex wall)");
  }

  /// An extent of the rectangular plan along an axis (m, > 0); `doc` says which.
  template <class Io>
  void visit_plan_extent(Io &io, std::string_view key, double &extent, std::string_view doc)
  {
    io.quantity(key, extent, "m", doc, io::Range::positive());
  }

  /**
   * The `plan` section: outline, eccentricity, storeys, isolators, moat and the second
   * ground-motion component. Masses, isolator law and damping come from the building and
   * isolator sections, the contact law from impact.
   */
  struct PlanSection
  {
    double                         width = 20.0;
    double                         depth = 20.0;
    std::vector<PlanPointScene>    outline;
    double                         eccentricity_x = 0.0;
    double                         eccentricity_y = 0.0;
    std::optional<double>          k_x;
    std::optional<double>          k_y;
    std::optional<double>          k_theta;
    std::vector<PlanElementScene>  elements;
    std::vector<PlanPointScene>    isolators;
    lumped::plan::PlanDampingModel damping = lumped::plan::PlanDampingModel::rayleigh;
    PlanMoatScene                  moat;
    double                         angle            = 0.0; ///< degrees
    SecondComponent                second_component = SecondComponent::none;
    std::string                    second_record    = "";
    double                         second_scale     = 1.0;
  };

  template <class Io>
  void visit(Io &io, PlanSection &s)
  {
    visit_plan_extent(io,
                      "width",
                      s.width,
                      "rectangular plan: extent along x (used when outline is empty)");
    visit_plan_extent(io,
                      "depth",
                      s.depth,
                      "rectangular plan: extent along y (used when outline is empty)");
    io.list("outline",
            s.outline,
            "slab outline polygon of every level (empty: width x depth centred at the origin)");
    io.quantity("eccentricity_x",
                s.eccentricity_x,
                "m",
                "mass eccentricity along x: centre of mass minus the outline's centroid");
    io.quantity("eccentricity_y",
                s.eccentricity_y,
                "m",
                "mass eccentricity along y: centre of mass minus the outline's centroid");
    visit_stiffness(io,
                    "k_x",
                    s.k_x,
                    "storey stiffness along x at the outline's centroid (null: "
                    "building.storey_stiffness)");
    visit_stiffness(io,
                    "k_y",
                    s.k_y,
                    "storey stiffness along y at the outline's centroid (null: "
                    "building.storey_stiffness)");
    io.quantity("k_theta",
                s.k_theta,
                "MN*m",
                "storey torsional stiffness per radian about the centroid (null: (k_x + k_y)/2 "
                "J/A, the stiffness spread evenly over the plan)",
                io::Range::positive());
    io.list("elements",
            s.elements,
            "storey layout: columns or walls at plan positions (non-empty: replaces k_x, k_y, "
            "k_theta)");
    io.list("isolators",
            s.isolators,
            "isolator positions (empty: one at each outline corner); the isolator section's law "
            "is shared equally among them");
    io.choice("damping",
              s.damping,
              {{"rayleigh", lumped::plan::PlanDampingModel::rayleigh},
               {"modal", lumped::plan::PlanDampingModel::modal}},
              "superstructure damping: rayleigh (per direction, first and last mode of each "
              "direction) or modal (the building's damping ratio in every mode of the coupled "
              "building)");
    io.section("moat", s.moat, "moat wall around the isolation level");
    io.quantity("angle",
                s.angle,
                "",
                "angle of incidence of ground_motion in degrees, counter-clockwise from x",
                io::Range::at_least(-360.0).and_at_most(360.0));
    io.choice("second_component",
              s.second_component,
              {{"none", SecondComponent::none},
               {"record", SecondComponent::record},
               {"synthetic", SecondComponent::synthetic}},
              "none (one component along angle), record (second_record along angle + 90 deg) "
              "or synthetic (ground_motion.synthetic with seed + 1 along angle + 90 deg)");
    io.text("second_record",
            s.second_record,
            "second_component record: a PEER record name or AT2 path (ground_motion's "
            "records_dir, record_unit and scale_to_pga apply)");
    visit_motion_scale(io,
                       "second_scale",
                       s.second_scale,
                       "factor on the second component after ground_motion's scaling");
  }

  /// A `kimp lumped` scene: the planar keys and an optional `plan` section.
  struct PlanLumpedScene
  {
    LumpedScene                base;
    std::optional<PlanSection> plan;
  };

  template <class Io>
  void visit(Io &io, PlanLumpedScene &s)
  {
    visit(io, s.base);
    io.optional_section("plan",
                        s.plan,
                        "pounding in plan: rigid diaphragms (u_x, u_y, theta), isolators at plan "
                        "positions, a moat wall around the base, two ground-motion components");
  }

  /// validate() of the planar keys, then the plan section's rules (polygons, wall enclosing the
  /// slab, gaps, isolator kinds, a second component given when asked for).
  void validate(const PlanLumpedScene &scene, io::ValidationContext &ctx);

  /// resolve_paths() of the planar keys and plan.second_record.
  void resolve_paths(PlanLumpedScene &scene, const std::filesystem::path &directory);

  /// The slab outline of `plan` (outline, or the width x depth rectangle), m.
  lumped::plan::Polygon plan_outline(const PlanSection &plan);

  /// The building and moat of a scene with a plan section.
  /// @throws std::invalid_argument naming the field the engine refuses.
  lumped::plan::PlanScene make_plan_scene(const LumpedScene &base, const PlanSection &plan);

  /// The integration options of a plan run (cdm; dt "auto"/"stable": the engine's stable step).
  lumped::plan::PlanOptions plan_options(const IntegrationScene &integration);

  /**
   * The two-component motion of a plan scene: ground_motion (loaded as a planar run loads it)
   * along plan.angle, and the second component along angle + 90°.
   * @throws io::SceneError for a record that cannot be found or read.
   */
  lumped::plan::PlanGroundMotion
  load_plan_motion(const LumpedScene                          &base,
                   const PlanSection                          &plan,
                   const std::optional<std::filesystem::path> &records_dir,
                   const std::string                          &file_name,
                   const std::string                          &scene_text);
} // namespace kimp::app
