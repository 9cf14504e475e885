// Yielding moat walls as OpenSees input (app/export/opensees_wall_export.h): every number written
// is the scene's per-metre value × width in OpenSees' argument order and sign convention, the
// materials are arranged in parallel (wall part) and in series (contact part) with the right
// element orientation, and Tcl and OpenSeesPy agree.
#include <gtest/gtest.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/export/opensees_wall_export.h"
#include "app/lumped/lumped_scene.h"

namespace
{
  using kimp::app::LumpedScene;

  constexpr double text = 1e-9; // relative: numbers written with 10 significant digits

  /// Left wall bilinear, right wall hyperbolic, both 20 m of wall, with their own masses.
  const char *const scene_text =
    "walls:\n"
    "  left:\n    gap: \"10 cm\"\n    sdof_mass: \"60 t\"\n"
    "    yielding:\n      width: \"20 m\"\n"
    "      stiffness: \"25 kN/mm/m\"\n      capacity: \"150 kN/m\"\n"
    "      hardening_ratio: \"2 %\"\n"
    "      radiation_damping: \"300 kN*s/m^2\"\n"
    "  right:\n    gap: \"12 cm\"\n    sdof_mass: \"40 t\"\n"
    "    yielding:\n      width: \"20 m\"\n      envelope: hyperbolic\n"
    "      stiffness: \"20 kN/mm/m\"\n      capacity: \"326 kN/m\"\n"
    "      unloading_stiffness: \"30 kN/mm/m\"\n"
    "      failure_ratio: 0.7\n      tension_capacity: \"0 kN/m\"\n"
    "      radiation_damping: \"0 kN*s/m^2\"\n";

  /// The words of every Tcl line starting with `command` (and, if given, `second`).
  std::vector<std::vector<std::string>>
  lines_of(const std::string &tcl, const std::string &command, const std::string &second = "")
  {
    std::vector<std::vector<std::string>> out;
    std::istringstream                    lines(tcl);
    for (std::string line; std::getline(lines, line);)
    {
      std::istringstream       words(line);
      std::vector<std::string> w;
      for (std::string x; words >> x;)
        w.push_back(x);
      if (!w.empty() && w[0] == command && (second.empty() || (w.size() > 1 && w[1] == second)))
        out.push_back(w);
    }
    return out;
  }

  bool near(const std::string &written, double expected)
  {
    return std::abs(std::stod(written) - expected) <= text * std::abs(expected);
  }
} // namespace

