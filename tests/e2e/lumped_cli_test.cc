// End-to-end `kimp lumped`: the built binary on small scenes; exit codes, lumped.h5 (units,
// status), summary.json, peaks.csv, failed cases, bad scenes leaving no output, --print-defaults.
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

#include "app/lumped/lumped_scene.h"
#include "tests/support/files.h"
#include "tests/support/hdf5_reader.h"
#include "tests/support/kimp_run.h"
#include "tests/support/messages.h"
#include "tests/support/scene_texts.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;

  using namespace kimp::testing;

  /// Isolated 4-storey building, walls at 4 cm, 6 s of the synthetic motion: a few impacts.
  const std::string small_scene = two_case_walled_scene("0.02 s", "  companion: true\n");

  constexpr double energy_balance_tolerance = 0.01; ///< relative error of the energy balance
  /// Penetration bound, m: the whole building (1530 t) arriving at about the peak ground velocity
  /// (~1 m/s) is stopped by k = 2500 kN/mm within v·sqrt(m/k) = 2.5 cm; without walls the base
  /// moves about 23 cm under this motion.
  constexpr double max_overshoot = 0.025;

  /// `kimp lumped <dir>/<file> -o <dir>/out` with `scene` written to `file` in `dir` first.
  KimpRun run_lumped(const TempDir &dir, const std::string &scene, const std::string &file)
  {
    const fs::path out = dir.path() / "out";
    return run_kimp("lumped " + dir.write(file, scene).string() + " -o " + out.string(),
                    dir.path());
  }

  /// `kimp lumped` of small_scene in a fresh directory, and its lumped.h5 (if it was written).
  struct SmallSceneRun
  {
    explicit SmallSceneRun(const char *name)
      : dir(name)
      , run(run_lumped(dir, small_scene, "scene.yaml"))
      , out(dir.path() / "out")
      , h5(out / "lumped.h5")
    {
    }
    TempDir    dir;
    KimpRun    run;
    fs::path   out;
    Hdf5Reader h5;
  };
} // namespace

TEST(LumpedCli, WritesResultsFileSummaryAndPeaks)
{
  const SmallSceneRun small("e2e_lumped_ok");
  ASSERT_EQ(small.run.exit_code, 0) << small.run.err;
  const fs::path   &out = small.out;
  const Hdf5Reader &h5  = small.h5;
  ASSERT_TRUE(h5.ok());
  for (const char *c : {"mkv", "hysteretic"})
  {
    const std::string g = std::string("/lumped/") + c;
    EXPECT_EQ(h5.attribute(g, "status"), "ok") << g;
    EXPECT_EQ(h5.attribute(g + "/peaks/displacement", "units"), "m");
    EXPECT_EQ(h5.attribute(g + "/peaks/absolute_acceleration", "units"), "m/s^2");
    EXPECT_EQ(h5.attribute(g + "/history/displacement/value", "units"), "m");
    EXPECT_EQ(h5.attribute(g + "/history/displacement/time", "units"), "s");
    EXPECT_EQ(h5.attribute(g + "/history/contact_force/value", "units"), "N");
    EXPECT_EQ(h5.attribute(g + "/dt", "units"), "s");
    EXPECT_EQ(h5.attribute(g + "/modal/building/period", "units"), "s");
    EXPECT_TRUE(h5.exists(g + "/contacts/left_wall/impact_time"));
    EXPECT_TRUE(h5.exists(g + "/energy/relative_error"));
    EXPECT_TRUE(h5.exists(g + "/amplification/displacement"));
    // The base cannot travel much past the wall: |u_0| <= gap + a small penetration.
    const std::vector<double> peaks = h5.doubles(g + "/peaks/displacement");
    ASSERT_EQ(peaks.size(), 5u);
    EXPECT_GT(peaks[0], 0.04) << c << ": the walls were reached";
    EXPECT_LT(peaks[0], 0.04 + max_overshoot) << c;
  }
  EXPECT_NE(h5.attribute("/input/scene", "units"), "<missing>");

  const nlohmann::json summary = read_json(out / "summary.json");
  ASSERT_EQ(summary["cases"].size(), 2u);
  for (const auto &c : summary["cases"])
  {
    EXPECT_EQ(c["status"], "ok");
    EXPECT_EQ(c["peaks"]["displacement"].size(), 5u);
    EXPECT_GT(c["n_impacts"].get<int>(), 0) << c["name"];
    EXPECT_LT(c["energy"]["relative_error"].get<double>(), energy_balance_tolerance) << c["name"];
    EXPECT_NEAR(c["dt"].get<double>(), 1e-4, 1e-12);
    EXPECT_EQ(c["n_steps"].get<long>(), 60000);
    // Isolated period with K1 (contacts open): T1 well above the superstructure's.
    EXPECT_GT(c["periods"]["building"][0].get<double>(), 0.5);
  }

  const std::string csv     = read_text(out / "peaks.csv");
  std::size_t       n_lines = 0;
  for (const char ch : csv)
    n_lines += ch == '\n';
  EXPECT_EQ(n_lines, 1u + 2u * 5u) << csv;
  EXPECT_EQ(csv.rfind("case,dof,peak_displacement_m", 0), 0u) << csv;
}

