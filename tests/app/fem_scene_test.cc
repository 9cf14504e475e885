// FEM scene (app/fem/fem_scene.h): defaults of docs/physics.md §4, every validation rule
// with file:line:key, printed defaults reading back to the defaults, shipped scenes, and the
// translation to geometry/ and fem/ parameters.
#ifdef KIMP_WITH_FEM

#  include <algorithm>
#  include <cmath>
#  include <cstdlib>
#  include <filesystem>
#  include <gtest/gtest.h>
#  include <stdexcept>
#  include <string>
#  include <vector>

#  include "app/fem/fem_common.h"
#  include "app/fem/fem_scene.h"
#  include "app/helper_programs.h"
#  include "geometry/scene_ids.h"
#  include "geometry/scene_layout.h"
#  include "io/scene_io.h"
#  include "tests/support/files.h"
#  include "tests/support/scene_errors.h"

namespace
{
  using namespace kimp::io;
  using kimp::app::FemScene;
  using kimp::testing::source_dir;
  using Integrator = kimp::fem::ImpactParameters::Integrator;

  constexpr double  exact_tolerance   = 1e-14; ///< relative: values set from decimal literals
  constexpr double  printed_tolerance = 1e-14; ///< relative: 15-digit printed defaults
  const std::string file_name         = "fem_scene.yaml";

  void expect_relative(double actual, double expected, double tolerance, const std::string &what)
  {
    EXPECT_NEAR(actual, expected, tolerance * std::abs(expected))
      << what << ": actual " << actual << ", expected " << expected;
  }

  /// The SceneError message of loading `text`, or "" if it loads.
  std::string scene_error(const std::string &text)
  {
    return kimp::testing::scene_error<FemScene>(text, file_name);
  }

  void expect_same_scene(const FemScene &a, const FemScene &b, double tolerance)
  {
    ASSERT_EQ(a.wall_heights.size(), b.wall_heights.size());
    for (std::size_t i = 0; i < a.wall_heights.size(); ++i)
      expect_relative(a.wall_heights[i], b.wall_heights[i], tolerance, "wall_heights");
    expect_relative(a.geometry.wall_thickness, b.geometry.wall_thickness, tolerance, "t_w");
    EXPECT_EQ(a.geometry.with_backfill, b.geometry.with_backfill);
    expect_relative(a.geometry.backfill_width, b.geometry.backfill_width, tolerance, "B");
    EXPECT_EQ(a.geometry.backfill_height.has_value(), b.geometry.backfill_height.has_value());
    expect_relative(a.geometry.slab_length, b.geometry.slab_length, tolerance, "L");
    expect_relative(a.geometry.slab_thickness, b.geometry.slab_thickness, tolerance, "t_s");
    EXPECT_EQ(a.geometry.slab_top.has_value(), b.geometry.slab_top.has_value());
    expect_relative(a.geometry.gap, b.geometry.gap, tolerance, "gap");
    expect_relative(a.geometry.h_contact, b.geometry.h_contact, tolerance, "h_contact");
    expect_relative(a.geometry.h_max, b.geometry.h_max, tolerance, "h_max");
    expect_relative(a.geometry.grading, b.geometry.grading, tolerance, "grading");
    EXPECT_EQ(a.mesh_level, b.mesh_level);
    using Pair = std::pair<kimp::app::FemMaterial, kimp::app::FemMaterial>;
    for (const auto &[x, y] : {Pair{a.materials.concrete, b.materials.concrete},
                               Pair{a.materials.soil, b.materials.soil}})
    {
      expect_relative(x.youngs_modulus, y.youngs_modulus, tolerance, "E");
      expect_relative(x.poisson_ratio, y.poisson_ratio, tolerance, "nu");
      expect_relative(x.density, y.density, tolerance, "rho");
    }
    EXPECT_EQ(a.solver.rigid_slab, b.solver.rigid_slab);
    EXPECT_EQ(a.rigid_slab_mass.has_value(), b.rigid_slab_mass.has_value());
    expect_relative(a.solver.initial_velocity, b.solver.initial_velocity, tolerance, "velocity");
    expect_relative(a.solver.penalty_factor, b.solver.penalty_factor, tolerance, "penalty");
    expect_relative(a.solver.contact_damping_ratio,
                    b.solver.contact_damping_ratio,
                    tolerance,
                    "contact_damping_ratio");
    EXPECT_EQ(a.smoothing_window, b.smoothing_window);
    EXPECT_EQ(a.solver.integrator, b.solver.integrator);
    EXPECT_EQ(a.dt, b.dt);
    expect_relative(a.solver.explicit_options.cfl_safety,
                    b.solver.explicit_options.cfl_safety,
                    tolerance,
                    "cfl_safety");
    expect_relative(a.solver.implicit_options.dt_factor,
                    b.solver.implicit_options.dt_factor,
                    tolerance,
                    "implicit_dt_factor");
    expect_relative(a.solver.end_time, b.solver.end_time, tolerance, "end_time");
    expect_relative(a.solver.separation_hold_time,
                    b.solver.separation_hold_time,
                    tolerance,
                    "separation_hold_time");
    expect_relative(a.solver.output_interval,
                    b.solver.output_interval,
                    tolerance,
                    "output_interval");
    EXPECT_EQ(a.solver.log_interval, b.solver.log_interval);
    EXPECT_EQ(a.output.vtu_interval, b.output.vtu_interval);
  }

