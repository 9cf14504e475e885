// The scene types of the scene-file tests (every Io verb, nested and listed sections, validators,
// ranges) and the error of loading a text as one of them.
#pragma once

#include <cmath>
#include <gtest/gtest.h>
#include <optional>
#include <string>
#include <vector>

#include "io/scene_io.h"
#include "io/units.h"
#include "tests/support/scene_errors.h"

namespace test_scene
{
  using kimp::io::format_quantity;
  using kimp::io::ValidationContext;

  enum class Law
  {
    linear,
    hertz
  };

  struct Isolator
  {
    std::string kind    = "bilinear";
    double      K1      = 200e6;
    double      K2      = 25e6;
    double      Q_ratio = 0.1;
  };

  template <class Io>
  void visit(Io &io, Isolator &s)
  {
    io.choice("kind", s.kind, {"linear", "bilinear"}, "isolator law");
    io.quantity("K1", s.K1, "MN/m", "initial stiffness");
    io.quantity("K2", s.K2, "MN/m", "post-yield stiffness");
    io.quantity("Q_ratio", s.Q_ratio, "%", "characteristic strength / total weight");
  }

  struct Case
  {
    std::string           name = "case";
    double                gap  = 0.15;
    Law                   law  = Law::linear;
    std::optional<double> cor;
  };

  template <class Io>
  void visit(Io &io, Case &s)
  {
    io.text("name", s.name, "case name");
    io.quantity("gap", s.gap, "cm", "clear gap to the moat wall");
    io.choice("law", s.law, {{"linear", Law::linear}, {"hertz", Law::hertz}}, "impact law");
    io.quantity("cor", s.cor, "", "coefficient of restitution");
  }

  struct Damper
  {
    double c = 1.5e6;
  };

  template <class Io>
  void visit(Io &io, Damper &s)
  {
    io.quantity("c", s.c, "MN*s/m", "damping coefficient");
  }

  struct Scene
  {
    int                   n_storeys  = 4;
    bool                  with_walls = true;
    std::string           record     = "synthetic";
    double                mass       = 320e3;
    double                pga        = 0.5 * 9.80665;
    double                k_hertz    = 750e3 / std::pow(1e-3, 1.5);
    double                damping    = 0.05;
    std::optional<double> duration;
    Isolator              isolator;
    std::optional<Damper> damper;
    std::vector<Case>     cases{Case{"near", 0.10, Law::hertz, 0.7}, Case{}};
    std::vector<double>   heights{1.0, 1.25};
  };

  template <class Io>
  void visit(Io &io, Scene &s)
  {
    io.integer("n_storeys", s.n_storeys, "storeys above the isolation level", 1, 50);
    io.flag("with_walls", s.with_walls, "moat walls present");
    io.text("record", s.record, "ground motion: 'synthetic' or an AT2 file name");
    io.quantity("mass", s.mass, "t", "floor mass");
    io.quantity("pga", s.pga, "g", "peak ground acceleration");
    io.quantity("k_hertz", s.k_hertz, "kN/mm^1.5", "Hertz impact stiffness");
    io.quantity("damping", s.damping, "%", "structural damping ratio");
    io.quantity("duration", s.duration, "s", "record duration (all of it when null)");
    io.section("isolator", s.isolator, "isolation system");
    io.optional_section("damper", s.damper, "supplemental damper");
    io.list("cases", s.cases, "cases run in one call");
    io.quantity_list("heights", s.heights, "m", "wall heights");
  }

  /// A validator of a nested struct, with keys relative to it.
  inline void validate(const Isolator &s, ValidationContext &ctx)
  {
    ctx.check(s.K2 < s.K1,
              "K2",
              format_quantity(s.K2, "MN/m"),
              "must be < K1 = " + format_quantity(s.K1, "MN/m"));
  }

  inline void validate(const Scene &s, ValidationContext &ctx)
  {
    {
      const auto scope = ctx.section("isolator");
      validate(s.isolator, ctx);
    }
    ctx.check(s.mass > 0, "mass", format_quantity(s.mass, "t"), "must be > 0");
    for (std::size_t i = 0; i < s.cases.size(); ++i)
    {
      const auto scope = ctx.section("cases[" + std::to_string(i) + "]");
      ctx.check(s.cases[i].gap >= 0, "gap", format_quantity(s.cases[i].gap, "cm"), "must be >= 0");
    }
  }

  /// A struct with a member validate() and an empty default list.
  struct Study
  {
    std::vector<Case> cases;
    double            dt        = 1e-4;
    std::size_t       n_threads = 1;

    void validate(ValidationContext &ctx) const
    {
      ctx.check(dt > 0, "dt", format_quantity(dt, "s"), "must be > 0");
    }
  };

  template <class Io>
  void visit(Io &io, Study &s)
  {
    io.list("cases", s.cases, "cases");
    io.quantity("dt", s.dt, "s", "time step");
    io.integer("n_threads", s.n_threads, "worker threads");
  }

  /// Quantities with ranges, and one rule linking two keys.
  struct Ranged
  {
    double                x = 1.0;
    std::optional<double> y;
    std::vector<double>   z = {0.5};
    double                r = 0.5;
    double                f = 1.0;
  };

  template <class Io>
  void visit(Io &io, Ranged &s)
  {
    using kimp::io::Range;
    io.quantity("x", s.x, "m", "length", Range::positive());
    io.quantity("y", s.y, "s", "time", Range::positive().because("or null"));
    io.quantity_list("z", s.z, "", "fractions", Range::greater(0.0).and_at_most(1.0));
    io.quantity("r", s.r, "%", "ratio", Range::at_least(0.0).and_less(1.0));
    io.quantity("f", s.f, "", "factor (negative flips it)", Range::nonzero());
  }

  inline void validate(const Ranged &s, ValidationContext &ctx)
  {
    ctx.check(s.z.size() <= 3, "z", std::to_string(s.z.size()) + " values", "must be at most 3");
    // A rule that follows from x's range too: reported once, by the range.
    ctx.check(s.x > 0.0 && s.x < 10.0, "x", format_quantity(s.x, "m"), "must be in (0, 10 m)");
  }
} // namespace test_scene

namespace scene_io_test
{
  using test_scene::Scene;

  inline const std::string file_name = "scene.yaml";

  /// The SceneError message of loading `text` as Scene, or "" if it loads.
  template <class T = Scene>
  std::string scene_error(const std::string &text)
  {
    return kimp::testing::scene_error<T>(text, file_name);
  }

  /// Expects `message` to contain every one of `parts`.
  inline void expect_contains(const std::string &message, const std::vector<std::string> &parts)
  {
    EXPECT_FALSE(message.empty()) << "expected an error containing '" << parts.front() << "'";
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos)
        << "message: " << message << "\nmissing: " << part;
  }
} // namespace scene_io_test