TEST(OpenSeesWallExport, MaterialsCarryTheSceneTimesWidthInArgumentOrder)
{
  const auto walls =
    kimp::app::opensees_walls(kimp::io::load_scene_text<LumpedScene>(scene_text, "scene.yaml"));
  ASSERT_EQ(walls.size(), 2u);
  const std::string tcl = kimp::app::opensees_walls_text(walls, false);

  // ElasticPPGap $tag $E $Fy $gap $eta damage: E = 25 kN/mm/m × 20 m, Fy = −150 kN/m × 20 m.
  const auto pp = lines_of(tcl, "uniaxialMaterial", "ElasticPPGap");
  ASSERT_EQ(pp.size(), 1u) << tcl;
  ASSERT_EQ(pp[0].size(), 8u) << tcl;
  EXPECT_EQ(pp[0][2], "11");
  EXPECT_TRUE(near(pp[0][3], 500e6) && near(pp[0][4], -3e6) && pp[0][5] == "0.0" &&
              near(pp[0][6], 0.02) && pp[0][7] == "damage")
    << tcl;
  // HyperbolicGapMaterial $tag $Kmax $Kur $Rf $Fult $gap.
  const auto hg = lines_of(tcl, "uniaxialMaterial", "HyperbolicGapMaterial");
  ASSERT_EQ(hg.size(), 1u) << tcl;
  ASSERT_EQ(hg[0].size(), 8u) << tcl;
  EXPECT_EQ(hg[0][2], "14");
  EXPECT_TRUE(near(hg[0][3], 400e6) && near(hg[0][4], 600e6) && near(hg[0][5], 0.7) &&
              near(hg[0][6], -6.52e6) && hg[0][7] == "0.0")
    << tcl;
  // Viscous $tag $C 1.0 in parallel: C = 300 kN·s/m² × 20 m; the right wall's is 0.
  const auto vi = lines_of(tcl, "uniaxialMaterial", "Viscous");
  ASSERT_EQ(vi.size(), 2u) << tcl;
  EXPECT_TRUE(near(vi[0][3], 6e6) && vi[0][4] == "1.0") << tcl;
  EXPECT_EQ(std::stod(vi[1][3]), 0.0);
  const auto pa = lines_of(tcl, "uniaxialMaterial", "Parallel");
  ASSERT_EQ(pa.size(), 2u);
  EXPECT_EQ(pa[0], (std::vector<std::string>{"uniaxialMaterial", "Parallel", "13", "11", "12"}));
  EXPECT_EQ(pa[1], (std::vector<std::string>{"uniaxialMaterial", "Parallel", "16", "14", "15"}));
  // The left wall's default pull-back has no counterpart; it is said, not hidden.
  EXPECT_NE(tcl.find("tension_capacity = 3000000 N (the wall's pull-back) has no counterpart"),
            std::string::npos)
    << tcl;

  // Nodes: each wall's mass, a fixed ground node.
  const auto nodes = lines_of(tcl, "node");
  ASSERT_EQ(nodes.size(), 4u);
  EXPECT_EQ(nodes[0], (std::vector<std::string>{"node", "1001", "0.0", "-mass", "60000"}));
  EXPECT_EQ(nodes[2], (std::vector<std::string>{"node", "1003", "0.0", "-mass", "40000"}));
  EXPECT_EQ(lines_of(tcl, "fix").size(), 2u);
  // Elements: u_j − u_i < 0 when closing. Left: wall part (ground, wall), contact (wall,
  // building); right: wall part (wall, ground), contact (building, wall).
  const auto el = lines_of(tcl, "element");
  ASSERT_EQ(el.size(), 4u) << tcl;
  EXPECT_EQ(
    el[0],
    (std::vector<
      std::string>{"element", "zeroLength", "1001", "1002", "1001", "-mat", "13", "-dir", "1"}));
  EXPECT_EQ(el[1],
            (std::vector<std::string>{"element",
                                      "zeroLength",
                                      "1002",
                                      "1001",
                                      "$kimpBuildingNode",
                                      "-mat",
                                      "$kimpImpactMaterial",
                                      "-dir",
                                      "1"}));
  EXPECT_EQ(el[2][3], "1003");
  EXPECT_EQ(el[2][4], "1004");
  EXPECT_EQ(el[3][3], "$kimpBuildingNode");
  EXPECT_EQ(el[3][4], "1003");
  EXPECT_NE(tcl.find("the contact part acts across a gap of 0.1 m"), std::string::npos);

  const std::string py = kimp::app::opensees_walls_text(walls, true);
  EXPECT_NE(py.find("import openseespy.opensees as ops"), std::string::npos);
  EXPECT_NE(py.find("ops.uniaxialMaterial('ElasticPPGap', 11, 500000000, -3000000, 0.0, 0.02, "
                    "'damage')"),
            std::string::npos)
    << py;
  EXPECT_NE(py.find("ops.element('zeroLength', 1002, 1001, kimpBuildingNode, '-mat', "
                    "kimpImpactMaterial, '-dir', 1)"),
            std::string::npos)
    << py;
  EXPECT_NE(py.find("ops.node(1001, 0.0, '-mass', 60000)"), std::string::npos) << py;
}

// No OpenSees material is exact for the curve envelope: the export refuses it, naming the wall
// and what is missing, and writes no file.
TEST(OpenSeesWallExport, RefusesTheCurveEnvelope)
{
  const auto walls = kimp::app::opensees_walls(kimp::io::load_scene_text<LumpedScene>(
    "walls:\n  left:\n    yielding:\n      envelope: curve\n      curve:\n"
    "        - {displacement: 0 mm, force: 0 kN/m}\n"
    "        - {displacement: 2 mm, force: 100 kN/m}\n"
    "        - {displacement: 1 cm, force: 140 kN/m}\n",
    "scene.yaml"));
  ASSERT_EQ(walls.size(), 1u);
  for (const bool python : {false, true})
  {
    try
    {
      kimp::app::opensees_walls_text(walls, python);
      ADD_FAILURE() << "the curve envelope was exported";
    }
    catch (const std::invalid_argument &e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("left_wall: the curve envelope (3 points) has no exact OpenSees "
                          "material"),
                std::string::npos)
        << what;
      EXPECT_NE(what.find("envelope: bilinear or hyperbolic"), std::string::npos) << what;
    }
  }
}