  TEST(FemScene, DefaultsAreThePhysicsSection4Scene)
  {
    const FemScene s;
    ASSERT_EQ(s.wall_heights.size(), 1u);
    expect_relative(s.wall_heights[0], 1.25, exact_tolerance, "H");
    expect_relative(s.geometry.wall_thickness, 0.25, exact_tolerance, "t_w");
    EXPECT_TRUE(s.geometry.with_backfill);
    expect_relative(s.geometry.backfill_width, 2.0, exact_tolerance, "B");
    EXPECT_FALSE(s.geometry.backfill_height) << "backfill flush with the wall top";
    expect_relative(s.geometry.slab_length, 8.0, exact_tolerance, "L");
    expect_relative(s.geometry.slab_thickness, 0.20, exact_tolerance, "t_s");
    EXPECT_FALSE(s.geometry.slab_top) << "slab top flush with the wall top";
    expect_relative(s.geometry.gap, 0.5e-3, exact_tolerance, "gap");
    expect_relative(s.solver.initial_velocity, 1.0, exact_tolerance, "v");
    expect_relative(s.materials.concrete.youngs_modulus, 30e9, exact_tolerance, "E_c");
    expect_relative(s.materials.concrete.poisson_ratio, 0.2, exact_tolerance, "nu_c");
    expect_relative(s.materials.concrete.density, 2400, exact_tolerance, "rho_c");
    expect_relative(s.materials.soil.youngs_modulus, 50e6, exact_tolerance, "E_s");
    expect_relative(s.materials.soil.poisson_ratio, 0.3, exact_tolerance, "nu_s");
    expect_relative(s.materials.soil.density, 1900, exact_tolerance, "rho_s");
    expect_relative(s.geometry.h_contact, 0.025, exact_tolerance, "h_contact");
    EXPECT_EQ(s.dt, "auto");
    EXPECT_EQ(s.solver.integrator, Integrator::explicit_central_difference);
    // docs/physics.md §4: 8.0 m x 0.20 m of concrete is 3840 kg per metre.
    expect_relative(kimp::app::slab_mass(s), 3840, exact_tolerance, "slab mass");

    const kimp::geometry::SceneGeometry g = kimp::app::scene_geometry(s, 1.25);
    expect_relative(g.wall_height, 1.25, exact_tolerance, "geometry H");
    expect_relative(g.resolved_slab_top(), 1.25, exact_tolerance, "slab top");
    expect_relative(g.resolved_backfill_height(), 1.25, exact_tolerance, "backfill height");
    EXPECT_TRUE(g.mesh_slab);
    EXPECT_NO_THROW(g.validate());
  }

  TEST(FemScene, PrintedDefaultsReadBackToTheDefaults)
  {
    const std::string text = default_scene_text<FemScene>("kimp fem scene");
    for (const char *key : {"wall_heights:",
                            "geometry:",
                            "mesh:",
                            "materials:",
                            "slab:",
                            "contact:",
                            "dynamics:",
                            "output:",
                            "h_contact:",
                            "dt:"})
      EXPECT_NE(text.find(key), std::string::npos) << "missing " << key << " in\n" << text;
    FemScene printed;
    ASSERT_NO_THROW(printed = load_scene_text<FemScene>(text, "defaults.yaml")) << text;
    expect_same_scene(printed, FemScene(), printed_tolerance);
  }

  TEST(FemScene, ReadsEveryKeyInItsUnit)
  {
    const std::string text = "wall_heights: [\"100 cm\", \"1.5 m\"]\n"
                             "geometry: {gap: \"2 mm\", slab_top: \"1 m\", backfill_height: "
                             "\"0.9 m\"}\n"
                             "materials: {soil: {E: \"80 MPa\"}}\n"
                             "slab: {rigid: true, mass: \"3 t/m\", velocity: \"2 m/s\"}\n"
                             "contact: {smoothing_window: \"0.1 ms\"}\n"
                             "dynamics: {integrator: implicit, dt: \"5 ms\", end_time: \"30 "
                             "ms\"}\n"
                             "output: {vtu_interval: \"1 ms\"}\n";
    const FemScene    s    = load_scene_text<FemScene>(text, file_name);
    ASSERT_EQ(s.wall_heights.size(), 2u);
    expect_relative(s.wall_heights[0], 1.0, exact_tolerance, "H0");
    expect_relative(s.geometry.gap, 2e-3, exact_tolerance, "gap");
    expect_relative(s.materials.soil.youngs_modulus, 80e6, exact_tolerance, "E_soil");
    expect_relative(kimp::app::slab_mass(s), 3000, exact_tolerance, "given rigid mass");

    const kimp::fem::ImpactParameters p =
      kimp::app::impact_parameters(s, 1.5, "H1.50.msh", "vtu/H1.50");
    EXPECT_TRUE(p.rigid_slab);
    expect_relative(p.slab_mass, 3000, exact_tolerance, "slab_mass");
    expect_relative(p.slab_face_y1, 1.0, exact_tolerance, "face top");
    expect_relative(p.slab_face_y0, 0.8, 1e-12, "face bottom");
    expect_relative(p.slab_front_x, -2e-3, exact_tolerance, "front x");
    expect_relative(p.initial_velocity, 2.0, exact_tolerance, "v");
    expect_relative(p.dt, 5e-3, exact_tolerance, "dt");
    expect_relative(p.smoothing_window, 1e-4, exact_tolerance, "smoothing");
    expect_relative(p.vtu_interval, 1e-3, exact_tolerance, "vtu");
    EXPECT_EQ(p.vtu_dir, std::filesystem::path("vtu/H1.50"));
    EXPECT_EQ(p.integrator, Integrator::implicit_newmark);
    EXPECT_EQ(p.materials.count(kimp::geometry::slab_material), 0u) << "rigid: no slab cells";
    expect_relative(p.materials.at(kimp::geometry::soil_material).youngs_modulus,
                    80e6,
                    exact_tolerance,
                    "soil E");
  }

