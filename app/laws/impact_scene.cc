// Impact law section: its cross-key rules, exponent, stiffness (text, k table or SI), bumper
// stiffness k_b = 2.25·N·A·K_r/t^n (thesis eqs. 6.2-6.3) and lumped::ForceLawSpec; see
// impact_scene.h.
#include "app/laws/impact_scene.h"

#include <stdexcept>

#include "app/laws/k_table.h"
#include "fit/fitter.h"
#include "io/units.h"
#include "lumped/laws/bumper_law.h"
#include "lumped/laws/law_traits.h"

namespace kimp::app
{
  using namespace kimp::io;
  namespace
  {
    /// Dimension of N/m^n: kg·m^(1−n)·s^−2.
    Dimension stiffness_dimension(const double exponent)
    {
      return Dimension{1.0, 1.0 - exponent, -2.0};
    }
  } // namespace

  void validate_law(const ImpactLawScene &law, ValidationContext &ctx, const bool bumper_allowed)
  {
    const lumped::LawTraits *traits = lumped::find_law_traits(law.law);
    if (!ctx.check(traits != nullptr, "law", law.law, "must be one of " + lumped::law_name_list()))
      return;
    if (!bumper_allowed)
      ctx.check(!traits->moat_wall_only,
                "law",
                law.law,
                law.law + " acts only at the moat walls (use another law for floor contacts)");
    if (law.exponent && traits->fixed_exponent())
      ctx.fail("exponent",
               format_quantity(*law.exponent, ""),
               "must be null: law " + law.law + " has a fixed exponent");
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

  ImpactScene with_table_stiffness(const ImpactScene &impact, ValidationContext &ctx, bool required)
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

  double impact_exponent(const ImpactLawScene &law)
  {
    // An unknown law (refused by validate_law) keeps a given exponent, else n = 1.
    const lumped::LawTraits *traits = lumped::find_law_traits(law.law);
    return traits ? traits->exponent(law.exponent) : law.exponent.value_or(1.0);
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
    if (!lumped::law_traits(impact.law, "impact").fixed_exponent())
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
} // namespace kimp::app
