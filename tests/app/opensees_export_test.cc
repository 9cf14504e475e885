// `kimp export-opensees` (app/export/opensees_export.h): every number written is checked against
// its formula — Kelvin-Voigt and Jankowski ξ from the COR, Hertzdamp ξ̄, and Muthukumar's bilinear
// ImpactMaterial, whose loop must dissipate the Hertz impact's energy ½·m_eff·v²·(1 − e²).
#include <cmath>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <vector>

#include "app/export/opensees_export.h"

namespace
{
  using kimp::app::OpenSeesLawInput;

  constexpr double pi    = 3.14159265358979323846;
  constexpr double exact = 1e-12; // relative: closed forms evaluated two ways
  constexpr double text  = 1e-9;  // relative: numbers written with 10 significant digits

  OpenSeesLawInput input()
  {
    OpenSeesLawInput in;
    in.k_kelvin_voigt  = 2496.09e6;                      // N/m (H = 1.25 m, k·W)
    in.k_hertz         = 1017.96e3 * std::pow(1e3, 1.5); // N/m^1.5
    in.cor             = 0.7;
    in.effective_mass  = 195e3;
    in.impact_velocity = 0.8;
    in.gap             = 0.15;
    return in;
  }

  /// The numeric arguments after the tag of the Tcl line `uniaxialMaterial <type> <tag> ...`.
  std::vector<double> tcl_arguments(const std::string &tcl, const std::string &type)
  {
    std::istringstream lines(tcl);
    for (std::string line; std::getline(lines, line);)
    {
      std::istringstream words(line);
      std::string        command, name;
      int                tag = 0;
      words >> command >> name >> tag;
      if (command != "uniaxialMaterial" || name != type)
        continue;
      std::vector<double> values;
      for (double v; words >> v;)
        values.push_back(v);
      return values;
    }
    return {};
  }

  TEST(OpenSeesExport, DampingRatiosFollowTheCor)
  {
    const OpenSeesLawInput in = input();
    const auto             p  = kimp::app::opensees_parameters(in);
    const double           e  = in.cor;
    // Kelvin-Voigt: ξ = −ln e/sqrt(π² + ln² e); at e = 0.7: 0.1128 (Anagnostopoulos).
    EXPECT_NEAR(p.kv_xi, -std::log(e) / std::sqrt(pi * pi + std::log(e) * std::log(e)), exact);
    EXPECT_NEAR(p.kv_xi, 0.11280, 1e-5);
    EXPECT_NEAR(p.kv_c,
                2.0 * p.kv_xi * std::sqrt(*in.k_kelvin_voigt * in.effective_mass),
                exact * p.kv_c);
    // Jankowski: ξ = (9√5/2)(1 − e²)/(e(e(9π − 16) + 16)); at e = 0.7: 0.2981.
    EXPECT_NEAR(p.jankowski_xi,
                9.0 * std::sqrt(5.0) / 2.0 * (1 - e * e) / (e * (e * (9 * pi - 16) + 16)),
                exact);
    EXPECT_NEAR(p.jankowski_xi, 0.29811, 1e-5);
    EXPECT_NEAR(p.hertzdamp_xi_norm, 0.3825, exact);             // 3(1 − 0.49)/4
    EXPECT_NEAR(p.hertzdamp_xi_norm_ye, 8.0 * 0.3 / 3.5, exact); // 8(1 − e)/(5e)
  }

  TEST(OpenSeesExport, ImpactMaterialDissipatesTheHertzImpactEnergy)
  {
    for (const double a : {0.1, 0.2})
    {
      OpenSeesLawInput in = input();
      in.yield_ratio      = a;
      const auto   p      = kimp::app::opensees_parameters(in);
      const double k = *in.k_hertz, m = in.effective_mass, v = in.impact_velocity, e = in.cor;
      // δ_m from the energy balance ½·m·v² = k·δ_m^2.5/2.5.
      EXPECT_NEAR(0.5 * m * v * v, k * std::pow(p.delta_m, 2.5) / 2.5, exact * m * v * v);
      EXPECT_NEAR(p.energy, 0.5 * m * v * v * (1 - e * e), exact * m * v * v);
      EXPECT_NEAR(p.k_eff, k * std::sqrt(p.delta_m), exact * p.k_eff);
      EXPECT_NEAR(p.delta_y, a * p.delta_m, exact * p.delta_m);
      // K1 = K_eff(1 + (1 − e²)/(2.5a)), K2 = K_eff(1 − (1 − e²)/(2.5(1 − a))).
      EXPECT_NEAR(p.k1, p.k_eff * (1 + (1 - e * e) / (2.5 * a)), exact * p.k1);
      EXPECT_NEAR(p.k2, p.k_eff * (1 - (1 - e * e) / (2.5 * (1 - a))), exact * p.k1);
      // The bilinear loop's area (K1 − K2)·δ_y·(δ_m − δ_y) is the Hertz impact's loss.
      EXPECT_NEAR((p.k1 - p.k2) * p.delta_y * (p.delta_m - p.delta_y), p.energy, 1e-10 * p.energy);
    }
  }

