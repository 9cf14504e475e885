// `kimp lumped` scene: defaults equal docs/physics.md §3, unit conversions, every validate() rule
// reported as file:line:key, printed defaults read back, the key schema, shipped scenes load.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/lumped/lumped_scene.h"
#include "io/units.h"
#include "lumped/isolators/bilinear_isolator.h"
#include "lumped/isolators/bouc_wen_isolator.h"
#include "lumped/isolators/friction_pendulum_isolator.h"
#include "lumped/structure/pounding_model.h"
#include "lumped/structure/shear_building.h"
#include "tests/support/files.h"
#include "tests/support/messages.h"
#include "tests/support/scene_errors.h"

namespace
{
  using kimp::testing::expect_contains;
  using kimp::testing::source_dir;
  using namespace kimp::io;
  using namespace kimp::app;

  constexpr double exact_tolerance     = 1e-12; ///< relative, conversions of decimal literals
  constexpr double table_tolerance     = 5e-4;  ///< relative, values quoted to 4-5 digits
  constexpr double g                   = 9.80665;
  constexpr double kn_per_mm_1_5_in_si = 750e3 * 31622.776601683792; ///< 750 kN/mm^1.5 in N/m^1.5

  LumpedScene load(const std::string &text)
  {
    return load_scene_text<LumpedScene>(text, "scene.yaml");
  }

  /// The message of the SceneError thrown by loading `text` ("" if none is thrown).
  std::string error_of(const std::string &text)
  {
    return kimp::testing::scene_error<LumpedScene>(text, "scene.yaml");
  }
} // namespace

TEST(LumpedScene, DefaultsEqualThesisTable42)
{
  const LumpedScene s;
  EXPECT_EQ(s.building.kind, BuildingKind::isolated);
  EXPECT_EQ(s.building.n_storeys, 4u);
  EXPECT_DOUBLE_EQ(s.building.floor_mass, 320e3);
  EXPECT_DOUBLE_EQ(s.building.top_mass, 250e3);
  EXPECT_DOUBLE_EQ(s.building.isolation_mass, 320e3);
  EXPECT_DOUBLE_EQ(s.building.storey_stiffness, 600e6);
  EXPECT_DOUBLE_EQ(s.building.damping_ratio, 0.02);
  EXPECT_DOUBLE_EQ(s.building.fixed_base_damping_ratio, 0.05);
  EXPECT_DOUBLE_EQ(s.isolator.damping_ratio, 0.05);
  EXPECT_DOUBLE_EQ(s.walls.left.gap, 0.15);
  EXPECT_DOUBLE_EQ(s.walls.right.gap, 0.15);
  EXPECT_DOUBLE_EQ(s.walls.left.mass, 500e3);
  EXPECT_EQ(s.impact.law, "modified_kelvin_voigt");
  EXPECT_NEAR(impact_stiffness(s.impact), 2.5e9, 2.5e9 * exact_tolerance);
  EXPECT_DOUBLE_EQ(s.impact.cor, 0.7);
  EXPECT_FALSE(s.ground_motion.is_record());

  // Derived values quoted in docs/physics.md §3: W_tot 1530 t, Q = 1500.9 kN, F_y = 1715.3 kN,
  // u_y = 8.58 mm, c_iso = 1.0496 MN·s/m.
  const kimp::lumped::ShearBuilding b = make_building(s);
  EXPECT_NEAR(b.total_mass(), 1530e3, 1e-6);
  const auto *iso = dynamic_cast<const kimp::lumped::BilinearIsolator *>(b.isolator.get());
  ASSERT_NE(iso, nullptr);
  EXPECT_NEAR(iso->yield_force(), 1715.3e3, 1715.3e3 * table_tolerance);
  EXPECT_NEAR(iso->yield_force() * (1.0 - 25.0 / 200.0), 1500.9e3, 1500.9e3 * table_tolerance);
  EXPECT_NEAR(iso->yield_displacement(), 8.58e-3, 8.58e-3 * table_tolerance * 2);
  const kimp::lumped::BuildingDamping d = kimp::lumped::building_damping(b);
  EXPECT_NEAR(d.c_iso, 1.0496e6, 1.0496e6 * table_tolerance);

  // The walls get the modified Kelvin-Voigt law at 15 cm on both sides.
  const kimp::lumped::PoundingScene p = make_pounding_scene(s);
  ASSERT_TRUE(p.left_wall && p.right_wall);
  EXPECT_DOUBLE_EQ(p.left_wall->clear_gap(), 0.15);
  EXPECT_FALSE(p.left_neighbour || p.right_neighbour);
}

TEST(LumpedScene, FixedBaseFourStoreyPeriodIs0398)
{
  LumpedScene      s        = load("building:\n  kind: fixed_base\nwalls:\n  left:\n    present: "
                                   "false\n  right:\n    present: false\n");
  const auto       building = make_building(s);
  const auto       damping  = kimp::lumped::building_damping(building);
  constexpr double t1_tol   = 1.5e-3; // the thesis quotes 3 digits
  EXPECT_NEAR(damping.modes.period[0], 0.398, 0.398 * t1_tol) << "T1 = " << damping.modes.period[0];
  EXPECT_EQ(building.floor_masses.size(), 4u);
  EXPECT_DOUBLE_EQ(building.floor_masses.back(), 250e3);
}