TEST(LumpedCli, LabelledHistoriesIsolatorForceAndFullRatePulses)
{
  const SmallSceneRun small("e2e_lumped_outputs");
  ASSERT_EQ(small.run.exit_code, 0) << small.run.err;
  const Hdf5Reader &h5 = small.h5;
  ASSERT_TRUE(h5.ok());
  const std::string g = "/lumped/mkv";
  // Columns named, not bare indices.
  EXPECT_EQ(h5.attribute(g + "/history/displacement", "labels"),
            "building isolation level,building floor 1,building floor 2,building floor 3,"
            "building floor 4");
  EXPECT_EQ(h5.attribute(g + "/history/interstorey_drift", "labels"),
            "building storey 1,building storey 2,building storey 3,building storey 4");
  EXPECT_EQ(h5.attribute(g + "/history/contact_force", "labels"),
            "contact left_wall,contact right_wall");
  EXPECT_TRUE(h5.exists(g + "/history/displacement/labels"));

  // Impact pulses at full rate (every step with a force): their maximum is the peak force, which
  // the 0.02 s history sampling underestimates.
  const std::vector<double> sampled     = h5.doubles(g + "/history/contact_force/value");
  double                    sampled_max = 0.0;
  for (const double f : sampled)
    sampled_max = std::max(sampled_max, f);
  double full_max = 0.0;
  for (const char *wall : {"left_wall", "right_wall"})
  {
    const std::string         c     = g + "/contacts/" + wall;
    const std::vector<double> force = h5.doubles(c + "/force_full_rate/value");
    const std::vector<double> time  = h5.doubles(c + "/force_full_rate/time");
    ASSERT_FALSE(force.empty()) << wall;
    ASSERT_EQ(force.size(), time.size()) << wall;
    EXPECT_EQ(h5.attribute(c + "/force_full_rate/value", "units"), "N");
    double peak = 0.0;
    for (const double f : force)
      peak = std::max(peak, f);
    EXPECT_EQ(peak, h5.doubles(c + "/peak_force").at(0)) << wall;
    full_max = std::max(full_max, peak);
    // Consecutive samples of one pulse are one step (1e-4 s) apart.
    EXPECT_NEAR(time[1] - time[0], 1e-4, 1e-12) << wall;
    // The deformation at the same steps: in contact, so positive (an impact's indentation is
    // its largest value).
    const std::vector<double> delta = h5.doubles(c + "/deformation_full_rate/value");
    EXPECT_EQ(h5.doubles(c + "/deformation_full_rate/time"), time) << wall;
    EXPECT_EQ(h5.attribute(c + "/deformation_full_rate/value", "units"), "m");
    ASSERT_EQ(delta.size(), force.size()) << wall;
    for (std::size_t i = 0; i < delta.size(); ++i)
      EXPECT_GT(delta[i], 0.0) << wall << " at " << time[i] << " s, force " << force[i] << " N";
  }
  EXPECT_GE(full_max, sampled_max);

  // Isolator: force history, peak and hysteretic energy (the bilinear default, Q = 0.1 g·1530 t,
  // K2 = 25 MN/m): |F| <= K2·|u| + Q, reached at the peak displacement while loading.
  const double              Q       = 0.1 * 9.80665 * 1530e3;
  const double              peak_u  = h5.doubles(g + "/peaks/displacement").at(0);
  const double              peak_f  = h5.doubles(g + "/isolator/peak_force").at(0);
  const std::vector<double> f_iso   = h5.doubles(g + "/history/isolator_force/value");
  const std::vector<double> e_hyst  = h5.doubles(g + "/history/hysteretic_energy/value");
  constexpr double          f_tol   = 1e-9; ///< relative, round-off of the bound
  double                    max_iso = 0.0;
  for (const double f : f_iso)
    max_iso = std::max(max_iso, std::abs(f));
  EXPECT_LE(max_iso, peak_f);
  EXPECT_LE(peak_f, (25e6 * peak_u + Q) * (1.0 + f_tol));
  EXPECT_GT(peak_f, 0.99 * (25e6 * peak_u + Q));
  EXPECT_EQ(h5.text(g + "/isolator/kind"), "bilinear");
  ASSERT_FALSE(e_hyst.empty());
  EXPECT_EQ(e_hyst.back(), h5.doubles(g + "/energy/hysteretic").at(0));
  EXPECT_EQ(e_hyst.back(), h5.doubles(g + "/isolator/dissipated_energy").at(0));
  const nlohmann::json summary = read_json(small.out / "summary.json");
  EXPECT_EQ(summary["cases"][0]["isolator"]["peak_force"].get<double>(), peak_f);
}

