// kimp::testing lumped scenes and records: the contact-law spec, moat wall and bumper wall the
// lumped tests build again and again, walled_scene() (the thesis building between two equal moat
// walls, shared with bench/lumped_bench.cc), the synthetic near-fault record of a given length and
// a record of zeros, a bilinear wall-and-backfill part. Only for targets linking kimp::lumped.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include "lumped/excitation/ground_motion.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/wall_backfill_law.h"
#include "lumped/structure/pounding_model.h"
#include "lumped/structure/shear_building.h"

namespace kimp::testing
{
  /**
   * The contact law `law` (a make_force_law() name) of stiffness `stiffness` [SI units of that
   * law, e.g. N/m or N/m^1.5] and COR `cor`, every other law parameter at its default.
   */
  inline lumped::ForceLawSpec
  contact_law(const std::string &law, double stiffness, double cor = 0.7)
  {
    lumped::ForceLawSpec spec;
    spec.law       = law;
    spec.stiffness = stiffness;
    spec.cor       = cor;
    return spec;
  }

  /// A rigid moat wall at `gap` [m] with the contact law `spec`.
  inline lumped::MoatWall moat_wall(double gap, const lumped::ForceLawSpec &spec)
  {
    lumped::MoatWall wall;
    wall.gap = gap;
    wall.law = lumped::force_law_factory(spec);
    return wall;
  }

  /**
   * A moat wall at `gap` [m] with the bumper example of the scenes: four 150 x 150 x 50 mm
   * bumpers, k_b = 4·2.25·A·K_r/t^2.65, crushed at 0.75 t, on a wall of 1500 kN/mm.
   */
  inline lumped::MoatWall bumper_wall(double gap)
  {
    lumped::ForceLawSpec bumper;
    bumper.law                         = "bumper";
    bumper.stiffness                   = 4.0 * 2.25 * 0.0225 * 55835e3 / std::pow(0.05, 2.65);
    bumper.bumper_ultimate_deformation = 0.75 * 0.05;
    bumper.bumper_wall_stiffness       = 1.5e9;
    lumped::MoatWall wall              = moat_wall(gap, bumper);
    wall.bumper_thickness              = 0.05;
    return wall;
  }

  /**
   * The 4-storey isolated reference building of docs/physics.md §3 with a moat wall at `gap` [m]
   * on each side, both walls with contact_law(law, stiffness, cor).
   */
  inline lumped::PoundingScene
  walled_scene(const std::string &law, double stiffness, double gap, double cor = 0.7)
  {
    const lumped::MoatWall wall = moat_wall(gap, contact_law(law, stiffness, cor));
    lumped::PoundingScene  scene;
    scene.building   = lumped::reference_isolated_building(4);
    scene.left_wall  = wall;
    scene.right_wall = wall;
    return scene;
  }

  /**
   * A bilinear wall-and-backfill part: pushover stiffness `stiffness` [N/m], capacity
   * `capacity` [N], hardening ratio `hardening_ratio` and unloading stiffness
   * `unloading_stiffness` [N/m]; no pull-back, dashpot or mass (the tests add theirs).
   */
  inline lumped::WallBackfillParams bilinear_wall_part(double stiffness,
                                                       double capacity,
                                                       double hardening_ratio,
                                                       double unloading_stiffness)
  {
    lumped::WallBackfillParams p;
    p.envelope            = lumped::WallEnvelope::bilinear;
    p.stiffness           = stiffness;
    p.capacity            = capacity;
    p.hardening_ratio     = hardening_ratio;
    p.unloading_stiffness = unloading_stiffness;
    return p;
  }

  /// The synthetic near-fault record of default parameters, `duration` [s] long.
  inline lumped::GroundMotion near_fault_motion(double duration)
  {
    lumped::SyntheticMotionSpec spec;
    spec.duration = duration;
    return lumped::synthetic_near_fault(spec);
  }

  /// The 48 s synthetic near-fault record sampled at 0.01 s (Kobe KJMA length and sampling) of
  /// the benchmarks, made once.
  inline const lumped::GroundMotion &kobe_length_motion()
  {
    static const lumped::GroundMotion g = []
    {
      lumped::SyntheticMotionSpec spec;
      spec.duration          = 48.0;
      spec.dt                = 0.01;
      spec.envelope_duration = 30.0;
      return lumped::synthetic_near_fault(spec);
    }();
    return g;
  }

  /// A record of zero acceleration, step `dt` [s], `duration` [s] long (for free vibration).
  inline lumped::GroundMotion zero_motion(double dt, double duration)
  {
    lumped::GroundMotion g;
    g.dt = dt;
    g.acceleration.assign(static_cast<std::size_t>(std::lround(duration / dt)), 0.0);
    g.name = "zero";
    return g;
  }
} // namespace kimp::testing