  TEST(FemScene, SlabDampingReachesTheSolver)
  {
    const FemScene s = load_scene_text<FemScene>("slab: {damping_ratio: 0.05}\n", file_name);
    const kimp::fem::ImpactParameters p =
      kimp::app::impact_parameters(s, 1.25, "H1.25.msh", "vtu/H1.25");
    EXPECT_FALSE(p.rigid_slab);
    expect_relative(p.slab_damping_ratio, 0.05, exact_tolerance, "slab damping");
    EXPECT_EQ(kimp::app::impact_parameters(load_scene_text<FemScene>("{}\n", file_name),
                                           1.25,
                                           "H1.25.msh",
                                           "vtu/H1.25")
                .slab_damping_ratio,
              0.0)
      << "undamped by default";
  }

  TEST(FemScene, InelasticMaterialKeysSelectLawsAndPresets)
  {
    // Default: elastic, no laws. A preset sets E, nu, rho, c, phi, psi; c given overrides it.
    const FemScene elastic;
    EXPECT_TRUE(kimp::app::impact_parameters(elastic, 1.25, "m.msh").material_laws.empty());
    const FemScene s = load_scene_text<FemScene>("materials:\n"
                                                 "  soil: {model: mohr_coulomb, preset: dense_sand,"
                                                 " c: \"5 kPa\"}\n"
                                                 "  concrete: {model: damage_plasticity, f_cm: "
                                                 "\"48 MPa\"}\n",
                                                 file_name);
    const auto     p = kimp::app::impact_parameters(s, 1.25, "m.msh");
    namespace ids    = kimp::geometry;
    ASSERT_EQ(p.material_laws.count(ids::soil_material), 1u);
    ASSERT_EQ(p.material_laws.count(ids::wall_material), 1u);
    EXPECT_NE(dynamic_cast<const kimp::fem::MohrCoulombLaw *>(
                p.material_laws.at(ids::soil_material).get()),
              nullptr);
    EXPECT_DOUBLE_EQ(p.materials.at(ids::soil_material).youngs_modulus, 70e6);
    const auto sp = kimp::app::soil_parameters(s.materials.soil);
    EXPECT_DOUBLE_EQ(sp.cohesion, 5e3);
    EXPECT_NEAR(sp.friction_angle, 38 * M_PI / 180, 1e-14);
    // f_cm = 48 MPa: E_ci = 21.5 GPa 4.8^(1/3) = 36.27 GPa is the solver's E.
    EXPECT_NEAR(p.materials.at(ids::wall_material).youngs_modulus, 36.27e9, 0.01e9);
    EXPECT_THROW(load_scene_text<FemScene>("materials: {soil: {preset: sandy}}\n", file_name),
                 SceneError);
    EXPECT_THROW(load_scene_text<FemScene>("materials: {soil: {phi: 20, psi: 25}}\n", file_name),
                 SceneError);
    // E, nu or rho beside a preset would be ignored (the preset sets them): refused, naming the
    // key and the preset's value.
    for (const char *key : {"E: \"80 MPa\"", "nu: 0.35", "rho: \"2000 kg/m^3\""})
    {
      try
      {
        load_scene_text<FemScene>(std::string("materials: {soil: {preset: medium_dense_sand, ") +
                                    key + "}}\n",
                                  file_name);
        ADD_FAILURE() << key << " beside a preset was accepted";
      }
      catch (const SceneError &error)
      {
        const std::string what = error.what();
        EXPECT_NE(what.find("materials.soil." +
                            std::string(key).substr(0, std::string(key).find(':'))),
                  std::string::npos)
          << what;
        EXPECT_NE(what.find("E = 40 MPa"), std::string::npos) << what;
      }
    }
  }