TEST(LumpedCli, FailedCaseIsRecordedAndExitsNonZero)
{
  TempDir dir("e2e_lumped_fail");
  // Two cases at dt = 5e-4 s: k = 2500 kN/mm is stable (dt_cr of about 0.01 s); k = 1e8 kN/mm
  // has omega_imp = sqrt(1e14 N/m / 195 t) = 2.3e4 rad/s, dt_cr of about 9e-5 s: refused.
  const std::string scene =
    std::string("walls:\n  left:\n    gap: \"4 cm\"\n  right:\n    gap: \"4 cm\"\n"
                "ground_motion:\n  duration: \"3 s\"\n"
                "integration:\n  dt: \"5e-4 s\"\n  output_interval: \"0.05 s\"\n"
                "cases:\n  - name: soft\n    k: \"2500 kN/mm\"\n"
                "  - name: stiff\n    k: \"1e8 kN/mm\"\n");
  const KimpRun  run = run_lumped(dir, scene, "scene.yaml");
  const fs::path out = dir.path() / "out";
  EXPECT_NE(run.exit_code, 0);
  expect_contains(run.err, {"stiff"});
  Hdf5Reader h5(out / "lumped.h5");
  ASSERT_TRUE(h5.ok()) << "the other cases are written";
  EXPECT_EQ(h5.attribute("/lumped/soft", "status"), "ok");
  const std::string failed = h5.attribute("/lumped/stiff", "status");
  EXPECT_EQ(failed.rfind("failed: ", 0), 0u) << failed;
  EXPECT_NE(failed.find("stab"), std::string::npos) << "names the stability limit: " << failed;
  const nlohmann::json summary = read_json(out / "summary.json");
  EXPECT_EQ(summary["cases"][1]["status"].get<std::string>().rfind("failed", 0), 0u);
}