TEST(LumpedScene, UnitsConvertToSi)
{
  const LumpedScene s = load("building:\n"
                             "  floor_mass: \"320000 kg\"\n"
                             "  storey_stiffness: \"600000 kN/m\"\n"
                             "  damping_ratio: \"3 %\"\n"
                             "isolator:\n"
                             "  Q: \"1500.9 kN\"\n"
                             "walls:\n"
                             "  left:\n"
                             "    gap: \"150 mm\"\n"
                             "    mass: \"500000 kg\"\n"
                             "impact:\n"
                             "  law: hysteretic\n"
                             "  k: \"750 kN/mm^1.5\"\n"
                             "ground_motion:\n"
                             "  scale_to_pga: \"0.821 g\"\n"
                             "integration:\n"
                             "  dt: \"2e-5 s\"\n");
  EXPECT_NEAR(s.building.floor_mass, 320e3, 320e3 * exact_tolerance);
  EXPECT_NEAR(s.building.storey_stiffness, 600e6, 600e6 * exact_tolerance);
  EXPECT_NEAR(s.building.damping_ratio, 0.03, 0.03 * exact_tolerance);
  EXPECT_NEAR(*s.isolator.Q, 1500.9e3, 1500.9e3 * exact_tolerance);
  EXPECT_NEAR(s.walls.left.gap, 0.15, 0.15 * exact_tolerance);
  EXPECT_NEAR(impact_stiffness(s.impact), kn_per_mm_1_5_in_si, kn_per_mm_1_5_in_si * 1e-9);
  EXPECT_DOUBLE_EQ(impact_exponent(s.impact), 1.5);
  EXPECT_NEAR(*s.ground_motion.scale_to_pga, 0.821 * g, 0.821 * g * exact_tolerance);
  EXPECT_NEAR(*requested_time_step(s.integration), 2e-5, 2e-5 * exact_tolerance);
  EXPECT_FALSE(requested_time_step(LumpedScene{}.integration).has_value());
}

TEST(LumpedScene, BumperStiffnessFromMaterialMatchesThesis)
{
  // docs/physics.md §1.7: one 150 x 150 x 50 mm bumper k_b = 0.089 kN/mm^2.65, four = 0.36.
  LumpedScene s;
  s.impact.law                     = "bumper";
  const double     kn_per_mm_2_65  = 1e3 * std::pow(1e3, 2.65);
  constexpr double quoted_2_digits = 0.01; // 0.089 is quoted to 2 significant digits
  s.impact.bumper.count            = 1;
  const double one                 = bumper_stiffness(s.impact) / kn_per_mm_2_65;
  EXPECT_NEAR(one, 0.089, 0.089 * quoted_2_digits) << "k_b = " << one << " kN/mm^2.65";
  s.impact.bumper.count = 4;
  EXPECT_NEAR(bumper_stiffness(s.impact) / kn_per_mm_2_65, 4 * one, 4 * one * exact_tolerance);
  // The clear gap of the shipped example: 24 cm wall gap - 5 cm bumper = 19 cm.
  s.walls.left.gap = 0.24;
  const auto p     = make_pounding_scene(s);
  ASSERT_TRUE(p.left_wall.has_value());
  EXPECT_NEAR(p.left_wall->clear_gap(), 0.19, 1e-12);
  s.impact.bumper.k_b = "0.5 kN/mm^2.65";
  EXPECT_NEAR(bumper_stiffness(s.impact), 0.5 * kn_per_mm_2_65, 0.5 * kn_per_mm_2_65 * 1e-9);
}

TEST(LumpedScene, CasesOverrideTheScene)
{
  const LumpedScene s     = load("impact:\n"
                                 "  law: hysteretic\n"
                                 "  k: \"750 kN/mm^1.6\"\n"
                                 "  exponent: 1.6\n"
                                 "cases:\n"
                                 "  - name: kv\n"
                                 "    law: kelvin_voigt\n"
                                 "    k: \"2500 kN/mm\"\n"
                                 "    gap: \"10 cm\"\n"
                                 "    right_gap: \"12 cm\"\n"
                                 "  - name: weak\n"
                                 "    cor: 0.5\n"
                                 "    ground_motion_scale: 0.5\n");
  const auto        cases = resolve_cases(s);
  ASSERT_EQ(cases.size(), 2u);
  const LumpedScene &kv = cases[0].second;
  EXPECT_EQ(cases[0].first, "kv");
  EXPECT_EQ(kv.impact.law, "kelvin_voigt");
  EXPECT_FALSE(kv.impact.exponent.has_value()) << "a new law starts from its own exponent";
  EXPECT_DOUBLE_EQ(impact_stiffness(kv.impact), 2.5e9);
  EXPECT_DOUBLE_EQ(kv.walls.left.gap, 0.10);
  EXPECT_DOUBLE_EQ(kv.walls.right.gap, 0.12);
  const LumpedScene &weak = cases[1].second;
  EXPECT_EQ(weak.impact.law, "hysteretic");
  EXPECT_DOUBLE_EQ(*weak.impact.exponent, 1.6);
  EXPECT_DOUBLE_EQ(weak.impact.cor, 0.5);
  EXPECT_DOUBLE_EQ(weak.ground_motion.scale, 0.5);
  EXPECT_DOUBLE_EQ(weak.walls.left.gap, 0.15);

  const auto single = resolve_cases(LumpedScene{});
  ASSERT_EQ(single.size(), 1u);
  EXPECT_EQ(single[0].first, "default");
}

