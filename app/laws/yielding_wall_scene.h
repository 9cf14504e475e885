// The `yielding` section of a moat wall in `kimp lumped` scenes (docs/physics.md §2 "Yielding moat
// wall"): the wall-and-backfill part per metre of wall, its first-guess defaults from a published
// abutment-backfill curve and the soil's impedance, and its lumped::WallBackfillParams.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/laws/wall_keys.h"
#include "fit/fitter.h"
#include "io/scene_io.h"
#include "lumped/laws/wall_backfill_law.h"

namespace kimp::app
{
  /**
   * The wall-and-backfill part of a yielding wall, per metre of wall (× width for the whole
   * wall). Keys left null take their first guess from the loaded height h (resolved()):
   * stiffness and capacity from the Caltrans-style height-dependent abutment backfill spring
   * (K = w·(5.5h + 20) kip/in, P = w·5.5h^2.5/(1 + 2.37h) kip, w and h in ft, as coded for
   * ElasticPPGap backfill springs in public OpenSees bridge models; at h = 5.5 ft it gives
   * 50 kip/in/ft and 5 ksf over the height), the dashpot from the soil's impedance ρ·c·h, the
   * unloading stiffness equal to the stiffness, the pull-back equal to the capacity, and the
   * failure limit at 10 % of h.
   */
  /// One point of a curve envelope: the wall's displacement and its force per metre.
  struct WallCurvePointScene
  {
    double displacement = 0.0; ///< m
    double force        = 0.0; ///< N per m
  };

  template <class Io>
  void visit(Io &io, WallCurvePointScene &s)
  {
    io.quantity("displacement",
                s.displacement,
                "mm",
                "the wall's displacement into its backfill",
                io::Range::non_negative());
    io.quantity("force",
                s.force,
                "kN/m",
                "the pushover force per metre",
                io::Range::non_negative());
  }

  struct YieldingWallScene
  {
    double                           width    = fit::thesis_building_width; ///< m
    double                           height   = 1.5;                        ///< loaded height h, m
    lumped::WallEnvelope             envelope = lumped::WallEnvelope::bilinear;
    std::optional<double>            stiffness; ///< N/m per m
    std::optional<double>            capacity;  ///< N per m
    double                           hardening_ratio = 0.0;
    std::optional<double>            ultimate_capacity; ///< N per m (null: no cap)
    double                           failure_ratio = 0.7;
    std::optional<double>            unloading_stiffness;      ///< N/m per m
    std::optional<double>            tension_capacity;         ///< N per m
    double                           soil_density    = 1800.0; ///< kg/m³
    double                           soil_wave_speed = 200.0;  ///< m/s
    std::optional<double>            radiation_damping;        ///< N·s/m per m
    std::optional<double>            failure_displacement;     ///< m
    std::vector<WallCurvePointScene> curve; ///< envelope curve: the points, from (0, 0)

    /// The Caltrans-style first guesses at `height` (per metre): stiffness N/m/m, capacity N/m.
    double default_stiffness() const;
    double default_capacity() const;
    /// The capacity per metre, N/m: the curve's last force, or `capacity` (null: the first
    /// guess).
    double capacity_per_metre() const;

    /// The engine's parameters of the whole wall (× width), null keys resolved; `mass` is left
    /// to the model (the wall DOF's mass).
    lumped::WallBackfillParams resolved() const;
  };

  /// The rules of a yielding section its ranges cannot say, with keys under `prefix` (e.g.
  /// "walls.left.yielding."): the curve envelope's points (concave, monotone, from (0, 0), the
  /// failing point's index named) and the keys it sets itself (stiffness, capacity,
  /// hardening_ratio, ultimate_capacity) left out; points refused without the curve envelope.
  void validate_yielding_wall(const YieldingWallScene &y,
                              const std::string       &prefix,
                              io::ValidationContext   &ctx);

  /// A stiffness of the wall and backfill per metre of wall (shown in kN/mm/m, > 0); `doc` says
  /// which.
  template <class Io>
  void visit_stiffness_per_metre(Io                    &io,
                                 std::string_view       key,
                                 std::optional<double> &stiffness,
                                 std::string_view       doc)
  {
    io.quantity(key, stiffness, "kN/mm/m", doc, io::Range::positive());
  }