  TEST(FemScene, PresetWrittenOutIsTheSameSoil)
  {
    // without_preset() (the study's sensitivity run scales its E): the same soil as the preset,
    // with c given beside the preset kept; a soil without preset is returned unchanged.
    const FemScene s = load_scene_text<FemScene>(
      "materials: {soil: {model: mohr_coulomb, preset: dense_sand, c: \"5 kPa\"}}\n",
      file_name);
    const kimp::app::FemSoil out = kimp::app::without_preset(s.materials.soil);
    const auto               a   = kimp::app::soil_parameters(s.materials.soil);
    const auto               b   = kimp::app::soil_parameters(out);
    EXPECT_EQ(out.preset, "none");
    EXPECT_EQ(b.youngs_modulus, a.youngs_modulus);
    EXPECT_EQ(b.poisson_ratio, a.poisson_ratio);
    EXPECT_EQ(b.density, a.density);
    EXPECT_EQ(b.cohesion, 5e3);
    EXPECT_NEAR(b.friction_angle, a.friction_angle, 1e-14);
    EXPECT_NEAR(b.dilatancy, a.dilatancy, 1e-14);
    EXPECT_EQ(b.tension_cutoff, a.tension_cutoff);
    const FemScene plain;
    EXPECT_EQ(kimp::app::without_preset(plain.materials.soil).youngs_modulus,
              plain.materials.soil.youngs_modulus);
  }

  TEST(FemScene, ReinforcementKeysGiveEachBodyItsBars)
  {
    // Default: no bars (the plain law, 6 history values). The wall's and the slab's sections
    // give each body its own law; percent ratios, f_y, E_s, hardening reach the law; bars on an
    // elastic concrete are refused, naming the key.
    namespace ids = kimp::geometry;
    using kimp::fem::ConcreteDamageLaw;
    const FemScene plain =
      load_scene_text<FemScene>("materials: {concrete: {model: damage_plasticity}}\n", file_name);
    const auto p0 = kimp::app::impact_parameters(plain, 1.25, "m.msh");
    EXPECT_EQ(p0.material_laws.at(ids::wall_material)->n_history(), 8u);
    EXPECT_EQ(p0.material_laws.at(ids::wall_material), p0.material_laws.at(ids::slab_material));
    const FemScene s = load_scene_text<FemScene>(
      "materials:\n"
      "  concrete:\n"
      "    model: damage_plasticity\n"
      "    wall_reinforcement: {ratio_y: \"0.8 %\", ratio_x: \"0.2 %\", f_y: \"550 MPa\"}\n"
      "    slab_reinforcement: {ratio_x: \"0.5 %\", E_s: \"210 GPa\", hardening: 0.02}\n",
      file_name);
    const auto p = kimp::app::impact_parameters(s, 1.25, "m.msh");
    const auto wall =
      dynamic_cast<const ConcreteDamageLaw *>(p.material_laws.at(ids::wall_material).get());
    const auto slab =
      dynamic_cast<const ConcreteDamageLaw *>(p.material_laws.at(ids::slab_material).get());
    ASSERT_NE(wall, nullptr);
    ASSERT_NE(slab, nullptr);
    EXPECT_EQ(wall->n_history(), 14u);
    EXPECT_DOUBLE_EQ(wall->reinforcement().ratio_y, 0.008);
    EXPECT_DOUBLE_EQ(wall->reinforcement().ratio_x, 0.002);
    EXPECT_DOUBLE_EQ(wall->reinforcement().yield_stress, 550e6);
    EXPECT_DOUBLE_EQ(wall->reinforcement().youngs_modulus, 200e9);
    EXPECT_DOUBLE_EQ(slab->reinforcement().ratio_x, 0.005);
    EXPECT_DOUBLE_EQ(slab->reinforcement().ratio_y, 0);
    EXPECT_DOUBLE_EQ(slab->reinforcement().youngs_modulus, 210e9);
    EXPECT_DOUBLE_EQ(slab->reinforcement().hardening, 0.02);
    EXPECT_NE(scene_error("materials: {concrete: {wall_reinforcement: {ratio_y: \"1 %\"}}}\n")
                .find("concrete.wall_reinforcement.ratio_y"),
              std::string::npos);
    EXPECT_NE(scene_error("materials: {concrete: {model: damage_plasticity, slab_reinforcement: "
                          "{ratio_x: 0.01}}}\n"),
              "");
    EXPECT_NE(scene_error("materials: {concrete: {model: damage_plasticity, slab_reinforcement: "
                          "{ratio_x: \"12 %\"}}}\n"),
              "");
  }

  TEST(FemScene, GeostaticKeysResolveToTheSolversOptions)
  {
    // auto: off for the elastic default (results unchanged), on with an inelastic soil with
    // K0 = 1 - sin(phi) (Jaky); K0 given overrides it; on/off force it.
    namespace ids = kimp::geometry;
    const FemScene elastic;
    EXPECT_FALSE(kimp::app::impact_parameters(elastic, 1.25, "m.msh").geostatic.enabled);
    const FemScene sand = load_scene_text<FemScene>(
      "materials: {soil: {model: mohr_coulomb, preset: medium_dense_sand}}\n",
      file_name);
    const auto p = kimp::app::impact_parameters(sand, 1.25, "m.msh");
    EXPECT_TRUE(p.geostatic.enabled);
    EXPECT_NEAR(p.geostatic.initial_stress_K0.at(ids::soil_material),
                1 - std::sin(34 * M_PI / 180),
                1e-14);
    const FemScene given =
      load_scene_text<FemScene>("geostatic: on\nmaterials: {soil: {K0: 0.6}}\n", file_name);
    const auto q = kimp::app::impact_parameters(given, 1.25, "m.msh");
    EXPECT_TRUE(q.geostatic.enabled);
    EXPECT_DOUBLE_EQ(q.geostatic.initial_stress_K0.at(ids::soil_material), 0.6);
    const FemScene off =
      load_scene_text<FemScene>("geostatic: off\nmaterials: {soil: {model: mohr_coulomb}}\n",
                                file_name);
    EXPECT_FALSE(kimp::app::impact_parameters(off, 1.25, "m.msh").geostatic.enabled);
    EXPECT_THROW(load_scene_text<FemScene>("materials: {soil: {K0: -1}}\n", file_name),
                 kimp::io::SceneError);
    EXPECT_THROW(load_scene_text<FemScene>("geostatic: maybe\n", file_name), kimp::io::SceneError);
  }