TEST(LumpedScene, EveryValidationRuleNamesFileLineAndKey)
{
  struct Rule
  {
    const char *yaml;
    const char *expected; ///< substring: "scene.yaml:LINE: key = value"
  };
  const std::vector<Rule> rules = {
    {"building:\n  floor_mass: \"-1 t\"\n", "scene.yaml:2: building.floor_mass = -1 t"},
    {"building:\n  top_mass: \"0 t\"\n", "scene.yaml:2: building.top_mass = 0 t"},
    {"building:\n  isolation_mass: \"0 t\"\n", "scene.yaml:2: building.isolation_mass"},
    {"building:\n  storey_stiffness: \"0 MN/m\"\n", "scene.yaml:2: building.storey_stiffness"},
    {"building:\n  damping_ratio: \"120 %\"\n", "scene.yaml:2: building.damping_ratio = 120 %"},
    {"building:\n  fixed_base_damping_ratio: \"-1 %\"\n",
     "scene.yaml:2: building.fixed_base_damping_ratio"},
    {"isolator:\n  K1: \"-3 MN/m\"\n", "scene.yaml:2: isolator.K1 = -3 MN/m"},
    {"isolator:\n  K1: \"200 MN/m\"\n  K2: \"250 MN/m\"\n",
     "scene.yaml:3: isolator.K2 = 250 MN/m: must be < K1 = 200 MN/m"},
    {"isolator:\n  Q_ratio: \"0 %\"\n", "scene.yaml:2: isolator.Q_ratio = 0 %"},
    {"isolator:\n  Q: \"-5 kN\"\n", "scene.yaml:2: isolator.Q = -5 kN"},
    {"isolator:\n  kind: linear\n  k: \"0 MN/m\"\n", "scene.yaml:3: isolator.k = 0 MN/m"},
    {"isolator:\n  kind: friction_pendulum\n  mu_slow: 0.1\n  mu_fast: 0.05\n",
     "scene.yaml:4: isolator.mu_fast = 0.05: must be >= mu_slow = 0.1"},
    {"isolator:\n  kind: friction_pendulum\n  radius: \"0 m\"\n",
     "scene.yaml:3: isolator.radius = 0 m"},
    {"isolator:\n  kind: bouc_wen\n  beta: 0.2\n  gamma: 0.5\n",
     "scene.yaml:3: isolator.beta = 0.2: must be >= |gamma| = 0.5"},
    {"isolator:\n  kind: bouc_wen\n  n: 0.5\n", "scene.yaml:3: isolator.n = 0.5"},
    {"isolator:\n  damping_ratio: \"1 %\"\n",
     "scene.yaml:2: isolator.damping_ratio = 1 %: must be >= building.damping_ratio"},
    {"walls:\n  left:\n    gap: \"-2 cm\"\n", "scene.yaml:3: walls.left.gap = -2 cm"},
    {"walls:\n  right:\n    mass: \"0 t\"\n", "scene.yaml:3: walls.right.mass = 0 t"},
    {"building:\n  kind: fixed_base\n",
     "scene.yaml: walls.left.present = true (default): must be false"},
    {"impact:\n  law: jankowski\n  k: \"2500 kN/mm\"\n",
     "scene.yaml:3: impact.k = 2500 kN/mm: law jankowski (n = 1.5) needs a stiffness"},
    {"impact:\n  k: \"750 kN/mm^1.5\"\n", "scene.yaml:2: impact.k = 750 kN/mm^1.5"},
    {"impact:\n  k: \"2500 kN/furlong\"\n", "scene.yaml:2: impact.k = 2500 kN/furlong"},
    {"impact:\n  k: \"-5 kN/mm\"\n", "scene.yaml:2: impact.k = -5 kN/mm: must be > 0"},
    {"impact:\n  cor: 0\n", "scene.yaml:2: impact.cor = 0: must be in (0, 1]"},
    {"impact:\n  exponent: 1.5\n", "scene.yaml:2: impact.exponent = 1.5: must be null"},
    {"impact:\n  law: hertzdamp\n  k: \"750 kN/mm^0.5\"\n  exponent: 0.5\n",
     "scene.yaml:4: impact.exponent = 0.5: must be >= 1"},
    {"impact:\n  law: hysteretic\n  k: \"750 kN/mm^1.5\"\n  a1: \"-1 s/m\"\n",
     "scene.yaml:4: impact.a1 = -1 s/m"},
    {"impact:\n  law: bumper\n  bumper:\n    thickness: \"200 mm\"\n",
     "scene.yaml: walls.left.gap = 15 cm (default): must be > impact.bumper.thickness = 200 mm"},
    {"impact:\n  law: bumper\n  bumper:\n    ultimate_strain: 1.5\n",
     "scene.yaml:4: impact.bumper.ultimate_strain = 1.5"},
    {"impact:\n  law: bumper\n  bumper:\n    k_b: \"0.36 kN/mm\"\n",
     "scene.yaml:4: impact.bumper.k_b = 0.36 kN/mm: needs a stiffness in N/m^n with n = 2.65"},
    {"impact:\n  law: bumper\n  bumper:\n    wall_stiffness: \"0 kN/mm\"\n",
     "scene.yaml:4: impact.bumper.wall_stiffness"},
    {"neighbours:\n  left:\n    present: true\n    separation: \"0 cm\"\n",
     "scene.yaml:4: neighbours.left.separation = 0 cm"},
    {"neighbours:\n  right:\n    present: true\n    impact:\n      law: bumper\n",
     "scene.yaml:5: neighbours.right.impact.law = bumper"},
    {"ground_motion:\n  scale: 0\n", "scene.yaml:2: ground_motion.scale = 0"},
    {"ground_motion:\n  scale_to_pga: \"-1 g\"\n", "scene.yaml:2: ground_motion.scale_to_pga"},
    {"ground_motion:\n  duration: \"30 s\"\n",
     "scene.yaml:2: ground_motion.duration = 30 s: must be <= synthetic.duration = 20 s"},
    {"ground_motion:\n  synthetic:\n    dt: \"-1 s\"\n",
     "scene.yaml:3: ground_motion.synthetic.dt"},
    {"integration:\n  dt: \"fast\"\n", "scene.yaml:2: integration.dt = fast: must be \"auto\""},
    {"integration:\n  dt: \"2e-5 m\"\n", "scene.yaml:2: integration.dt = 2e-5 m"},
    {"integration:\n  safety: 1.5\n", "scene.yaml:2: integration.safety = 1.5"},
    {"integration:\n  output_interval: \"-1 s\"\n", "scene.yaml:2: integration.output_interval"},
    {"integration:\n  duration: \"0 s\"\n", "scene.yaml:2: integration.duration = 0 s"},
    {"cases:\n  - name: a\n  - name: a\n", "scene.yaml:3: cases[1].name = a: must be unique"},
    {"cases:\n  - name: \"a/b\"\n", "scene.yaml:2: cases[0].name = \"a/b\""},
    {"cases:\n  - name: j\n    law: jankowski\n",
     "scene.yaml:3: cases[0].law = 2500 kN/mm: law jankowski (n = 1.5) needs"},
    {"cases:\n  - name: j\n    k: \"750 kN/mm^1.5\"\n", "scene.yaml:3: cases[0].k = 750 kN/mm^1.5"},
    {"cases:\n  - name: c\n    cor: 1.5\n", "scene.yaml:3: cases[0].cor = 1.5"},
    {"cases:\n  - name: c\n    gap: \"-1 cm\"\n", "scene.yaml:3: cases[0].gap = -1 cm"},
    {"cases:\n  - name: c\n    ground_motion_scale: 0\n",
     "scene.yaml:3: cases[0].ground_motion_scale"},
    {"impact:\n  law: bumper\ncases:\n  - name: c\n    right_gap: \"3 cm\"\n",
     "scene.yaml:5: cases[0].right_gap = 3 cm: must be > impact.bumper.thickness"},
    {"building:\n  kind: fixed_base\nwalls:\n  left:\n    present: false\n  right:\n    present: "
     "false\ncases:\n  - name: c\n    gap: \"10 cm\"\n",
     "scene.yaml:10: cases[0].gap = 10 cm: needs an isolated building"},
    {"walls:\n  basement: true\nbuilding:\n  kind: fixed_base\n", "scene.yaml:2: walls.basement"},
  };
  for (const Rule &rule : rules)
  {
    const std::string message = error_of(rule.yaml);
    EXPECT_NE(message.find(rule.expected), std::string::npos)
      << "scene:\n"
      << rule.yaml << "\nexpected: " << rule.expected << "\ngot: " << message;
  }
  EXPECT_EQ(error_of("impact:\n  law: bumper\n"), "") << "the default bumper scene is valid";
}

