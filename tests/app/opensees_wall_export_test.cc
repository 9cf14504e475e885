// Yielding moat walls as OpenSees input (app/export/opensees_wall_export.h): every number written
// is the scene's per-metre value × width in OpenSees' argument order and sign convention, the
// materials are arranged in parallel (wall part) and in series (contact part) with the right
// element orientation, and Tcl and OpenSeesPy agree. A curve envelope is a parallel of
// ElasticPPGap springs whose sum, run by OpenSees' rule, is kimp's envelope.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/export/opensees_wall_export.h"
#include "app/lumped/lumped_scene.h"
#include "lumped/laws/wall_backfill_law.h"
#include "tests/support/messages.h"

namespace
{
  using kimp::app::LumpedScene;
  using kimp::testing::expect_contains;

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
  expect_contains(tcl, {"tension_capacity = 3000000 N (the wall's pull-back) has no counterpart"});

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
  expect_contains(tcl, {"the contact part acts across a gap of 0.1 m"});

  const std::string py = kimp::app::opensees_walls_text(walls, true);
  expect_contains(py,
                  {"import openseespy.opensees as ops",
                   "ops.uniaxialMaterial('ElasticPPGap', 11, 500000000, -3000000, 0.0, 0.02, "
                   "'damage')",
                   "ops.element('zeroLength', 1002, 1001, kimpBuildingNode, '-mat', "
                   "kimpImpactMaterial, '-dir', 1)",
                   "ops.node(1001, 0.0, '-mass', 60000)"});
}

namespace
{
  /// Left wall: a curve of 4 segments, slopes 50, 20, 6, 1 kN/mm/m, flat past 20 mm at
  /// 200 kN/m; right wall: 2 segments, slopes 25 and 2 kN/mm/m, flat past 30 mm at 198 kN/m.
  /// Both 20 m of wall.
  const char *const curve_scene_text =
    "walls:\n"
    "  left:\n    gap: \"10 cm\"\n    sdof_mass: \"60 t\"\n"
    "    yielding:\n      width: \"20 m\"\n      envelope: curve\n"
    "      curve:\n"
    "        - {displacement: 0 mm, force: 0 kN/m}\n"
    "        - {displacement: 2 mm, force: 100 kN/m}\n"
    "        - {displacement: 5 mm, force: 160 kN/m}\n"
    "        - {displacement: 10 mm, force: 190 kN/m}\n"
    "        - {displacement: 20 mm, force: 200 kN/m}\n"
    "      unloading_stiffness: \"30 kN/mm/m\"\n"
    "      radiation_damping: \"300 kN*s/m^2\"\n"
    "  right:\n    gap: \"12 cm\"\n    sdof_mass: \"40 t\"\n"
    "    yielding:\n      width: \"20 m\"\n      envelope: curve\n"
    "      curve:\n"
    "        - {displacement: 0 mm, force: 0 kN/m}\n"
    "        - {displacement: 6 mm, force: 150 kN/m}\n"
    "        - {displacement: 30 mm, force: 198 kN/m}\n"
    "      tension_capacity: \"0 kN/m\"\n"
    "      radiation_damping: \"0 kN*s/m^2\"\n";

  /**
   * OpenSees' ElasticPPGap (EPPGapMaterial) on its compression side as the export writes it:
   * F_y < 0, gap 0, eta 0, "damage". Its documented rule: with the yield strain e_y (initially
   * F_y/E) and the set e_0 (initially the gap, 0), a trial strain e below e_y gives the stress
   * F_y, above e_0 gives 0, in between E·(e − e_0); a commit below e_y moves e_y to e and e_0 to
   * e − F_y/E ("damage": the set never closes again). Written here from that rule, not from
   * kimp's law.
   */
  struct ElasticPPGapModel
  {
    double e, fy;
    double yield_strain = fy / e;
    double set          = 0.0;
    double strain       = 0.0;

    double trial(const double strain_)
    {
      strain = strain_;
      if (strain < yield_strain)
        return fy;
      if (strain > set)
        return 0.0;
      return e * (strain - set);
    }
    void commit()
    {
      if (strain < yield_strain)
      {
        yield_strain = strain;
        set          = strain - fy / e;
      }
    }
  };