TEST(LumpedCli, BadSceneNamesFileLineKeyAndWritesNothing)
{
  TempDir       dir("e2e_lumped_bad");
  const KimpRun run =
    run_lumped(dir, "isolator:\n  K1: \"200 MN/m\"\n  K2: \"300 MN/m\"\n", "bad.yaml");
  const fs::path out = dir.path() / "out";
  EXPECT_NE(run.exit_code, 0);
  expect_contains(run.err, {"bad.yaml:3: isolator.K2 = 300 MN/m"});
  EXPECT_FALSE(fs::exists(out / "lumped.h5"));
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  EXPECT_FALSE(fs::exists(out / "peaks.csv"));
}

TEST(LumpedCli, PrintDefaultsReadsBackToTheDefaults)
{
  TempDir       dir("e2e_lumped_defaults");
  const KimpRun run = run_kimp("lumped --print-defaults", dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  using kimp::app::LumpedScene;
  const LumpedScene back = kimp::io::load_scene_text<LumpedScene>(run.out, "defaults");
  EXPECT_EQ(kimp::io::to_json_text(back), kimp::io::to_json_text(LumpedScene{}));
}

TEST(LumpedCli, YieldingWallsReportForceAgainstCapacityDisplacementsAndFailure)
{
  // Both walls yielding, 1 MN per wall (50 kN/m over 20 m): the building's impacts push them
  // back; the left one may go 1 cm before it counts as failed, the right one 1 m.
  TempDir           dir("e2e_lumped_yielding");
  const std::string wall  = "    gap: \"4 cm\"\n    sdof_mass: \"50 t\"\n    yielding:\n"
                            "      width: \"20 m\"\n      capacity: \"50 kN/m\"\n"
                            "      stiffness: \"10 kN/mm/m\"\n";
  const std::string scene = "walls:\n  left:\n" + wall +
                            "      failure_displacement: \"1 cm\"\n  right:\n" + wall +
                            "      failure_displacement: \"1 m\"\n"
                            "ground_motion:\n  record: synthetic\n  duration: \"6 s\"\n"
                            "integration:\n  dt: \"1e-4 s\"\n";
  const KimpRun run = run_lumped(dir, scene, "yielding.yaml");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const fs::path   out = dir.path() / "out";
  const Hdf5Reader h5(out / "lumped.h5");
  ASSERT_TRUE(h5.ok());
  const nlohmann::json summary = read_json(out / "summary.json");
  const nlohmann::json c       = summary["cases"][0];
  ASSERT_EQ(c["walls"].size(), 2u) << c.dump();
  for (const nlohmann::json &w : c["walls"])
  {
    const std::string g =
      "/lumped/" + c["name"].get<std::string>() + "/walls/" + w["name"].get<std::string>();
    EXPECT_EQ(h5.doubles(g + "/capacity").at(0), 1e6);
    EXPECT_EQ(w["capacity"].get<double>(), 1e6);
    // Pushed to its cap and no farther (no hardening); the dashpot adds to the force.
    EXPECT_DOUBLE_EQ(w["peak_resistance_ratio"].get<double>(), 1.0) << w.dump();
    EXPECT_GT(w["peak_force"].get<double>(), w["peak_resistance"].get<double>());
    EXPECT_EQ(h5.doubles(g + "/peak_force").at(0), w["peak_force"].get<double>());
    EXPECT_EQ(h5.units(g + "/peak_displacement"), "m");
    // Beyond the yield displacement 1 MN / 200 MN/m = 5 mm, and a permanent set left behind.
    EXPECT_GT(w["peak_displacement"].get<double>(), 0.005) << w.dump();
    EXPECT_GT(w["residual_displacement"].get<double>(), 0.0) << w.dump();
    EXPECT_LT(w["residual_displacement"].get<double>(), w["peak_displacement"].get<double>());
  }
  EXPECT_EQ(c["walls"][0]["name"], "left_wall");
  const bool left_failed = c["walls"][0]["peak_displacement"].get<double>() > 0.01;
  EXPECT_EQ(c["walls"][0]["failed"].get<bool>(), left_failed);
  EXPECT_EQ(c["walls"][0].contains("failure_time"), left_failed);
  EXPECT_FALSE(c["walls"][1]["failed"].get<bool>());
  EXPECT_TRUE(left_failed) << "the scene should push the left wall past 1 cm";
  expect_contains(run.err, {"left_wall failed at t ="});
  // The walls' plastic and radiated work are in the energy balance, which closes.
  EXPECT_GT(c["energy"]["wall_plastic"].get<double>(), 0.0);
  EXPECT_GT(c["energy"]["wall_radiated"].get<double>(), 0.0);
  EXPECT_LT(c["energy"]["relative_error"].get<double>(), 1e-4);
}

TEST(LumpedCli, ExportOpenSeesWritesTheYieldingWallsOfALumpedScene)
{
  TempDir        dir("e2e_lumped_opensees_walls");
  const fs::path scene =
    dir.write("walls.yaml",
              "walls:\n  right:\n    gap: \"10 cm\"\n    sdof_mass: \"60 t\"\n"
              "    yielding:\n      width: \"20 m\"\n"
              "      capacity: \"150 kN/m\"\n      stiffness: \"25 kN/mm/m\"\n");
  // The laws' k and m_eff given, the walls from `lumped_scene`, into the directory `out`.
  const auto export_walls = [&dir](const std::string &out, const fs::path &lumped_scene)
  {
    return run_kimp("-q export-opensees -o " + out +
                      " --k-kv \"2496 kN/mm\" --effective-mass \"144.8 t\" --lumped-scene " +
                      lumped_scene.string(),
                    dir.path());
  };
  const KimpRun run = export_walls("os", scene);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string tcl = read_text(dir.path() / "os" / "opensees_walls.tcl");
  expect_contains(tcl,
                  {"uniaxialMaterial ElasticPPGap 11 500000000 -3000000 0.0 0 damage",
                   "node 1001 0.0 -mass 60000"});
  EXPECT_NE(read_text(dir.path() / "os" / "opensees_walls.py").find("ops.uniaxialMaterial("),
            std::string::npos);
  const nlohmann::json summary = read_json(dir.path() / "os" / "summary.json");
  EXPECT_EQ(summary["files"].size(), 4u) << summary.dump();

  // A curve envelope (a pushover's hull) is one ElasticPPGap per kink in the Parallel.
  const fs::path curve     = dir.write("curve.yaml",
                                   "walls:\n  right:\n    gap: \"10 cm\"\n"
                                       "    yielding:\n      width: \"20 m\"\n"
                                       "      envelope: curve\n      curve:\n"
                                       "        - {displacement: 0 mm, force: 0 kN/m}\n"
                                       "        - {displacement: 6 mm, force: 150 kN/m}\n"
                                       "        - {displacement: 30 mm, force: 198 kN/m}\n");
  const KimpRun  curve_run = export_walls("curve", curve);
  ASSERT_EQ(curve_run.exit_code, 0) << curve_run.err;
  const std::string curve_tcl = read_text(dir.path() / "curve" / "opensees_walls.tcl");
  expect_contains(curve_tcl,
                  {"uniaxialMaterial ElasticPPGap 11 460000000 -2760000 0.0 0 damage\n"
                   "uniaxialMaterial ElasticPPGap 12 40000000 -1200000 0.0 0 damage",
                   "uniaxialMaterial Parallel 14 11 12 13\n"});

  // A scene without a yielding wall is refused, and nothing is left behind.
  const fs::path rigid = dir.write("rigid.yaml", "walls:\n  right:\n    gap: \"10 cm\"\n");
  const KimpRun  none  = export_walls("none", rigid);
  EXPECT_EQ(none.exit_code, 1);
  expect_contains(none.err, {"has no yielding wall"});
  EXPECT_FALSE(fs::exists(dir.path() / "none" / "opensees_impact.tcl"));
}