  TEST(FemScene, InterfaceContactMeshesSeparateNodesAndDefaultsToTanTwoThirdsPhi)
  {
    // bonded by default; contact: separate interface nodes in the mesh, mu = tan(2 phi / 3),
    // geostatic (auto) on; refused with the implicit integrator.
    const FemScene bonded;
    EXPECT_FALSE(kimp::app::impact_parameters(bonded, 1.25, "m.msh").wall_soil_interface.contact);
    EXPECT_FALSE(kimp::app::scene_geometry(bonded, 1.25).interface_contact);
    const FemScene s =
      load_scene_text<FemScene>("interface: {model: contact}\nmaterials: {soil: {phi: 30}}\n",
                                file_name);
    const auto p = kimp::app::impact_parameters(s, 1.25, "m.msh");
    EXPECT_TRUE(p.wall_soil_interface.contact);
    EXPECT_NEAR(p.wall_soil_interface.friction, std::tan(20 * M_PI / 180), 1e-14);
    EXPECT_TRUE(p.geostatic.enabled);
    EXPECT_TRUE(kimp::app::scene_geometry(s, 1.25).interface_contact);
    const FemScene given =
      load_scene_text<FemScene>("interface: {model: contact, friction: 0.3}\n", file_name);
    EXPECT_DOUBLE_EQ(
      kimp::app::impact_parameters(given, 1.25, "m.msh").wall_soil_interface.friction,
      0.3);
    EXPECT_NE(scene_error("interface: {model: contact}\ndynamics: {integrator: implicit}\n")
                .find("interface.model"),
              std::string::npos);
  }

  /// Largest height/width of the wall's cells of the case meshed from @p scene at 1.25 m.
  double wall_cell_aspect(const FemScene &scene)
  {
    const auto layout  = kimp::geometry::SceneLayout::build(kimp::app::scene_geometry(scene, 1.25));
    const double width = layout.wall_x[1] - layout.wall_x[0];
    double       aspect = 0.0;
    for (std::size_t i = 1; i < layout.wall_y.size(); ++i)
      aspect = std::max(aspect, (layout.wall_y[i] - layout.wall_y[i - 1]) / width);
    return aspect;
  }

  TEST(FemScene, InelasticConcreteBoundsTheWallCellsUnlessTheSceneSaysOtherwise)
  {
    // Inelastic concrete without mesh.wall_aspect_max: square wall cells on every mesh level
    // (tall plain-Q1 cells lock once the wall cracks). Elastic concrete keeps the graded rows,
    // with or without an inelastic backfill, so the linear default scene meshes as before; a
    // value in the scene wins.
    const std::string graded = "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5";
    const std::string damaged =
      "materials: {concrete: {model: damage_plasticity, f_cm: \"38 MPa\"}, soil: {model: "
      "mohr_coulomb, preset: medium_dense_sand}}\n";
    const FemScene inelastic = load_scene_text<FemScene>(graded + "}\n" + damaged, file_name);
    EXPECT_EQ(kimp::app::scene_geometry(inelastic, 1.25).wall_aspect_max, 1.0);
    EXPECT_LE(wall_cell_aspect(inelastic), 1.0 + 1e-9);
    FemScene refined   = inelastic;
    refined.mesh_level = 1;
    EXPECT_EQ(kimp::app::scene_geometry(refined, 1.25).wall_aspect_max, 1.0);
    EXPECT_LE(wall_cell_aspect(refined), 1.0 + 1e-9);

    const FemScene linear = load_scene_text<FemScene>(graded + "}\n", file_name);
    EXPECT_FALSE(kimp::app::scene_geometry(linear, 1.25).wall_aspect_max.has_value());
    EXPECT_GT(wall_cell_aspect(linear), 3.0) << "the graded wall's base rows stay tall";
    const FemScene soil_only = load_scene_text<FemScene>(
      graded + "}\nmaterials: {soil: {model: mohr_coulomb, preset: medium_dense_sand}}\n",
      file_name);
    EXPECT_FALSE(kimp::app::scene_geometry(soil_only, 1.25).wall_aspect_max.has_value());

    const FemScene given =
      load_scene_text<FemScene>(graded + ", wall_aspect_max: 3}\n" + damaged, file_name);
    EXPECT_EQ(kimp::app::scene_geometry(given, 1.25).wall_aspect_max, 3.0);
    EXPECT_GT(wall_cell_aspect(given), 1.5);
    EXPECT_LE(wall_cell_aspect(given), 3.0 + 1e-9);
  }