  /// The Parallel of the written springs: the sum of their stresses at the strain −w, as the
  /// resistance R(w) > 0 into the backfill; each step committed.
  struct ParallelModel
  {
    std::vector<ElasticPPGapModel> springs;

    double push(const double w)
    {
      double stress = 0.0;
      for (ElasticPPGapModel &s : springs)
        stress += s.trial(-w);
      for (ElasticPPGapModel &s : springs)
        s.commit();
      return -stress;
    }
  };

  ParallelModel parallel_of(const std::vector<kimp::app::OpenSeesGapSpring> &springs)
  {
    ParallelModel m;
    for (const auto &s : springs)
      m.springs.push_back({s.stiffness, -s.yield_force});
    return m;
  }
} // namespace

// The curve envelope is one ElasticPPGap "damage" per kink, in parallel with the dashpot: the
// written E_i = s_i − s_(i+1) and F_y,i = −E_i·w_(i+1) of a 4- and a 2-segment curve, their
// tags, the Parallel's list, Tcl and Python alike.
TEST(OpenSeesWallExport, CurveEnvelopeIsElasticPPGapSpringsInParallel)
{
  const auto walls = kimp::app::opensees_walls(
    kimp::io::load_scene_text<LumpedScene>(curve_scene_text, "scene.yaml"));
  ASSERT_EQ(walls.size(), 2u);
  const std::string tcl = kimp::app::opensees_walls_text(walls, false);

  // Left: slopes × 20 m = 1e9, 4e8, 1.2e8, 2e7 N/m, then 0; breakpoints 2, 5, 10, 20 mm.
  const std::vector<std::pair<double, double>> left = {{6e8, 1.2e6},
                                                       {2.8e8, 1.4e6},
                                                       {1e8, 1e6},
                                                       {2e7, 4e5}};
  // Right: 5e8, 4e7 N/m, then 0; breakpoints 6, 30 mm.
  const std::vector<std::pair<double, double>> right = {{4.6e8, 2.76e6}, {4e7, 1.2e6}};
  const auto pp = lines_of(tcl, "uniaxialMaterial", "ElasticPPGap");
  ASSERT_EQ(pp.size(), left.size() + right.size()) << tcl;
  double sum_fy = 0.0;
  for (std::size_t i = 0; i < pp.size(); ++i)
  {
    const bool l       = i < left.size();
    const auto &[e, f] = l ? left[i] : right[i - left.size()];
    const int tag      = l ? 11 + int(i) : 17 + int(i - left.size()); // left: 4 + 2 tags
    ASSERT_EQ(pp[i].size(), 8u) << tcl;
    EXPECT_EQ(pp[i][2], std::to_string(tag));
    EXPECT_TRUE(near(pp[i][3], e) && near(pp[i][4], -f) && pp[i][5] == "0.0" && pp[i][6] == "0" &&
                pp[i][7] == "damage")
      << i << "\n"
      << tcl;
    if (l)
      sum_fy += std::stod(pp[i][4]);
  }
  EXPECT_TRUE(std::abs(sum_fy + 4e6) <= text * 4e6) << sum_fy; // the last force, 200 kN/m × 20 m
  // The same numbers from opensees_curve_springs(), unrounded.
  const auto springs = kimp::app::opensees_curve_springs(walls[0].part);
  ASSERT_EQ(springs.size(), left.size());
  for (std::size_t i = 0; i < left.size(); ++i)
  {
    EXPECT_NEAR(springs[i].stiffness, left[i].first, 1e-12 * 1e9);
    EXPECT_NEAR(springs[i].yield_force, left[i].second, 1e-12 * 4e6);
  }

  const auto vi = lines_of(tcl, "uniaxialMaterial", "Viscous");
  ASSERT_EQ(vi.size(), 2u) << tcl;
  EXPECT_EQ(vi[0],
            (std::vector<std::string>{"uniaxialMaterial", "Viscous", "15", "6000000", "1.0"}));
  EXPECT_EQ(vi[1][2], "19");
  const auto pa = lines_of(tcl, "uniaxialMaterial", "Parallel");
  ASSERT_EQ(pa.size(), 2u);
  EXPECT_EQ(
    pa[0],
    (std::vector<std::string>{"uniaxialMaterial", "Parallel", "16", "11", "12", "13", "14", "15"}));
  EXPECT_EQ(pa[1],
            (std::vector<std::string>{"uniaxialMaterial", "Parallel", "20", "17", "18", "19"}));
  const auto el = lines_of(tcl, "element");
  ASSERT_EQ(el.size(), 4u) << tcl;
  EXPECT_EQ(el[0][6], "16");
  EXPECT_EQ(el[2][6], "20");
  // What differs is said: the unloading, the set past the last kink, the pull-back.
  expect_contains(tcl,
                  {"the curve envelope (5 points) as 4 ElasticPPGap springs in parallel",
                   "keep a set only past the last kink: max(0, w_max - 0.02 m)",
                   "max(unloading_stiffness = 600000000 N/m, E(w_max)/w_max)",
                   "tension_capacity = 4000000 N (the wall's pull-back) has no counterpart"});

  const std::string py = kimp::app::opensees_walls_text(walls, true);
  expect_contains(py,
                  {"ops.uniaxialMaterial('ElasticPPGap', 11, 600000000, -1200000, 0.0, 0, "
                   "'damage')",
                   "ops.uniaxialMaterial('ElasticPPGap', 18, 40000000, -1200000, 0.0, 0, "
                   "'damage')",
                   "ops.uniaxialMaterial('Parallel', 16, 11, 12, 13, 14, 15)"});
  EXPECT_EQ(lines_of(tcl, "uniaxialMaterial").size(), 10u);
}