TEST(LumpedScene, OneGravityForSceneAndReferenceBuilding)
{
  // Q = 0.1·g·W_tot with the same g in the scene path and the library's reference building
  // (docs/physics.md §3 "Gravity"): 1500.42 kN for 1530 t.
  const auto  scene_building = make_building(LumpedScene{});
  const auto  reference      = kimp::lumped::reference_isolated_building(4);
  const auto *a =
    dynamic_cast<const kimp::lumped::BilinearIsolator *>(scene_building.isolator.get());
  const auto *b = dynamic_cast<const kimp::lumped::BilinearIsolator *>(reference.isolator.get());
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(a->yield_force(), b->yield_force());
  EXPECT_NEAR(a->yield_force() * (1.0 - 25.0 / 200.0),
              0.1 * 9.80665 * 1530e3,
              exact_tolerance * 1500e3);
  EXPECT_EQ(kimp::io::standard_gravity, kimp::lumped::standard_gravity);
}

TEST(LumpedScene, FlexibleWallsAreSdofBlocks)
{
  const LumpedScene scene =
    load("walls:\n  left:\n    flexible: true\n    stiffness: \"800 MN/m\"\n"
         "    damping_ratio: \"3 %\"\n    mass: \"400 t\"\n");
  const auto pounding = make_pounding_scene(scene);
  ASSERT_TRUE(pounding.left_wall && pounding.right_wall);
  EXPECT_TRUE(pounding.left_wall->flexible);
  EXPECT_NEAR(pounding.left_wall->stiffness, 800e6, exact_tolerance * 800e6);
  EXPECT_NEAR(pounding.left_wall->damping_ratio, 0.03, exact_tolerance);
  EXPECT_FALSE(pounding.right_wall->flexible);
  const kimp::lumped::PoundingModel model(pounding);
  ASSERT_EQ(model.n_dofs(), 6u);
  EXPECT_NEAR(model.masses()[5], 400e3, exact_tolerance * 400e3);
  EXPECT_EQ(model.contacts()[0].left_dof, 5);
  EXPECT_EQ(model.contacts()[1].right_dof, -1);
  expect_contains(error_of("walls:\n  left:\n    flexible: true\n    stiffness: \"0 MN/m\"\n"),
                  {"scene.yaml:4: walls.left.stiffness = 0 MN/m"});
}