  TEST(FemScene, AutomaticTimesBecomeZeroForTheSolver)
  {
    const FemScene                    s;
    const kimp::fem::ImpactParameters p = kimp::app::impact_parameters(s, 1.25, "m.msh");
    EXPECT_EQ(p.dt, 0.0);
    EXPECT_EQ(p.smoothing_window, 0.0);
    EXPECT_FALSE(p.rigid_slab);
    EXPECT_EQ(p.materials.size(), 3u);
    EXPECT_TRUE(p.vtu_dir.empty());
    expect_relative(p.slab_face_y0, 1.05, 1e-12, "face bottom");
  }

  TEST(FemScene, CaseNamesHaveTwoDecimalsOrMoreWhenNeeded)
  {
    EXPECT_EQ(kimp::app::fem_case_name(1.25), "H1.25");
    EXPECT_EQ(kimp::app::fem_case_name(1.0), "H1.00");
    EXPECT_EQ(kimp::app::fem_case_name(2.0), "H2.00");
    EXPECT_EQ(kimp::app::fem_case_name(1.125), "H1.125");
  }

  /// One validation rule: a scene text and the key and line its message must name.
  struct Rule
  {
    std::string text;
    std::string key;
    int         line;
    std::string expectation;
  };

  /// The rule of a scene that sets only `key` (dotted: "materials.soil.nu") to `value` (YAML),
  /// one level of indentation per part of the key: the message names the key's own line.
  Rule one_key(const std::string &key, const std::string &value, const std::string &expectation)
  {
    std::string text, indent;
    std::size_t begin = 0;
    int         line  = 1;
    for (std::size_t dot; (dot = key.find('.', begin)) != std::string::npos; begin = dot + 1)
    {
      text += indent + key.substr(begin, dot - begin) + ":\n";
      indent += "  ";
      ++line;
    }
    return {text + indent + key.substr(begin) + ": " + value + "\n", key, line, expectation};
  }

  TEST(FemScene, EveryValidationRuleNamesFileLineAndKey)
  {
    // One key each, at its own line.
    std::vector<Rule> rules = {
      one_key("wall_heights", "[]", "at least one"),
      one_key("geometry.backfill_width", "\"-2 m\"", "in [0.1 m, 100 m]"),
      one_key("geometry.slab_length", "\"0 m\"", "in [0.1 m, 500 m]"),
      one_key("geometry.slab_thickness", "\"-1 cm\"", "in [0.02 m, 5 m]"),
      one_key("geometry.gap", "\"0 mm\"", "overlap"),
      one_key("geometry.gap", "\"-1 mm\"", "in (0, 1000 mm]"),
      one_key("geometry.backfill_height", "\"2 m\"", "<= wall_heights[0] = 1.25 m"),
      one_key("geometry.backfill_height", "\"0 m\"", "in [0.01 m, 20 m]"),
      one_key("geometry.slab_top", "\"1.5 m\"", "face the wall"),
      one_key("geometry.slab_top", "\"0.1 m\"", "above the ground"),
      one_key("mesh.h_contact", "\"0 cm\"", "in [0.0001 cm, 100 cm]"),
      one_key("mesh.h_max", "\"1 cm\"", ">= h_contact"),
      one_key("mesh.grading", "0.9", ">= 1"),
      one_key("mesh.wall_aspect_max", "0.5", "in [1, 20]"),
      one_key("materials.concrete.E", "\"0 GPa\"", "in [0.0001 GPa, 1000 GPa]"),
      one_key("materials.soil.nu", "0.5", "[0, 0.5)"),
      one_key("materials.soil.nu", "-0.1", "[0, 0.5)"),
      one_key("materials.soil.rho", "\"0 kg/m^3\"", "in [100 kg/m^3, 20000 kg/m^3]"),
      one_key("slab.mass", "\"3 t/m\"", "only for a rigid slab"),
      one_key("slab.velocity", "\"0 m/s\"", "> 0"),
      one_key("slab.damping_ratio", "1.5", "[0, 1]"),
      one_key("contact.penalty_factor", "0", "> 0"),
      one_key("contact.contact_damping_ratio", "1.5", "[0, 1]"),
      one_key("contact.smoothing_window", "soon", "'auto'"),
      one_key("contact.smoothing_window", "\"0 s\"", "in [1e-06 ms, 1000 ms]"),
      one_key("dynamics.dt", "\"2 m\"", "'auto' or a time"),
      one_key("dynamics.dt", "\"-1 s\"", "in [1e-10 s, 0.01 s]"),
      one_key("dynamics.cfl_safety", "1.5", "(0, 1]"),
      one_key("dynamics.implicit_dt_factor", "0", "> 0"),
      one_key("dynamics.end_time", "\"0 ms\"", "> 0"),
      one_key("dynamics.separation_hold_time", "\"-1 ms\"", ">= 0"),
      one_key("dynamics.output_interval", "\"-1 ms\"", ">= 0"),
      one_key("output.vtu_interval", "\"-1 ms\"", ">= 0"),
    };
    // Scenes of several keys, in flow style or after a blank line, array elements, and a rule
    // whose message names no line (0).
    const std::vector<Rule> combined = {
      {"wall_heights: [\"-1 m\"]\n", "wall_heights[0]", 1, "in [0.1 m, 20 m]"},
      {"wall_heights: [\"1.25 m\", \"125 cm\"]\n", "wall_heights[1]", 1, "twice"},
      {"\ngeometry:\n  wall_thickness: \"0 m\"\n",
       "geometry.wall_thickness",
       3,
       "in [0.02 m, 5 m]"},
      {"wall_heights: [\"0.1 m\"]\nmesh: {h_contact: \"1 cm\"}\n",
       "geometry.slab_thickness",
       0,
       "flush"},
      {"mesh:\n  h_contact: \"30 cm\"\n  h_max: \"40 cm\"\n",
       "mesh.h_contact",
       2,
       "wall_thickness"},
      {"geometry: {wall_thickness: \"1 m\"}\nmesh:\n  h_contact: \"22 cm\"\n",
       "mesh.h_contact",
       3,
       "slab_thickness"},
      {"slab:\n  rigid: true\n  mass: \"-1 kg/m\"\n", "slab.mass", 3, "> 0"},
      {"slab:\n  rigid: true\n  damping_ratio: 0.05\n",
       "slab.damping_ratio",
       3,
       "only for an elastic slab"},
      {"slab:\n  damping_ratio: 0.05\ndynamics:\n  integrator: implicit\n",
       "slab.damping_ratio",
       2,
       "needs dynamics.integrator: explicit"},
      {"contact:\n  subcycles: 2\ndynamics:\n  integrator: implicit\n",
       "contact.subcycles",
       2,
       "must be 1 (off) with dynamics.integrator: implicit"},
    };
    rules.insert(rules.end(), combined.begin(), combined.end());
    for (const Rule &rule : rules)
    {
      const std::string message = scene_error(rule.text);
      const std::string where =
        rule.line > 0 ? file_name + ":" + std::to_string(rule.line) + ": " + rule.key + " = " :
                        file_name + ": " + rule.key + " = ";
      EXPECT_NE(message.find(where), std::string::npos)
        << "scene:\n"
        << rule.text << "message: " << message << "\nexpected: " << where;
      EXPECT_NE(message.find(rule.expectation), std::string::npos)
        << "scene:\n"
        << rule.text << "message: " << message << "\nexpected: " << rule.expectation;
    }
  }