// The Parallel of the written springs, run as OpenSees' ElasticPPGap rule does, is kimp's
// envelope on a monotonic push to 1e-12, at every breakpoint and between them; unloaded, each
// spring keeps its own set w_max − w_(i+1), so the arrangement's force is
// Σ E_i·max(0, w − max(0, w_max − w_(i+1))) and its set max(0, w_max − w_c), w_c the last kink,
// against kimp's w_max − E(w_max)/max(k_ur, E(w_max)/w_max).
TEST(OpenSeesWallExport, CurveSpringsReproduceTheEnvelopeAndKeepTheirOwnSets)
{
  const auto walls = kimp::app::opensees_walls(
    kimp::io::load_scene_text<LumpedScene>(curve_scene_text, "scene.yaml"));
  for (const kimp::app::OpenSeesWall &wall : walls)
  {
    kimp::lumped::WallBackfillParams p = wall.part;
    p.mass = wall.mass; // the wall DOF's (the law checks it; it does not enter R)
    const auto                 springs = kimp::app::opensees_curve_springs(p);
    const std::vector<double> &x       = p.curve_displacements;
    const double               f_n     = p.curve_forces.back();
    const double               w_c     = springs.back().yield_force / springs.back().stiffness;
    EXPECT_NEAR(w_c, x.back(), 1e-15);
    // The push: every breakpoint, its neighbours and the thirds of each segment, to 1.3 w_n.
    std::vector<double> path;
    for (std::size_t i = 1; i < x.size(); ++i)
      for (const double t : {1.0 / 3.0, 0.5, 2.0 / 3.0, 1.0 - 1e-9, 1.0, 1.0 + 1e-9})
        path.push_back(x[i - 1] + t * (x[i] - x[i - 1]));
    path.push_back(1.3 * x.back());
    for (const double w_max : {0.6 * x.back(), 1.3 * x.back()})
    {
      kimp::lumped::WallBackfillLaw law(p);
      ParallelModel                 model = parallel_of(springs);
      for (const double w : path)
      {
        if (w > w_max)
          break;
        law.set_trial(w, 0.0);
        law.commit();
        EXPECT_NEAR(model.push(w), law.committed_state().spring_force, 1e-12 * f_n)
          << wall.name << " at w = " << w;
      }
      law.set_trial(w_max, 0.0);
      law.commit();
      EXPECT_NEAR(model.push(w_max), law.committed_state().spring_force, 1e-12 * f_n);
      // Unloading: the closed form of the parallel springs, step by step to 0.
      const double set = std::max(0.0, w_max - w_c);
      for (int step = 1; step <= 200; ++step)
      {
        const double w        = w_max * (1.0 - step / 200.0);
        double       expected = 0.0;
        for (const auto &s : springs)
          expected +=
            s.stiffness * std::max(0.0, w - std::max(0.0, w_max - s.yield_force / s.stiffness));
        EXPECT_NEAR(model.push(w), expected, 1e-12 * f_n) << wall.name << " at w = " << w;
        if (w <= set)
          EXPECT_EQ(model.push(w), 0.0) << wall.name << " at w = " << w;
        else
          EXPECT_GT(model.push(w), 0.0) << wall.name << " at w = " << w;
      }
      const double kimp_set = law.permanent_indentation();
      const double e_max    = law.envelope(w_max);
      EXPECT_NEAR(kimp_set, w_max - e_max / std::max(p.unloading_stiffness, e_max / w_max), 1e-15);
      std::printf("%s: w_max %.4g mm: OpenSees springs' set %.4g mm, kimp's %.4g mm\n",
                  wall.name.c_str(),
                  w_max * 1e3,
                  set * 1e3,
                  kimp_set * 1e3);
    }
  }
}