TEST(LumpedScene, FlexibleWallSdofMassIsNotTheLawsWallMass)
{
  // sdof_mass is the wall DOF's mass; the law's m_eff keeps `mass` (docs/physics.md §2).
  const LumpedScene scene =
    load("walls:\n  left:\n    flexible: true\n    mass: \"500 t\"\n    sdof_mass: \"20 t\"\n");
  const auto pounding = make_pounding_scene(scene);
  ASSERT_TRUE(pounding.left_wall && pounding.left_wall->sdof_mass);
  EXPECT_NEAR(*pounding.left_wall->sdof_mass, 20e3, exact_tolerance * 20e3);
  EXPECT_FALSE(pounding.right_wall->sdof_mass);
  const kimp::lumped::PoundingModel model(pounding);
  ASSERT_EQ(model.n_dofs(), 6u);
  EXPECT_NEAR(model.masses()[5], 20e3, exact_tolerance * 20e3);
  const kimp::lumped::PoundingModel rigid(
    make_pounding_scene(load("walls:\n  left:\n    mass: \"500 t\"\n")));
  // Same law: the same force at the same approach.
  const auto a = model.contacts()[0].law->clone();
  const auto b = rigid.contacts()[0].law->clone();
  EXPECT_EQ(a->set_trial(1e-3, 0.5).force, b->set_trial(1e-3, 0.5).force);
  expect_contains(error_of("walls:\n  left:\n    flexible: true\n    sdof_mass: \"0 t\"\n"),
                  {"walls.left.sdof_mass"});
}

TEST(LumpedScene, YieldingWallsTakeFirstGuessesPerMetreTimesWidth)
{
  // Caltrans-style backfill spring at h = 5.5 ft = 1.6764 m: (5.5·5.5 + 20) kip/in per ft and
  // 5.5·5.5^2.5/(1 + 2.37·5.5) kip per ft, i.e. 50.25 kip/in/ft and 27.80 kip/ft, per metre:
  constexpr double kip = 4448.2216152605, ft = 0.3048, in = 0.0254;
  const double     k = 50.25 * kip / in / ft;
  const double     f = 5.5 * std::pow(5.5, 2.5) / (1.0 + 2.37 * 5.5) * kip / ft;
  EXPECT_NEAR(k, 28.9e6, 0.001 * 28.9e6); // the 28.9 kN/mm/m of a 1.68 m backwall
  const LumpedScene scene =
    load("walls:\n  left:\n    sdof_mass: \"60 t\"\n    yielding:\n      width: \"20 m\"\n"
         "      height: \"1.6764 m\"\n");
  const auto pounding = make_pounding_scene(scene);
  ASSERT_TRUE(pounding.left_wall && pounding.left_wall->yielding);
  EXPECT_FALSE(pounding.right_wall->yielding);
  const kimp::lumped::WallBackfillParams &p = *pounding.left_wall->yielding;
  EXPECT_NEAR(p.stiffness, 20.0 * k, exact_tolerance * 20.0 * k);
  EXPECT_NEAR(p.capacity, 20.0 * f, exact_tolerance * 20.0 * f);
  EXPECT_EQ(p.unloading_stiffness, p.stiffness);
  EXPECT_EQ(p.tension_capacity, p.capacity);
  EXPECT_NEAR(p.radiation_damping, 1800.0 * 200.0 * 1.6764 * 20.0, exact_tolerance * 1.2e7);
  EXPECT_NEAR(p.failure_displacement, 0.16764, exact_tolerance);
  EXPECT_EQ(p.envelope, kimp::lumped::WallEnvelope::bilinear);
  const kimp::lumped::PoundingModel model(pounding);
  ASSERT_EQ(model.n_dofs(), 6u);
  EXPECT_NEAR(model.masses()[5], 60e3, exact_tolerance * 60e3);
  EXPECT_EQ(model.contacts().back().name, "left_wall_backfill");

  // Keys given explicitly, per metre.
  const LumpedScene given =
    load("walls:\n  right:\n    yielding:\n      width: \"10 m\"\n      envelope: hyperbolic\n"
         "      stiffness: \"20 kN/mm/m\"\n      capacity: \"300 kN/m\"\n      failure_ratio: 0.7\n"
         "      unloading_stiffness: \"40 kN/mm/m\"\n      tension_capacity: \"0 kN/m\"\n"
         "      radiation_damping: \"150 kN*s/m^2\"\n      failure_displacement: \"8 cm\"\n");
  const kimp::lumped::WallBackfillParams q = *make_pounding_scene(given).right_wall->yielding;
  EXPECT_EQ(q.envelope, kimp::lumped::WallEnvelope::hyperbolic);
  EXPECT_NEAR(q.stiffness, 200e6, exact_tolerance * 200e6);
  EXPECT_NEAR(q.capacity, 3e6, exact_tolerance * 3e6);
  EXPECT_NEAR(q.unloading_stiffness, 400e6, exact_tolerance * 400e6);
  EXPECT_EQ(q.tension_capacity, 0.0);
  EXPECT_NEAR(q.radiation_damping, 1.5e6, exact_tolerance * 1.5e6);
  EXPECT_NEAR(q.failure_displacement, 0.08, exact_tolerance);

  // The cap of the bilinear envelope, per metre; refused below the capacity.
  const LumpedScene capped =
    load("walls:\n  left:\n    yielding:\n      width: \"10 m\"\n      capacity: \"110 kN/m\"\n"
         "      hardening_ratio: \"2 %\"\n      ultimate_capacity: \"143 kN/m\"\n");
  EXPECT_NEAR(make_pounding_scene(capped).left_wall->yielding->ultimate_capacity,
              1.43e6,
              exact_tolerance * 1.43e6);
  EXPECT_EQ(q.ultimate_capacity, std::numeric_limits<double>::infinity()); // null: no cap
  expect_contains(error_of("walls:\n  left:\n    yielding:\n      capacity: \"110 kN/m\"\n"
                           "      ultimate_capacity: \"100 kN/m\"\n"),
                  {"walls.left.yielding.ultimate_capacity = 100 kN/m: must be >= capacity = "
                   "110 kN/m"});

  expect_contains(error_of(
                    "walls:\n  left:\n    flexible: true\n    yielding:\n      height: \"1 m\"\n"),
                  {"walls.left.flexible = true: must be false for a yielding wall"});
  // An unloading softer than the loading (a cracked wall's spring-back) is accepted: the law
  // unloads at the larger of it and the envelope's secant.
  EXPECT_EQ(error_of("walls:\n  left:\n    yielding:\n      stiffness: \"20 kN/mm/m\"\n"
                     "      unloading_stiffness: \"10 kN/mm/m\"\n"),
            "");
}

