// The output of `kimp fit` is a k source of its own: `kimp fit` -> `kimp export-opensees` and
// -> `kimp lumped` (impact.k_table) with no hand copying, the k of both the fitted k·W. And the
// export takes the contact's effective mass, COR and velocity from a study's own files, or
// refuses to guess a building it was not given (one error line).
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/fem_results.h"
#include "tests/support/csv.h"
#include "tests/support/fem_cases.h"
#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  constexpr double pi        = 3.14159265358979323846;
  constexpr double slab_mass = 3840.0; // kg/m
  constexpr double width     = 27.78;  // m, the default building width of the fits

  /**
   * An FEM case of a rigid slab (slab_mass, 1 m/s) on a rigid wall imitated by the Kelvin-Voigt
   * law of k (N/m per metre) at COR 0.7, in closed form: m x'' + c x' + k x = 0, x(0) = 0,
   * x'(0) = v, c = 2 xi sqrt(k m), xi = -ln e/sqrt(pi^2 + ln^2 e); contact while x > 0.
   */
  kimp::io::FemCase kelvin_voigt_case(const std::string &name, double height, double k)
  {
    const double      e = 0.7, v = 1.0, m = slab_mass;
    const double      xi      = -std::log(e) / std::sqrt(pi * pi + std::log(e) * std::log(e));
    const double      omega   = std::sqrt(k / m);
    const double      omega_d = omega * std::sqrt(1.0 - xi * xi);
    const double      c       = 2.0 * xi * std::sqrt(k * m);
    const double      end     = pi / omega_d;
    const double      dt      = end / 400.0;
    kimp::io::FemCase fem;
    fem.name            = name;
    fem.wall_height     = height;
    fem.slab_mass       = m;
    fem.impact_velocity = v;
    for (int j = -40; j <= 1200; ++j)
    {
      const double t = 0.001 + j * dt, s = j * dt;
      double       x = v * s, force = 0.0;
      if (s > 0.0 && s < end)
      {
        x                  = v / omega_d * std::exp(-xi * omega * s) * std::sin(omega_d * s);
        const double x_dot = v * std::exp(-xi * omega * s) *
                             (std::cos(omega_d * s) - xi * omega / omega_d * std::sin(omega_d * s));
        force = k * x + c * x_dot;
      }
      else if (s >= end)
        x = -e * v * (s - end);
      // Measurement noise of 1 % (deterministic): an exact history gives a zero-width
      // confidence interval, which is a warning of its own.
      force *= 1.0 + 0.01 * std::sin(12.9898 * j);
      kimp::testing::add_sample(fem, t, force, x);
      fem.indentation.push_back(x);
    }
    return fem;
  }

  /// What the shell command `command` run in `dir` printed (stdout and stderr).
  std::string output_of(const std::string &command, const std::filesystem::path &dir)
  {
    const std::filesystem::path log = dir / "command.txt";
    EXPECT_EQ(run_command("cd '" + dir.string() + "' && " + command, log), 0) << read_text(log);
    return read_text(log);
  }

  /// Counts the lines of `text` that begin with "error:".
  int error_lines(const std::string &text)
  {
    int         n  = 0;
    std::size_t at = 0;
    while ((at = text.find("error:", at)) != std::string::npos)
    {
      if (at == 0 || text[at - 1] == '\n')
        ++n;
      at += 6;
    }
    return n;
  }

  TEST(KSourceCli, FitOutputFeedsExportOpenSeesAndLumpedWithoutCopying)
  {
    const TempDir dir("k_source_fit");
    // k per metre of wall: 150 kN/mm/m at H = 1 m, 25 kN/mm/m at H = 2 m.
    write_fem_cases(dir.path() / "fem.h5",
                    {kelvin_voigt_case("H1.00", 1.0, 1.5e8),
                     kelvin_voigt_case("H2.00", 2.0, 2.5e7)});
    const KimpRun fit = run_kimp("-q fit fem.h5 -o fit", dir.path());
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    // The fit reproduces its own law: k and peak ratio 1, in the table.
    std::vector<double> k_total; // kN/mm, H = 1 m then 2 m
    for (const auto &row : read_csv_records(dir.path() / "fit" / "fit_table.csv"))
    {
      if (row.at("variant") != "kelvin_voigt_cor_fixed")
        continue;
      // Its status may warn of the sampled misfit's kink, never of the peak, nor fail.
      EXPECT_EQ(row.at("status").find("peak force"), std::string::npos) << row.at("status");
      EXPECT_NE(row.at("status").rfind("failed", 0), 0u) << row.at("status");
      EXPECT_NEAR(std::stod(row.at("peak_force_ratio")), 1.0, 0.03) << row.at("case");
      EXPECT_EQ(row.at("impact_velocity_m_per_s"), "1");
      k_total.push_back(std::stod(row.at("k_total")));
    }
    ASSERT_EQ(k_total.size(), 2u);
    EXPECT_NEAR(k_total[0], 150.0 * width, 0.02 * 150.0 * width);
    EXPECT_NEAR(k_total[1], 25.0 * width, 0.02 * 25.0 * width);

    // k at H = 1.5 m: halfway between the table's two heights (k_total = k per metre x W).
    const double k_kv = 0.5 * (k_total[0] + k_total[1]) * 1e6; // N/m

    // export-opensees straight from the fit directory; kimp fit knows no building, so m_eff
    // must be given, and is refused with one error line when it is not.
    const KimpRun no_mass =
      run_kimp("-q export-opensees fit --wall-height \"1.5 m\" -o none", dir.path());
    EXPECT_EQ(no_mass.exit_code, 1);
    EXPECT_NE(no_mass.err.find("--effective-mass"), std::string::npos) << no_mass.err;
    EXPECT_EQ(error_lines(no_mass.err), 1) << no_mass.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "none"));

    const KimpRun os =
      run_kimp("-q export-opensees fit --wall-height \"1.5 m\" --effective-mass \"200 t\" -o os",
               dir.path());
    ASSERT_EQ(os.exit_code, 0) << os.err;
    const nlohmann::json exported = read_json(dir.path() / "os" / "summary.json");
    EXPECT_NEAR(exported.at("input").at("k_kelvin_voigt").get<double>(), k_kv, 1e-5 * k_kv);
    EXPECT_EQ(exported.at("input").at("effective_mass").get<double>(), 200e3);
    EXPECT_EQ(exported.at("input").at("cor").get<double>(), 0.7);
    EXPECT_NE(exported.at("sources").at("k").get<std::string>().find("fit_table.csv"),
              std::string::npos);
    const std::string tcl = read_text(dir.path() / "os" / "opensees_impact.tcl");
    EXPECT_NE(tcl.find("fit_table.csv at wall height 1.5 m"), std::string::npos) << tcl;

    // kimp lumped with impact.k_table = the fit directory.
    write_text(
      dir.path() / "scene.yaml",
      "building:\n  n_storeys: 3\nwalls:\n  left:\n    gap: \"8 cm\"\n  right:\n"
      "    gap: \"8 cm\"\nimpact:\n  law: kelvin_voigt\n  k_table: fit\n"
      "  wall_height: \"1.5 m\"\nground_motion:\n  record: synthetic\n  duration: \"2 s\"\n");
    const KimpRun lumped = run_kimp("-q lumped scene.yaml -o lumped", dir.path());
    ASSERT_EQ(lumped.exit_code, 0) << lumped.err;
    const nlohmann::json s = read_json(dir.path() / "lumped" / "summary.json");
    ASSERT_TRUE(s.at("cases").at(0).contains("impact_k")) << s.dump(1);
    const nlohmann::json &k = s.at("cases").at(0).at("impact_k");
    EXPECT_NEAR(k.at("k").get<double>(), k_kv, 1e-5 * k_kv) << k.dump();
    EXPECT_EQ(k.at("wall_height").get<double>(), 1.5);
  }

  /// A study directory as `kimp study` writes it, reduced to what the export reads: the k table,
  /// the consistent k of one record and the summary's contact (400 t against 600 t: m_eff 240 t).
  void write_study_dir(const std::filesystem::path &dir)
  {
    std::filesystem::create_directories(dir);
    write_text(dir / "k_table.csv",
               "wall_height_m,impact_velocity_m_per_s,reference_velocity,"
               "kelvin_voigt_total_kN_per_mm,jankowski_total_kN_per_mm1.5,"
               "kelvin_voigt_status,jankowski_status\n"
               "1,1,yes,4000,20000,ok,ok\n2,1,yes,2000,10000,ok,ok\n"
               "1,2,no,4400,21000,ok,ok\n2,2,no,2200,11000,ok,ok\n");
    write_text(dir / "consistent_k.csv",
               "record,wall_height_m,law,k_reference,k_consistent,k_unit,change_percent,"
               "impact_velocity_m_per_s,velocity_used_m_per_s,iterations,converged,"
               "peak_impact_force_reference_kN,peak_impact_force_consistent_kN,status\n"
               "kobe,1,modified_kelvin_voigt,4000,4320,kN/mm,8,1.8,1.8,3,yes,900,950,ok\n"
               "kobe,1,jankowski,20000,20800,kN/mm^1.5,4,1.6,1.6,3,yes,800,820,ok\n"
               "kobe,1,hysteretic,20000,20700,kN/mm^1.5,3.5,1.5,1.5,3,yes,800,810,ok\n"
               "sylmar,1,modified_kelvin_voigt,4000,4100,kN/mm,2.5,1.2,1.2,10,no,700,720,"
               "ok\n");
    write_text(dir / "summary.json",
               R"({"command": "study", "reference_velocity": 1.0,
                   "contact": {"isolation_mass": 400000.0, "wall_mass": 600000.0,
                               "effective_mass": 240000.0, "cor": 0.65}})");
  }

  TEST(KSourceCli, ExportTakesTheStudysMassCorVelocityAndARecordsConsistentK)
  {
    const TempDir dir("k_source_study");
    write_study_dir(dir.path() / "study");
    const KimpRun os = run_kimp("-q export-opensees study --wall-height \"1 m\" -o os", dir.path());
    ASSERT_EQ(os.exit_code, 0) << os.err;
    const nlohmann::json j = read_json(dir.path() / "os" / "summary.json");
    EXPECT_EQ(j.at("input").at("effective_mass").get<double>(), 240e3); // not the default 195 t
    EXPECT_EQ(j.at("input").at("cor").get<double>(), 0.65);
    EXPECT_EQ(j.at("input").at("impact_velocity").get<double>(), 1.0);
    EXPECT_EQ(j.at("input").at("k_kelvin_voigt").get<double>(), 4000e6); // the reference row
    const std::string tcl = read_text(dir.path() / "os" / "opensees_impact.tcl");
    EXPECT_NE(tcl.find("m_eff = 240000 kg"), std::string::npos) << tcl;
    EXPECT_NE(tcl.find("isolation level 400 t against its wall 600 t"), std::string::npos) << tcl;
    EXPECT_NE(tcl.find("uniaxialMaterial JankowskiImpact 3 "), std::string::npos) << tcl;
    EXPECT_NE(tcl.find(" 240000 -0.15 1.5"), std::string::npos) << tcl; // Meff of JankowskiImpact

    // The consistent k of a record: its converged k and its own impact velocity.
    const KimpRun kobe =
      run_kimp("-q export-opensees study --wall-height \"1 m\" --record kobe -o kobe", dir.path());
    ASSERT_EQ(kobe.exit_code, 0) << kobe.err;
    const nlohmann::json k = read_json(dir.path() / "kobe" / "summary.json");
    EXPECT_EQ(k.at("input").at("k_kelvin_voigt").get<double>(), 4320e6);
    EXPECT_NEAR(k.at("input").at("k_hertz").get<double>(), 20800e3 * std::pow(1e3, 1.5), 1.0);
    EXPECT_EQ(k.at("input").at("impact_velocity").get<double>(), 1.6); // the Jankowski run's
    EXPECT_NE(k.at("sources").at("k").get<std::string>().find("consistent k of record 'kobe'"),
              std::string::npos);

    // Two heights: which one is for the user to say.
    const KimpRun which = run_kimp("-q export-opensees study -o which", dir.path());
    EXPECT_EQ(which.exit_code, 1);
    EXPECT_NE(which.err.find(
                "--wall-height is needed: study/k_table.csv holds the heights 1 m, 2 m"),
              std::string::npos)
      << which.err;

    // Explicit values win; a record that did not converge or is unknown is refused.
    const KimpRun given =
      run_kimp("-q export-opensees study --wall-height \"1 m\" --effective-mass \"100 t\" -o given",
               dir.path());
    ASSERT_EQ(given.exit_code, 0) << given.err;
    EXPECT_EQ(read_json(dir.path() / "given" / "summary.json")
                .at("input")
                .at("effective_mass")
                .get<double>(),
              100e3);
    const KimpRun sylmar =
      run_kimp("-q export-opensees study --wall-height \"1 m\" --record sylmar -o s", dir.path());
    EXPECT_EQ(sylmar.exit_code, 1);
    EXPECT_NE(sylmar.err.find("did not converge"), std::string::npos) << sylmar.err;
    const KimpRun unknown =
      run_kimp("-q export-opensees study --wall-height \"1 m\" --record elcentro -o u", dir.path());
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_NE(unknown.err.find("no record 'elcentro' (records: kobe, sylmar)"), std::string::npos)
      << unknown.err;
    EXPECT_EQ(error_lines(unknown.err), 1) << unknown.err;
  }

  TEST(KSourceCli, ExportedFilesRunAsTheyAreAndReportShowsThem)
  {
    const TempDir dir("k_source_run");
    write_study_dir(dir.path() / "study");
    ASSERT_EQ(
      run_kimp("-q export-opensees study --wall-height \"1.5 m\" -o os", dir.path()).exit_code,
      0);
    // Tcl: the file as OpenSees runs it, with OpenSees' two commands recorded by stubs.
    write_text(
      dir.path() / "stub.tcl",
      "set calls {}\nproc model {args} {global calls; lappend calls [list model {*}$args]}\n"
      "proc uniaxialMaterial {args} {global calls; lappend calls "
      "[list uniaxialMaterial {*}[lrange $args 0 1]]}\n"
      "source os/opensees_impact.tcl\nputs [join $calls \\n]\n");
    const std::string tcl = output_of("tclsh stub.tcl", dir.path());
    EXPECT_EQ(tcl,
              "model basic -ndm 1 -ndf 1\nuniaxialMaterial ViscoelasticGap 1\n"
              "uniaxialMaterial ElasticPPGap 2\nuniaxialMaterial JankowskiImpact 3\n"
              "uniaxialMaterial Hertzdamp 4\nuniaxialMaterial ImpactMaterial 5\n");
    // Sourced into a model of one's own: no model line.
    write_text(dir.path() / "own.tcl",
               "set kimp_own_model 1\nproc model {args} {puts model}\n"
               "proc uniaxialMaterial {args} {}\nsource os/opensees_impact.tcl\nputs done\n");
    EXPECT_EQ(output_of("tclsh own.tcl", dir.path()), "done\n");
    // OpenSeesPy: run as a script against a stub module.
    std::filesystem::create_directories(dir.path() / "stub" / "openseespy");
    write_text(dir.path() / "stub" / "openseespy" / "__init__.py", "");
    write_text(dir.path() / "stub" / "openseespy" / "opensees.py",
               "def wipe():\n    print('wipe')\n\n\ndef model(*a):\n    print('model', *a)\n\n\n"
               "def uniaxialMaterial(*a):\n    print('uniaxialMaterial', a[0], a[1])\n");
    EXPECT_EQ(output_of("PYTHONPATH=stub python3 os/opensees_impact.py", dir.path()),
              "wipe\nmodel basic -ndm 1 -ndf 1\nuniaxialMaterial ViscoelasticGap 1\n"
              "uniaxialMaterial ElasticPPGap 2\nuniaxialMaterial JankowskiImpact 3\n"
              "uniaxialMaterial Hertzdamp 4\nuniaxialMaterial ImpactMaterial 5\n");

    // kimp report of the export directory: a page with the parameters and both files.
    const KimpRun report = run_kimp("-q report os --json", dir.path());
    ASSERT_EQ(report.exit_code, 0) << report.err;
    const nlohmann::json data = nlohmann::json::parse(report.out);
    EXPECT_EQ(data.at("kind"), "export-opensees");
    EXPECT_NE(data.at("text").at("opensees_impact.tcl").get<std::string>().find("ViscoelasticGap"),
              std::string::npos);
    EXPECT_TRUE(data.at("text").contains("opensees_impact.py"));
  }
  TEST(KSourceCli, AnUnreadableKTableIsOneErrorAtItsKeyNotOnePerCase)
  {
    const TempDir dir("k_source_bad");
    write_text(dir.path() / "bad.csv", "a,b\n1,2\n");
    write_text(dir.path() / "scene.yaml",
               "building:\n  n_storeys: 3\nwalls:\n  left:\n    gap: \"8 cm\"\n  right:\n"
               "    gap: \"8 cm\"\nimpact:\n  law: kelvin_voigt\n  k_table: bad.csv\n"
               "ground_motion:\n  record: synthetic\n  duration: \"2 s\"\ncases:\n"
               "  - name: a\n    wall_height: \"1 m\"\n  - name: b\n    wall_height: \"1.5 m\"\n"
               "  - name: c\n    wall_height: \"2 m\"\n");
    const KimpRun run = run_kimp("-q lumped scene.yaml -o out", dir.path());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_EQ(error_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find("scene.yaml:10: impact.k_table = bad.csv: "), std::string::npos)
      << run.err;
    EXPECT_NE(run.err.find("no column 'wall_height_m'"), std::string::npos) << run.err;
  }
} // namespace