  TEST(OpenSeesExport, TclAndPythonCarryTheNumbersInOpenSeesArgumentOrder)
  {
    const OpenSeesLawInput in  = input();
    const auto             p   = kimp::app::opensees_parameters(in);
    const std::string      tcl = kimp::app::opensees_tcl(in);
    EXPECT_NE(tcl.find("Units: N, m, s"), std::string::npos) << tcl;
    EXPECT_NE(tcl.find("k_KV = 2496090000 N/m"), std::string::npos) << tcl;

    const auto near = [](double a, double b) { return std::abs(a - b) <= text * std::abs(b); };
    // ViscoelasticGap $K $C $gap
    const auto vg = tcl_arguments(tcl, "ViscoelasticGap");
    ASSERT_EQ(vg.size(), 3u) << tcl;
    EXPECT_TRUE(near(vg[0], *in.k_kelvin_voigt) && near(vg[1], p.kv_c) && vg[2] == -0.15) << tcl;
    // ElasticPPGap $E $Fy $gap $eta (compression only: Fy and gap negative)
    const auto pp = tcl_arguments(tcl, "ElasticPPGap");
    ASSERT_EQ(pp.size(), 4u) << tcl;
    EXPECT_TRUE(near(pp[0], *in.k_kelvin_voigt) && pp[1] < 0.0 && pp[2] == -0.15 && pp[3] == 0.0);
    // JankowskiImpact $Kh $xi $Meff $gap $n
    const auto jk = tcl_arguments(tcl, "JankowskiImpact");
    ASSERT_EQ(jk.size(), 5u) << tcl;
    EXPECT_TRUE(near(jk[0], *in.k_hertz) && near(jk[1], p.jankowski_xi) &&
                near(jk[2], in.effective_mass) && jk[3] == -0.15 && jk[4] == 1.5)
      << tcl;
    // Hertzdamp $Kh $xiNorm $gap $n
    const auto hd = tcl_arguments(tcl, "Hertzdamp");
    ASSERT_EQ(hd.size(), 4u) << tcl;
    EXPECT_TRUE(near(hd[0], *in.k_hertz) && near(hd[1], 0.3825) && hd[2] == -0.15) << tcl;
    // ImpactMaterial $K1 $K2 $δy $gap (δy and gap negative)
    const auto im = tcl_arguments(tcl, "ImpactMaterial");
    ASSERT_EQ(im.size(), 4u) << tcl;
    EXPECT_TRUE(near(im[0], p.k1) && near(im[1], p.k2) && near(im[2], -p.delta_y) && im[3] == -0.15)
      << tcl;

    const std::string py = kimp::app::opensees_python(in);
    EXPECT_NE(py.find("import openseespy.opensees as ops"), std::string::npos);
    EXPECT_NE(py.find("ops.uniaxialMaterial('ImpactMaterial', 5, "), std::string::npos) << py;
    EXPECT_NE(py.find("ops.uniaxialMaterial('ViscoelasticGap', 1, 2496090000, "), std::string::npos)
      << py;
  }

  TEST(OpenSeesExport, BadInputIsRefused)
  {
    OpenSeesLawInput none = input();
    none.k_kelvin_voigt.reset();
    none.k_hertz.reset();
    EXPECT_THROW(kimp::app::opensees_parameters(none), std::invalid_argument);
    OpenSeesLawInput low = input();
    low.cor              = 0.05;
    low.yield_ratio      = 0.7; // K2 < 0: the bilinear loop cannot dissipate that much
    EXPECT_THROW(kimp::app::opensees_parameters(low), std::invalid_argument);
  }
} // namespace