TEST(LumpedScene, YieldingWallCurveEnvelopeFromPointsPerMetre)
{
  // Points {displacement, force per metre} × width; k = the first slope, capacity = the last
  // force, the pull-back (null) = the capacity, k_ur (null) = k.
  const LumpedScene scene =
    load("walls:\n  left:\n    yielding:\n      width: \"10 m\"\n      envelope: curve\n"
         "      curve:\n        - {displacement: \"0 mm\", force: \"0 kN/m\"}\n"
         "        - {displacement: \"2 mm\", force: \"100 kN/m\"}\n"
         "        - {displacement: \"1 cm\", force: \"140 kN/m\"}\n");
  const auto                              pounding = make_pounding_scene(scene);
  const kimp::lumped::WallBackfillParams &p        = *pounding.left_wall->yielding;
  EXPECT_EQ(p.envelope, kimp::lumped::WallEnvelope::curve);
  ASSERT_EQ(p.curve_displacements.size(), 3u);
  EXPECT_NEAR(p.curve_displacements[2], 0.01, exact_tolerance);
  EXPECT_NEAR(p.curve_forces[1], 1e6, exact_tolerance * 1e6);
  EXPECT_NEAR(p.curve_forces[2], 1.4e6, exact_tolerance * 1.4e6);
  EXPECT_NEAR(p.capacity, 1.4e6, exact_tolerance * 1.4e6);
  EXPECT_NEAR(p.stiffness, 500e6, exact_tolerance * 500e6);
  EXPECT_NEAR(p.unloading_stiffness, 500e6, exact_tolerance * 500e6);
  EXPECT_NEAR(p.tension_capacity, 1.4e6, exact_tolerance * 1.4e6);
  const kimp::lumped::PoundingModel model(pounding); // the law accepts it

  // Refused: a convex kink (naming the point), a curve not from the origin, points without the
  // curve envelope, a curve envelope without points, and the keys the curve sets itself.
  const std::string head = "walls:\n  left:\n    yielding:\n      envelope: curve\n";
  const std::string pts  = "      curve:\n        - {displacement: 0 mm, force: 0 kN/m}\n"
                           "        - {displacement: 2 mm, force: 100 kN/m}\n";
  expect_contains(
    error_of(head + pts + "        - {displacement: 3 mm, force: 160 kN/m}\n"),
    {"walls.left.yielding.curve[2] = {3 mm, 160 kN/m}: the slope rises from the previous "
     "segment's (the curve must be concave)"});
  expect_contains(error_of(head + pts + "        - {displacement: 1 mm, force: 160 kN/m}\n"),
                  {"walls.left.yielding.curve[2] = {1 mm, 160 kN/m}: displacement must be larger"});
  expect_contains(error_of(head + pts + "        - {displacement: 3 mm, force: 90 kN/m}\n"),
                  {"walls.left.yielding.curve[2] = {3 mm, 90 kN/m}: force must not be below"});
  expect_contains(error_of(head + "      curve:\n        - {displacement: 1 mm, force: 0 kN/m}\n"
                                  "        - {displacement: 2 mm, force: 100 kN/m}\n"),
                  {"walls.left.yielding.curve[0]"});
  expect_contains(error_of(head),
                  {"walls.left.yielding.curve = 0 points (default): needs at least two"});
  expect_contains(error_of("walls:\n  left:\n    yielding:\n" + pts),
                  {"walls.left.yielding.curve = 2 points: is the curve envelope's"});
  expect_contains(error_of(head + pts + "      capacity: 100 kN/m\n"),
                  {"walls.left.yielding.capacity = set: is given by the curve envelope's points"});
  expect_contains(error_of(head + pts + "      hardening_ratio: 2 %\n"),
                  {"walls.left.yielding.hardening_ratio = set"});
}