  /// A force of the wall and backfill per metre of wall: a capacity (shown in kN/m, > 0, or
  /// `range` where zero is admitted); `doc` says which.
  template <class Io>
  void visit_force_per_metre(Io                    &io,
                             std::string_view       key,
                             std::optional<double> &force,
                             std::string_view       doc,
                             const io::Range       &range = io::Range::positive())
  {
    io.quantity(key, force, "kN/m", doc, range);
  }

  template <class Io>
  void visit(Io &io, YieldingWallScene &s)
  {
    visit_building_width(io, s.width, "wall length the building hits (k, F × width)");
    visit_wall_height(io,
                      "height",
                      s.height,
                      "loaded height h of wall and backfill (for the first guesses of null keys)");
    io.choice("envelope",
              s.envelope,
              {{"bilinear", lumped::WallEnvelope::bilinear},
               {"hyperbolic", lumped::WallEnvelope::hyperbolic},
               {"curve", lumped::WallEnvelope::curve}},
              "virgin pushover: bilinear (k up to the capacity, then hardening_ratio*k; OpenSees "
              "ElasticPPGap), hyperbolic (w/(1/k + failure_ratio*w/capacity); OpenSees "
              "HyperbolicGapMaterial) or curve (piecewise linear through `curve`, flat past its "
              "last point)");
    io.list("curve",
            s.curve,
            "envelope curve: points {displacement, force per metre} from {0 mm, 0 kN/m}, "
            "displacements increasing, forces not decreasing, slopes not increasing (concave); "
            "k is the first slope and the capacity the last force");
    visit_stiffness_per_metre(
      io,
      "stiffness",
      s.stiffness,
      "initial (cracked) stiffness of wall and backfill per metre (null: Caltrans-style "
      "(5.5h + 20) kip/in per ft, h in ft; curve: its first slope, leave null)");
    visit_force_per_metre(
      io,
      "capacity",
      s.capacity,
      "bilinear: the force cap; hyperbolic: F_ult; per metre (null: Caltrans-style "
      "5.5h^2.5/(1 + 2.37h) kip per ft, h in ft; curve: its last force, leave null)");
    io.quantity("hardening_ratio",
                s.hardening_ratio,
                "%",
                "bilinear: post-yield tangent as a fraction of stiffness",
                io::Range::at_least(0.0).and_less(1.0));
    visit_force_per_metre(
      io,
      "ultimate_capacity",
      s.ultimate_capacity,
      "bilinear: the force the hardening stops at, per metre (>= capacity; a pushover's "
      "largest force; null: no cap)");
    io.quantity("failure_ratio",
                s.failure_ratio,
                "",
                "hyperbolic: R_f, the curve tends to capacity/R_f",
                io::Range::greater(0.0).and_at_most(1.0));
    visit_stiffness_per_metre(
      io,
      "unloading_stiffness",
      s.unloading_stiffness,
      "unloading and reloading stiffness per metre (null: stiffness; below it, a "
      "cracked wall's spring-back: the element unloads at the larger of it and the "
      "envelope's secant, never leaving a negative set)");
    visit_force_per_metre(
      io,
      "tension_capacity",
      s.tension_capacity,
      "largest force pulling the wall back towards the building, per metre (its elastic "
      "spring-back; 0: compression only, like the OpenSees gap materials; null: capacity)",
      io::Range::non_negative());
    io.quantity("soil_density",
                s.soil_density,
                "kg/m^3",
                "backfill density rho (radiation dashpot first guess)",
                io::Range::positive());
    io.quantity("soil_wave_speed",
                s.soil_wave_speed,
                "m/s",
                "backfill wave speed c (radiation dashpot first guess)",
                io::Range::positive());
    io.quantity("radiation_damping",
                s.radiation_damping,
                "kN*s/m^2",
                "radiation dashpot to the ground per metre (null: rho*c*height)",
                io::Range::non_negative());
    io.quantity("failure_displacement",
                s.failure_displacement,
                "cm",
                "the wall is reported failed once pushed back farther (null: 10 % of height, "
                "where the published backfill curves end)",
                io::Range::positive());
  }
} // namespace kimp::app