// A 2-segment curve flat past its knee is the bilinear without hardening: the same
// ElasticPPGap, Viscous and Parallel lines, the same tags.
TEST(OpenSeesWallExport, FlatTwoSegmentCurveIsTheBilinearWithoutHardening)
{
  const std::string head  = "walls:\n  left:\n    gap: \"10 cm\"\n    sdof_mass: \"60 t\"\n"
                            "    yielding:\n      width: \"20 m\"\n"
                            "      radiation_damping: \"300 kN*s/m^2\"\n";
  const auto        curve = kimp::app::opensees_walls(
    kimp::io::load_scene_text<LumpedScene>(head +
                                             "      envelope: curve\n      curve:\n"
                                                    "        - {displacement: 0 mm, force: 0 kN/m}\n"
                                                    "        - {displacement: 6 mm, force: 150 kN/m}\n"
                                                    "        - {displacement: 30 mm, force: 150 kN/m}\n",
                                           "curve.yaml"));
  const auto bilinear = kimp::app::opensees_walls(kimp::io::load_scene_text<LumpedScene>(
    head + "      stiffness: \"25 kN/mm/m\"\n      capacity: \"150 kN/m\"\n"
           "      hardening_ratio: \"0 %\"\n",
    "bilinear.yaml"));
  for (const bool python : {false, true})
  {
    const std::string a        = kimp::app::opensees_walls_text(curve, python);
    const std::string b        = kimp::app::opensees_walls_text(bilinear, python);
    const auto        commands = [](const std::string &t)
    {
      std::vector<std::string> out;
      std::istringstream       lines(t);
      for (std::string line; std::getline(lines, line);)
        if (!line.empty() && line[0] != '#')
          out.push_back(line);
      return out;
    };
    EXPECT_EQ(commands(a), commands(b)) << a << "\n" << b;
    expect_contains(a,
                    {python ? "('ElasticPPGap', 11, 500000000, -3000000, 0.0, 0, 'damage')" :
                              "ElasticPPGap 11 500000000 -3000000 0.0 0 damage"});
  }
}

// A collinear point is no kink: it gets no spring, and the envelope is still exact.
TEST(OpenSeesWallExport, CollinearCurvePointGetsNoSpring)
{
  const auto walls = kimp::app::opensees_walls(kimp::io::load_scene_text<LumpedScene>(
    "walls:\n  left:\n    yielding:\n      width: \"1 m\"\n      envelope: curve\n"
    "      curve:\n"
    "        - {displacement: 0 mm, force: 0 kN/m}\n"
    "        - {displacement: 1 mm, force: 50 kN/m}\n"
    "        - {displacement: 2 mm, force: 100 kN/m}\n"
    "        - {displacement: 4 mm, force: 120 kN/m}\n",
    "scene.yaml"));
  ASSERT_EQ(walls.size(), 1u);
  const auto springs = kimp::app::opensees_curve_springs(walls[0].part);
  ASSERT_EQ(springs.size(), 2u);
  EXPECT_NEAR(springs[0].stiffness, 4e7, 1e-6);
  EXPECT_NEAR(springs[0].yield_force, 8e4, 1e-6);
  EXPECT_NEAR(springs[1].stiffness, 1e7, 1e-6);
  EXPECT_NEAR(springs[1].yield_force, 4e4, 1e-6);
  EXPECT_THROW(kimp::app::opensees_curve_springs(kimp::lumped::WallBackfillParams{}),
               std::invalid_argument);
}