TEST(LumpedScene, FrictionPendulumAndBoucWenIsolators)
{
  // Friction pendulum: W = g·Σm unless given; initial stiffness k_init + W/R.
  const LumpedScene fp          = load("isolator:\n  kind: friction_pendulum\n  radius: \"2.5 m\"\n"
                                       "  mu_slow: 0.03\n  mu_fast: 0.07\n  rate: \"25 s/m\"\n"
                                       "  k_init: \"800 MN/m\"\n");
  const auto        fp_building = make_building(fp);
  const auto       *friction =
    dynamic_cast<const kimp::lumped::FrictionPendulumIsolator *>(fp_building.isolator.get());
  ASSERT_NE(friction, nullptr);
  const double W = g * 1530e3;
  EXPECT_NEAR(friction->pendulum_stiffness(), W / 2.5, exact_tolerance * W / 2.5);
  EXPECT_NEAR(friction->initial_stiffness(), 800e6 + W / 2.5, exact_tolerance * 800e6);
  EXPECT_NEAR(friction->friction_coefficient(0.0), 0.03, exact_tolerance);
  EXPECT_NEAR(friction->friction_coefficient(1.0), 0.07 - 0.04 * std::exp(-25.0), 1e-12);
  const LumpedScene fp_w  = load("isolator:\n  kind: friction_pendulum\n  weight: \"10 MN\"\n");
  const auto       *given = dynamic_cast<const kimp::lumped::FrictionPendulumIsolator *>(
    make_building(fp_w).isolator.get());
  ASSERT_NE(given, nullptr);
  EXPECT_NEAR(given->pendulum_stiffness(), 10e6 / fp_w.isolator.radius, 1e-6);

  // Bouc-Wen: the bilinear keys K1, K2, Q give α = K2/K1 and F_y = Q/(1 − α).
  const LumpedScene bw = load("isolator:\n  kind: bouc_wen\n  Q: \"1500 kN\"\n  n: 3\n");
  const auto       *bouc_wen =
    dynamic_cast<const kimp::lumped::BoucWenIsolator *>(make_building(bw).isolator.get());
  ASSERT_NE(bouc_wen, nullptr);
  EXPECT_NEAR(bouc_wen->characteristic_strength(), 1500e3, exact_tolerance * 1500e3);
  EXPECT_NEAR(bouc_wen->yield_displacement(),
              1500e3 / (1.0 - 0.125) / 200e6,
              exact_tolerance * 1e-2);
  EXPECT_NEAR(bouc_wen->initial_stiffness(), 200e6, exact_tolerance * 200e6);
}

TEST(LumpedScene, UnknownKeysAndBadUnitsAreRejected)
{
  expect_contains(error_of("building:\n  n_floors: 4\n"), {"scene.yaml:2"});
  expect_contains(error_of("walls:\n  left:\n    gap: \"15 kg\"\n"), {"scene.yaml:3"});
  expect_contains(error_of("impact:\n  law: elastic\n"), {"scene.yaml:2"});
}

TEST(LumpedScene, PrintedDefaultsReadBackToTheDefaults)
{
  const std::string text = default_scene_text<LumpedScene>("kimp lumped scene");
  const LumpedScene back = load(text);
  EXPECT_EQ(to_json_text(back), to_json_text(LumpedScene{}));
  // Every section and the key quantities appear with their units.
  for (const char *needle : {"building:",
                             "isolator:",
                             "walls:",
                             "impact:",
                             "bumper:",
                             "neighbours:",
                             "ground_motion:",
                             "integration:",
                             "cases:",
                             "\"2500 kN/mm\"",
                             "\"320 t\"",
                             "\"600 MN/m\"",
                             "\"15 cm\"",
                             "\"5 %\""})
    EXPECT_NE(text.find(needle), std::string::npos) << needle << " missing in\n" << text;
}

namespace
{
  /// Every scalar key path of a resolved JSON object ("building.floor_mass", "cases").
  void
  collect_paths(const nlohmann::json &object, const std::string &prefix, std::set<std::string> &out)
  {
    for (const auto &[key, value] : object.items())
    {
      const std::string path = prefix.empty() ? key : prefix + "." + key;
      if (value.is_object())
        collect_paths(value, path, out);
      else
        out.insert(path);
    }
  }

  /// Schema entries by path ("building.floor_mass"); sections recurse, list items are skipped.
  void index_schema(const nlohmann::json &keys, std::map<std::string, nlohmann::json> &out)
  {
    for (const auto &entry : keys)
    {
      out[entry.at("path").get<std::string>()] = entry;
      if (entry.contains("keys"))
        index_schema(entry.at("keys"), out);
    }
  }

  /// A scene text that writes every default of the schema explicitly.
  void schema_defaults_yaml(const nlohmann::json &keys, const std::string &lead, std::string &out)
  {
    for (const auto &entry : keys)
    {
      const std::string     type = entry.at("type");
      const std::string     key  = entry.at("key");
      const nlohmann::json &d = entry.contains("default") ? entry.at("default") : nlohmann::json();
      if (type == "section" || (type == "optional section" && !d.is_null()))
      {
        out += lead + key + ":\n";
        schema_defaults_yaml(entry.at("keys"), lead + "  ", out);
      }
      else if (type == "list")
      {
        ASSERT_TRUE(d.empty()) << key << ": the lumped scene's lists are empty by default";
        out += lead + key + ": []\n";
      }
      else if (type == "integer" || type == "flag")
        out += lead + key + ": " + d.dump() + "\n";
      else // quantities (as text, e.g. "15 cm"), lists of them, text, choices, null
        out += lead + key + ": " + d.dump() + "\n";
    }
  }
} // namespace