  TEST(FemScene, ReaderErrorsNameFileLineAndKey)
  {
    const std::string unknown = scene_error("mesh:\n  h_contac: \"2 cm\"\n");
    EXPECT_NE(unknown.find(file_name + ":2"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("h_contac"), std::string::npos) << unknown;
    const std::string wrong_unit = scene_error("geometry:\n  gap: \"5 kg\"\n");
    EXPECT_NE(wrong_unit.find(file_name + ":2: geometry.gap"), std::string::npos) << wrong_unit;
    const std::string wrong_choice = scene_error("dynamics:\n  integrator: rk4\n");
    EXPECT_NE(wrong_choice.find(file_name + ":2: dynamics.integrator"), std::string::npos)
      << wrong_choice;
    const std::string subcycles = scene_error("contact:\n  subcycles: 65\n");
    EXPECT_NE(subcycles.find(file_name + ":2: contact.subcycles"), std::string::npos) << subcycles;
    EXPECT_NE(subcycles.find("integer in [0, 64]"), std::string::npos) << subcycles;
  }

  TEST(FemScene, ShippedScenesLoad)
  {
    const std::filesystem::path dir = source_dir() / "data" / "scenes";
    std::size_t                 n   = 0;
    for (const auto &entry : std::filesystem::directory_iterator(dir))
    {
      const std::string name = entry.path().filename().string();
      if (name.rfind("fem_", 0) != 0 || entry.path().extension() != ".yaml")
        continue;
      ++n;
      EXPECT_NO_THROW(kimp::io::load_scene<FemScene>(entry.path())) << name;
    }
    EXPECT_GE(n, 2u) << "fem_default.yaml and fem_quick.yaml in " << dir;

    const FemScene            all = kimp::io::load_scene<FemScene>(dir / "fem_default.yaml");
    const std::vector<double> heights{1.00, 1.25, 1.50, 2.00};
    ASSERT_EQ(all.wall_heights.size(), heights.size());
    for (std::size_t i = 0; i < heights.size(); ++i)
      expect_relative(all.wall_heights[i], heights[i], exact_tolerance, "default heights");
    FemScene expected;
    expected.wall_heights = heights;
    expect_same_scene(all, expected, exact_tolerance);

    const FemScene quick = kimp::io::load_scene<FemScene>(dir / "fem_quick.yaml");
    EXPECT_TRUE(quick.solver.rigid_slab);
    expect_relative(kimp::app::slab_mass(quick), 3840, exact_tolerance, "quick slab mass");
  }

  TEST(FemScene, FarBoundaryKeySelectsTheDashpots)
  {
    // Default rollers: no absorbing ids (results unchanged); absorbing: the soil's fixed base
    // and far side; without a backfill there is no soil to put dashpots on.
    EXPECT_TRUE(
      kimp::app::impact_parameters(FemScene(), 1.25, "m.msh").absorbing_boundaries.empty());
    const FemScene s = load_scene_text<FemScene>("boundary: {far: absorbing}\n", file_name);
    EXPECT_EQ(s.boundary.far, kimp::app::FemBoundary::Far::absorbing);
    const auto ids = kimp::app::impact_parameters(s, 1.25, "m.msh").absorbing_boundaries;
    EXPECT_EQ(ids,
              (std::vector<unsigned int>{kimp::geometry::fixed_base,
                                         kimp::geometry::soil_far_side}));
    // With an inelastic soil the geostatic state comes along (the static step holds the
    // released faces on rollers and applies their reactions as forces).
    const FemScene inelastic = load_scene_text<FemScene>(
      "boundary: {far: absorbing}\nmaterials: {soil: {model: mohr_coulomb, preset: "
      "medium_dense_sand}}\n",
      file_name);
    const auto pi = kimp::app::impact_parameters(inelastic, 1.25, "m.msh");
    EXPECT_TRUE(pi.geostatic.enabled);
    EXPECT_EQ(pi.absorbing_boundaries, ids);
    const std::string no_soil =
      scene_error("geometry: {with_backfill: false}\nboundary: {far: absorbing}\n");
    EXPECT_NE(no_soil.find("boundary.far"), std::string::npos) << no_soil;
    EXPECT_NE(no_soil.find("needs a backfill"), std::string::npos) << no_soil;
    EXPECT_NE(scene_error("boundary: {far: sponge}\n").find("boundary.far"), std::string::npos);
  }

  TEST(FemScene, ViscousSpringBoundaryPutsSpringsBesideTheDashpots)
  {
    // viscous_spring: the dashpots' faces, with alpha_n = 1.0 and alpha_t = 0.5 unless given;
    // the dashpots alone have no springs; alphas are refused without viscous_spring.
    const auto absorbing =
      kimp::app::impact_parameters(load_scene_text<FemScene>("boundary: {far: absorbing}\n",
                                                             file_name),
                                   1.25,
                                   "m.msh");
    EXPECT_EQ(absorbing.boundary_spring_normal, 0.0);
    EXPECT_EQ(absorbing.boundary_spring_tangential, 0.0);
    const auto springs =
      kimp::app::impact_parameters(load_scene_text<FemScene>("boundary: {far: viscous_spring}\n",
                                                             file_name),
                                   1.25,
                                   "m.msh");
    EXPECT_EQ(springs.absorbing_boundaries, absorbing.absorbing_boundaries);
    EXPECT_EQ(springs.boundary_spring_normal, 1.0);
    EXPECT_EQ(springs.boundary_spring_tangential, 0.5);
    const auto given = kimp::app::impact_parameters(
      load_scene_text<FemScene>(
        "boundary: {far: viscous_spring, spring_normal: 1.2, spring_tangential: 0.35}\n",
        file_name),
      1.25,
      "m.msh");
    EXPECT_EQ(given.boundary_spring_normal, 1.2);
    EXPECT_EQ(given.boundary_spring_tangential, 0.35);
    for (const char *text : {"boundary: {far: absorbing, spring_normal: 1.0}\n",
                             "boundary: {spring_tangential: 0.5}\n"})
    {
      const std::string e = scene_error(text);
      EXPECT_NE(e.find("needs boundary.far: viscous_spring"), std::string::npos) << e;
    }
    for (const char *text : {"boundary: {far: viscous_spring, spring_normal: 0}\n",
                             "boundary: {far: viscous_spring, spring_tangential: 5}\n"})
      EXPECT_NE(scene_error(text).find("boundary.spring_"), std::string::npos) << text;
    const std::string no_soil =
      scene_error("geometry: {with_backfill: false}\nboundary: {far: viscous_spring}\n");
    EXPECT_NE(no_soil.find("needs a backfill"), std::string::npos) << no_soil;
  }

  TEST(FemCommands, ErrorMessageKeepsTheAdditionalInformationOfDealIIExceptions)
  {
    const std::runtime_error deal_ii(
      "\n--------------------------------------------------------\n"
      "An error occurred in line <212> of file <impact.cc> in function\n"
      "    void require(bool, const string&)\n"
      "The violated condition was: \n    ok\n"
      "Additional information: \n"
      "    dt = 1 s (must be <= the stable limit\n    1e-06 s)\n"
      "--------------------------------------------------------\n");
    EXPECT_EQ(kimp::app::error_message(deal_ii), "dt = 1 s (must be <= the stable limit 1e-06 s)");
    const std::runtime_error plain("geometry.gap = 0 mm");
    EXPECT_EQ(kimp::app::error_message(plain), "geometry.gap = 0 mm");
  }

  TEST(FemCommands, PlotScriptIsFoundInTheSourceTree)
  {
    const std::filesystem::path script = kimp::app::find_helper_script("plot_mesh.py");
    ASSERT_FALSE(script.empty());
    EXPECT_EQ(script.filename(), "plot_mesh.py");
    EXPECT_TRUE(std::filesystem::is_regular_file(script)) << script;
  }
} // namespace

#endif // KIMP_WITH_FEM