TEST(LumpedScene, SchemaListsEveryKeyWithUnitRangeAndDefault)
{
  const nlohmann::json schema = nlohmann::json::parse(schema_text<LumpedScene>());
  ASSERT_TRUE(schema.contains("keys"));
  std::map<std::string, nlohmann::json> by_path;
  index_schema(schema.at("keys"), by_path);

  // Every key of the resolved scene is in the schema; every quantity has a unit and a range.
  std::set<std::string> paths;
  collect_paths(nlohmann::json::parse(to_json_text(LumpedScene{})), "", paths);
  ASSERT_GT(paths.size(), 50U);
  for (const std::string &path : paths)
  {
    ASSERT_EQ(by_path.count(path), 1U) << path << " missing in the schema";
    const nlohmann::json &entry = by_path.at(path);
    const std::string     type  = entry.at("type");
    if (type.find("quantity") != std::string::npos)
    {
      EXPECT_TRUE(entry.at("unit").is_string()) << path;
      EXPECT_TRUE(entry.contains("range")) << path;
    }
    EXPECT_TRUE(entry.at("doc").is_string()) << path;
  }

  const nlohmann::json &floor_mass = by_path.at("building.floor_mass");
  EXPECT_EQ(floor_mass.at("type"), "quantity");
  EXPECT_EQ(floor_mass.at("unit"), "t");
  EXPECT_EQ(floor_mass.at("default"), "320 t");
  EXPECT_EQ(floor_mass.at("range").at("min"), 0.0);
  EXPECT_EQ(floor_mass.at("range").at("min_open"), true);
  EXPECT_EQ(floor_mass.at("range").at("text"), "> 0");
  EXPECT_EQ(by_path.at("building.damping_ratio").at("range").at("text"), "in [0 %, 100 %)");
  EXPECT_EQ(by_path.at("integration.safety").at("range").at("text"), "in (0, 1]");
  EXPECT_EQ(by_path.at("building.n_storeys").at("range").at("min"), 1);
  EXPECT_EQ(by_path.at("impact.law").at("type"), "choice");
  EXPECT_FALSE(by_path.at("impact.law").at("options").empty());
  EXPECT_EQ(by_path.at("cases").at("type"), "list");
  EXPECT_FALSE(by_path.at("cases").at("item").empty());
  EXPECT_EQ(by_path.at("neighbours.left.impact").at("type"), "optional section");

  // The schema's defaults, written out as a scene, read back to the defaults.
  std::string text;
  schema_defaults_yaml(schema.at("keys"), "", text);
  const LumpedScene back = load(text);
  EXPECT_EQ(to_json_text(back), to_json_text(LumpedScene{})) << text;
}

TEST(LumpedScene, RangesAreCheckedWhereWrittenAndListedInTheDefaults)
{
  expect_contains(error_of("building:\n  floor_mass: \"0 t\"\n"),
                  {"scene.yaml:2: building.floor_mass = 0 t: must be > 0"});
  expect_contains(error_of("integration:\n  duration: \"-1 s\"\n"),
                  {"scene.yaml:2: integration.duration = -1 s: must be > 0 (or null)"});
  EXPECT_EQ(error_of("integration:\n  duration: null\n"), "");
  const std::string text = default_scene_text<LumpedScene>("kimp lumped scene");
  EXPECT_NE(text.find("floor_mass: \"320 t\"  # mass of every floor below the top [t, > 0]"),
            std::string::npos)
    << text;
}

TEST(LumpedScene, EveryShippedLumpedSceneLoads)
{
  const std::filesystem::path dir = source_dir() / "data" / "scenes";
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  const std::vector<std::string> shipped = {"isolated_4storey_no_walls.yaml",
                                            "table_4_3_kobe_gap15.yaml",
                                            "fixed_base_2storey.yaml",
                                            "fixed_base_3storey.yaml",
                                            "fixed_base_4storey.yaml",
                                            "fixed_base_5storey.yaml",
                                            "fixed_base_6storey.yaml",
                                            "isolated_between_neighbours.yaml",
                                            "bumper_example.yaml"};
  for (const std::string &name : shipped)
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  std::size_t n_loaded = 0;
  for (const auto &entry : std::filesystem::directory_iterator(dir))
  {
    if (entry.path().extension() != ".yaml")
      continue;
    // Lumped scenes are the ones with a top-level `building:` section (others: FEM scenes).
    std::ifstream in(entry.path());
    std::string   line;
    bool          lumped = false;
    bool          plan   = false;
    while (std::getline(in, line))
    {
      lumped = lumped || line.rfind("building:", 0) == 0;
      plan   = plan || line.rfind("plan:", 0) == 0;
    }
    if (!lumped || plan) // a scene in plan is read as PlanLumpedScene (e2e_plan_cli)
      continue;
    LumpedScene scene;
    EXPECT_NO_THROW(scene = load_scene<LumpedScene>(entry.path())) << entry.path();
    // The model is assembled too (walls, neighbours, laws), without running.
    for (const auto &[name, resolved] : resolve_cases(scene))
      EXPECT_NO_THROW(kimp::lumped::PoundingModel(make_pounding_scene(resolved)))
        << entry.path() << " case " << name;
    ++n_loaded;
  }
  EXPECT_GE(n_loaded, shipped.size());
}
